"""What the visitor chose in the DEM card's "Impacts" tab, and the upload that follows.

`ImpactState.test`, `material` and `model` are checked by their parameters (the material's
choices are the test's: a new test whose materials do not hold the one chosen takes its
first); `upload` reads a file's bytes (`app.dem.impacts.read_upload`) into `results`
(`refuse` drops them), and `reference` and `scores` are the exact reference at the
results' incidences and their score, set by the tab once computed (`scored`), or
`message` saying why there are none.
"""

from __future__ import annotations

import param

from app.dem.impacts import DEFAULT_MODEL, DEFAULT_TEST, ImpactCurves, read_upload, scores
from core.dem_check.impact_cases import TESTS
from core.dem_check.lammps import MODELS


class ImpactState(param.Parameterized):
    """The tab's test, material, LAMMPS model and uploaded results with their score."""

    test = param.Selector(default=DEFAULT_TEST, objects=list(TESTS),
                          doc="Chung & Ooi's test shown (4 to 8)")
    material = param.Selector(default=TESTS[DEFAULT_TEST].materials[0],
                              objects=list(TESTS[DEFAULT_TEST].materials),
                              doc="the test's material shown")
    model = param.Selector(default=DEFAULT_MODEL, objects=list(MODELS),
                           doc="LAMMPS' tangential model drawn")
    results = param.ClassSelector(class_=ImpactCurves, default=None, allow_None=True,
                                  doc="the uploaded results, None before an upload or after "
                                      "a refused one")
    reference = param.ClassSelector(class_=ImpactCurves, default=None, allow_None=True,
                                    doc="the exact reference at the results' incidences, "
                                        "for the test and material shown")
    scores = param.Dict(default=None, allow_None=True,
                        doc="quantity -> CurveScore of the results against `reference`")
    message = param.String(default="", doc="why the upload has no score; '' if it has")

    @param.depends("test", watch=True, on_init=True)
    def _materials(self) -> None:
        choices = list(TESTS[self.test].materials)
        self.param.material.objects = choices
        if self.material not in choices:
            self.material = choices[0]

    @param.depends("test", "material", watch=True)
    def _stale(self) -> None:
        """Another test or material: the score of the results is not this one's."""
        self.param.update(reference=None, scores=None)

    def upload(self, data: object) -> None:
        """Read an uploaded file's bytes: its results replace the last, or the reason it is
        refused is the message and no results are kept."""
        try:
            results = read_upload(data, self.test)
        except ValueError as err:
            self.param.update(results=None, reference=None, scores=None, message=str(err))
            return
        self.param.update(results=results, reference=None, scores=None, message="")

    def refuse(self, message: str) -> None:
        """A file refused before it was read (`message`: why): no results are kept."""
        self.param.update(results=None, reference=None, scores=None, message=message)

    def scored(self, reference: ImpactCurves) -> None:
        """The reference at the results' incidences has been computed: the score."""
        if self.results is None or reference.incidence_deg.size != \
                self.results.incidence_deg.size:
            return
        self.param.update(reference=reference, scores=scores(self.results, reference),
                          message="")

    def failed(self, message: str) -> None:
        """The reference could not be computed (`message`: why)."""
        self.param.update(reference=None, scores=None, message=message)
