"""Third-party values of Chung & Ooi's test 4, as shipped in ``core/dem_check/data/``:
the published curves (alumina, aluminium alloy) and Kharaz, Gorham & Salman's (2001)
measurements, with their source in the file's ``# key: value`` header.

``published(quantity, series)`` returns (incidence_deg, value) with the spin's sign turned
to ``core.impact``'s (positive in the rolling sense). ``experiment_scatter`` is the stand-in
for the experiment's scatter: the data carry no error bars, so the bench takes the RMS
difference between the measured points and the exact reference at their incidences.
"""

from __future__ import annotations

import csv
from functools import lru_cache
from importlib.resources import files

import numpy as np
from numpy.typing import NDArray

QUANTITIES = ("tangential_cor", "rebound_spin", "rebound_angle")
SERIES = ("alumina", "aluminium_alloy", "experiment")
FILE = "chung_ooi_test4.csv"


@lru_cache(maxsize=1)
def _table() -> tuple[dict[str, str], tuple[tuple[str, str, float, float], ...]]:
    text = files("core.dem_check").joinpath("data", FILE).read_text()
    header: dict[str, str] = {}
    body = []
    for line in text.splitlines():
        if line.startswith("#"):
            key, _, value = line[1:].partition(":")
            header[key.strip()] = value.strip()
        elif line.strip():
            body.append(line)
    rows = tuple((q, s, float(a), float(v)) for q, s, a, v in csv.reader(body[1:]))
    return header, rows


def header() -> dict[str, str]:
    """The data file's ``# key: value`` lines (name, what, source, caveats, units)."""
    return dict(_table()[0])


def published(quantity: str, series: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(incidence_deg, value) of one published series, sorted by incidence; rebound_spin
    with core.impact's sign."""
    if quantity not in QUANTITIES:
        raise ValueError(f"quantity must be one of {', '.join(QUANTITIES)}, got {quantity!r}")
    if series not in SERIES:
        raise ValueError(f"series must be one of {', '.join(SERIES)}, got {series!r}")
    pts = sorted((a, v) for q, s, a, v in _table()[1] if q == quantity and s == series)
    inc = np.array([p[0] for p in pts])
    val = np.array([p[1] for p in pts])
    return inc, (-val if quantity == "rebound_spin" else val)


__all__ = ["FILE", "QUANTITIES", "SERIES", "header", "published"]
