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
