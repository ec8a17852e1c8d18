"""`held`: Panel's hold, entered only where the document does not hold its changes."""

from __future__ import annotations

from contextlib import contextmanager

import panel as pn
from bokeh.document import Document
from bokeh.models import Label
from panel.io.state import set_curdoc

import app.kit.batch as batch
from app.kit.batch import held


@contextmanager
def counted(entries: list) -> None:
    real = batch.hold

    @contextmanager
    def hold():
        entries.append(pn.state.curdoc)
        with real():
            yield
    batch.hold = hold
    try:
        yield
    finally:
        batch.hold = real


def _page() -> tuple[Document, Label, list]:
    """A document holding one label, and the list its changes are sent to."""
    doc, label, events = Document(), Label(x=0, y=0, text="a"), []
    doc.add_root(label)
    doc.on_change(events.append)
    return doc, label, events


def test_held_holds_a_document_that_is_not_held_and_releases_it() -> None:
    (doc, label, events), entries = _page(), []
    with set_curdoc(doc), counted(entries):
        with held():
            label.text = "b"
            label.text = "c"
            assert doc.callbacks.hold_value == "combine" and events == []
        assert doc.callbacks.hold_value is None
    assert entries == [doc]
    assert [(e.attr, e.new) for e in events] == [("text", "c")]  # combined, sent at exit


def test_held_inside_a_hold_adds_no_hold_of_its_own() -> None:
    (doc, label, events), entries = _page(), []
    with set_curdoc(doc), counted(entries):
        with held():
            for text in "bcd":
                with held():
                    label.text = text
            assert events == []
        assert doc.callbacks.hold_value is None
    assert entries == [doc]  # the outer one only
    assert [(e.attr, e.new) for e in events] == [("text", "d")]


def test_held_without_a_document_changes_nothing() -> None:
    label = Label(x=0, y=0, text="a")
    with held():
        label.text = "b"
    assert label.text == "b"
