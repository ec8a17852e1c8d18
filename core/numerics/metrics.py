"""Errors of a ``MethodResult`` against the closed form of ``core`` (benchmarks, app).

All errors are absolute in the units of ``result.py``: T in T0, b in a*, the impulse
ratio T_imp / (mu P_imp) as it is (order one).
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from core.numerics.result import MethodResult

REVERSAL_GAP = 1e-9
"""b jumps from 0 (slip) to a* (partial stick) at tau = pi/2: points closer than this
to pi/2 are left out of the stick-radius error. At psi = 1 stick and slip coincide
(|tau_u| = mu p everywhere), b is not defined by the tractions and its error is nan."""


@dataclass(frozen=True)
class Errors:
    """Errors of one run: T (max over the run's own times, units T0), impulse ratio,
    stick radius (nan when the method has none), and the relative versions: T error
    over max |T_closed| and impulse error over |impulse ratio| (grazing contact has
    T ~ (1 - s0)^{3/2} T0, so the absolute error alone says little there)."""

    T: float
    impulse: float
    b: float
    T_rel: float
    impulse_rel: float

    @property
    def combined(self) -> float:
        """max(T error, impulse-ratio error), absolute."""
        return max(self.T, self.impulse)

    @property
    def combined_rel(self) -> float:
        """max of the relative T and impulse-ratio errors."""
        return max(self.T_rel, self.impulse_rel)


def errors(res: MethodResult, contact) -> Errors:
    """Errors of ``res`` against ``contact`` (a ``core.Contact``)."""
    exact_T = np.asarray(contact.tangential_force(res.tau), dtype=float)
    t_err = float(np.max(np.abs(res.T - exact_T)))
    exact_ratio = float(contact.impulse_ratio)
    i_err = float(abs(res.impulse_ratio - exact_ratio))
    t_scale = float(np.max(np.abs(exact_T))) or 1.0
    if res.b is None or contact.psi == 1.0:
        b_err = float("nan")
    else:
        keep = np.abs(res.tau - np.pi / 2) > REVERSAL_GAP
        exact = np.asarray(contact.stick_radius(res.tau[keep]))
        b_err = float(np.max(np.abs(res.b[keep] - exact))) if keep.any() else float("nan")
    return Errors(t_err, i_err, b_err, t_err / t_scale, i_err / abs(exact_ratio))


def closed_form_time(contact_cls, psi: float, tau0: float, n: int = 200,
                     repeat: int = 20) -> float:
    """Best-of-``repeat`` seconds for the closed form to give what a method gives from a
    contact: T and b on ``tau_grid(n)`` and the impulse ratio (eq 41).

    As ``solve`` times a method on a Contact it is given, the Contact is built (and
    validated) before the clock starts; each repeat gets a fresh one, so that tau1, F0
    and the impulse ratio, which a Contact computes on first use, are timed every time."""
    best = np.inf
    for _ in range(repeat):
        c = contact_cls(psi, tau0)
        start = time.perf_counter()
        line = c.at(c.tau_grid(n))  # T and b from one clock evaluation
        _ = line.tangential_force, line.stick_radius, c.impulse_ratio
        best = min(best, time.perf_counter() - start)
    return float(best)
