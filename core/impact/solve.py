"""The exact oblique impact: rebound velocities and spins, restitutions, rebound angle,
contact time and the force histories of one impact (``solve``), and Maw, Barber &
Fawcett's normalised rebound (``normalised``).

Method (``kernel``): Hertz normal contact and the Mindlin-Deresiewicz tangential history
by the method of dimensionality reduction (``core.numerics.mdr.march``: exact for any
history of normal and tangential motion under the Cattaneo-Mindlin approximation, with
an error ~ springs^-2), coupled to the rigid-body equations of motion reduced to the two
relative coordinates of the contact (approach and slip of the contact points, with the
masses m_n and m_t of ``bodies.Impact``), integrated by velocity Verlet with step-doubling
error control (second order; the tolerance bounds each step's error). The body
velocities after the impact follow from the impulses: J_n = m_n (v_n + v_n'),
J_t = m_t (v_slip' - v_slip) on the sphere (minus on the target), so

    vx' = vx + J_t / m1,   w' = w - R1 J_t / I1,   vz' = vz + J_n / m1,
    vx2' = vx2 - J_t / m2, w2' = w2 - R2 J_t / I2, vz2' = vz2 - J_n / m2.

Assumptions (those of MBF 1976/1981 and of Chung & Ooi's theory): small strains, the
contact normal fixed during the impact, normal and tangential problems uncoupled
(exact for Dundurs' beta = 0: identical or rigid-on-elastic pairs with equal (1-2nu)/G
terms), Cattaneo-Mindlin tractions (the non-axisymmetric terms dropped), quasi-static
contact (no waves), Coulomb friction with one coefficient.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from core.impact.bodies import BOUNDS, Impact, check_real
from core.impact.kernel import impact as _integrate
from core.impact.kernel import separation_time, spring_row
from core.impact.normal import dashpot

DEFAULT_SPRINGS = 2000
DEFAULT_TOL = 1e-9
MAX_SPRINGS = 100_000
MAX_STEPS = 2_000_000


def check_numerics(springs: object, tol: object) -> tuple[int, float]:
    """(springs, tol) checked: springs an integer in [16, 100000], tol in [1e-13, 1e-3]."""
    if isinstance(springs, bool) or not isinstance(springs, int | np.integer) or not (
            16 <= springs <= MAX_SPRINGS):
        raise ValueError(f"springs must be an integer in [16, {MAX_SPRINGS}], got {springs!r}")
    return int(springs), check_real("tol", tol, 1e-13, 1e-3)


@dataclass(frozen=True)
class Normalised:
    """One impact in MBF's units: incidence psi1 and chi in, rebound out."""

    psi1: float
    chi: float
    e: float  # normal restitution obtained (-d' at separation)
    psi2: float  # rebound of the contact point D'(end) / e (MBF's Psi2)
    slip_ratio: float  # D'(end) / psi1 = v_slip' / v_slip (nan for psi1 = 0)
    contact_time: float  # in alpha* / v_n (2.9432 for Hertz, e = 1)
    slip_work: float  # frictional dissipation in mu E* alpha* a* delta* (kernel's units)
    steps: int
    rejected: int
    history: NDArray[np.float64] = field(repr=False)  # rows of kernel.HISTORY_COLUMNS

    def energy_balance(self) -> float:
        """Tangential kinetic energy lost minus the slip work, both in the units of
        (1/2) m_t v_slip-units: psi1^2 - D'(end)^2 - (15/4) chi S. Zero for an exact
        history (the springs store nothing once the contact has ended)."""
        dv_end = self.history[-1, 4]
        return self.psi1 ** 2 - dv_end ** 2 - 3.75 * self.chi * self.slip_work


def normalised(psi1: float, chi: float, e: float = 1.0, springs: int = DEFAULT_SPRINGS,
               tol: float = DEFAULT_TOL, *, h0: float = 1e-3, bound: str = "total"
               ) -> Normalised:
    """The impact in MBF's normalised form: D'' = -(15/8) chi T, d'' = -(15/16) P (plus
    the dashpot for e < 1), from d = 0, d' = 1, D = 0, D' = psi1 (``kernel``).
    ``tol`` 0 with ``h0`` gives fixed steps (for convergence studies); ``bound`` as
    ``Impact.bound``."""
    psi1 = check_real("psi1", psi1, -1e6, 1e6)
    chi = check_real("chi", chi, 0.0, 100.0, lo_open=True)
    e = check_real("e", e, 0.05, 1.0)
    springs, tol = (check_numerics(springs, tol) if tol != 0.0
                    else (check_numerics(springs, 1e-9)[0], 0.0))
    h0 = check_real("h0", h0, 1e-7, 0.5, lo_open=True)
    x, scale = spring_row(springs)
    gamma = dashpot(e, springs, tol if tol > 0 else 1e-10)
    if bound not in BOUNDS:
        raise ValueError(f"bound must be one of {', '.join(BOUNDS)}, got {bound!r}")
    out, rejected = _integrate(psi1, chi, gamma, x, scale, tol, h0, MAX_STEPS,
                               bound == "total")
    if rejected < 0:
        raise RuntimeError(f"the impact did not end within {MAX_STEPS} steps (tol {tol:g})")
    last, prev = out[-1], out[-2]
    t_c = float(separation_time(prev[0], prev[1], prev[2], last[0], last[1], last[2]))
    e_obt = float(-last[2])
    return Normalised(
        psi1=psi1, chi=chi, e=e_obt, psi2=float(last[4]) / e_obt,
        slip_ratio=float(last[4]) / psi1 if psi1 else math.nan,
        contact_time=t_c, slip_work=float(out[:, 7].sum()), steps=out.shape[0] - 1,
        rejected=rejected, history=out)


@dataclass(frozen=True)
class ImpactResult:
    """One impact in SI units (``solve``). Velocities in m/s, spins in rad/s (about y,
    ``bodies``), forces in N on the sphere (z normal, x tangential), times in s."""

    impact: Impact
    vx: float
    vz: float
    w: float
    vx2: float
    vz2: float
    w2: float
    normal_cor: float  # e obtained: separation speed / approach speed
    tangential_cor: float  # vx' / vx of the sphere's centre (nan for vx = 0)
    contact_point_cor: float  # beta = -v_slip' / v_slip (Walton's sign; nan for v_slip = 0)
    rebound_angle: float  # atan(v_slip' / v_n') of the contact point (deg, + forward)
    incidence_angle: float  # atan(v_slip / v_n) (deg)
    contact_time: float
    normal_impulse: float  # J_n on the sphere (N s)
    tangential_impulse: float  # J_t on the sphere (N s)
    dissipated: float  # kinetic energy lost (J): slip work plus the dashpot's
    slip_work: float  # frictional dissipation of the history (J)
    psi1: float
    psi2: float
    chi: float
    t: NDArray[np.float64] = field(repr=False)
    P: NDArray[np.float64] = field(repr=False)  # normal force on the sphere, +z
    T: NDArray[np.float64] = field(repr=False)  # tangential force on the sphere, +x
    approach: NDArray[np.float64] = field(repr=False)  # alpha (m)
    slip: NDArray[np.float64] = field(repr=False)  # relative displacement of the contact
    # points (m)
    steps: int = 0

    @property
    def slip_velocity(self) -> float:
        """v_slip' = (vx' - R1 w') - (vx2' + R2 w2') (m/s)."""
        r2 = 0.0 if not self.impact.target.free else self.impact.target.radius
        return (self.vx - self.impact.radius * self.w) - (self.vx2 + r2 * self.w2)

    def angular_momentum_about_contact(self, after: bool = True) -> float:
        """Angular momentum about y of the sphere about the contact point (a point fixed
        on the target's surface for a fixed target): I1 w + m1 R1 vx (kg m^2 / s)."""
        i = self.impact
        w, vx = (self.w, self.vx) if after else (i.w, i.vx)
        return i.inertia * w + i.mass * i.radius * vx

    def kinetic_energy(self, after: bool = True) -> float:
        """Kinetic energy of the bodies (J; a fixed target has none)."""
        i = self.impact
        if after:
            v = (self.vx, self.vz, self.w, self.vx2, self.vz2, self.w2)
        else:
            v = (i.vx, i.vz, i.w, i.vx2, i.vz2, i.w2)
        e = 0.5 * i.mass * (v[0] ** 2 + v[1] ** 2) + 0.5 * i.inertia * v[2] ** 2
        if i.target.free:
            m2 = i.target.mass
            e += 0.5 * m2 * (v[3] ** 2 + v[4] ** 2) + 0.5 * i.target.K2 * m2 * (
                i.target.radius * v[5]) ** 2
        return e


def solve(impact: Impact, springs: int = DEFAULT_SPRINGS, tol: float = DEFAULT_TOL
          ) -> ImpactResult:
    """The exact impact of ``impact`` (``Impact``, SI units) with ``springs`` springs and
    error tolerance ``tol`` (module docstring). ValueError for bad numerics."""
    if not isinstance(impact, Impact):
        raise ValueError(f"impact must be a core.impact.Impact, got {type(impact).__name__}")
    springs, tol = check_numerics(springs, tol)
    n = normalised(impact.psi1, impact.chi, impact.e, springs, tol, bound=impact.bound)
    i = impact
    vn, ts = i.v_n, i.time_scale
    slip_unit = i.mu * i.E_star * i.alpha_star / (4.0 * i.G_e)  # delta*
    vslip_unit = slip_unit / ts
    h = n.history
    vn_after = float(-h[-1, 2]) * vn  # separation speed
    vslip_after = float(h[-1, 4]) * vslip_unit
    J_n = i.m_n * (vn + vn_after)
    J_t = i.m_t * (vslip_after - i.slip_velocity)
    m2 = i.target.mass
    free = i.target.free
    vx2 = i.vx2 - J_t / m2 if free else 0.0
    vz2 = i.vz2 - J_n / m2 if free else 0.0
    w2 = i.w2 - i.target.radius * J_t / (i.target.K2 * m2 * i.target.radius ** 2) if free \
        else 0.0
    force_unit = i.m_n * vn ** 2 / i.alpha_star  # of f
    p0 = i.E_star * i.alpha_star * math.sqrt(i.R_star * i.alpha_star)
    vs = i.slip_velocity
    res = ImpactResult(
        impact=i,
        vx=i.vx + J_t / i.mass, vz=i.vz + J_n / i.mass,
        w=i.w - i.radius * J_t / i.inertia,
        vx2=vx2, vz2=vz2, w2=w2,
        normal_cor=n.e,
        tangential_cor=(i.vx + J_t / i.mass) / i.vx if i.vx else math.nan,
        contact_point_cor=-vslip_after / vs if vs else math.nan,
        rebound_angle=math.degrees(math.atan2(vslip_after, vn_after)),
        incidence_angle=math.degrees(i.incidence),
        contact_time=n.contact_time * ts,
        normal_impulse=J_n, tangential_impulse=J_t,
        dissipated=math.nan, slip_work=n.slip_work * i.mu * p0 * slip_unit,
        psi1=n.psi1, psi2=n.psi2, chi=n.chi,
        t=h[:, 0] * ts, P=h[:, 5] * force_unit, T=-h[:, 6] * i.mu * p0,
        approach=np.maximum(h[:, 1], 0.0) * i.alpha_star, slip=h[:, 3] * slip_unit,
        steps=n.steps)
    lost = res.kinetic_energy(after=False) - res.kinetic_energy(after=True)
    return replace(res, dissipated=lost)


__all__ = ["DEFAULT_SPRINGS", "DEFAULT_TOL", "ImpactResult", "Normalised", "check_numerics",
           "normalised", "solve"]
