"""Tangential tractions, force and impulse (eqs 18-41), dimensionless.

Phases (``Phase``): full stick for psi <= 1 (eq 36); for psi > 1 slip while loading
(tau0 <= tau <= pi/2, eq 18), partial stick (pi/2 < tau < tau1, eq 24) and counter-slip
(tau1 <= tau <= pi - tau0, eq 33).

In the clock variable w of ``core.clock`` the stick disc of eq 30 is simply

    (b / a*)^2 = (1 - w/k)(1 + w/k),   k = sqrt(2 / (psi + 1)),

so partial stick ends at w = k, i.e. tau1 = pi/2 + 2 arcsin(k sin(e/2)) (eq 31, in a form
that keeps its digits for huge psi, where tau1 - pi/2 ~ 2 sqrt((1 - sin tau0)/psi), eq 35).
Scales: traction in mu p*, force in T0 (eq 37), radii in a*.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from enum import IntEnum

import numpy as np
from numpy.typing import ArrayLike, NDArray

from core.clock import HALF_PI_HI, HALF_PI_LO, one_minus_square
from core.elliptic import quartic_integral, quartic_integral_float
from core.hertz import SQRT8, pressure


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


def stick_clock(psi: float) -> float:
    """k = sqrt(2 / (psi + 1)): the clock value w at tau1 (psi > 1)."""
    return math.sqrt(2.0 / (psi + 1.0))


def tau1(psi: float, sin_half_e: float, cos_half_e: float) -> float:
    """End of partial stick, pi/2 < tau1 <= pi - tau0 (eq 31); nan for psi <= 1.

    tau1 = pi/2 + 2 arcsin(x), x = k sin(e/2). Where x > 1/2 (psi near 1) arcsin is
    ill-conditioned, so it is taken through the complement
    1 - x = (psi - 1)/((psi + 1)(1 + k)) + k cos^2(e/2)/(1 + sin(e/2)), which never cancels:
    tau1 = 3 pi/2 - 4 arcsin(sqrt((1 - x)/2)).
    """
    if psi <= 1.0:
        return float("nan")
    k = stick_clock(psi)
    x = k * sin_half_e
    if x <= 0.5:
        return HALF_PI_HI + (2.0 * math.asin(x) + HALF_PI_LO)
    one_minus_x = (psi - 1.0) / ((psi + 1.0) * (1.0 + k)) + k * cos_half_e**2 / (1.0 + sin_half_e)
    quarter = math.asin(math.sqrt(0.5 * one_minus_x))
    return 3.0 * HALF_PI_HI - (4.0 * quarter - 3.0 * HALF_PI_LO)


def phase(w: NDArray[np.float64], psi: float) -> NDArray[np.int_]:
    """Phase code at each clock value w (see ``Phase``)."""
    inside = np.abs(w) <= 1.0
    if psi <= 1.0:
        return np.where(inside, Phase.FULL_STICK, Phase.NO_CONTACT).astype(int)
    k = stick_clock(psi)
    out = np.full(w.shape, int(Phase.SLIP))
    out[w > 0.0] = Phase.PARTIAL_STICK
    out[w >= k] = Phase.COUNTER_SLIP
    out[~inside] = Phase.NO_CONTACT
    return out


def stick_radius_squared(w: NDArray[np.float64], psi: float) -> NDArray[np.float64]:
    """(b / a*)^2: a^2 in full stick, (1 - w/k)(1 + w/k) in partial stick (eq 30), else 0."""
    if psi <= 1.0:
        return one_minus_square(w)
    # v = w / k in unloading and 1 while loading, where (1 - v)(1 + v) is then 0; it is
    # clipped to 0 for v >= 1 (counter-slip): no masks needed
    unloading = w > 0.0
    v = np.divide(w, stick_clock(psi), out=np.ones_like(w), where=unloading)
    return one_minus_square(v)


def tangential_force(
    a3: NDArray[np.float64],
    b3: NDArray[np.float64] | None,
    w: NDArray[np.float64],
    psi: float,
    sin_half_e: float,
) -> NDArray[np.float64]:
    """T / T0 on the upper sphere, positive along the drive (eqs 38, 39), from the cubed
    radii a3 = (a/a*)^3 and b3 = (b/a*)^3 (unused, may be None, for psi <= 1) at clock w.

    T / T0 = (1 - sin tau0)^(3/2) times: psi a^3 (stick); a^3 (slip); 2 b^3 - a^3
    (partial stick); -a^3 (counter-slip). b3 is 0 outside partial stick, so the last three
    are one expression: 2 b^3 -+ a^3, with the sign of a^3 flipped in unloading (w > 0).
    """
    scale = SQRT8 * sin_half_e**3
    if psi <= 1.0:
        return a3 * (psi * scale)
    t = np.negative(a3, out=np.array(a3), where=w > 0.0)
    t += 2.0 * b3
    t *= scale
    return t


def traction(r: ArrayLike, w: NDArray[np.float64], psi: float) -> NDArray[np.float64]:
    """tau_u / (mu p*) at radius r (units of a*; sign of r ignored) and clock w (eqs 18, 24,
    33, 36); r and w broadcast against each other."""
    r, w = np.broadcast_arrays(np.abs(np.asarray(r, dtype=float)), w)
    a2 = one_minus_square(w)
    hertz = pressure(r, a2)
    if psi <= 1.0:
        return psi * hertz
    out = np.where(w > 0.0, -hertz, hertz)
    b2 = stick_radius_squared(w, psi)
    return out + 2.0 * pressure(r, b2)


def impulse_ratio(psi: ArrayLike, sin_half_e: float, cos_half_e: float) -> NDArray[np.float64]:
    """T_imp / (mu P_imp) (eq 41) for an array of psi at one tau0.

    psi <= 1: psi. psi > 1: ((psi+1)/2)^(3/2) F(tau1)/F(tau0) = k J(k^2 m0) / J(m0) with
    m0 = sin^2(e/2) and J of ``core.elliptic`` (F = 12 m^2 J), free of cancellation.
    """
    m0, mc0 = sin_half_e**2, cos_half_e**2
    if np.ndim(psi) == 0:  # one contact: floats only, no array calls
        p = float(psi)
        return np.asarray(p if p <= 1.0 else _ratio_above_one(p, m0, mc0,
                                                              quartic_integral_float))
    psi = np.asarray(psi, dtype=float)
    out = psi.copy()
    big = psi > 1.0
    if big.any():
        out[big] = _ratio_above_one(psi[big], m0, mc0)
    return out


def _ratio_above_one(
    psi: ArrayLike, m0: float, mc0: float, J: Callable = quartic_integral
) -> NDArray[np.float64]:
    """k J(k^2 m0) / J(m0) for psi > 1, with 1 - k^2 m0 formed without cancellation
    (J: ``quartic_integral``, or ``quartic_integral_float`` for one float psi)."""
    k2 = 2.0 / (psi + 1.0)
    j1 = J(k2 * m0, (psi - 1.0) / (psi + 1.0) + k2 * mc0)
    return np.sqrt(k2) * j1 / J(m0, mc0)
