"""app.kit.texts without a browser: what the components hold and send."""

from __future__ import annotations

import json

import pytest

from app.kit.texts import TextTable


def test_a_tables_rows_travel_as_json_the_sanitizer_leaves_alone() -> None:
    """`TextTable.rows` reads back as given, and its JSON (`cells`, what the browser is
    sent) holds no '<', '>' or '&' (Panel's HTML sanitizer would rewrite them)."""
    rows = [["<b>q</b> & co", "<script>alert(1)</script>"], ["ψ", "1 < 2 > 0"]]
    table = TextTable(caption="c", rows=rows)
    assert table.rows == rows
    assert not any(ch in table.cells for ch in "<>&")
    assert json.loads(table.cells) == rows
    table.rows = [["a", "1"]]
    assert table.rows == [["a", "1"]] and json.loads(table.cells) == [["a", "1"]]
    table.write(rows=[["b", "2"], ["c", "3"]])
    assert table.rows == [["b", "2"], ["c", "3"]]


@pytest.mark.parametrize("rows", [[["a"]], [["a", 1]], [["a", "b", "c"]], [("a", None)]])
def test_a_table_refuses_rows_that_are_not_pairs_of_text(rows) -> None:
    table = TextTable(caption="c")
    with pytest.raises(TypeError, match="rows must be"):
        table.rows = rows
    assert table.rows == []


def test_the_url_writers_query_travels_as_json_the_sanitizer_leaves_alone() -> None:
    """`UrlWriter.write(query=pairs)`: the browser is sent the pairs' JSON, which holds
    no '<', '>' or '&' and reads back as the pairs, in order; anything but pairs of text
    is refused, naming the query."""
    from app.page.url import UrlWriter

    pairs = [["psi", "2.5"], ["material", "a&b <c>"], ["tau0", "0.5"]]
    writer = UrlWriter(name="url_writer")
    writer.write(query=pairs)
    assert not any(ch in writer.query for ch in "<>&")
    assert json.loads(writer.query) == pairs
    with pytest.raises(TypeError, match="query must be"):
        writer.write(query=[["psi", 2.5]])
    assert json.loads(writer.query) == pairs


def test_a_text_only_the_server_writes_lives_in_its_data_model_once_rendered() -> None:
    """`WrittenHTML.write` of a text the browser never sends back (`MIRRORED` False, a
    description): rendered in the current document, the text goes to its data model
    alone (`shown` reads it there; sent once, not again when equal); not rendered, the
    parameter takes it.  A slider's value (`MIRRORED`) is kept on the component too:
    Panel compares what the browser sends with it."""
    import panel as pn
    from bokeh.document import Document
    from panel.io.state import set_curdoc

    from app.kit.texts import Description
    from app.kit.widgets import LabelledSlider

    loose = Description(label="l", name="loose")
    loose.write(description="first")
    assert loose.description == loose.shown("description") == "first"

    text = Description(label="fig", description="built", name="d_test")
    slider = LabelledSlider(label="s", value=1.0, start=0.0, end=5.0, name="s_test")
    doc, events = Document(), []
    with set_curdoc(doc):
        doc.add_root(pn.Column(text, slider).get_root(doc))
        doc.on_change(events.append)
        text.write(description="moved")
        slider.write(value=2.0)
        assert text.data_model(doc).description == text.shown("description") == "moved"
        assert text.description == "built"  # (the text it was rendered with)
        assert slider.value == slider.data_model(doc).value == 2.0
        sent = [(e.model.name, e.attr, e.new) for e in events]
        assert ("d_test", "description", "moved") in sent
        assert ("s_test", "value", 2.0) in sent and len(sent) == 2
        events.clear()
        text.write(description="moved")
        slider.write(value=2.0)
        assert events == []
    assert text.shown("description") == "built"  # (no current document: the parameter)
