"""A job's progress bar that keeps its place on the page: `JobProgress`.

A card shows a bar while its job runs on the runner (`app.kit.jobs.RUNNER`) and hides it
when the outcome arrives, on every move of a slider beside it.  Hiding it with Panel's
`visible` would make BokehJS lay the card's column out again, re-inserting its children,
and a slider being dragged in that column would lose the pointer after the move's first
step (and so would a change of its CSS classes).  This bar is hidden by its host's
style instead (`visibility: hidden`, which its own stylesheet passes on to the bar inside
its shadow root, where Panel's stylesheet sets the bar visible): it keeps its box, nothing
around it moves or is re-inserted, and a drag goes on.
"""

from __future__ import annotations

import panel as pn
import param

#: The host's style while no job runs, and while one does.
HIDDEN, SHOWN = {"visibility": "hidden"}, {"visibility": "visible"}
#: The bar as visible as its host (hidden from sight and from a screen reader with it).
CSS = "progress { visibility: inherit !important; }"


class JobProgress(pn.viewable.Viewer):
    """An indeterminate progress bar, shown (and animated) while `busy`."""

    busy = param.Boolean(default=False, doc="a job runs: the bar is shown")

    def __init__(self, width: int = 200) -> None:
        super().__init__()
        self._bar = pn.indicators.Progress(active=False, width=width, styles=HIDDEN,
                                           stylesheets=[CSS])

    def __panel__(self) -> pn.indicators.Progress:
        return self._bar

    @param.depends("busy", watch=True)
    def _show(self) -> None:
        self._bar.param.update(active=self.busy, styles=SHOWN if self.busy else HIDDEN)
