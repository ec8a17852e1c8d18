"""app.kit.texts without a browser: what the components hold and send."""

from __future__ import annotations

import json

import pytest

from app.kit.texts import TextTable


def test_a_tables_rows_travel_as_json_the_sanitizer_leaves_alone() -> None:
    """A `TextTable`'s rows read back as given from their JSON (`cells`, what the browser
    is sent), which holds no '<', '>' or '&' (Panel's HTML sanitizer would rewrite them)."""
    rows = [["<b>q</b> & co", "<script>alert(1)</script>"], ["ψ", "1 < 2 > 0"]]
    table = TextTable(caption="c", rows=rows)
    assert not any(ch in table.cells for ch in "<>&")
    assert json.loads(table.cells) == rows
    table.write(rows=[["a", "1"]])
    assert json.loads(table.cells) == [["a", "1"]]
    table.write(rows=[["b", "2"], ["c", "3"]])
    assert json.loads(table.cells) == [["b", "2"], ["c", "3"]]


@pytest.mark.parametrize("rows", [[["a"]], [["a", 1]], [["a", "b", "c"]], [("a", None)]])
def test_a_table_refuses_rows_that_are_not_pairs_of_text(rows) -> None:
    table = TextTable(caption="c")
    with pytest.raises(TypeError, match="rows must be"):
        table.write(rows=rows)
    assert json.loads(table.cells) == []


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


def test_a_written_text_is_held_by_its_parameter_and_sent_to_its_data_model() -> None:
    """`WrittenHTML.write`: rendered in the current document, the change goes to its data
    model (sent once, not again when equal) and the parameter holds it too, for a text
    only the server writes (a description) as for a slider's value; not rendered, the
    parameter takes it."""
    import panel as pn
    from bokeh.document import Document
    from panel.io.state import set_curdoc

    from app.kit.sliders import LabelledSlider
    from app.kit.texts import Description

    loose = Description(label="l", name="loose")
    loose.write(description="first")
    assert loose.description == "first"

    text = Description(label="fig", description="built", name="d_test")
    slider = LabelledSlider(label="s", value=1.0, start=0.0, end=5.0, name="s_test")
    doc, events = Document(), []
    with set_curdoc(doc):
        doc.add_root(pn.Column(text, slider).get_root(doc))
        doc.on_change(events.append)
        text.write(description="moved")
        slider.write(value=2.0)
        assert text.description == text.data_model(doc).description == "moved"
        assert slider.value == slider.data_model(doc).value == 2.0
        sent = [(e.model.name, e.attr, e.new) for e in events]
        assert ("d_test", "description", "moved") in sent
        assert ("s_test", "value", 2.0) in sent and len(sent) == 2
        events.clear()
        text.write(description="moved")
        slider.write(value=2.0)
        assert events == []
    assert text.description == "moved"  # (no current document: the parameter, the same)
