"""Score a DEM code's force history over one contact against the exact solution.

``score(case, tau, T, P)`` takes T / T0 and P / P0 on the held (upper) sphere, T along the
drive, at the times tau = omega t (rad, any increasing sampling that covers the contact)
and returns a ``DemScore``. Integrals are trapezoid rules over the samples given, the way
a DEM code's own impulse would be summed; the exact values are core's closed form at the
same times (T, P, phase) and over the whole contact (impulse ratio, dissipated energy).
Energies are in T0 u0 (u0: the tangential drive amplitude, eq 3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from core.dem_check.case import Case
from core.dem_check.exact import dissipated_energy, drive_work
from core.tangential import PHASE_NAMES

MAX_SAMPLES = 10**7
#: How much of the contact's length the samples may leave out at either end.
COVER_TOLERANCE = 0.01


@dataclass(frozen=True)
class DemScore:
    """How far one contact of a DEM code is from the exact solution."""

    impulse_ratio: float  # T_imp / (mu P_imp) of the history (trapezoid)
    exact_impulse_ratio: float  # eq 41
    impulse_ratio_error: float  # impulse_ratio - exact (signed)
    max_T_error: float  # worst |T - T_exact| / T0 over the samples
    worst_tau: float  # where it is (rad)
    worst_phase: str  # the exact solution's phase there ("slip", "partial stick", ...)
    max_P_error: float  # worst |P - P_exact| / P0 (the normal model and the loading)
    dissipated_energy: float  # D / (T0 u0) = integral of T d(sin tau) over the history
    exact_dissipated_energy: float  # D / (T0 u0) of the closed form
    energy_error: float  # dissipated_energy - exact (signed), T0 u0
    energy_gain: float  # max(0, -min W): work returned above what the drive put in, T0 u0
    coulomb_excess: float  # max(0, max(|T| - P)) in T0: |T| <= mu P broken by this much
    loading_work: float  # (2/5)(1 - sin tau0)^{5/2}, the scale of the energies (Case)

    @property
    def impulse_ratio_relative_error(self) -> float:
        """impulse_ratio_error / exact_impulse_ratio (0 when both are 0, psi = 0)."""
        e = self.exact_impulse_ratio
        return self.impulse_ratio_error / e if e else abs(self.impulse_ratio_error)

    def as_dict(self) -> dict[str, float | str]:
        """The fields and the relative impulse error, for JSON and tables."""
        out: dict[str, float | str] = dict(self.__dict__)
        out["impulse_ratio_relative_error"] = self.impulse_ratio_relative_error
        return out


def _series(name: str, values: ArrayLike) -> NDArray[np.float64]:
    """values as a 1-D float array of finite numbers; ValueError naming the argument and
    the first bad element otherwise."""
    try:
        a = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a sequence of real numbers") from None
    if a.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {a.shape}")
    if a.size > MAX_SAMPLES:
        raise ValueError(f"{name} has {a.size} samples, more than {MAX_SAMPLES}")
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        raise ValueError(f"{name}[{bad[0]}] = {a[bad[0]]} is not a finite number")
    return a


def check_history(case: Case, tau: ArrayLike, T: ArrayLike, P: ArrayLike
                  ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """(tau, T, P) as float arrays of one length (>= 2), tau strictly increasing and
    covering the contact [tau0, pi - tau0] to within ``COVER_TOLERANCE`` of its length;
    ValueError naming the argument (and element) otherwise."""
    tau, T, P = _series("tau", tau), _series("T", T), _series("P", P)
    if not tau.size == T.size == P.size:
        raise ValueError(f"tau, T and P must have one length, got {tau.size}, {T.size}, "
                         f"{P.size}")
    if tau.size < 2:
        raise ValueError(f"a history needs at least 2 samples, got {tau.size}")
    back = np.flatnonzero(np.diff(tau) <= 0)
    if back.size:
        i = back[0] + 1
        raise ValueError(f"tau must increase: tau[{i}] = {float(tau[i])!r} <= tau[{i - 1}] = "
                         f"{float(tau[i - 1])!r}")
    slack = COVER_TOLERANCE * (case.tau_end - case.tau0)
    if tau[0] > case.tau0 + slack or tau[-1] < case.tau_end - slack:
        raise ValueError(f"tau must cover the contact [{case.tau0:.6g}, {case.tau_end:.6g}] "
                         f"(rad), got [{tau[0]:.6g}, {tau[-1]:.6g}]")
    return tau, T, P


def score(case: Case, tau: ArrayLike, T: ArrayLike, P: ArrayLike) -> DemScore:
    """Score the history (tau, T / T0, P / P0) of one contact of ``case`` (see the module
    docstring); ValueError (``check_history``) for a malformed history."""
    tau, T, P = check_history(case, tau, T, P)
    c = case.contact
    line = c.at(tau)
    T_err = np.abs(T - line.tangential_force)
    worst = int(np.argmax(T_err))
    dtau = np.diff(tau)
    p_sum = float(np.sum(0.5 * (P[1:] + P[:-1]) * dtau))
    ratio = float(np.sum(0.5 * (T[1:] + T[:-1]) * dtau)) / p_sum if p_sum > 0 else 0.0
    work = drive_work(tau, T)
    exact_ratio = c.impulse_ratio
    exact_D = dissipated_energy(case)
    return DemScore(
        impulse_ratio=ratio,
        exact_impulse_ratio=exact_ratio,
        impulse_ratio_error=ratio - exact_ratio,
        max_T_error=float(T_err[worst]),
        worst_tau=float(tau[worst]),
        worst_phase=PHASE_NAMES[int(line.phase[worst])],
        max_P_error=float(np.max(np.abs(P - line.normal_force))),
        dissipated_energy=float(work[-1]),
        exact_dissipated_energy=exact_D,
        energy_error=float(work[-1]) - exact_D,
        energy_gain=max(0.0, -float(np.min(work))),
        coulomb_excess=max(0.0, float(np.max(np.abs(T) - P))),
        loading_work=case.loading_work,
    )


__all__ = ["COVER_TOLERANCE", "MAX_SAMPLES", "DemScore", "check_history", "score"]
