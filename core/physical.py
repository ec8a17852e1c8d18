"""Physical units at the edge: SI inputs to the dimensionless problem, and the SI scales
that turn every dimensionless result back into newtons, metres, pascals, joules and N s.

Two dissimilar bodies (docs/physics.md, section 11.1) enter through Goodman's
approximation, which neglects the coupling of the normal and tangential problems (measured
by Dundurs' beta, ``dundurs_beta``). Under it every formula of the paper's eqs 5-41 holds
with the contact's effective constants, and those are exactly the constants of one pair of
identical spheres, the *equivalent pair* (``equivalent_pair``):

    G_eq = 2 G1 G2 / (G1 + G2)              (harmonic mean of the shear moduli)
    nu_eq = (nu1 G2 + nu2 G1) / (G1 + G2)   (the Poisson ratios weighted by compliance)
    R_eq = 2 R1 R2 / (R1 + R2)              (harmonic mean of the radii; 2 R1 for a flat R2)

for which G_eq / (1 - nu_eq) = E* (1/E* = (1 - nu1)/(2 G1) + (1 - nu2)/(2 G2)),
G_eq / (2 (2 - nu_eq)) = G* (1/G* = (2 - nu1)/G1 + (2 - nu2)/G2) and R_eq / 2 is the
effective radius. Identical bodies are their own equivalent pair, bit for bit.

The pair's centre motion (eqs 42, 43) is half the relative tangential displacement of
the two surfaces; each body takes its own share of it, in proportion to its tangential
compliance (2 - nu) / G (``upper_share``; docs/physics.md, section 11.1).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from core.validation import DOMAIN, check_param, is_flat, shown

SQRT8 = 2.0 * math.sqrt(2.0)

#: The |beta| above which ``beta_warning`` warns that Goodman's approximation may be poor,
#: from the 3D boundary-element referee's map of the model's error (``core.bem``,
#: docs/bem.md): on the paper's loading T(tau)'s error grows as beta^2 and passes 1 % of
#: T0 at |beta| = 0.43 for mu = 0.2, and near 0.26 for mu = 0.1 (estimated from one
#: coarse run); this bound holds for mu from 0.1 up.
BETA_WARN = 0.25


def equivalent_pair(R: float, G: float, nu: float, R2: float | None = None,
                    G2: float | None = None, nu2: float | None = None
                    ) -> tuple[float, float, float]:
    """(R_eq, G_eq, nu_eq): the identical spheres with the effective constants of body 1
    (R, G, nu) against body 2 (R2, G2, nu2; each None means body 1's value, R2 = inf a
    flat face). SI (m, Pa). Identical bodies return (R, G, nu) themselves."""
    R2 = R if R2 is None else R2
    G2 = G if G2 is None else G2
    nu2 = nu if nu2 is None else nu2
    if G2 == G and nu2 == nu:
        G_eq, nu_eq = G, nu
    else:
        G_eq = 2.0 * G * (G2 / (G + G2))
        nu_eq = (nu * G2 + nu2 * G) / (G + G2)
    if R2 == R:
        R_eq = R
    elif math.isinf(R2):
        R_eq = 2.0 * R
    else:
        R_eq = 2.0 * R * (R2 / (R + R2))
    return R_eq, G_eq, nu_eq


def upper_share(G: float, nu: float, G2: float | None = None, nu2: float | None = None
                ) -> float:
    """The fraction of the contact's relative tangential displacement that body 1 (the
    upper body: G in Pa, nu) takes against body 2 (the lower, driven body: G2, nu2; None
    means body 1's value), under Goodman's approximation (docs/physics.md, section 11.1).

    Parameters
    ----------
    G, nu : float
        Shear modulus (Pa) and Poisson ratio of the upper body.
    G2, nu2 : float or None
        The same of the lower body; None: the upper body's value.

    Returns
    -------
    float
        lambda = C1 / (C1 + C2) in (0, 1), with C = (2 - nu) / G each body's tangential
        compliance (Cerruti: a traction q(r) displaces the surface point r = 0 by
        C / 2 times the integral of q over 0 < r < a); exactly 1/2 for identical bodies.

    See Also
    --------
    equivalent_pair : the identical pair whose u2 is half the relative displacement.
    core.Contact.centre_displacement : the upper body's own motion, 2 lambda times it.
    """
    G2 = G if G2 is None else G2
    nu2 = nu if nu2 is None else nu2
    if G2 == G and nu2 == nu:
        return 0.5
    upper = (2.0 - nu) * G2  # C1 G1 G2: no product here can overflow (G <= 1e13)
    return upper / (upper + (2.0 - nu2) * G)


def dundurs_beta(G: float, nu: float, G2: float, nu2: float) -> float:
    """Dundurs' second constant beta = [(1 - 2 nu1)/G1 - (1 - 2 nu2)/G2] /
    [2 ((1 - nu1)/G1 + (1 - nu2)/G2)] (dimensionless): the coupling of normal and
    tangential tractions that Goodman's approximation neglects. 0 for identical bodies;
    it changes sign when the bodies are swapped.

    For fixed Poisson ratios beta is monotonic in G1 / G2, between -f(nu2) (body 1 rigid)
    and f(nu1) (body 2 rigid), f(nu) = (1 - 2 nu) / (2 (1 - nu)), which falls from 3/4 at
    nu = -1 to 0 at nu = 1/2. So over the domain (nu in (-1, 1/2]) |beta| < 3/4, and
    |beta| <= 1/2 when both nu >= 0 (the bound usually quoted); an auxetic body reaches
    beyond it (G2 = 1e3 Pa, nu2 = -0.9 against steel: beta = -0.737)."""
    num = (1.0 - 2.0 * nu) * G2 - (1.0 - 2.0 * nu2) * G
    return num / (2.0 * ((1.0 - nu) * G2 + (1.0 - nu2) * G))


def beta_warning(beta: float) -> str | None:
    """A sentence for users when |beta| > BETA_WARN, else None."""
    if abs(beta) <= BETA_WARN:
        return None
    return (f"Dundurs' beta = {beta:.3g}: the bodies are elastically dissimilar enough "
            f"(|beta| > {BETA_WARN:g}) that Goodman's approximation, which neglects the "
            "coupling of normal and tangential tractions, may be in error by more than 1 % "
            "of T0 in T(tau) (the 3D boundary-element referee's map, docs/bem.md)")


def second_body(R2: object, G2: object, nu2: object) -> tuple[float | None, ...]:
    """(R2, G2, nu2) validated: None (body 1's value), or G2 in DOMAIN["G"], nu2 in
    DOMAIN["nu"], R2 in DOMAIN["R"] or +inf (a flat face). ValueError naming the input."""
    R2_ = None if R2 is None else (
        math.inf if is_flat(R2) else DOMAIN["R"].check("R2", R2))
    G2_ = None if G2 is None else DOMAIN["G"].check("G2", G2)
    nu2_ = None if nu2 is None else DOMAIN["nu"].check("nu2", nu2)
    return R2_, G2_, nu2_


@dataclass(frozen=True)
class PhysicalInputs:
    """SI inputs of eq 3: radius R (m), shear modulus G (Pa), Poisson ratio nu, friction
    coefficient mu, vertical and horizontal drive amplitudes H and u0 (m), gap h at t = 0
    (m; h < 0 is a preload) and angular frequency omega (rad/s); optionally a second,
    dissimilar body R2 (m; inf: a flat face), G2 (Pa), nu2 (None: body 1's value, the
    paper's identical spheres).

    Validated (ValueError naming the input): each against ``core.DOMAIN`` (R2 also inf),
    whose ranges keep every ``Scales`` value finite; then h in (-H, H), and psi of u0 / H,
    mu and the effective Poisson ratio in [0, 1e12]."""

    R: float
    G: float
    nu: float
    mu: float
    H: float
    u0: float
    h: float
    omega: float
    R2: float | None = None
    G2: float | None = None
    nu2: float | None = None

    def __post_init__(self) -> None:
        for name in ("R", "G", "nu", "mu", "H", "u0", "h", "omega"):
            object.__setattr__(self, name, check_param(name, getattr(self, name)))
        R2, G2, nu2 = second_body(self.R2, self.G2, self.nu2)
        object.__setattr__(self, "R2", R2)
        object.__setattr__(self, "G2", G2)
        object.__setattr__(self, "nu2", nu2)
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
    def equivalent(self) -> tuple[float, float, float]:
        """(R_eq, G_eq, nu_eq), the identical pair of the two bodies (``equivalent_pair``);
        (R, G, nu) when there is no second body."""
        return equivalent_pair(self.R, self.G, self.nu, self.R2, self.G2, self.nu2)

    @property
    def upper_share(self) -> float:
        """The upper body's share of the relative tangential displacement
        (``upper_share``); 1/2 when there is no second body."""
        return upper_share(self.G, self.nu, self.G2, self.nu2)

    @property
    def beta(self) -> float:
        """Dundurs' beta of the two bodies (``dundurs_beta``); 0 for identical ones."""
        G2 = self.G if self.G2 is None else self.G2
        nu2 = self.nu if self.nu2 is None else self.nu2
        return dundurs_beta(self.G, self.nu, G2, nu2)

    @property
    def psi(self) -> float:
        """psi = 2 (1 - nu) u0 / (mu (2 - nu) H) (eq 23), nu the effective nu_eq; for two
        bodies 4 G* u0 / (mu E* H)."""
        nu = self.equivalent[2]
        # in this order no product can underflow to a zero divisor (H >= 1e-15, mu > 0)
        return 2.0 * (1.0 - nu) / (2.0 - nu) * (self.u0 / self.H) / self.mu


@dataclass(frozen=True)
class Scales:
    """SI scales of one contact: multiply a dimensionless result by its scale.

    T0 (N, eq 37) for T / T0; P0 = T0 / mu (N) for P / P0; a_star = sqrt(R (H - h) / 2) (m)
    for radii; p_star = 4 G a* / ((1 - nu) pi R) (Pa) for pressure, and mu p_star for
    tractions; alpha_star = H - h (m) for the approach; u0 (m) and v_star = omega u0 (m/s)
    for the contact-centre motion; normal_impulse (eq 10) and tangential_impulse (eq 41)
    in N s; period = 2 pi / omega (s), and time t = tau / omega; energy = T0 u0 (J) for
    ``Contact.dissipated_energy`` and energy_density = T0 u0 / (pi a*^2) (J/m^2) for
    ``Contact.dissipation_density``. For two dissimilar bodies every scale is that of
    the equivalent pair (G, nu, R replaced by G_eq, nu_eq, R_eq), and beta is Dundurs'
    constant (0 for identical bodies; ``beta_warning`` says when it is large).
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
    energy: float = math.nan
    energy_density: float = math.nan
    beta: float = 0.0

    @property
    def beta_warning(self) -> str | None:
        """A warning for users when |beta| > BETA_WARN, else None."""
        return beta_warning(self.beta)

    @classmethod
    def of(cls, inputs: PhysicalInputs, F0: float, impulse_ratio: float) -> Scales:
        """Scales of ``inputs``, given F(tau0) and T_imp / (mu P_imp) of the same contact."""
        (R, G, nu), mu, H = inputs.equivalent, inputs.mu, inputs.H
        P0 = SQRT8 * G / (3.0 * (1.0 - nu)) * math.sqrt(R) * H**1.5
        a_star = math.sqrt(R * (H - inputs.h) / 2.0)
        p_star = 4.0 * G * a_star / ((1.0 - nu) * math.pi * R)
        normal_impulse = 8.0 * G * math.sqrt(R) * H**1.5 * F0 / (9.0 * (1.0 - nu) * inputs.omega)
        energy = mu * P0 * inputs.u0
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
            energy=energy,
            energy_density=energy / (math.pi * a_star) / a_star,
            beta=inputs.beta,
        )
