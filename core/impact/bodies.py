"""The bodies of an oblique impact and their contact constants (SI units).

A sphere (radius R1, mass m1, moment of inertia I1 = K1^2 m1 R1^2, K^2 = 2/5 for a solid
sphere) strikes a target: a flat (R2 = inf) or a second sphere, rigid or elastic, fixed
or free. The contact constants are the classical ones (Johnson, *Contact Mechanics*,
eqs 4.22-4.27 and 7.4; Mindlin 1949):

    1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2        Hertz's contact modulus
    1 / G_e = (2 - nu1) / G1 + (2 - nu2) / G2           Mindlin's: k_t = 8 G_e a
    1 / R* = 1 / R1 + 1 / R2                            a^2 = R* alpha
    1 / m_n = 1 / m1 + 1 / m2                           normal (approach) mass
    1 / m_t = (1 + 1/K1^2) / m1 + (1 + 1/K2^2) / m2     mass of the contact points' slip

(a rigid body has 1/E = 1/G = 0, a fixed one 1/m = 0). A rigid or fixed target enters
with zero terms. ``Impact`` holds the bodies, friction and restitution and the velocities
before contact; it is validated once, here.

Geometry: z is the target's outward normal at the contact (the sphere comes down in -z),
x the tangent, y = z cross x. Spins are about y: the sphere's contact point (at -R1 z
from its centre) moves at vx1 - R1 w1, the target's (at +R2 z) at vx2 + R2 w2, so a
positive sphere spin is the rolling sense for vx1 > 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from core.validation import shown


def check_real(name: str, value: object, lo: float = -math.inf, hi: float = math.inf, *,
               lo_open: bool = False, hi_open: bool = False, allow_inf: bool = False
               ) -> float:
    """value as a float in the interval (lo or [lo, hi] or hi) or ValueError naming the
    argument, its value and the range. Infinite values only with ``allow_inf``."""
    bad = isinstance(value, bool) or not isinstance(value, int | float)
    if not bad:
        v = float(value)
        bad = math.isnan(v) or (math.isinf(v) and not allow_inf)
    left, right = ("(" if lo_open else "["), (")" if hi_open else "]")
    where = f"{left}{shown(lo)}, {shown(hi)}{right}"
    if bad:
        raise ValueError(f"{name} must be a real number in {where}, got {shown(value)}")
    if (v < lo or (lo_open and v == lo)) or (v > hi or (hi_open and v == hi)):
        raise ValueError(f"{name} = {shown(value)} is outside the allowed range {where}")
    return v


#: Where Coulomb's bound sits when e < 1 (``Impact.bound``).
BOUNDS = ("total", "elastic")


@dataclass(frozen=True)
class Material:
    """An isotropic elastic material: Young's modulus E (Pa), Poisson ratio nu, density
    (kg/m^3) and where the numbers come from."""

    name: str
    E: float
    nu: float
    density: float
    source: str = ""

    def __post_init__(self) -> None:
        check_real("E", self.E, 0.0, 1e15, lo_open=True)
        check_real("nu", self.nu, -0.99, 0.5, hi_open=True)
        check_real("density", self.density, 0.0, 1e6, lo_open=True)

    @property
    def G(self) -> float:
        """Shear modulus E / (2 (1 + nu)) (Pa)."""
        return self.E / (2.0 * (1.0 + self.nu))


@dataclass(frozen=True)
class Target:
    """What the sphere strikes: a flat (``radius`` inf) or a sphere; rigid when
    ``material`` is None (then it is also fixed); free to move (``free``) or fixed.
    A free target needs a material (its density) and a finite radius."""

    radius: float = math.inf
    material: Material | None = None
    free: bool = False
    K2: float = 0.4  # I / (m R^2)

    def __post_init__(self) -> None:
        check_real("target radius", self.radius, 0.0, math.inf, lo_open=True, allow_inf=True)
        check_real("target K2", self.K2, 0.0, 1.0, lo_open=True)
        if self.free and (self.material is None or math.isinf(self.radius)):
            raise ValueError("a free target needs a material (for its mass) and a finite "
                             "radius")

    @property
    def mass(self) -> float:
        """m2 (kg), inf when fixed."""
        if not self.free:
            return math.inf
        assert self.material is not None
        return 4.0 / 3.0 * math.pi * self.radius ** 3 * self.material.density

    @property
    def is_flat(self) -> bool:
        return math.isinf(self.radius)


@dataclass(frozen=True)
class Impact:
    """One oblique impact, SI units: the sphere (radius, material, K2), the target,
    friction ``mu``, normal restitution ``e`` (1: elastic Hertz; < 1: the viscous model of
    ``core.impact.normal``, a model choice) and the velocities just before contact: the
    sphere's centre (vx, vz; vz < vz2 so that the bodies approach), its spin w (rad/s,
    about y), the target's (vx2, vz2, w2; zero unless the target is free). ``bound``: for
    e < 1, Coulomb's bound on the total normal force ("total", elastic plus dashpot) or on
    the elastic force alone ("elastic"); both are model choices (``core.impact.kernel``)."""

    radius: float
    material: Material
    target: Target = field(default_factory=Target)
    mu: float = 0.3
    e: float = 1.0
    vx: float = 0.0
    vz: float = -1.0
    w: float = 0.0
    vx2: float = 0.0
    vz2: float = 0.0
    w2: float = 0.0
    K2: float = 0.4
    bound: str = "total"

    def __post_init__(self) -> None:
        check_real("radius", self.radius, 0.0, 1e3, lo_open=True)
        if self.bound not in BOUNDS:
            raise ValueError(f"bound must be one of {', '.join(BOUNDS)}, got {self.bound!r}")
        check_real("mu", self.mu, 0.0, 10.0, lo_open=True)
        check_real("e", self.e, 0.05, 1.0)
        check_real("K2", self.K2, 0.0, 1.0, lo_open=True)
        for name in ("vx", "vz", "w", "vx2", "vz2", "w2"):
            check_real(name, getattr(self, name), -1e4, 1e4)
        if not self.target.free and (self.vx2 or self.vz2 or self.w2):
            raise ValueError("vx2, vz2 and w2 must be 0 for a fixed target")
        if not self.vz2 - self.vz > 0.0:
            raise ValueError(f"the bodies must approach: vz2 - vz = {shown(self.vz2 - self.vz)}"
                             " must be > 0 (the sphere moves in -z towards the target)")

    # ---- masses and contact constants ----------------------------------------------
    @property
    def mass(self) -> float:
        """m1 = (4/3) pi R1^3 rho (kg)."""
        return 4.0 / 3.0 * math.pi * self.radius ** 3 * self.material.density

    @property
    def inertia(self) -> float:
        """I1 = K1^2 m1 R1^2 (kg m^2)."""
        return self.K2 * self.mass * self.radius ** 2

    @property
    def E_star(self) -> float:
        """Hertz's contact modulus E* (Pa)."""
        m2 = self.target.material
        c = (1.0 - self.material.nu ** 2) / self.material.E
        if m2 is not None:
            c += (1.0 - m2.nu ** 2) / m2.E
        return 1.0 / c

    @property
    def G_e(self) -> float:
        """Mindlin's tangential modulus G_e, k_t = 8 G_e a (Pa)."""
        m2 = self.target.material
        c = (2.0 - self.material.nu) / self.material.G
        if m2 is not None:
            c += (2.0 - m2.nu) / m2.G
        return 1.0 / c

    @property
    def R_star(self) -> float:
        """Effective radius R* (m)."""
        t = self.target
        return self.radius if t.is_flat else self.radius * t.radius / (self.radius + t.radius)

    @property
    def m_n(self) -> float:
        """Normal mass 1 / (1/m1 + 1/m2) (kg)."""
        return 1.0 / (1.0 / self.mass + 1.0 / self.target.mass)

    @property
    def m_t(self) -> float:
        """Mass of the contact points' relative slip (kg)."""
        inv = (1.0 + 1.0 / self.K2) / self.mass
        if self.target.free:
            inv += (1.0 + 1.0 / self.target.K2) / self.target.mass
        return 1.0 / inv

    @property
    def v_n(self) -> float:
        """Approach speed vz2 - vz > 0 (m/s)."""
        return self.vz2 - self.vz

    @property
    def slip_velocity(self) -> float:
        """Tangential velocity of the sphere's contact point relative to the target's,
        (vx - R1 w) - (vx2 + R2 w2) (m/s)."""
        r2w2 = 0.0 if not self.target.free else self.target.radius * self.w2
        return (self.vx - self.radius * self.w) - (self.vx2 + r2w2)

    @property
    def incidence(self) -> float:
        """Angle of incidence of the contact point, atan(slip velocity / v_n) (rad)."""
        return math.atan2(self.slip_velocity, self.v_n)

    @property
    def chi(self) -> float:
        """Maw, Barber & Fawcett's chi generalised: (2 G_e / E*) (m_n / m_t); for a sphere
        on a rigid flat (or two identical spheres) (1 - nu)(1 + 1/K^2) / (2 - nu)."""
        return 2.0 * self.G_e / self.E_star * self.m_n / self.m_t

    @property
    def psi1(self) -> float:
        """MBF's normalised incidence (4 G_e / (mu E*)) v_slip / v_n; for a sphere on a rigid
        flat 2 (1 - nu) tan(theta) / (mu (2 - nu))."""
        return 4.0 * self.G_e / (self.mu * self.E_star) * self.slip_velocity / self.v_n

    @property
    def alpha_star(self) -> float:
        """Largest approach of the elastic (Hertz) impact,
        (15 m_n v_n^2 / (16 E* R*^(1/2)))^(2/5) (m) (Johnson eq 11.26)."""
        return (15.0 * self.m_n * self.v_n ** 2
                / (16.0 * self.E_star * math.sqrt(self.R_star))) ** 0.4

    @property
    def time_scale(self) -> float:
        """alpha* / v_n (s): the unit of time of the dimensionless problem."""
        return self.alpha_star / self.v_n


__all__ = ["BOUNDS", "Impact", "Material", "Target", "check_real"]
