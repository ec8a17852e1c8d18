"""The exact reference of one case: T / T0, P / P0 and the phase over the contact, the
impulse ratio (eq 41) and the energy dissipated by slip, from the closed form of ``core``.

Units: tau = omega t (rad); T in T0 (eq 37), P in P0 = T0 / mu (eq 9); the drive
u_x0 / u0 = sin tau (eq 3) and the approach alpha / H = sin tau - sin tau0 (eq 8); work and
energy in T0 u0.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import quad

from core.dem_check.case import Case


@dataclass(frozen=True)
class Reference:
    """The exact contact of ``case`` on the times ``tau`` (arrays of one length)."""

    case: Case
    tau: NDArray[np.float64]
    drive: NDArray[np.float64]  # u_x0 / u0 = sin tau (eq 3)
    approach: NDArray[np.float64]  # alpha / H = sin tau - sin tau0, >= 0 (eq 8)
    T: NDArray[np.float64]  # T / T0 (eqs 38, 39), on the upper sphere, along the drive
    P: NDArray[np.float64]  # P / P0 (eq 9)
    phase: NDArray[np.int_]  # core.Phase codes: 1 stick, 2 slip, 3 partial stick, 4 counter-slip
    work: NDArray[np.float64]  # W / (T0 u0): work of the drive since tau0 (see drive_work)
    impulse_ratio: float  # T_imp / (mu P_imp) (eq 41)
    dissipated_energy: float  # D / (T0 u0) over the whole contact


def drive_work(tau: NDArray[np.float64], T: NDArray[np.float64]) -> NDArray[np.float64]:
    """W / (T0 u0) = integral of (T / T0) d(sin tau) from the first time on: the work of the
    drive on the contact (trapezoid rule in sin tau, exact for T linear in the drive between
    samples). For any passive contact that starts unloaded it is the stored tangential
    energy plus the energy dissipated so far, so it is never negative."""
    s = np.sin(tau)
    return np.concatenate(([0.0], np.cumsum(0.5 * (T[1:] + T[:-1]) * np.diff(s))))


def dissipated_energy(case: Case) -> float:
    """D / (T0 u0) = integral over [tau0, pi - tau0] of (T / T0) cos tau dtau, the energy
    dissipated by slip over one contact of a held rotor (docs: physics, "Friction
    dissipation"): the same quantity as ``core.Contact.dissipated_energy``, here by adaptive
    quadrature of ``core.Contact.tangential_force`` with breakpoints at pi/2 and tau1.

    Integrating eq 39 in s = sin tau gives the closed form
    (4/5) (1 - sin tau0)^{5/2} (psi - 1) / (psi + 1) for psi > 1, and 0 for psi <= 1 (the
    loading and unloading halves cancel); the tests hold the quadrature to it.
    """
    if case.psi <= 1.0:
        return 0.0
    c = case.contact
    cuts = [case.tau0, math.pi / 2, c.tau1, case.tau_end]
    total = 0.0
    for a, b in itertools.pairwise(cuts):
        if b > a:
            total += quad(lambda t: float(c.tangential_force(t)) * math.cos(t), a, b,
                          epsabs=0.0, epsrel=1e-12, limit=200)[0]
    return total


def exact(case: Case, n: int = 2000) -> Reference:
    """The exact contact of ``case`` on about n times over [tau0, pi - tau0] holding tau0,
    pi/2, tau1 and pi - tau0 (``core.Contact.tau_grid``)."""
    c = case.contact
    tau = c.tau_grid(n)
    line = c.at(tau)
    T = np.array(line.tangential_force)
    return Reference(
        case=case,
        tau=tau,
        drive=np.sin(tau),
        approach=np.maximum(np.sin(tau) - math.sin(case.tau0), 0.0),
        T=T,
        P=np.array(line.normal_force),
        phase=np.array(line.phase),
        work=drive_work(tau, T),
        impulse_ratio=c.impulse_ratio,
        dissipated_energy=dissipated_energy(case),
    )
