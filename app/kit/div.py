"""HTML that changes on every move: a Bokeh `Div` whose text is written directly.

Panel's `HTML` pane recomputes all its model's properties, and builds new stylesheet
models, on every change of its `object`: about 2 ms of server CPU on these machines,
against 0.02 ms for setting a Bokeh `Div`'s `text`.  A psi move rewrites the four plots'
descriptions and the table of derived quantities, so these are `HtmlDiv`s.  Their text
is HTML, shown as markup: callers escape what is text.
"""

from __future__ import annotations

from collections.abc import Sequence

import panel as pn
from bokeh.models import Div
from panel.io import hold


class HtmlDiv(pn.viewable.Viewer):
    """A Bokeh `Div` showing `object` (HTML), with `stylesheets` (CSS, `:host` is the
    Div), named `name` in the document; math in it is never typeset."""

    def __init__(self, text: str = "", *, stylesheets: Sequence[str] = (),
                 name: str | None = None, sizing_mode: str | None = "stretch_width",
                 margin: int | tuple[int, ...] = 0) -> None:
        super().__init__()
        #: the Bokeh model (one per page: each session builds its own)
        self.div = Div(text=text, disable_math=True, stylesheets=list(stylesheets),
                       name=name, sizing_mode=sizing_mode, margin=margin)
        self._pane = pn.pane.Bokeh(self.div, sizing_mode=sizing_mode, margin=0)

    def __panel__(self) -> pn.pane.Bokeh:
        return self._pane

    @property
    def object(self) -> str:
        """The HTML shown."""
        return self.div.text

    @object.setter
    def object(self, text: str) -> None:
        with hold():  # (a Bokeh model changed outside Panel's handling of an event
            self.div.text = text  # needs it; Bokeh sends nothing when it is unchanged)
