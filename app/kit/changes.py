"""A scene's sources and properties set only when their values change.

Bokeh sends every ``source.data = ...`` to the browser, equal or not, and validates
every value it is given before comparing it with the one held: a psi move that set each
source and label afresh sent data the browser held already and paid for the checks.
`changed` says what to give a source, only when a column differs in value from what it
holds (`show` gives it);
`put` sets only the properties that differ.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from bokeh.core.property.validation import validate
from bokeh.model import Model
from bokeh.models import ColumnDataSource

from app.kit.wire import inline


def changed(source: ColumnDataSource, data: dict[str, Any]) -> dict[str, Any] | None:
    """What to give `source` for it to hold `data`: the data, its numeric arrays sent
    inline (`app.kit.wire.inline`), or None when the source holds it already (every
    column the same: `same`), since Bokeh would send it even if equal.  Pure: the scene
    writes it (``source.data = new``, inside ``validate(False)``: `show`)."""
    new, held = inline(data), source.data
    if new.keys() != held.keys() or not all(same(held[k], v) for k, v in new.items()):
        return new
    return None


def show(source: ColumnDataSource, data: dict[str, Any]) -> None:
    """Give `source` this data unless it holds it already (`changed`).  Bokeh does not
    validate the columns (`validate(False)`, local to this call): they are arrays and
    lists of text that the scenes make, and Bokeh's check of every column was ~a third
    of a psi move's source updates."""
    new = changed(source, data)
    if new is not None:
        with validate(False):
            source.data = new


def same(held: Any, new: Any) -> bool:
    """Whether column `new` is column `held`: numeric arrays of one dtype and shape, bit
    for bit (a column of NaN held already is the same, -0.0 is not 0.0; a comparison of
    the bytes, faster than numpy's element by element for a plot's columns,
    `InlineColumn`s above all), lists of text equal; others equal in value
    (`np.array_equal`)."""
    if isinstance(held, np.ndarray) and isinstance(new, np.ndarray) \
            and new.dtype.kind in "fiu":
        return (held.dtype == new.dtype and held.shape == new.shape
                and held.tobytes() == new.tobytes())
    if isinstance(held, list) and isinstance(new, list) \
            and all(isinstance(x, str) for x in new):
        return held == new
    return np.array_equal(np.asarray(held), np.asarray(new))


def put(model: Model, **values: Any) -> None:
    """Set the properties `values` of a Bokeh `model` that differ from those it holds
    (Bokeh sends no equal value either, but validates it first: a set costs more than
    a look)."""
    for name, value in values.items():
        if getattr(model, name) != value:
            setattr(model, name, value)
