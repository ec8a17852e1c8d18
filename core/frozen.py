"""Frozen dataclasses of arrays: their fields as read-only numpy copies.

A result dataclass (``@dataclass(frozen=True)``) calls `freeze(self)` in its
``__post_init__``: the caller's arrays are copied (a later change of them does not reach
the result) and marked read-only (the result cannot be changed through them).
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np


def freeze(obj: object, *, arrays_only: bool = False) -> None:
    """Replace each field of the frozen dataclass `obj` by a read-only numpy copy (0-d
    for a scalar); with `arrays_only`, only the fields that hold arrays."""
    for f in fields(obj):
        value = getattr(obj, f.name)
        if arrays_only and not isinstance(value, np.ndarray):
            continue
        value = np.array(value)
        value.setflags(write=False)
        object.__setattr__(obj, f.name, value)
