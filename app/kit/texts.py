"""Text that changes on every move, cheap for the server and for the browser.

A psi move rewrites the four plots' descriptions and the table of derived quantities.
Panel's `HTML` pane recomputes all its model's properties, and builds new stylesheet
models, on every change of its `object`; a Bokeh `Div` costs the server little, but
BokehJS renders a Div anew on every change of its text and lays out the whole page again
(`python -m benchmarks.app.app_latency --revs` measures the difference in the browser).
These are `ReactiveHTML`s whose text is a property of their data model: a change sends
that property and a few lines of JavaScript write it into the elements as text (never
markup), and nothing is laid out again.

Even a `ReactiveHTML`'s change makes Panel recompute the component's design (its
stylesheets among them) on every change of any property.  `WrittenHTML.write` writes the
changed parameters straight into the component's Bokeh data model in the current
document: the same message, the same property, without Panel's recomputation (the
server CPU of a move: `python -m benchmarks.app.move_cost`), and the parameter holds
what the page shows.
"""

from __future__ import annotations

import json
from typing import Any, ClassVar

import panel as pn
import param
from bokeh.core.property.validation import validate
from bokeh.document import Document
from bokeh.model import Model
from panel.reactive import ReactiveHTML

from app.kit.batch import held


def write_past_panel(component: param.Parameterized, values: dict[str, Any], model: Model,
                     properties: dict[str, Any]) -> None:
    """Set `component`'s parameters `values` without calling Panel's watchers, and its
    Bokeh `model`'s `properties` (what Panel would have written for them) in the current
    document: the same message, without Panel's recomputation of the component."""
    with param.parameterized.discard_events(component):  # (Panel's watchers not called)
        for name, value in values.items():  # (not `param.update`: it reads every
            setattr(component, name, value)  # parameter of the component first)
    write_model(model, properties)


def write_model(model: Model, properties: dict[str, Any]) -> None:
    """Set the Bokeh `model`'s `properties` in the current document, values a component's
    parameters accept: a change held already goes out with the others; outside Panel's
    handling of a change, Bokeh's lock may not be held (`held`); the values passed the
    parameters' own checks, so Bokeh's are not repeated."""
    with held(), validate(False):
        model.update(**properties)


class WrittenHTML(ReactiveHTML):
    """A `ReactiveHTML` whose parameters are written into its Bokeh data model (`write`).

    The one way the app sets a text (or a slider's value) that changes on every move:
    `write(**values)` sets the parameters, so that each always holds what the page shows,
    and writes those that changed into the component's data model in the current
    document without Panel's watchers (`write_past_panel`): the same message, the same
    property, without Panel's recomputation of the component.

    The data model carries the component's `name`, by which `write` finds it in the
    document (Bokeh indexes the models by name): give each a name of its own in its
    page.  A parameter that the component's scripts set from the browser
    (`data.NAME = ...`) is one Panel watches on the model: inside a served document's
    `panel.io.hold` Panel sends the write without running that watcher; elsewhere the
    watcher runs and finds the parameter equal already.  The parameters written on every
    move are declared `allow_refs=False`: they take values, and Panel would otherwise
    look for a reference in each value set.
    """

    def data_model(self, doc: Document | None) -> Model | None:
        """This component's data model in `doc`; None where it is not rendered (or its
        name is not its own)."""
        if doc is None:
            return None
        try:
            return doc.get_model_by_name(self.name)
        except ValueError:  # (several models of that name)
            return None

    def write(self, **values: Any) -> None:
        """Set the parameters to `values`; those that change are also written into the
        component's data model in the current document (`panel.state.curdoc`), outside
        Panel's update of the component, as they are (Panel would pass a text through
        its HTML sanitizer first, which writes '&' as '&amp;': the scripts set texts as
        text).  Where it is not rendered (no document, or another one) the parameters
        are set as usual (Panel updates what it rendered)."""
        changed = {k: v for k, v in values.items() if getattr(self, k) != v}
        if not changed:
            return
        model = self.data_model(pn.state.curdoc)
        if model is None:
            self.param.update(**changed)
        else:
            write_past_panel(self, changed, model, changed)


class PaneText:
    """The text of a pane whose Bokeh model's `text` is its object as given (a `LaTeX`
    pane rendered by KaTeX), written past Panel's update of the pane: Panel would build
    the pane's stylesheet models anew for the same message.

    The pane's model is found in the current document by its tag `tag`: a search of the
    whole document, so once per document, and again only while it is not
    found and the document has gained models since (a write while the page is being
    built comes before the pane is rendered)."""

    def __init__(self, pane: pn.pane.PaneBase, tag: str) -> None:
        self.pane, self.tag = pane, tag
        #: the document searched, its number of models then, the model found there
        self._found: tuple[Document, int, Model | None] | None = None

    def write(self, text: str) -> None:
        """Set the pane's object to `text` and write it into the pane's model in the
        current document; where the pane is not rendered there (or more than once), set
        it as usual."""
        if self.pane.object == text:
            return
        doc = pn.state.curdoc
        model = self._model(doc) if doc is not None else None
        if model is None:
            self.pane.object = text
            return
        write_past_panel(self.pane, {"object": text}, model, {"text": text})

    def _model(self, doc: Document) -> Model | None:
        found = self._found
        if found is not None and found[0] is doc:
            model = found[2]
            if model is not None and model.document is doc:
                return model
            if model is None and found[1] == len(doc.models):
                return None
        try:
            model = doc.select_one({"tags": [self.tag]})
        except ValueError:  # (several models of that tag)
            model = None
        self._found = (doc, len(doc.models), model)
        return model


_DESCRIBE = """
fig.setAttribute("aria-label", data.label);
fig.setAttribute("aria-describedby", desc.id);
desc.textContent = data.description;
"""


class Description(WrittenHTML):
    """A figure named `label` for a screen reader (`role="figure"`), described by
    `description` (`aria-describedby`); the page hides it from sight (its `stylesheets`).
    `write(description=...)` changes the description."""

    label = param.String(default="", allow_refs=False)
    description = param.String(default="", allow_refs=False)

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
for (const [quantity, value] of JSON.parse(data.cells)) {
  const row = body.insertRow();
  const th = document.createElement("th");
  th.scope = "row";
  th.textContent = quantity;
  row.appendChild(th);
  row.insertCell().textContent = value;
}
"""


class TextTable(WrittenHTML):
    """A table (class `readout`) named by `caption`, with a header row of `columns` and a
    row per (quantity, value) of `rows`, each quantity a row header; all of it text.
    `write(rows=...)` changes the rows; `cells` holds them as the page shows them.

    The rows travel as one text, their JSON (`cells`, `pairs_json`): a list of lists
    costs param and Bokeh a walk of every item at each change, a text one comparison."""

    caption = param.String(default="")
    columns = param.List(default=["Quantity", "Value"], item_type=str)
    cells = param.String(default="[]", allow_refs=False, doc="the rows as JSON (`rows`)")

    _template = '<table id="table" class="readout"></table>'
    _scripts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("render", "caption", "columns", "cells"), _TABULATE)

    def __init__(self, rows: list[list[str]] | None = None, **params) -> None:
        params.setdefault("margin", 0)
        params.setdefault("sizing_mode", "stretch_width")
        if rows is not None:
            params["cells"] = pairs_json(rows)
        super().__init__(**params)

    def write(self, **values: Any) -> None:
        """`WrittenHTML.write`, `rows` given as such."""
        if "rows" in values:
            values["cells"] = pairs_json(values.pop("rows"))
        super().write(**values)


def pairs_json(pairs: list[list[str]], what: str = "rows") -> str:
    """The JSON of (name, value) pairs of str (TypeError naming `what` for anything
    else), with no '<', '>' or '&' (written as JSON escapes): Panel passes a text
    parameter through its HTML sanitizer when it renders the component, which would
    change those.  A list of pairs as one text costs param and Bokeh one comparison at a
    change, where a list of lists costs a walk of every item."""
    if not all(len(r) == 2 and all(isinstance(x, str) for x in r) for r in pairs):
        raise TypeError(f"{what} must be (name, value) pairs of str, not {pairs!r:.80}")
    text = json.dumps([list(r) for r in pairs], ensure_ascii=False)
    return text.replace("&", "\\u0026").replace("<", "\\u003c").replace(">", "\\u003e")
