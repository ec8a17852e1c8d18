"""HTML that changes on every move, cheap for the server and for the browser.

A psi move rewrites the four plots' descriptions and the table of derived quantities.
Panel's `HTML` pane recomputes all its model's properties, and builds new stylesheet
models, on every change of its `object` (about 2 ms of server CPU on these machines); a
Bokeh `Div` costs the server nothing (0.02 ms) but BokehJS renders a Div anew on every
change of its text and lays out the whole page again (30 ms more per move in the
browser, `benchmarks/app/app_latency.py --revs`).  `HtmlDiv` is a `ReactiveHTML` whose
text is a property of its data model: a change sends that property and a line of
JavaScript writes it into the element, nothing is laid out again.  Its text is HTML,
shown as markup: callers escape what is text.
"""

from __future__ import annotations

from typing import ClassVar

import param
from panel.reactive import ReactiveHTML


class HtmlDiv(ReactiveHTML):
    """A <div> showing `object` (HTML); `stylesheets` style it (`:host` is the component)."""

    object = param.String(default="", doc="the HTML shown")

    _template = '<div id="box"></div>'
    _scripts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("render", "object"), "box.innerHTML = data.object;")

    def __init__(self, object: str = "", **params) -> None:
        params.setdefault("margin", 0)
        params.setdefault("sizing_mode", "stretch_width")
        super().__init__(object=object, **params)
