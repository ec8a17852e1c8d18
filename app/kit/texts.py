"""Text that changes on every move, cheap for the server and for the browser.

A psi move rewrites the four plots' descriptions and the table of derived quantities.
Panel's `HTML` pane recomputes all its model's properties, and builds new stylesheet
models, on every change of its `object` (about 2 ms of server CPU on these machines); a
Bokeh `Div` costs the server little (0.02 ms) but BokehJS renders a Div anew on every
change of its text and lays out the whole page again (30 ms more per move in the
browser, `benchmarks/app/app_latency.py --revs`).  These are `ReactiveHTML`s whose text
is a property of their data model: a change sends that property and a few lines of
JavaScript write it into the elements as text (never markup), and nothing is laid out
again.
"""

from __future__ import annotations

from typing import ClassVar

import param
from panel.reactive import ReactiveHTML

_DESCRIBE = """
fig.setAttribute("aria-label", data.label);
fig.setAttribute("aria-describedby", desc.id);
desc.textContent = data.description;
"""


class Description(ReactiveHTML):
    """A figure named `label` for a screen reader (`role="figure"`), described by
    `description` (`aria-describedby`); the page hides it from sight (its `stylesheets`)."""

    label = param.String(default="")
    description = param.String(default="")

    _template = '<div id="fig" role="figure"><p id="desc"></p></div>'
    _scripts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("render", "label", "description"), _DESCRIBE)

    def __init__(self, **params) -> None:
        params.setdefault("margin", 0)
        super().__init__(**params)


_TABULATE = """
table.replaceChildren();
table.createCaption().textContent = data.caption;
const head = table.createTHead().insertRow();
for (const name of data.columns) {
  const th = document.createElement("th");
  th.scope = "col";
  th.textContent = name;
  head.appendChild(th);
}
const body = table.createTBody();
for (const [quantity, value] of data.rows) {
  const row = body.insertRow();
  const th = document.createElement("th");
  th.scope = "row";
  th.textContent = quantity;
  row.appendChild(th);
  row.insertCell().textContent = value;
}
"""


class TextTable(ReactiveHTML):
    """A table (class `readout`) named by `caption`, with a header row of `columns` and a
    row per (quantity, value) of `rows`, each quantity a row header; all of it text."""

    caption = param.String(default="")
    columns = param.List(default=["Quantity", "Value"], item_type=str)
    rows = param.List(default=[], doc="(quantity, value) pairs of str, top to bottom")

    _template = '<table id="table" class="readout"></table>'
    _scripts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("render", "caption", "columns", "rows"), _TABULATE)

    def __init__(self, **params) -> None:
        params.setdefault("margin", 0)
        params.setdefault("sizing_mode", "stretch_width")
        super().__init__(**params)
