"""The paper's loading in the boundary-element model's units (eqs 3, 4, 8; Fig. 2).

The lower body's centre moves as u_x0 = u0 sin tau, u_z0 = H sin tau; the bodies are a gap
h = H sin tau0 apart at tau = 0, touch at tau0 and separate at pi - tau0 (sin tau < sin tau0:
no contact); the next contact starts afresh (local motions decay in between, so every
contact is the same independent problem and the history is reset at re-contact). Lengths
in a* = sqrt(R_e (H - h)) (the largest contact radius; a*^2 = R (H - h)/2 for identical
spheres), displacements in a*^2 / R_e = H - h:

    approach   alpha / (H - h) = (sin tau - s0) / (1 - s0)                     (eq 8)
    shift      u_x0 / (H - h)  = psi mu kappa sin tau / (1 - s0)               (eq 23)

with s0 = sin tau0 and kappa = E* / (4 G*) = (2 - nu)/(2 (1 - nu)) (``Pair.kappa``), since
psi = 4 G* u0 / (mu E* H). Forces in the scales of ``core.Contact``: P0 = (2 pi / 3) p* a*^2
/ (1 - s0)^(3/2) (the Hertz load at approach H), T0 = mu P0.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from core.bem.pair import Pair, hertz_load
from core.validation import DOMAIN

#: Fewest and most time steps of one contact.
MIN_STEPS, MAX_STEPS = 4, 100_000


@dataclass(frozen=True)
class PaperLoading:
    """One contact of the paper's loading: psi, tau0 (``core.DOMAIN``), mu, the material
    ``pair`` and the number of equal time ``steps`` over [tau0, pi - tau0] (even, so that
    pi/2, where the drive reverses, is a time of the grid)."""

    psi: float
    tau0: float
    mu: float
    pair: Pair
    steps: int = 200

    def __post_init__(self) -> None:
        for name in ("psi", "tau0", "mu"):
            object.__setattr__(self, name, DOMAIN[name].check(name, getattr(self, name)))
        n = self.steps
        if (isinstance(n, bool) or not isinstance(n, int | np.integer)
                or not MIN_STEPS <= n <= MAX_STEPS or n % 2):
            raise ValueError(f"steps must be an even integer in [{MIN_STEPS}, {MAX_STEPS}],"
                             f" got {n!r}")
        object.__setattr__(self, "steps", operator.index(n))

    @property
    def s0(self) -> float:
        return math.sin(self.tau0)

    @cached_property
    def tau(self) -> NDArray[np.float64]:
        """steps + 1 equal times from tau0 to pi - tau0, pi/2 exactly in the middle."""
        t = np.linspace(self.tau0, math.pi - self.tau0, self.steps + 1)
        t[self.steps // 2] = math.pi / 2
        return t

    def approach(self, tau: NDArray[np.float64]) -> NDArray[np.float64]:
        """alpha / (H - h), clipped at 0 (no contact before tau0, after pi - tau0)."""
        return np.maximum((np.sin(tau) - self.s0) / (1.0 - self.s0), 0.0)

    def shift(self, tau: NDArray[np.float64]) -> NDArray[np.float64]:
        """u_x0 / (H - h) = psi mu kappa sin tau / (1 - s0)."""
        return self.psi * self.mu * self.pair.kappa * np.sin(tau) / (1.0 - self.s0)

    @property
    def P0(self) -> float:
        """P0 in units p* a*^2: the Hertz load at approach H."""
        return hertz_load() / (1.0 - self.s0) ** 1.5

    @property
    def u0(self) -> float:
        """u0 / (H - h)."""
        return self.psi * self.mu * self.pair.kappa / (1.0 - self.s0)
