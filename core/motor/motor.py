"""The motor of Fig. 1 with the rotor held: drive, start of contact and stall thrust along
the rod, vectorised over the contact point x0. See docs/physics.md, section 10.

    from core.motor import Rod, Motor
    rod = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
    m = Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05)
    x0 = np.linspace(-0.0199, 0.0199, 1000)
    m.psi(x0), m.tau0(x0), m.stall_thrust(x0)   # 1, rad, N (signed); nan: never opens
    p = m.profile(x0)                             # every quantity at once (MotorProfile)
    c = m.contact(-0.01)                          # core.Contact of one point, SI scales set
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from core.contact import Contact
from core.frozen import freeze
from core.motor import balance, thrust
from core.motor.rod import POSITIVE, Rod
from core.physical import beta_warning, dundurs_beta, equivalent_pair
from core.validation import DOMAIN, MOTOR_DOMAIN, PHI_MIN, check_param, is_flat, shown


@dataclass(frozen=True)
class MotorProfile:
    """Every quantity of the held-rotor motor at the points x0 (read-only arrays of
    x0's shape). SI: x0, u0, H, h (m), stall_thrust (N). Dimensionless: psi, tan_theta,
    load_factor (Phi: the F(tau0) the preload requires), m0 = (1 - sin tau0) / 2, tau0
    (rad), impulse_ratio (T_imp / (mu P_imp), eq 41, in [0, 1]) and thrust_ratio (the
    signed stall thrust over mu N, in [-1, 1]). ``opens`` is False where the contact never
    opens (Phi >= 8): the model does not apply there and every quantity that depends on
    tau0 is nan. ``beta`` is Dundurs' constant of the rotor and the rod (0-d; 0 for the
    paper's identical bodies)."""

    x0: NDArray[np.float64]
    u0: NDArray[np.float64]
    H: NDArray[np.float64]
    tan_theta: NDArray[np.float64]
    psi: NDArray[np.float64]
    load_factor: NDArray[np.float64]
    opens: NDArray[np.bool_]
    m0: NDArray[np.float64]
    tau0: NDArray[np.float64]
    h: NDArray[np.float64]
    impulse_ratio: NDArray[np.float64]
    thrust_ratio: NDArray[np.float64]
    stall_thrust: NDArray[np.float64]
    beta: float = 0.0

    def __post_init__(self) -> None:
        freeze(self)  # (copies, also of 0-d results)


@dataclass(frozen=True)
class Motor:
    """A rotor on the rod of Fig. 1, pressed on it by a steady ``preload`` N (newtons: the
    rotor's weight, or a spring). The rotor's contact is a sphere of radius R (m), shear
    modulus G (Pa) and Poisson ratio nu; mu is the friction coefficient of the pair. The
    rod's contact point is, as in the paper, an identical sphere (rod_R, rod_G, rod_nu
    None), or a body of its own: rod_G (Pa), rod_nu, and rod_R (m; ``math.inf`` for the
    flat face of the rod), each None taking the rotor's value. Dissimilar bodies enter
    under Goodman's approximation, through the equivalent identical pair
    (``core.physical.equivalent_pair``; docs/physics.md, section 11.1): psi, Phi, tau0 and
    the thrust use its constants (``equivalent``); ``beta`` measures what it neglects.

    Validated (ValueError naming the parameter, its value and the range): ``rod`` a
    ``Rod``; R, G, nu, mu and rod_R, rod_G, rod_nu in core's domain
    (``core.validation.DOMAIN``, as ``Contact.from_physical``; rod_R also inf); preload
    > 0 and in ``MOTOR_DOMAIN["preload"]``; and jointly, Phi at the rod's centre at least
    ``PHI_MIN`` (else the contact would only graze and the balance has no root in
    core's tau0 range). Every method takes x0 (m) as a scalar or array with |x0| < L and
    returns arrays of its shape.
    """

    rod: Rod
    R: float
    G: float
    nu: float
    mu: float
    preload: float
    rod_G: float | None = None
    rod_nu: float | None = None
    rod_R: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.rod, Rod):
            raise ValueError(f"rod must be a core.motor.Rod, got {self.rod!r}")
        for name in ("R", "G", "nu", "mu"):
            object.__setattr__(self, name, check_param(name, getattr(self, name)))
        preload = POSITIVE.check("preload", self.preload)
        object.__setattr__(self, "preload", MOTOR_DOMAIN["preload"].check("preload", preload))
        for name, row in (("rod_G", "G"), ("rod_nu", "nu"), ("rod_R", "R")):
            value = getattr(self, name)
            if value is not None:
                flat = name == "rod_R" and is_flat(value)
                object.__setattr__(self, name,
                                   math.inf if flat else DOMAIN[row].check(name, value))
        centre = float(self._load_factor(np.array(abs(self.rod.vertical_amplitude))))
        if not centre >= PHI_MIN:
            raise ValueError(
                f"preload = {shown(self.preload)} N is too small for this rod and rotor: "
                f"Phi = {shown(centre)} at the rod's centre is below {PHI_MIN:g} "
                "(the contact would only graze, tau0 -> pi/2): raise the preload, or "
                "lower the rod's amplitude or thickness")

    @property
    def equivalent(self) -> tuple[float, float, float]:
        """(R_eq, G_eq, nu_eq): the identical spheres equivalent to rotor and rod under
        Goodman's approximation (m, Pa, 1); (R, G, nu) for the paper's identical bodies."""
        return equivalent_pair(self.R, self.G, self.nu, self.rod_R, self.rod_G, self.rod_nu)

    @property
    def beta(self) -> float:
        """Dundurs' beta of rotor (body 1) and rod (body 2); 0 for identical bodies."""
        G2 = self.G if self.rod_G is None else self.rod_G
        nu2 = self.nu if self.rod_nu is None else self.rod_nu
        return dundurs_beta(self.G, self.nu, G2, nu2)

    @property
    def beta_warning(self) -> str | None:
        """A warning for users when |beta| exceeds ``core.physical.BETA_WARN``."""
        return beta_warning(self.beta)

    @property
    def tan_theta0(self) -> float:
        """tan theta0 = mu (2 - nu) / (2 (1 - nu)) (eq 23), nu the equivalent nu_eq:
        psi = tan theta / tan theta0."""
        nu = self.equivalent[2]
        return self.mu * (2.0 - nu) / (2.0 * (1.0 - nu))

    @property
    def theta0(self) -> float:
        """Critical angle of incidence arctan(tan theta0) (eq 23), radians."""
        return math.atan(self.tan_theta0)

    # ---- single quantities ---------------------------------------------------------
    def psi(self, x0: ArrayLike) -> NDArray[np.float64]:
        """psi(x0) = tan theta(x0) / tan theta0 (eq 23 with eqs 1, 2), dimensionless; 0 at
        the centre, growing without bound towards the ends."""
        u0, H = self.rod.drive(self.rod.check_x0(x0))
        return self._psi(u0, H)

    def load_factor(self, x0: ArrayLike) -> NDArray[np.float64]:
        """Phi(x0) = 9 pi (1 - nu) N / (4 G R^(1/2) H^(3/2)), the value of F(tau0) the
        preload requires (eq 10, mean contact force N); >= 8: the contact never opens."""
        _, H = self.rod.drive(self.rod.check_x0(x0))
        return self._load_factor(H)

    def opens(self, x0: ArrayLike) -> NDArray[np.bool_]:
        """True where the contact opens once per period (Phi < 8), i.e. where this model
        applies; False near the ends of the rod."""
        return self.load_factor(x0) < balance.PHI_MAX

    def tau0(self, x0: ArrayLike) -> NDArray[np.float64]:
        """tau0(x0) (rad) in (-pi/2, pi/2): start of contact fixed by the preload,
        F(tau0) = Phi (eq 10, 11); nan where the contact never opens."""
        m0, mc0 = balance.solve(self.load_factor(x0))
        return balance.tau0_of(m0, mc0)

    def stall_thrust(self, x0: ArrayLike) -> NDArray[np.float64]:
        """Mean tangential force on the held rotor (N), signed: positive along +x on the
        rotor's bottom surface (counter-clockwise rotation, x0 < 0), negative for x0 > 0,
        0 at the centre; nan where the contact never opens. mu N times eq 41."""
        u0, H = self.rod.drive(self.rod.check_x0(x0))
        m0, mc0 = balance.solve(self._load_factor(H))
        ratio = thrust.impulse_ratio(self._psi(u0, H), m0, mc0)
        return thrust.stall_thrust(ratio, u0, self.mu, self.preload)

    # ---- everything at once --------------------------------------------------------
    def profile(self, x0: ArrayLike) -> MotorProfile:
        """Every quantity of ``MotorProfile`` at x0, from one evaluation of the drive and
        one root solve."""
        x = self.rod.check_x0(x0)
        u0, H = self.rod.drive(x)
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            tan_theta = np.abs(u0) / H
        psi = self._psi(u0, H)
        phi = self._load_factor(H)
        m0, mc0 = balance.solve(phi)
        ratio = thrust.impulse_ratio(psi, m0, mc0)
        force = thrust.stall_thrust(ratio, u0, self.mu, self.preload)
        return MotorProfile(
            x0=x, u0=u0, H=H, tan_theta=tan_theta, psi=psi, load_factor=phi,
            opens=phi < balance.PHI_MAX, m0=m0, tau0=balance.tau0_of(m0, mc0),
            h=H * (mc0 - m0), impulse_ratio=ratio,
            thrust_ratio=force / (self.mu * self.preload), stall_thrust=force,
            beta=self.beta,
        )

    def contact(self, x0: float) -> Contact:
        """The paper's contact at one point x0, as a ``core.Contact`` with SI ``scales``
        (its drive along +x: multiply tangential results by sign u0(x0) for the rod's
        frame). ValueError where the contact never opens. Its
        ``scales.normal_impulse / scales.period`` is the preload and
        ``scales.tangential_impulse / scales.period`` the magnitude of the stall thrust."""
        x = self.rod.check_x0(x0)
        if x.ndim != 0:
            raise ValueError(f"x0 must be one number for contact(), got shape {x.shape}")
        p = self.profile(x)
        if not p.opens:
            raise ValueError(
                f"x0 = {float(x)!r}: the contact never opens there (Phi = "
                f"{float(p.load_factor):g} >= 8): the preload exceeds what an intermittent "
                "contact can carry, and the model does not apply"
            )
        return Contact.from_physical(
            R=self.R, G=self.G, nu=self.nu, mu=self.mu, H=float(p.H), u0=abs(float(p.u0)),
            h=float(p.h), omega=self.rod.omega, R2=self.rod_R, G2=self.rod_G, nu2=self.rod_nu,
        )

    # ---- helpers -------------------------------------------------------------------
    def _psi(self, u0: NDArray[np.float64], H: NDArray[np.float64]) -> NDArray[np.float64]:
        tan_theta0 = self.tan_theta0
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            return np.abs(u0) / H / tan_theta0

    def _load_factor(self, H: NDArray[np.float64]) -> NDArray[np.float64]:
        R, G, nu = self.equivalent
        return balance.load_factor(self.preload, R, G, nu, H)
