"""The contact clock: where a time tau falls inside one contact, in a form that never cancels.

Contact lasts tau0 <= tau <= pi - tau0 (eq 4), symmetric about pi/2 with half-width

    e = pi/2 - tau0      (0 < e < pi; e > pi/2 is a preloaded contact, h < 0).

With u = (tau - pi/2) / 2 the relative approach of eq 8 factorises exactly:

    sin tau - sin tau0 = 2 (sin^2(e/2) - sin^2 u) = 2 sin^2(e/2) (1 - w)(1 + w),

    w(tau) = sin(u) / sin(e/2)

runs from -1 at tau0 through 0 at pi/2 to +1 at pi - tau0 (|w| > 1: no contact). Every
contact quantity is a simple function of w, so the whole solution costs one sine per time
point and keeps full relative accuracy near both contact ends and for grazing contact,
where the textbook difference sin tau - sin tau0 loses its digits.

pi/2 is split into a double-double pair so that e and u are exact to a few ulp even when
they are tiny (grazing contact with tau0 within 1e-8 of pi/2).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

HALF_PI_HI = np.pi / 2
HALF_PI_LO = 6.123233995736766e-17  # pi/2 - HALF_PI_HI
TWO_PI = 2 * np.pi

# pi/2 in three parts of 33 bits each (fdlibm's Cody-Waite constants): n * part is exact
# for |n| < 2**20, so tau - n pi/2 keeps full relative accuracy for |tau| up to ~1e5.
_PIO2 = (1.57079632673412561417e00, 6.07710050630396597660e-11, 2.02226624871116645580e-21)


def half_width(tau0: float) -> float:
    """e = pi/2 - tau0 (radians), the half-duration of the contact in tau."""
    return (HALF_PI_HI - tau0) + HALF_PI_LO


def _offset(t: NDArray[np.float64], n: NDArray[np.float64] | float) -> NDArray[np.float64]:
    """t - n pi/2 by Cody-Waite reduction (n an odd integer, |n| < 2**20)."""
    x = np.subtract(t, n * _PIO2[0], out=np.empty_like(t))
    x -= n * _PIO2[1]
    x -= n * _PIO2[2]
    return x


def half_offset(tau: ArrayLike) -> NDArray[np.float64]:
    """u = (tau - pi/2 - 2 pi k) / 2 with the period k chosen so that u is in [-pi/2, pi/2).

    The offset tau - (4k + 1) pi/2 is formed by Cody-Waite reduction, so it is exact to a
    few ulp of itself even when tiny (grazing contact) or a few periods away. Times already
    in [-pi/2, 3 pi/2) (every time of one contact) take the cheap path k = 0.
    """
    t = np.asarray(tau, dtype=float)
    x = _offset(t, 1.0)  # an array, also for 0-d input: the updates below are in place
    if x.size and not (x.min() >= -np.pi and x.max() < np.pi):  # (nan: general path, stays nan)
        away = (x < -np.pi) | (x >= np.pi)
        ta = t[away]
        x[away] = _offset(ta, 4.0 * np.floor((ta + HALF_PI_HI) / TWO_PI) + 1.0)
    x *= 0.5
    return x


def clock(tau: ArrayLike, sin_half_e: float) -> NDArray[np.float64]:
    """w = sin((tau - pi/2)/2) / sin(e/2): -1 at tau0, 0 at pi/2, +1 at pi - tau0."""
    w = half_offset(tau)
    np.sin(w, out=w)
    w *= 1.0 / sin_half_e
    return w


def one_minus_square(w: NDArray[np.float64]) -> NDArray[np.float64]:
    """(1 - w)(1 + w), clipped at 0 outside contact: the squared radius a^2 / a*^2 (eq 7, 8)."""
    out = np.subtract(1.0, w, out=np.empty_like(w))
    out *= 1.0 + w
    return np.maximum(out, 0.0, out=out)
