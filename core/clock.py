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


def half_width(tau0: float) -> float:
    """e = pi/2 - tau0 (radians), the half-duration of the contact in tau."""
    return (HALF_PI_HI - tau0) + HALF_PI_LO


def half_offset(tau: ArrayLike) -> NDArray[np.float64]:
    """u = (tau - pi/2) / 2 with tau first reduced modulo 2 pi into [-pi/2, 3 pi/2).

    Times already in that window (every time of one contact) are used as given, so a time
    passed exactly as tau0 or pi - tau0 stays exact.
    """
    t = np.asarray(tau, dtype=float)
    if t.size and (t.min() < -HALF_PI_HI or t.max() >= 3 * HALF_PI_HI):
        t = np.mod(t + HALF_PI_HI, TWO_PI) - HALF_PI_HI
    return 0.5 * ((t - HALF_PI_HI) - HALF_PI_LO)


def clock(tau: ArrayLike, sin_half_e: float) -> NDArray[np.float64]:
    """w = sin((tau - pi/2)/2) / sin(e/2): -1 at tau0, 0 at pi/2, +1 at pi - tau0."""
    return np.sin(half_offset(tau)) / sin_half_e


def one_minus_square(w: NDArray[np.float64]) -> NDArray[np.float64]:
    """(1 - w)(1 + w), clipped at 0 outside contact: the squared radius a^2 / a*^2 (eq 7, 8)."""
    return np.maximum((1.0 - w) * (1.0 + w), 0.0)
