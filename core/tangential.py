"""Tangential tractions, force and impulse (eqs 18-41), dimensionless.

Phases (``Phase``): full stick for psi <= 1 (eq 36); for psi > 1 slip while loading
(tau0 <= tau <= pi/2, eq 18), partial stick (pi/2 < tau < tau1, eq 24) and counter-slip
(tau1 <= tau <= pi - tau0, eq 33).

In the clock variable w of ``core.clock`` the stick disc of eq 30 is simply

    (b / a*)^2 = (1 - w/k)(1 + w/k),   k = sqrt(2 / (psi + 1)),

so partial stick ends at w = k, i.e. tau1 = pi/2 + 2 arcsin(k sin(e/2)) (eq 31, in a form
that keeps its digits for huge psi, where tau1 - pi/2 ~ 2 sqrt((1 - sin tau0)/psi), eq 35).
Scales: traction in mu p*, force in T0 (eq 37), radii in a*.

The formulas of one time point (phase, b^2, T) are numba kernels inlined by the compiled
loops of ``core.kernels``; ``traction`` is numpy over (r, tau). Eq 41 is compiled three
ways, the same values bit for bit: ``impulse_ratio_float`` (one contact),
``impulse_ratio_of_psis`` (many psi at one tau0, a SIMD pass) and the ufunc
``impulse_ratio`` (arrays of psi and tau0).
"""

from __future__ import annotations

import math
from enum import IntEnum

import numpy as np
from numba import float64, njit, vectorize
from numpy.typing import ArrayLike, NDArray

from core.clock import HALF_PI_HI, HALF_PI_LO, clock, one_minus_square
from core.elliptic import SERIES_LIMIT, quartic_integral_float, quartic_series
from core.hertz import pressure


class Phase(IntEnum):
    """Phase of the contact at one time (the integer codes of ``Contact.phase``)."""

    NO_CONTACT = 0
    FULL_STICK = 1
    SLIP = 2
    PARTIAL_STICK = 3
    COUNTER_SLIP = 4


PHASE_NAMES: dict[int, str] = {
    Phase.NO_CONTACT: "no contact",
    Phase.FULL_STICK: "full stick",
    Phase.SLIP: "slip",
    Phase.PARTIAL_STICK: "partial stick",
    Phase.COUNTER_SLIP: "counter-slip",
}


@njit(cache=True, inline="always")
def stick_clock(psi: float) -> float:
    """k = sqrt(2 / (psi + 1)): the clock value w at tau1 (psi > 1)."""
    return math.sqrt(2.0 / (psi + 1.0))


@njit(cache=True, nogil=True)
def tau1(psi: float, sin_half_e: float, cos_half_e: float) -> float:
    """End of partial stick, pi/2 < tau1 <= pi - tau0 (eq 31); nan for psi <= 1.

    tau1 = pi/2 + 2 arcsin(x), x = k sin(e/2). Where x > 1/2 (psi near 1) arcsin is
    ill-conditioned, so it is taken through the complement
    1 - x = (psi - 1)/((psi + 1)(1 + k)) + k cos^2(e/2)/(1 + sin(e/2)), which never cancels:
    tau1 = 3 pi/2 - 4 arcsin(sqrt((1 - x)/2)).

    The float returned is the first float at which the clock reaches k (``phase`` and
    ``stick_radius_squared`` read counter-slip, b = 0): the formula's value moved by the
    few ulp its rounding leaves, so that the phase at tau1 is counter-slip by the same
    rule as everywhere (one rule at the boundary), and the float before it partial stick.
    """
    if psi <= 1.0:
        return math.nan
    k = stick_clock(psi)
    x = k * sin_half_e
    if x <= 0.5:
        t = HALF_PI_HI + (2.0 * math.asin(x) + HALF_PI_LO)
    else:
        one_minus_x = ((psi - 1.0) / ((psi + 1.0) * (1.0 + k))
                       + k * cos_half_e**2 / (1.0 + sin_half_e))
        quarter = math.asin(math.sqrt(0.5 * one_minus_x))
        t = 3.0 * HALF_PI_HI - (4.0 * quarter - 3.0 * HALF_PI_LO)
    return _first_counter_slip(t, k, 1.0 / sin_half_e)


@njit(cache=True, nogil=True)
def _first_counter_slip(t: float, k: float, inv_sin_half_e: float) -> float:
    """The first float at or near t whose clock is >= k (the clock rises through k)."""
    for _ in range(64):  # the formula is a few ulp off; the bound only guards the loop
        if clock(t, inv_sin_half_e) < k:
            t = np.nextafter(t, math.inf)
        elif clock(np.nextafter(t, -math.inf), inv_sin_half_e) >= k:
            t = np.nextafter(t, -math.inf)
        else:
            break
    return t


@njit(cache=True, inline="always")
def phase(w: float, psi: float, k: float) -> int:
    """Phase code at clock value w (see ``Phase``); k = ``stick_clock(psi)`` (psi > 1)."""
    if not abs(w) <= 1.0:
        return 0
    if psi <= 1.0:
        return 1
    if w <= 0.0:
        return 2
    return 3 if w < k else 4


@njit(cache=True, inline="always")
def stick_radius_squared(w: float, psi: float, k: float) -> float:
    """(b / a*)^2 at clock w: a^2 in full stick (psi <= 1), (1 - w/k)(1 + w/k) in partial
    stick (eq 30), 0 while loading and in counter-slip (where w/k >= 1 clips it)."""
    # both branches computed, then selected: the loops over times stay branch-free (SIMD)
    partial = one_minus_square(w / k)
    unloading = partial if w > 0.0 else 0.0
    return one_minus_square(w) if psi <= 1.0 else unloading


@njit(cache=True, inline="always")
def tangential_force(a3: float, b3: float, w: float, psi: float, scale: float) -> float:
    """T / T0 on the upper sphere, positive along the drive (eqs 38, 39), from the cubed
    radii a3 = (a/a*)^3 and b3 = (b/a*)^3 (unused for psi <= 1) at clock w, with
    scale = (1 - sin tau0)^(3/2) (``hertz.force_scale``).

    T / T0 = scale times: psi a^3 (stick); a^3 (slip); 2 b^3 - a^3 (partial stick); -a^3
    (counter-slip). b3 is 0 outside partial stick, so the last three are one expression:
    2 b^3 -+ a^3, with the sign of a^3 flipped in unloading (w > 0).
    """
    signed = -a3 if w > 0.0 else a3
    above = (signed + 2.0 * b3) * scale
    return a3 * (psi * scale) if psi <= 1.0 else above


def traction(r: ArrayLike, w: NDArray[np.float64], a2: NDArray[np.float64],
             b2: NDArray[np.float64], psi: float) -> NDArray[np.float64]:
    """tau_u / (mu p*) at radius r (units of a*; sign of r ignored) and clock w (eqs 18, 24,
    33, 36), from the squared radii a2 = (a/a*)^2 and b2 = (b/a*)^2 at the same times;
    r broadcasts against w."""
    r = np.abs(np.asarray(r, dtype=float))
    hertz = pressure(r, a2)
    if psi <= 1.0:
        return psi * hertz
    out = np.where(w > 0.0, -hertz, hertz)
    return out + 2.0 * pressure(r, b2)


@njit(cache=True, nogil=True)
def impulse_ratio_float(psi: float, m0: float, mc0: float) -> float:
    """T_imp / (mu P_imp) (eq 41) of one contact, from psi and m0 = sin^2(e/2) =
    (1 - sin tau0)/2, mc0 = cos^2(e/2) = 1 - m0.

    psi <= 1: psi. psi > 1: ((psi+1)/2)^(3/2) F(tau1)/F(tau0) = k J(k^2 m0) / J(m0) with
    k^2 = 2/(psi + 1) and J of ``core.elliptic`` (F = 12 m^2 J), free of cancellation:
    1 - k^2 m0 is formed as (psi - 1)/(psi + 1) + k^2 mc0.
    """
    if psi <= 1.0:
        return psi
    return ratio_above_one(psi, m0, mc0, quartic_integral_float(m0, mc0))


@njit(cache=True, inline="always")
def _k2_and_m1(psi: float, m0: float) -> tuple[float, float]:
    """k^2 = 2/(psi + 1) and the parameter k^2 m0 of J(tau1) in eq 41 (psi > 1)."""
    k2 = 2.0 / (psi + 1.0)
    return k2, k2 * m0


@njit(cache=True, inline="always")
def _ratio_of(k2: float, j1: float, j0: float) -> float:
    """Eq 41 for psi > 1 from k^2, J(k^2 m0) and J(m0): k J(k^2 m0) / J(m0)."""
    return math.sqrt(k2) * j1 / j0


@njit(cache=True, inline="always")
def ratio_above_one(psi: float, m0: float, mc0: float, j0: float) -> float:
    """k J(k^2 m0) / J(m0) of eq 41 for psi > 1, given j0 = J(m0) (one per tau0)."""
    k2, m1 = _k2_and_m1(psi, m0)
    return _ratio_of(k2, quartic_integral_float(m1, (psi - 1.0) / (psi + 1.0) + k2 * mc0), j0)


@njit(cache=True, nogil=True, error_model="numpy")
def impulse_ratio_of_psis(psi: np.ndarray, m0: float, mc0: float) -> np.ndarray:
    """``impulse_ratio_float`` of every element of psi at one tau0, bit for bit (J(m0)
    computed once).

    Two passes, so that the first compiles to SIMD code: every element by the
    branch-free series of J (``quartic_series``, which is ``quartic_integral_float``
    where k^2 m0 < SERIES_LIMIT, i.e. for every psi > 10 m0 - 1, and for every psi when
    m0 < SERIES_LIMIT), then the few elements with psi > 1 and k^2 m0 >= SERIES_LIMIT
    again by ``ratio_above_one``. (error_model="numpy": divisions without a zero check,
    which would keep the loop scalar; no divisor here can be 0.)
    """
    out = np.empty(psi.shape)
    flat, o = psi.reshape(-1), out.reshape(-1)
    j0 = quartic_integral_float(m0, mc0)
    for i in range(flat.size):
        p = flat[i]
        k2, m1 = _k2_and_m1(p, m0)
        above = _ratio_of(k2, quartic_series(min(m1, SERIES_LIMIT)), j0)
        o[i] = p if p <= 1.0 else above
    if m0 >= SERIES_LIMIT:  # else k^2 m0 < m0 < SERIES_LIMIT for every psi > 1
        # k^2 m0 = 2 m0 / (psi + 1) falls with psi: only psi + 1 <= 2 m0 / SERIES_LIMIT
        # can reach the limit (the margin, 1e-12, is far above the rounding of either
        # side), so most elements skip the division of the exact test
        reach = 2.0 * m0 / SERIES_LIMIT * (1.0 + 1e-12)
        for i in range(flat.size):
            p = flat[i]
            if 1.0 < p and p + 1.0 <= reach and _k2_and_m1(p, m0)[1] >= SERIES_LIMIT:
                o[i] = ratio_above_one(p, m0, mc0, j0)
    return out


@vectorize([float64(float64, float64, float64)], cache=True)
def _impulse_ratio(psi: float, m0: float, mc0: float) -> float:
    return impulse_ratio_float(psi, m0, mc0)


impulse_ratio = _impulse_ratio.ufunc
"""T_imp / (mu P_imp) (eq 41) element-wise over arrays (broadcast) of psi >= 0 and of
m0 = (1 - sin tau0)/2, mc0 = 1 - m0 in [0, 1]: a numpy ufunc of ``impulse_ratio_float``
(no validation: ``core.impulse_ratio`` is the checked entry point)."""
