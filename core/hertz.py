"""Hertz normal contact of two identical spheres (eqs 5-11), dimensionless.

Scales: lengths in a* = sqrt(R (H - h) / 2) (largest contact radius), approach in H - h,
pressure in p* = 4 G a* / ((1 - nu) pi R), normal force in P0 = T0 / mu (eq 37), so that
P / P0 = (sin tau - sin tau0)^(3/2) (eq 9). Inputs are powers of the contact radius,
(a/a*)^2 = (1 - w)(1 + w) with the contact clock w of ``core.clock``, and s = sin(e/2)
with e = pi/2 - tau0; 1 - sin tau0 = 2 s^2.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import ArrayLike, NDArray

SQRT8 = 2.0 * math.sqrt(2.0)


@njit(cache=True, inline="always")
def cube(a2: float) -> float:
    """(a2)^(3/2) without the cost of a general power."""
    return a2 * math.sqrt(a2)


@njit(cache=True, inline="always")
def force_scale(sin_half_e: float) -> float:
    """(1 - sin tau0)^(3/2) = (2 s^2)^(3/2) = sqrt(8) s^3: P / P0 at a = a* (eq 9), and
    the factor of every T / T0 (eqs 38, 39)."""
    return SQRT8 * sin_half_e**3


@njit(cache=True, inline="always")
def normal_force(a3: float, scale: float) -> float:
    """P / P0 = (sin tau - sin tau0)^(3/2) = scale (a/a*)^3 (eq 9), from a3 = (a/a*)^3 and
    scale = ``force_scale``."""
    return scale * a3


def pressure(r: ArrayLike, a2: ArrayLike) -> NDArray[np.float64]:
    """p / p* = sqrt(a2 - r^2) inside the contact, 0 outside (eq 6); r in units of a*,
    a2 = (a / a*)^2 (arrays, broadcast)."""
    r = np.asarray(r, dtype=float)
    return np.sqrt(np.maximum(np.asarray(a2) - r * r, 0.0))
