"""`app.kit.changes`: a source is sent new data only when a column differs from what it
holds, bit for bit (NaN held is the same NaN; -0.0 is not 0.0), whatever array type the
scene gives it."""

from __future__ import annotations

import math

import numpy as np
import pytest
from bokeh.document import Document
from bokeh.models import ColumnDataSource

from app.kit.changes import same, show
from app.kit.wire import InlineColumn


def _sends(source: ColumnDataSource, data: dict) -> int:
    """How many changes `show(source, data)` makes to the source's document."""
    events: list = []
    source.document.on_change(events.append)
    try:
        show(source, data)
    finally:
        source.document.remove_on_change(events.append)
    return len(events)


@pytest.fixture
def source() -> ColumnDataSource:
    s = ColumnDataSource({"x": [], "label": []})
    Document().add_root(s)
    return s


def test_equal_data_is_not_sent_again_nan_and_integers_included(source) -> None:
    x = np.array([0.0, 1.5, math.nan, -2.0])
    assert _sends(source, {"x": x, "label": ["a", "b", "c", "d"]}) == 1
    assert isinstance(source.data["x"], InlineColumn)  # (held as sent: float64)
    assert _sends(source, {"x": x.copy(), "label": ["a", "b", "c", "d"]}) == 0
    # an integer column equal in value to the float64 one held
    assert _sends(source, {"x": np.array([0, 1, 2, 3]), "label": list("abcd")}) == 1
    assert _sends(source, {"x": np.array([0, 1, 2, 3]), "label": list("abcd")}) == 0
    assert source.data["x"].dtype == np.float64


@pytest.mark.parametrize("change", ["ulp", "sign of zero", "label", "length", "column"])
def test_a_column_that_differs_sends_the_data(source, change: str) -> None:
    x = np.array([0.0, 1.5, 3.0])
    show(source, {"x": x, "label": ["a", "b", "c"]})
    new = {"x": x.copy(), "label": ["a", "b", "c"]}
    if change == "ulp":
        new["x"][1] = np.nextafter(1.5, 2.0)
    elif change == "sign of zero":
        new["x"][0] = -0.0
    elif change == "label":
        new["label"] = ["a", "b", "C"]
    elif change == "length":
        new = {"x": np.append(x, 4.0), "label": ["a", "b", "c", "d"]}
    else:
        new["y"] = x
    assert _sends(source, new) == 1
    np.testing.assert_array_equal(source.data["x"], new["x"])
    assert source.data["label"] == new["label"]


def test_same_compares_bits_dtype_and_shape() -> None:
    a = np.array([1.0, math.nan])
    assert same(a, a.copy())
    assert not same(a, a.astype(np.float32))
    assert not same(a, a.reshape(2, 1))
    assert not same(np.array([0.0]), np.array([-0.0]))
    assert same(["a", "b"], ["a", "b"]) and not same(["a"], ["b"])
    assert same([1.0, 2.0], [1, 2])  # (other lists: equal in value)
