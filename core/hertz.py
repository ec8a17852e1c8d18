"""Hertz normal contact of two identical spheres (eqs 5-11), dimensionless.

Scales: lengths in a* = sqrt(R (H - h) / 2) (largest contact radius), approach in H - h,
pressure in p* = 4 G a* / ((1 - nu) pi R), normal force in P0 = T0 / mu (eq 37), so that
P / P0 = (sin tau - sin tau0)^(3/2) (eq 9). Inputs are powers of the contact radius,
(a/a*)^2 = (1 - w)(1 + w) with the contact clock w of ``core.clock``, and s = sin(e/2)
with e = pi/2 - tau0; 1 - sin tau0 = 2 s^2.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

SQRT8 = 2.0 * np.sqrt(2.0)


def cube(a2: NDArray[np.float64]) -> NDArray[np.float64]:
    """(a2)^(3/2) without the cost of a general power."""
    out = np.sqrt(a2, out=np.empty_like(a2))
    out *= a2
    return out


def normal_force(a3: NDArray[np.float64], sin_half_e: float) -> NDArray[np.float64]:
    """P / P0 = (sin tau - sin tau0)^(3/2) = (2 s^2)^(3/2) (a/a*)^3 (eq 9), from a3 = (a/a*)^3."""
    return (SQRT8 * sin_half_e**3) * a3


def pressure(r: ArrayLike, a2: ArrayLike) -> NDArray[np.float64]:
    """p / p* = sqrt(a2 - r^2) inside the contact, 0 outside (eq 6); r in units of a*,
    a2 = (a / a*)^2."""
    r = np.asarray(r, dtype=float)
    return np.sqrt(np.maximum(np.asarray(a2) - r * r, 0.0))
