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

Every function here is a numba kernel of one float (``@njit(cache=True, nogil=True)``):
the compiled loops of ``core.kernels`` inline them, and Python may call them directly.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from core.horner import horner

HALF_PI_HI = math.pi / 2
HALF_PI_LO = 6.123233995736766e-17  # pi/2 - HALF_PI_HI
TWO_PI = 2 * math.pi

# pi/2 in three parts of 33 bits each (fdlibm's Cody-Waite constants): n * part is exact
# for |n| < 2**20, so tau - n pi/2 keeps full relative accuracy for |tau| up to ~1e5.
_P0, _P1, _P2 = 1.57079632673412561417e00, 6.07710050630396597660e-11, 2.02226624871116645580e-21

# Taylor coefficients of sin(u) / u - 1 in powers of u^2, (-1)^k / (2k + 1)!, k = 10 ... 1
# (highest first). On |u| <= pi/2 the first omitted term, u^23 / 23!, is below
# 1.3e-18 sin(u): the polynomial is exact to rounding (1-2 ulp), and unlike a library sine
# it has no branch, so the loops over times compile to SIMD code.
_SINE = tuple((-1.0) ** k / math.factorial(2 * k + 1) for k in range(10, 0, -1))


@njit(cache=True, inline="always")
def sine(u: float) -> float:
    """sin(u) for |u| <= pi/2 (Taylor to u^21, 1-2 ulp); the argument of every clock."""
    z = u * u
    return u + (u * z) * horner(z, _SINE)


@njit(cache=True, inline="always")
def half_width(tau0: float) -> float:
    """e = pi/2 - tau0 (radians), the half-duration of the contact in tau."""
    return (HALF_PI_HI - tau0) + HALF_PI_LO


@njit(cache=True, nogil=True)
def half_sines(tau0: float) -> tuple[float, float]:
    """(sin(e/2), cos(e/2)) for e = pi/2 - tau0: the scale of the clock and of eq 11's
    m0 = sin^2(e/2) = (1 - sin tau0)/2, mc0 = cos^2(e/2). cos(e/2) is taken as
    sin((pi - e)/2) with pi - e = tau0 + pi/2 formed exactly, so both keep their digits
    at either end of (-pi/2, pi/2)."""
    return sine(0.5 * half_width(tau0)), sine(0.5 * ((tau0 + HALF_PI_HI) + HALF_PI_LO))


@njit(cache=True, inline="always")
def half_offset(tau: float) -> float:
    """u = (tau - pi/2 - 2 pi k) / 2 with the period k chosen so that u is in [-pi/2, pi/2].

    The offset tau - (4k + 1) pi/2 is formed by Cody-Waite reduction, so it is exact to a
    few ulp of itself even when tiny (grazing contact) or a few periods away; beyond
    |tau| ~ 1e5 the phase within the period is lost to rounding (u stays in range).
    """
    n = 4.0 * np.floor((tau + HALF_PI_HI) * (1.0 / TWO_PI)) + 1.0
    u = 0.5 * (((tau - n * _P0) - n * _P1) - n * _P2)
    return min(max(u, -HALF_PI_HI), HALF_PI_HI)


@njit(cache=True, inline="always")
def clock(tau: float, inv_sin_half_e: float) -> float:
    """w = sin((tau - pi/2)/2) / sin(e/2): -1 at tau0, 0 at pi/2, +1 at pi - tau0
    (given 1 / sin(e/2))."""
    return sine(half_offset(tau)) * inv_sin_half_e


@njit(cache=True, inline="always")
def one_minus_square(w: float) -> float:
    """(1 - w)(1 + w), clipped at 0 outside contact: a^2 / a*^2 (eqs 7, 8) of clock w."""
    return max((1.0 - w) * (1.0 + w), 0.0)
