"""Validation of scalar parameters at the boundary (constructors), with messages that
name the parameter, its value and the allowed range."""

from __future__ import annotations

import math
import numbers


def _interval(lo: float | None, hi: float | None, lo_open: bool, hi_open: bool) -> str:
    left = "(-inf" if lo is None else ("(" if lo_open else "[") + f"{lo:g}"
    right = "inf)" if hi is None else f"{hi:g}" + (")" if hi_open else "]")
    return f"{left}, {right}"


def check_real(
    name: str,
    value: object,
    lo: float | None = None,
    hi: float | None = None,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
) -> float:
    """Return ``value`` as a float if it is a finite real number in the given interval.

    Raises ValueError naming the parameter, its value and the allowed range otherwise
    (nan, inf, booleans, strings and out-of-range numbers alike).
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        allowed = _interval(lo, hi, lo_open, hi_open)
        raise ValueError(f"{name} must be a real number in {allowed}, got {value!r}")
    v = float(value)
    below = lo is not None and (v <= lo if lo_open else v < lo)
    above = hi is not None and (v >= hi if hi_open else v > hi)
    if below or above or not math.isfinite(v):
        allowed = _interval(lo, hi, lo_open, hi_open)
        if not math.isfinite(v):
            raise ValueError(f"{name} must be a finite number in {allowed}, got {v!r}")
        raise ValueError(f"{name} = {v!r} is outside the allowed range {allowed}")
    return v


#: The domain of the dimensionless parameters: (lo, hi, lo_open, hi_open).
PSI_MAX = 1e12
DOMAIN: dict[str, tuple[float | None, float | None, bool, bool]] = {
    "psi": (0.0, PSI_MAX, False, False),
    "tau0": (-math.pi / 2, math.pi / 2, True, True),
    "mu": (0.0, None, True, False),
    "nu": (-1.0, 0.5, True, False),
}


def check_param(name: str, value: object) -> float:
    """``check_real`` against the domain of the parameter ``name`` (see ``DOMAIN``)."""
    lo, hi, lo_open, hi_open = DOMAIN[name]
    return check_real(name, value, lo, hi, lo_open=lo_open, hi_open=hi_open)
