"""The DEM card's "Impacts" tab: `ImpactsTab`, Chung & Ooi's (2011) impact tests 4 to 8
drawn against incidence and a visitor's results scored.

Inside: a test, one of its materials and one of LAMMPS' tangential models; three figures
(tangential restitution, rebound spin, rebound angle against incidence) with the exact
reference (`core.impact`), LAMMPS' model (both precomputed, `app.dem.impacts`), test 4's
published values (Chung & Ooi's curve, Kharaz et al.'s measurements) and the visitor's
results, from named sources updated in place (`dem_impact_exact`, `dem_impact_lammps`,
`dem_impact_published`, `dem_impact_experiment`, `dem_impact_upload`); the upload box of
the card's other tab (`app.dem.upload.CsvUpload`, the same size cap and messages), the
reason under it when a file is refused, and the score table (LAMMPS' model and the file
against the reference: worst and mean difference and where). The reference at an
uploaded incidence off the shipped grid is solved on the job runner
(`app.kit.jobs.RUNNER`) while a progress bar shows.
"""

from __future__ import annotations

import html
from functools import partial

import numpy as np
import panel as pn
from bokeh.core.properties import value
from bokeh.models import ColumnDataSource

from app.dem import data, impacts
from app.dem.impacts_state import ImpactState
from app.dem.upload import CsvUpload
from app.kit.batch import held
from app.kit.figures import fit_range, new_figure, style_figure
from app.kit.jobs import RUNNER
from app.kit.progress import JobProgress
from app.kit.widgets import ERROR_STYLE, follow, shortened, sync, text_html
from core.dem_check.impact_cases import TESTS
from core.dem_check.lammps import MODELS

INTRO = (
    "Chung & Ooi's (2011) oblique-impact tests, the yardstick DEM codes are verified on: "
    "the thick grey curve is the exact reference (Maw, Barber & Fawcett's problem solved "
    "with the Mindlin-Deresiewicz history, `core.impact`), the coloured one LAMMPS' "
    "tangential model, the squares Chung & Ooi's published curve and the triangles Kharaz, "
    "Gorham & Salman's (2001) measurements (test 4, alumina). Run the test in your own "
    "code and upload its results as a CSV with a header row `incidence_deg,"
    "tangential_cor,rebound_spin,rebound_angle` and one row per incidence: the incidence "
    "of the contact point (deg, in [0, 90)), vx'/vx of the centre (tests 6-8 may leave "
    "the column out or give `nan`), the rebound spin (rad/s, positive in the rolling "
    "sense) and the rebound angle of the contact point (deg), at most "
    f"{data.size_text(data.MAX_UPLOAD_BYTES)} and {impacts.MAX_ROWS} rows. "
    "`docs/impact.md` says how the reference is computed and the scores defined.")

#: The names of the tests in the chooser.
TEST_OPTIONS = {f"Test {n}: {t.title}": n for n, t in TESTS.items()}
#: Each quantity's figure title and axis label.
TITLES = {"tangential_cor": "Tangential restitution of the centre",
          "rebound_spin": "Rebound spin", "rebound_angle": "Rebound angle of the contact point"}
AXES = {"tangential_cor": "vx' / vx", "rebound_spin": "ω' (rad/s)",
        "rebound_angle": "angle (deg)"}
#: The colours of the reference and of the published values.
EXACT_COLOR, PUBLISHED_COLOR, EXPERIMENT_COLOR = "black", "#333333", "#000000"


def material_options(test: int) -> dict[str, str]:
    """The chooser's materials of `test`: name shown -> name in core."""
    return {m.replace("_", " "): m for m in TESTS[test].materials}


def table_html(rows: list[tuple[str, ...]], heads: tuple[str, ...], caption: str) -> str:
    """A score table as HTML (every text escaped)."""
    head = "".join(f'<th scope="col">{html.escape(h)}</th>' for h in heads)
    body = "".join(
        f'<tr><th scope="row">{html.escape(r[0])}</th>'
        + "".join(f"<td>{html.escape(v)}</td>" for v in r[1:]) + "</tr>" for r in rows)
    return (f"<table><caption>{html.escape(caption)}</caption><tr>{head}</tr>{body}"
            "</table>")


class ImpactsTab(pn.viewable.Viewer):
    """The tab's content (built at once: it reads shipped files only); `table_css` is the
    card's score-table stylesheet."""

    def __init__(self, state: ImpactState | None = None, table_css: str = "") -> None:
        super().__init__()
        self.state = state or ImpactState()
        self._requests = 0
        self._closed = False
        blank = impacts.columns(None)
        self.sources = {
            "exact": ColumnDataSource(dict(blank), name="dem_impact_exact"),
            "lammps": ColumnDataSource(dict(blank), name="dem_impact_lammps"),
            "upload": ColumnDataSource(dict(blank), name="dem_impact_upload"),
            "published": ColumnDataSource(impacts.published(4, "alumina", "published"),
                                          name="dem_impact_published"),
            "experiment": ColumnDataSource(impacts.published(4, "alumina", "experiment"),
                                           name="dem_impact_experiment"),
        }
        s = self.state
        self.test_select = pn.widgets.Select(label="Test", options=TEST_OPTIONS, value=s.test,
                                             width=440)
        sync(self.test_select, s.param.test)
        self.material_select = pn.widgets.Select(label="Material",
                                                 options=material_options(s.test),
                                                 value=s.material, width=170)
        follow(self.material_select, s.param.material)  # (shown with its test's options)
        self.model_select = pn.widgets.Select(label="LAMMPS model", options=list(MODELS),
                                              value=s.model, width=200)
        sync(self.model_select, s.param.model)
        self.note = pn.pane.Markdown("", sizing_mode="stretch_width",
                                     styles={"font-size": "0.9em"})
        self.figures = {q: self._figure(q, legend=(q == impacts.QUANTITIES[0]))
                        for q in impacts.QUANTITIES}
        self.upload = CsvUpload(on_file=s.upload, on_refused=s.refuse,
                                label="Your code's impacts (CSV: incidence_deg, "
                                      "tangential_cor, rebound_spin, rebound_angle)",
                                accept=".csv,text/csv,text/plain",
                                max_bytes=data.MAX_UPLOAD_BYTES, name="dem_impact_upload_box",
                                margin=(5, 10), sizing_mode="stretch_width")
        self.progress = JobProgress(width=200)
        self.status = pn.pane.HTML("", sizing_mode="stretch_width")
        self.message = pn.pane.HTML("", visible=False, styles=ERROR_STYLE,
                                    sizing_mode="stretch_width", name="dem_impact_message")
        self.score_table = pn.pane.HTML("", stylesheets=[table_css],
                                        sizing_mode="stretch_width", name="dem_impact_score")
        s.param.watch(lambda *_: self._show_choice(), ["test", "material"])
        s.param.watch(lambda *_: self._show_model(), "model")
        s.param.watch(lambda *_: self._show_results(), "results")
        s.param.watch(lambda *_: self._request(), ["results", "test", "material"])
        s.param.watch(lambda *_: self._show_score(), ["scores", "message", "model"])
        self._show_choice()
        self.layout = pn.Column(
            pn.pane.Markdown(INTRO, sizing_mode="stretch_width"),
            pn.Row(self.test_select, self.material_select, self.model_select,
                   sizing_mode="stretch_width"),
            pn.FlexBox(*(pn.pane.Bokeh(f, sizing_mode="stretch_width", min_width=300,
                                       styles={"flex": "1 1 320px"})
                         for f in self.figures.values()),
                       flex_wrap="wrap", sizing_mode="stretch_width"),
            self.note,
            self.upload,
            pn.Row(self.progress, self.status, sizing_mode="stretch_width"),
            self.message,
            self.score_table,
            sizing_mode="stretch_width")

    def __panel__(self) -> pn.Column:
        return self.layout

    def close(self) -> None:
        """The session ended: drop a waiting solve of the reference."""
        self._closed = True
        RUNNER.cancel(self)

    # ---------------------------------------------------------------- figure

    def _figure(self, q: str, legend: bool):
        fig = new_figure(TITLES[q], "incidence θ (deg)", AXES[q], height=300)
        src = self.sources

        def named(text: str) -> dict:
            return {"legend_label": text} if legend else {}

        fig.line("incidence_deg", q, source=src["exact"], color=EXACT_COLOR, line_width=5,
                 alpha=0.35, **named("exact (core.impact)"))
        fig.line("incidence_deg", q, source=src["lammps"], color=data.COLORS["mindlin"],
                 line_width=2, name=f"lammps_line_{q}", **named("LAMMPS"))
        fig.scatter("incidence_deg", q, source=src["lammps"], color=data.COLORS["mindlin"],
                    size=6, name=f"lammps_points_{q}", **named("LAMMPS"))
        fig.scatter(f"{q}_x", f"{q}_y", source=src["published"], marker="square", size=8,
                    fill_color=None, line_color=PUBLISHED_COLOR, line_width=1.5,
                    **named("published (Chung & Ooi)"))
        fig.scatter(f"{q}_x", f"{q}_y", source=src["experiment"], marker="triangle", size=9,
                    color=EXPERIMENT_COLOR, **named("measured (Kharaz et al.)"))
        fig.line("incidence_deg", q, source=src["upload"], color=data.UPLOAD_COLOR,
                 line_width=2.5, **named("your file"))
        fig.scatter("incidence_deg", q, source=src["upload"], color=data.UPLOAD_COLOR,
                    marker="diamond", size=9, **named("your file"))
        fit_range(fig.x_range, [0.0, 90.0], pad=0.0)
        style_figure(fig)
        if legend:
            fig.legend.location = "bottom_right"
            fig.legend.label_text_font_size = "10pt"
        return fig

    # ------------------------------------------------------------------ show

    def _show_choice(self) -> None:
        """The test and material's reference, published values, LAMMPS and note."""
        s = self.state
        with held():
            self.material_select.param.update(options=material_options(s.test),
                                              value=s.material)
            self.sources["exact"].data = impacts.columns(impacts.exact_curves(s.test,
                                                                              s.material))
            for series in ("published", "experiment"):
                self.sources[series].data = impacts.published(s.test, s.material, series)
            self.note.object = impacts.lammps_note(s.test, s.material)
            self._show_model()

    def _show_model(self) -> None:
        s = self.state
        color = data.COLORS[s.model]
        with held():
            self.sources["lammps"].data = impacts.columns(
                impacts.lammps_curves(s.test, s.material, s.model))
            for fig in self.figures.values():
                for r in fig.renderers:
                    if r.name and r.name.startswith("lammps_"):
                        r.glyph.update(line_color=color, **(
                            {"fill_color": color} if hasattr(r.glyph, "fill_color") else {}))
                for item in (fig.legend[0].items if fig.legend else []):
                    if any(r.name and r.name.startswith("lammps_") for r in item.renderers):
                        item.label = value(f"LAMMPS {s.model}")
            self._fit()
            self._show_score()

    def _show_results(self) -> None:
        self.sources["upload"].data = impacts.columns(self.state.results)
        self._fit()

    def _fit(self) -> None:
        for q, fig in self.figures.items():
            fit_range(fig.y_range, *(self.sources[k].data[q]
                                     for k in ("exact", "lammps", "upload")),
                      self.sources["published"].data[f"{q}_y"],
                      self.sources["experiment"].data[f"{q}_y"])

    def _show_score(self) -> None:
        """The score table (LAMMPS' model, and the file once scored) and the message."""
        s = self.state
        text = shortened(s.message)
        lm = impacts.lammps_scores(s.test, s.material, s.model)
        heads = ("against the exact reference", f"LAMMPS {s.model}",
                 *(("your file",) if s.scores else ()))
        rows = [r if s.scores else r[:2] for r in impacts.score_rows(s.model, lm, s.scores)]
        material = s.material.replace("_", " ")
        with held():
            self.message.param.update(object=text_html(text), visible=bool(text))
            self.score_table.object = table_html(
                rows, heads, f"Test {s.test}, {material}: worst and mean |difference|")

    # ----------------------------------------------------------------- score

    def _request(self) -> None:
        """Score the results against the reference at their incidences: at once when
        they are all on the shipped grid, else on the job runner."""
        s = self.state
        if s.results is None or s.reference is not None or self._closed:
            return
        self._requests += 1
        inc = np.array(s.results.incidence_deg)
        solves = impacts.off_grid(inc)
        if not solves:
            s.scored(impacts.reference_at(s.test, s.material, inc))
            return
        self.progress.busy = True
        self.status.object = text_html(
            f"solving the exact reference at {solves} incidence{'s' * (solves > 1)}…")
        RUNNER.submit(self, partial(impacts.reference_at, s.test, s.material, inc),
                      partial(self._done, self._requests, s.test, s.material))

    def _done(self, request: int, test: int, material: str,
              outcome: impacts.ImpactCurves | Exception) -> None:
        """The reference's outcome (on the session's loop): used if it is the newest
        request's and still the choice shown."""
        if request != self._requests:
            return
        with held():
            self.progress.busy = False
            self.status.object = ""
            if isinstance(outcome, Exception):
                self.state.failed(f"the exact reference could not be computed: {outcome}")
            elif (test, material) == (self.state.test, self.state.material):
                self.state.scored(outcome)
