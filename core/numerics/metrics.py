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
    """Errors of one run: T (max over the run's own times), impulse ratio, stick radius
    (nan when the method has none), and ``combined`` = max(T, impulse) used for charts."""

    T: float
    impulse: float
    b: float

    @property
    def combined(self) -> float:
        return max(self.T, self.impulse)


def errors(res: MethodResult, contact) -> Errors:
    """Errors of ``res`` against ``contact`` (a ``core.Contact``)."""
    t_err = float(np.max(np.abs(res.T - np.asarray(contact.tangential_force(res.tau)))))
    i_err = float(abs(res.impulse_ratio - contact.impulse_ratio))
    if res.b is None or contact.psi == 1.0:
        b_err = float("nan")
    else:
        keep = np.abs(res.tau - np.pi / 2) > REVERSAL_GAP
        exact = np.asarray(contact.stick_radius(res.tau[keep]))
        b_err = float(np.max(np.abs(res.b[keep] - exact))) if keep.any() else float("nan")
    return Errors(t_err, i_err, b_err)


def closed_form_time(contact_cls, psi: float, tau0: float, n: int = 200,
                     repeat: int = 20) -> float:
    """Best-of-``repeat`` seconds for the closed form to give what a method gives:
    build the Contact, T and b on ``tau_grid(n)``, and the impulse ratio (eq 41)."""
    best = np.inf
    for _ in range(repeat):
        start = time.perf_counter()
        c = contact_cls(psi, tau0)
        tau = c.tau_grid(n)
        c.tangential_force(tau)
        c.stick_radius(tau)
        _ = c.impulse_ratio
        best = min(best, time.perf_counter() - start)
    return float(best)
