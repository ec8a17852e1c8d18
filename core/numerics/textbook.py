"""The closed form as printed (Zharii 1996), evaluated naively: a reference "method" that
shows where the formulas as written lose their digits (stability map only).

* F(tau0) = (1 + s0)(1 + 3 s0) K(k0) - 8 s0 E(k0), k0^2 = (1 - s0)/2 (eq 11), with
  scipy.special.ellipk / ellipe (parameter m = k0^2): both terms tend to 4 pi as
  s0 -> 1 while F ~ (1 - s0)^2 (grazing contact, and F(tau1) for large psi).
* tau1 = pi - arcsin(1 - 2 (1 - s0) / (psi + 1)) (eq 31): arcsin near 1 loses half
  the digits of its argument for large psi.
* sin tau - s0 and sin tau - sin tau1 formed directly (eqs 38, 39).
* b^2 / a*^2 = ((psi + 1) / 2) (sin tau - sin tau1) / (1 - s0) (eq 30).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.special import ellipe, ellipk

from core.numerics.loading import time_grid
from core.numerics.result import ContactLike, check_resolution, contact_parameters

DESCRIPTION = "closed form as printed (eq 11 with ellipk/ellipe, tau1 = pi - arcsin(...))"


def elliptic_f(s: float) -> float:
    """F of eq 11 as written, at s = sin(tau)."""
    m = (1.0 - s) / 2.0
    return float((1.0 + s) * (1.0 + 3.0 * s) * ellipk(m) - 8.0 * s * ellipe(m))


def tangential_force(psi: float, tau0: float, tau: NDArray[np.float64]) -> NDArray[np.float64]:
    """T / T0 by eqs 38-39 as written."""
    s0 = np.sin(tau0)
    s = np.sin(tau)
    inside = (tau >= tau0) & (tau <= np.pi - tau0)
    load = np.where(inside, np.abs(s - s0) ** 1.5, 0.0)
    if psi <= 1.0:
        return psi * load
    tau1 = np.pi - np.arcsin(1.0 - 2.0 * (1.0 - s0) / (psi + 1.0))
    s1 = np.sin(tau1)
    stick = 2.0 * ((psi + 1.0) / 2.0) ** 1.5 * np.abs(s - s1) ** 1.5
    return np.where(tau <= np.pi / 2, load, np.where(tau < tau1, -load + stick, -load))


def stick_radius(psi: float, tau0: float, tau: NDArray[np.float64]) -> NDArray[np.float64]:
    """b / a* by eq 30 as written (a / a* in full stick)."""
    s0 = np.sin(tau0)
    s = np.sin(tau)
    inside = (tau >= tau0) & (tau <= np.pi - tau0)
    if psi <= 1.0:
        return np.where(inside, np.sqrt(np.abs(s - s0) / (1.0 - s0)), 0.0)
    tau1 = np.pi - np.arcsin(1.0 - 2.0 * (1.0 - s0) / (psi + 1.0))
    b2 = (psi + 1.0) / 2.0 * (s - np.sin(tau1)) / (1.0 - s0)
    return np.where((tau > np.pi / 2) & (tau < tau1), np.sqrt(np.abs(b2)), 0.0)


def impulse_ratio(psi: float, tau0: float) -> float:
    """T_imp / (mu P_imp) by eq 41 as written."""
    if psi <= 1.0:
        return psi
    s0 = np.sin(tau0)
    s1 = 1.0 - 2.0 * (1.0 - s0) / (psi + 1.0)
    return ((psi + 1.0) / 2.0) ** 1.5 * elliptic_f(s1) / elliptic_f(s0)


def solve(contact: ContactLike, resolution: int) -> tuple:
    """Evaluate the printed formulas on ``loading.time_grid`` with ``resolution`` steps."""
    n = check_resolution(resolution, maximum=10**7)
    psi, tau0 = contact_parameters(contact)
    tau = time_grid(psi, tau0, n)
    return (tau, tangential_force(psi, tau0, tau), stick_radius(psi, tau0, tau),
            impulse_ratio(psi, tau0))
