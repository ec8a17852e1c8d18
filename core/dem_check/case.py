"""The paper's loading as a DEM test case: ``Case`` (psi, tau0, mu, nu, dimensionless) and
``CASES``, the documented set that ``python -m core.dem_check export`` writes.

Two identical spheres; the lower one's centre moves as u_x0 = u0 sin tau,
u_z0 = H sin tau (eq 3), the upper one is held; contact lasts tau0 <= tau <= pi - tau0 with
sin tau0 = h / H (eq 4), the approach is alpha = H (sin tau - sin tau0) (eq 8), and
psi = 2 (1 - nu) u0 / (mu (2 - nu) H) (eq 23).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from core.contact import Contact
from core.validation import check_param


@dataclass(frozen=True)
class Case:
    """One contact of the paper's loading. psi in [0, 1e12], tau0 in (-pi/2, pi/2) (rad;
    tau0 < 0 is a preload), mu in (0, 1e3], nu in (-1, 0.5], checked against
    ``core.DOMAIN`` (ValueError naming the parameter otherwise)."""

    psi: float
    tau0: float
    mu: float = 0.2
    nu: float = 0.3

    def __post_init__(self) -> None:
        for name in ("psi", "tau0", "mu", "nu"):
            object.__setattr__(self, name, check_param(name, getattr(self, name)))

    @property
    def contact(self) -> Contact:
        """The closed form of this case (``core.Contact``)."""
        return Contact(self.psi, self.tau0, self.mu, self.nu)

    @property
    def tau_end(self) -> float:
        """End of contact, pi - tau0 (eq 4)."""
        return math.pi - self.tau0

    @property
    def drive_ratio(self) -> float:
        """u0 / H = psi mu (2 - nu) / (2 (1 - nu)) (eq 23): the tangential drive amplitude
        in units of the normal one."""
        return self.psi * self.mu * (2.0 - self.nu) / (2.0 * (1.0 - self.nu))

    @property
    def loading_work(self) -> float:
        """W_L / (T0 u0) = (2/5) (1 - sin tau0)^{5/2}: the work of the drive from tau0 to
        pi/2 at the Coulomb bound T = mu P (eqs 9, 39), the scale of the energies here."""
        return 0.4 * (1.0 - math.sin(self.tau0)) ** 2.5


def _psi_of_tau1(tau1: float, tau0: float = math.pi / 6) -> float:
    """psi whose partial stick ends at tau1 (eq 31 solved for psi)."""
    return 2.0 * (1.0 - math.sin(tau0)) / (1.0 - math.sin(tau1)) - 1.0


#: The documented test cases (mu = 0.2, nu = 0.3): full stick, the critical angle, partial
#: stick, the paper's Fig. 7b (psi = 2.41, 6.46, 28.35 at tau0 = pi/6, so that tau1 = 3 pi/4,
#: 2 pi/3, 7 pi/12 exactly), grazing contact and a preload.
CASES: dict[str, Case] = {
    "full_stick": Case(psi=0.4, tau0=math.pi / 6),
    "critical": Case(psi=1.0, tau0=math.pi / 6),
    "partial_stick": Case(psi=2.0, tau0=0.0),
    "fig7_psi2.41": Case(psi=_psi_of_tau1(3 * math.pi / 4), tau0=math.pi / 6),
    "fig7_psi6.46": Case(psi=_psi_of_tau1(2 * math.pi / 3), tau0=math.pi / 6),
    "fig7_psi28.35": Case(psi=_psi_of_tau1(7 * math.pi / 12), tau0=math.pi / 6),
    "grazing": Case(psi=2.0, tau0=1.5),
    "preload": Case(psi=2.0, tau0=-0.5),
}

#: What each case tests, as the exported index says it.
NOTES: dict[str, str] = {
    "full_stick": "psi < 1: full stick for the whole contact (eq 36); T = psi P, no dissipation",
    "critical": "psi = 1, the critical angle theta0: stick at the Coulomb bound, largest impulse",
    "partial_stick": "psi = 2 from zero gap: slip, partial stick, counter-slip (eq 39)",
    "fig7_psi2.41": "the paper's Fig. 7b, psi = 2.41 (tau1 = 3 pi/4)",
    "fig7_psi6.46": "the paper's Fig. 7b, psi = 6.46 (tau1 = 2 pi/3)",
    "fig7_psi28.35": "the paper's Fig. 7b, psi = 28.35 (tau1 = 7 pi/12)",
    "grazing": "tau0 = 1.5: a short, shallow contact (0.14 rad, approach 1 - sin tau0 = 0.0025 H)",
    "preload": "tau0 = -0.5 (h < 0): the spheres are pressed together when contact starts",
}


def case_named(name: str) -> Case:
    """``CASES[name]``; ValueError listing the names otherwise."""
    try:
        return CASES[name]
    except KeyError:
        raise ValueError(f"no case named {name!r}; the cases are: {', '.join(CASES)}") from None
