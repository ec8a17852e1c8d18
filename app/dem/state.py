"""What the visitor chose in the "Check a DEM code" card, and the score that follows.

`DemState.case` and `DemState.models` are checked by their parameters (a name the card
does not offer is refused); `upload` reads a file's bytes (`app.dem.data.read_upload`)
into `history` (`refuse` drops it, for a file refused before it was read), and the
score of the history against the case follows whenever either changes: `score`, or
`message` saying why there is none.
"""

from __future__ import annotations

import param

from app.dem.data import (
    DEFAULT_CASE,
    DEFAULT_MODELS,
    History,
    read_upload,
    score_history,
)
from core.dem_check import CASES, DemScore, lammps


class DemState(param.Parameterized):
    """The card's case, overlaid models and uploaded history with its score."""

    case = param.Selector(default=DEFAULT_CASE, objects=list(CASES),
                          doc="the documented case of core.dem_check shown")
    models = param.ListSelector(default=list(DEFAULT_MODELS), objects=list(lammps.MODELS),
                                doc="LAMMPS' tangential models overlaid")
    history = param.ClassSelector(class_=History, default=None, allow_None=True,
                                  doc="the uploaded history, None before an upload or "
                                      "after a refused one")
    score = param.ClassSelector(class_=DemScore, default=None, allow_None=True,
                                doc="the history's score against the case")
    message = param.String(default="", doc="why the upload has no score; '' if it has")

    def upload(self, data: object) -> None:
        """Read an uploaded file's bytes: its history replaces the last (a file whose
        `# name:` line names a case switches to that case), or the reason it is refused
        is the message and no history is kept."""
        try:
            history = read_upload(data)
        except ValueError as err:
            self.param.update(history=None, score=None, message=str(err))
            return
        named = history.header.get("name")
        self.param.update(history=history, **({"case": named} if named in CASES else {}))

    def refuse(self, message: str) -> None:
        """A file refused before it was read (`message`: why): no history is kept."""
        self.param.update(history=None, score=None, message=message)

    @param.depends("case", "history", watch=True)
    def _score(self) -> None:
        if self.history is None:
            self.score = None
            return
        try:
            self.param.update(score=score_history(self.case, self.history), message="")
        except ValueError as err:
            self.param.update(score=None, message=str(err))
