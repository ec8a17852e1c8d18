"""A scene's sources and properties set only when their values change.

Bokeh sends every ``source.data = ...`` to the browser, equal or not, and validates
every value it is given before comparing it with the one held: a psi move that set each
source and label afresh sent data the browser held already and paid for the checks.
`show` gives a source data only when a column differs in value from what it holds;
`put` sets only the properties that differ.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from bokeh.core.property.validation import validate
from bokeh.model import Model
from bokeh.models import ColumnDataSource

from app.kit.wire import inline


def show(source: ColumnDataSource, data: dict[str, Any]) -> None:
    """Give `source` this data, its numeric arrays sent inline (`app.kit.wire.inline`),
    unless it holds it already (nothing is sent then): every column equal in value, as
    `np.array_equal` has it.  Bokeh does not validate the columns (`validate(False)`,
    local to this call): they are arrays and lists of text that the scenes make, and
    Bokeh's check of every column was ~a third of a psi move's source updates."""
    held = source.data
    if data.keys() != held.keys() or not all(same(held[k], v) for k, v in data.items()):
        with validate(False):
            source.data = inline(data)


def same(held: Any, new: Any) -> bool:
    """Whether column `new` equals column `held` in value (`np.array_equal`: NaN equals
    nothing), for two numeric arrays or two lists of text without its conversions."""
    if isinstance(held, np.ndarray) and isinstance(new, np.ndarray) \
            and held.dtype.kind in "fiu" and new.dtype.kind in "fiu":
        return held.shape == new.shape and bool((held == new).all())
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
