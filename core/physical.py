"""Physical units at the edge: SI inputs to the dimensionless problem, and the SI scales
that turn every dimensionless result back into newtons, metres, pascals and N s."""

from __future__ import annotations

import math
from dataclasses import dataclass

from core.validation import DOMAIN, check_param, shown

SQRT8 = 2.0 * math.sqrt(2.0)

#: Typical handbook values for identical spheres of one material (G in Pa); the friction
#: coefficient is a typical dry value for the pair and is meant to be edited.
MATERIALS: dict[str, dict[str, float]] = {
    "steel": {"G": 79.3e9, "nu": 0.29, "mu": 0.2},
    "aluminium": {"G": 26.0e9, "nu": 0.33, "mu": 0.3},
    "glass": {"G": 28.7e9, "nu": 0.22, "mu": 0.3},
    "PZT ceramic": {"G": 24.0e9, "nu": 0.31, "mu": 0.2},
}


@dataclass(frozen=True)
class PhysicalInputs:
    """SI inputs of eq 3: radius R (m), shear modulus G (Pa), Poisson ratio nu, friction
    coefficient mu, vertical and horizontal drive amplitudes H and u0 (m), gap h at t = 0
    (m; h < 0 is a preload) and angular frequency omega (rad/s).

    Validated (ValueError naming the input): each against ``core.DOMAIN``, whose ranges
    keep every ``Scales`` value finite; then h in (-H, H), and psi of u0 / H, mu and nu in
    [0, 1e12]."""

    R: float
    G: float
    nu: float
    mu: float
    H: float
    u0: float
    h: float
    omega: float

    def __post_init__(self) -> None:
        for name in ("R", "G", "nu", "mu", "H", "u0", "h", "omega"):
            object.__setattr__(self, name, check_param(name, getattr(self, name)))
        h, H = self.h, self.H
        if not -H < h < H:
            raise ValueError(
                f"h = {shown(h)} is outside the allowed range (-H, H) = ({shown(-H)},"
                f" {shown(H)}): the spheres must touch (h < H) and separate again (h > -H)"
            )
        if not DOMAIN["tau0"].contains(self.tau0):  # h / H rounds to -1
            raise ValueError(
                f"h = {shown(h)} is too close to -H = {shown(-H)}: the spheres would never"
                " separate (tau0 = -pi/2)"
            )
        if not DOMAIN["psi"].contains(self.psi):
            raise ValueError(
                f"psi = {shown(self.psi)} (from u0 / H = {shown(self.u0 / H)}, mu ="
                f" {shown(self.mu)}) is outside the allowed range {DOMAIN['psi'].describe()}:"
                " lower u0, or raise H or mu"
            )

    @property
    def tau0(self) -> float:
        """Start of contact, sin tau0 = h / H (eq 4); written as pi/2 - arccos(h/H) with
        arccos from (H - h) so that grazing contact keeps its digits."""
        e = 2.0 * math.asin(math.sqrt((self.H - self.h) / (2.0 * self.H)))
        return math.pi / 2 - e

    @property
    def psi(self) -> float:
        """psi = 2 (1 - nu) u0 / (mu (2 - nu) H) (eq 23)."""
        # in this order no product can underflow to a zero divisor (H >= 1e-15, mu > 0)
        return 2.0 * (1.0 - self.nu) / (2.0 - self.nu) * (self.u0 / self.H) / self.mu


@dataclass(frozen=True)
class Scales:
    """SI scales of one contact: multiply a dimensionless result by its scale.

    T0 (N, eq 37) for T / T0; P0 = T0 / mu (N) for P / P0; a_star = sqrt(R (H - h) / 2) (m)
    for radii; p_star = 4 G a* / ((1 - nu) pi R) (Pa) for pressure, and mu p_star for
    tractions; alpha_star = H - h (m) for the approach; u0 (m) and v_star = omega u0 (m/s)
    for the contact-centre motion; normal_impulse (eq 10) and tangential_impulse (eq 41)
    in N s; period = 2 pi / omega (s), and time t = tau / omega.
    """

    inputs: PhysicalInputs
    T0: float
    P0: float
    a_star: float
    p_star: float
    traction_star: float
    alpha_star: float
    u0: float
    v_star: float
    normal_impulse: float
    tangential_impulse: float
    period: float

    @classmethod
    def of(cls, inputs: PhysicalInputs, F0: float, impulse_ratio: float) -> Scales:
        """Scales of ``inputs``, given F(tau0) and T_imp / (mu P_imp) of the same contact."""
        R, G, nu, mu, H = inputs.R, inputs.G, inputs.nu, inputs.mu, inputs.H
        P0 = SQRT8 * G / (3.0 * (1.0 - nu)) * math.sqrt(R) * H**1.5
        a_star = math.sqrt(R * (H - inputs.h) / 2.0)
        p_star = 4.0 * G * a_star / ((1.0 - nu) * math.pi * R)
        normal_impulse = 8.0 * G * math.sqrt(R) * H**1.5 * F0 / (9.0 * (1.0 - nu) * inputs.omega)
        return cls(
            inputs=inputs,
            T0=mu * P0,
            P0=P0,
            a_star=a_star,
            p_star=p_star,
            traction_star=mu * p_star,
            alpha_star=H - inputs.h,
            u0=inputs.u0,
            v_star=inputs.omega * inputs.u0,
            normal_impulse=normal_impulse,
            tangential_impulse=mu * normal_impulse * impulse_ratio,
            period=2.0 * math.pi / inputs.omega,
        )
