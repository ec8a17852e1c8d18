"""The material pair of the boundary-element model, as the two numbers its kernels need:
the effective Poisson ratio nu and Dundurs' beta (``core.bem.convolution``), validated.

Every pair of isotropic bodies (G1, nu1), (G2, nu2) enters the half-space kernels only
through nu = nu_eq (``core.physical.equivalent_pair``: the cross term's weight
n = E* sum nu_i / (2 G_i) = nu_eq / (1 - nu_eq)) and beta (``core.physical.dundurs_beta``,
body 1 the held upper body of the paper), once lengths are in a, tractions in p* and
displacements in a^2 / R_e. The closed form (Goodman's approximation) uses nu_eq alone.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from core.physical import dundurs_beta, equivalent_pair
from core.validation import Interval

#: Allowed ranges of the model's parameters.
NU_RANGE = Interval(0.0, 0.5, hi_open=True)
BETA_RANGE = Interval(-0.5, 0.5, lo_open=True, hi_open=True)
LOAD_RANGE = Interval(0.0, 1.0, hi_open=True)


@dataclass(frozen=True)
class Pair:
    """Effective Poisson ratio ``nu`` in [0, 0.5) and Dundurs' ``beta`` in (-0.5, 0.5)
    (ValueError naming the argument otherwise)."""

    nu: float
    beta: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "nu", NU_RANGE.check("nu", self.nu))
        object.__setattr__(self, "beta", BETA_RANGE.check("beta", self.beta))

    @classmethod
    def of(cls, G1: float, nu1: float, G2: float, nu2: float) -> Pair:
        """The pair of body 1 (G1 in Pa, nu1) held above body 2 (G2, nu2)."""
        nu_eq = equivalent_pair(1.0, G1, nu1, 1.0, G2, nu2)[2]
        return cls(nu=nu_eq, beta=dundurs_beta(G1, nu1, G2, nu2))

    @property
    def kappa(self) -> float:
        """E* / (4 G*) = (2 - nu) / (2 (1 - nu)): the tangential over the normal compliance
        of the closed form (Mindlin's shift mu P / (8 G* a) = mu kappa a^2 / R_e
        times P / (4/3 E* a^3 / R_e))."""
        return (2.0 - self.nu) / (2.0 * (1.0 - self.nu))


def rigid_indenter_nu(beta: float) -> float:
    """The Poisson ratio of an elastic body under a rigid one with Dundurs' beta:
    beta = (1 - 2 nu) / (2 (1 - nu)) solved for nu, with |beta| (swapping the bodies
    changes beta's sign only)."""
    b = abs(beta)
    return (1.0 - 2.0 * b) / (2.0 * (1.0 - b))


def hertz_load() -> float:
    """The Hertz load of a contact of radius 1 and peak pressure 1 (units p* a^2): 2 pi / 3."""
    return 2.0 * math.pi / 3.0
