"""What a finished (or partly finished) study says: the best design per figure of merit,
the Pareto front of two merits, and the whole table as CSV.

Designs with a nan merit (not computed yet, or where the scalar API raises: see
``core.motor.designs``) take no part in a best design or a front.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from core.motor.designs import MERITS
from core.motor.study.chunks import SENSE, VARIABLES


def table(ds) -> pd.DataFrame:
    """One row per design: the axes' values, then every variable (SI units, the
    Dataset's attributes name them)."""
    frame = ds[list(VARIABLES)].to_dataframe().reset_index()
    return frame


def best(ds, merit: str) -> pd.Series | None:
    """The design with the best value of ``merit`` (largest, or smallest for the wear
    rate: ``SENSE``), as a row of ``table``; None if no design has it."""
    _check(merit)
    frame = table(ds)
    values = frame[merit].to_numpy(dtype=float)
    if not np.isfinite(values).any():
        return None
    i = int(np.nanargmax(SENSE[merit] * values))
    return frame.iloc[i]


def pareto(ds, first: str, second: str) -> pd.DataFrame:
    """The designs that no other design beats in both merits (each in its ``SENSE``):
    the Pareto front of ``first`` and ``second``, sorted by ``first`` from best to
    worst. Equal pairs are kept once (the first in the table)."""
    _check(first)
    _check(second)
    if first == second:
        raise ValueError(f"the Pareto front needs two different merits, got {first} twice")
    frame = table(ds)
    a = SENSE[first] * frame[first].to_numpy(dtype=float)
    b = SENSE[second] * frame[second].to_numpy(dtype=float)
    ok = np.flatnonzero(np.isfinite(a) & np.isfinite(b))
    order = ok[np.lexsort((-b[ok], -a[ok]))]  # best first, ties: best second first
    keep = []
    top = -np.inf
    for i in order:
        if b[i] > top:
            keep.append(i)
            top = b[i]
    return frame.iloc[keep].reset_index(drop=True)


def export_csv(ds, path: str | Path) -> Path:
    """The table of every design as CSV at path (a header row of names with units)."""
    frame = table(ds)
    units = {name: ds[name].attrs.get("units", "") for name in frame.columns}
    frame.columns = [f"{n} ({units[n]})" if units[n] else n for n in frame.columns]
    p = Path(path)
    frame.to_csv(p, index=False, float_format="%.17g")
    return p


def _check(merit: str) -> None:
    if merit not in MERITS:
        raise ValueError(f"{merit!r} is not a figure of merit: choose among "
                         f"{', '.join(MERITS)}")
