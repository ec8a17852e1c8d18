"""Columns sent inline (app/wire.py): one message per update, values bit for bit."""

from __future__ import annotations

import gzip

import numpy as np
import pytest
from bokeh.core.serialization import Deserializer, Serializer
from bokeh.document import Document
from bokeh.models import ColumnDataSource
from bokeh.protocol import Protocol

from app.kit.wire import STORED_BLOCK, InlineColumn, inline, stored_gzip
from app.page.explorer import Explorer

#: Values that a lossy or text encoding would change.
AWKWARD = np.array([0.1, -0.0, 5e-324, 1.7976931348623157e308, np.nan, np.inf, -np.inf,
                    1 / 3, -2.5e-310])


def roundtrip(values: np.ndarray) -> np.ndarray:
    rep = Serializer().encode(inline({"x": values})["x"])
    return Deserializer().decode(rep)


def test_an_inline_column_decodes_to_the_same_bits() -> None:
    out = roundtrip(AWKWARD)
    assert out.dtype == np.float64
    assert out.tobytes() == AWKWARD.tobytes()


@pytest.mark.parametrize("size", [0, 1, 8, 3600, STORED_BLOCK - 1, STORED_BLOCK,
                                  STORED_BLOCK + 1, 2 * STORED_BLOCK, 2 * STORED_BLOCK + 7])
def test_the_stored_gzip_stream_reads_back_and_is_gzips_own_up_to_64000_bytes(
        size: int) -> None:
    data = np.random.default_rng(size).bytes(size)
    out = stored_gzip(data)
    assert gzip.decompress(out) == data
    if size <= 64000:
        assert out == gzip.compress(data, compresslevel=0, mtime=1)


def test_inline_takes_numeric_1d_arrays_and_leaves_the_rest() -> None:
    cols = inline({"f": np.arange(3.0), "i": np.arange(3), "s": ["a", "b"],
                   "m": np.ones((2, 2)), "o": np.array(["a", "b"])})
    assert isinstance(cols["f"], InlineColumn) and isinstance(cols["i"], InlineColumn)
    assert cols["i"].dtype == np.float64 and list(cols["i"]) == [0.0, 1.0, 2.0]
    assert cols["s"] == ["a", "b"]
    assert not isinstance(cols["m"], InlineColumn)
    assert not isinstance(cols["o"], InlineColumn)
    # a strided view is sent as its values, not its base's
    assert roundtrip(np.arange(10.0)[::3]).tolist() == [0.0, 3.0, 6.0, 9.0]


def test_a_source_change_of_inline_columns_is_one_message_without_buffers() -> None:
    doc = Document()
    src = ColumnDataSource({"x": []})
    doc.add_root(src)
    events = []
    doc.on_change(events.append)
    src.data = inline({"x": AWKWARD})
    msg = Protocol().create("PATCH-DOC", events)
    assert msg.buffers == []
    plain = ColumnDataSource({"x": []})
    Document().add_root(plain)
    doc2 = plain.document
    events2 = []
    doc2.on_change(events2.append)
    plain.data = {"x": AWKWARD}
    assert len(Protocol().create("PATCH-DOC", events2).buffers) == 1  # the control


@pytest.fixture
def ex() -> Explorer:
    return Explorer()


def test_a_psi_move_sends_no_buffers_and_the_browser_gets_core_values(ex: Explorer) -> None:
    """Every float column a psi move changes travels inside the message, and decodes to
    the exact arrays the scenes hold (which the document tests compare with core)."""
    doc = Document()
    ex.view().server_doc(doc)
    events = []
    doc.on_change(events.append)
    ex.contact.controls.psi_slider.model.value = 2.5
    msg = Protocol().create("PATCH-DOC", events)
    assert msg.buffers == []
    decoded = 0
    for event in msg.content["events"]:
        if event["kind"] != "ColumnDataChanged":
            continue
        source = doc.get_model_by_id(event["model"]["id"])
        for name, rep in event["data"]["entries"]:
            if isinstance(rep, dict) and rep.get("type") == "ndarray":
                held = np.asarray(source.data[name], dtype=np.float64)
                assert Deserializer().decode(rep).tobytes() == held.tobytes()
                decoded += 1
    assert decoded >= 10  # traction 6, force 4 columns (closed tabs send nothing)
