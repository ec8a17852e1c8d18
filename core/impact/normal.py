"""The normal restitution e < 1 as a model choice: a nonlinear (Tsuji-type) dashpot.

The exact problem is elastic (e = 1). Where a test prescribes a measured restitution
(Chung & Ooi's test 4: e = 0.98), the reference adds a dashpot to the Hertz force,

    F = (4/3) E* R*^(1/2) alpha^(3/2) + c (m_n k_n)^(1/2) alpha^(1/4) alpha'    (F >= 0),

k_n = (4/3) E* R*^(1/2) (Tsuji, Tanaka & Ishida 1992, Powder Technol. 71: 239-250; the
form of LAMMPS' ``damping tsuji``). In the units of ``kernel`` it is gamma d^(1/4) d'
with gamma = c (5/4)^(1/2), independent of the speed, so e depends on gamma alone;
``dashpot(e)`` finds gamma by the secant method on the normal impact itself (the same springs,
integrator and tolerance as the full impact), so that the reference rebounds with e to
the integrator's tolerance. Coulomb's bound is on the total normal force, elastic plus
dashpot, shared among the springs like the elastic force (a second model choice,
``kernel.step``): gross sliding then gives the rigid-body tangential impulse
mu (1 + e) m_n v_n.

LAMMPS' ``damping tsuji`` takes e and sets c from Tsuji's polynomial fit
(``tsuji_coefficient``); its restitution is then e to the accuracy of the fit.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.optimize import brentq

from core.impact.kernel import impact, spring_row


def tsuji_coefficient(e: float) -> float:
    """Tsuji's fit of the dashpot factor c(e) as LAMMPS' ``damping tsuji`` evaluates it
    (pair granular: 1.2728 - 4.2783 e + 11.087 e^2 - 22.348 e^3 + 27.467 e^4 - 18.022 e^5
    + 4.8218 e^6)."""
    p = (4.8218, -18.022, 27.467, -22.348, 11.087, -4.2783, 1.2728)
    return float(np.polyval(p, e))


def restitution(gamma: float, springs: int, tol: float) -> float:
    """The normal restitution -d'(end) of the normal impact with dashpot gamma."""
    x, scale = spring_row(springs)
    out, _ = impact(0.0, 1.0, gamma, x, scale, tol, 1e-3, 2_000_000)
    return float(-out[-1, 2])


@lru_cache(maxsize=64)
def dashpot(e: float, springs: int, tol: float) -> float:
    """gamma such that the normal impact rebounds with restitution e (0 for e = 1)."""
    if e >= 1.0:
        return 0.0

    def miss(g: float) -> float:
        return restitution(g, springs, tol) - e

    # secant from Tsuji's fit (close to the answer), brentq if it strays
    g0 = tsuji_coefficient(e) * 1.25 ** 0.5
    g1 = 1.02 * g0 + 1e-3
    f0, f1 = miss(g0), miss(g1)
    for _ in range(10):
        if abs(f1) < 1e-11 or f1 == f0:
            return float(g1)
        g0, g1, f0 = g1, g1 - f1 * (g1 - g0) / (f1 - f0), f1
        if not 0.0 < g1 < 20.0:
            break
        f1 = miss(g1)
    return float(brentq(miss, 0.0, 20.0, xtol=1e-14, rtol=1e-12))


__all__ = ["dashpot", "restitution", "tsuji_coefficient"]
