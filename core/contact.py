"""One contact of the problem: the public face of the closed-form solution."""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from core import dissipation, hertz, kernels, tangential
from core.clock import half_sines
from core.elliptic import impulse_factor
from core.physical import PhysicalInputs, Scales
from core.timeline import Timeline
from core.validation import DOMAIN, as_reals, check_param, common_shape, shown

MAX_GRID = 10**8


def _grid_size(n: object) -> int:
    """n as an int if it is an integer in [2, MAX_GRID]; ValueError otherwise."""
    if (isinstance(n, bool | np.timedelta64) or not isinstance(n, int | np.integer)
            or not 2 <= n <= MAX_GRID):
        raise ValueError(f"n must be an integer in [2, {MAX_GRID}], got {shown(n)}")
    return operator.index(n)


#: Timelines of single times a Contact keeps (``Contact._timeline``).
INSTANTS = 8


@dataclass(frozen=True)
class Contact:
    """Two identical elastic spheres in one intermittent oblique contact (Zharii 1996).

    Parameters (validated against ``core.DOMAIN``; ValueError names the parameter, value
    and allowed range):

    - psi in [0, 1e12]: drive ratio 2 (1 - nu) u0 / (mu (2 - nu) H) = tan theta / tan theta0
      (eq 23); psi <= 1 is full stick, psi > 1 slip, partial stick and counter-slip.
    - tau0 in (-pi/2, pi/2): start of contact, sin tau0 = h / H (eq 4); tau0 < 0 is a preload.
    - mu in (0, 1e3]: friction coefficient; nu in (-1, 0.5]: Poisson ratio.
    - upper_share in (0, 1): the upper body's share of the relative tangential
      displacement, 1/2 (the default) for the paper's identical spheres; it enters only
      each body's centre motion (``core.physical.upper_share``; ``from_physical`` sets it).

    Times tau = omega t are in radians and taken modulo 2 pi; every method accepts scalars
    or arrays and returns arrays of the broadcast shape, zero (never nan) outside contact
    (the functions of time return read-only arrays, as ``at`` does: copy one to modify it).
    Times and radii r may be Python or numpy ints and floats of any precision, alone, in
    lists or in arrays; any other dtype (bool, complex, str, bytes, object, datetime) raises
    TypeError, and nan or inf raises ValueError naming the first such element: no result
    is ever nan.
    Results are dimensionless: forces in T0 (eq 37) or P0 = T0 / mu, radii in
    a* = sqrt(R (H - h) / 2), pressure in p* = 4 G a* / ((1 - nu) pi R), tractions in mu p*.
    ``scales`` carries the SI values of those scales when built with ``from_physical``.
    """

    psi: float
    tau0: float
    mu: float = 0.2
    nu: float = 0.3
    scales: Scales | None = field(default=None, repr=False, compare=False)
    upper_share: float = 0.5

    def __post_init__(self) -> None:
        for name in ("psi", "tau0", "mu", "nu", "upper_share"):
            object.__setattr__(self, name, check_param(name, getattr(self, name)))

    @classmethod
    def from_physical(
        cls,
        *,
        R: float,
        G: float,
        nu: float,
        mu: float,
        H: float,
        u0: float,
        h: float,
        omega: float,
        R2: float | None = None,
        G2: float | None = None,
        nu2: float | None = None,
    ) -> Contact:
        """The contact of SI inputs (R, H, u0, h in m; G in Pa; omega in rad/s), with
        ``scales`` set. Each input must lie in its range of ``core.DOMAIN``, h in (-H, H),
        and psi of u0 / H in [0, 1e12] (ValueError naming the inputs otherwise); every
        scale is then finite.

        A second, dissimilar body (R2 in m, inf for a flat face; G2 in Pa; nu2; each None:
        body 1's value, the paper's identical spheres) enters under Goodman's
        approximation: the contact is that of the equivalent identical pair
        (``core.physical.equivalent_pair``), so ``nu`` is then its effective Poisson ratio
        nu_eq, psi = 4 G* u0 / (mu E* H), and ``scales`` (also Dundurs' ``beta``) are
        the pair's."""
        inputs = PhysicalInputs(R=R, G=G, nu=nu, mu=mu, H=H, u0=u0, h=h, omega=omega,
                                R2=R2, G2=G2, nu2=nu2)
        c = cls(psi=inputs.psi, tau0=inputs.tau0, mu=inputs.mu, nu=inputs.equivalent[2],
                upper_share=inputs.upper_share)
        return replace(c, scales=Scales.of(inputs, c.F0, c.impulse_ratio))

    # ---- scalars -------------------------------------------------------------------
    @cached_property
    def _half_e(self) -> tuple[float, float]:
        """(sin(e/2), cos(e/2)), e = pi/2 - tau0 (``core.clock.half_sines``)."""
        return half_sines(self.tau0)

    @property
    def tau_end(self) -> float:
        """End of contact, pi - tau0."""
        return math.pi - self.tau0

    @cached_property
    def tau1(self) -> float:
        """End of partial stick (eq 31), in (pi/2, pi - tau0]; nan when psi <= 1.

        (For psi within ~1e-12 of 1 and grazing contact, tau1 and pi - tau0 round to the
        same float; tau1 is then reported as pi - tau0.)"""
        return min(tangential.tau1(self.psi, *self._half_e), self.tau_end)

    @cached_property
    def F0(self) -> float:
        """F(tau0) of eq 11 (dimensionless), the elliptic factor of the normal impulse."""
        s, c = self._half_e
        return float(impulse_factor(s * s, c * c))

    @property
    def theta0(self) -> float:
        """Critical angle of incidence arctan(mu (2 - nu) / (2 (1 - nu))) (eq 23), radians."""
        return math.atan(self.mu * (2.0 - self.nu) / (2.0 * (1.0 - self.nu)))

    @property
    def theta(self) -> float:
        """Angle of incidence arctan(u0 / H) = arctan(psi tan theta0), radians."""
        return math.atan(self.psi * math.tan(self.theta0))

    @cached_property
    def impulse_ratio(self) -> float:
        """T_imp / (mu P_imp) (eq 41): psi for psi <= 1, largest (1) at psi = 1."""
        s, c = self._half_e
        return tangential.impulse_ratio_float(self.psi, s * s, c * c)

    # ---- friction dissipation (core.dissipation) --------------------------------------
    @cached_property
    def dissipated_energy(self) -> float:
        """D / (T0 u0): the work of the drive on the held body over one contact, all of it
        dissipated by slip, (4/5)(1 - sin tau0)^(5/2)(psi - 1)/(psi + 1) for psi > 1 and
        0 for psi <= 1 (docs/physics.md, section 11.2). ``scales.energy`` is T0 u0 (J)."""
        return float(dissipation.energy(self.psi, self._half_e[0]))

    def dissipation_density(self, r: ArrayLike) -> NDArray[np.float64]:
        """q(r) / (T0 u0 / (pi a*^2)): the friction work per unit area over one contact at
        radius r (units of a*), exact; 0 for psi <= 1 and outside r < 1, so that
        int_0^1 q(r) 2 r dr = ``dissipated_energy``. ``scales.energy_density`` is
        T0 u0 / (pi a*^2) (J/m^2)."""
        return dissipation.density(self._radii(r), self.psi, self._half_e[0])

    def dissipation_rate(self, r: ArrayLike, tau: ArrayLike) -> NDArray[np.float64]:
        """Friction power per unit area at radius r (units of a*) and time tau, in units
        of T0 u0 omega / (pi a*^2): |tau_u| times the slip speed (eqs 14, 21, 27); 0 in
        the stick zone and outside contact; its integral over tau is
        ``dissipation_density``. r broadcasts against tau."""
        r, tau = self._radii(r), as_reals(tau, "tau")
        line = self._timeline(tau)
        if self.psi <= 1.0:
            return np.zeros(np.broadcast_shapes(r.shape, tau.shape))
        return dissipation.rate(r, tau, line.phase, line.approach, line.stick_radius_squared,
                                self.psi, self._half_e[0])

    # ---- time grid -------------------------------------------------------------------
    def tau_grid(self, n: int = 400) -> NDArray[np.float64]:
        """About n sorted times over [tau0, pi - tau0] that hold tau0, pi/2, tau1 and
        pi - tau0 exactly, with n/8 extra points in partial stick (short for large psi)."""
        return kernels.tau_grid(self.psi, self.tau0, self.tau1, _grid_size(n))

    # ---- functions of time -----------------------------------------------------------
    def at(self, tau: ArrayLike) -> Timeline:
        """Every quantity below at the times tau, each computed on first use and kept
        (``core.timeline``): ask it for several quantities on the same times rather than
        calling the methods one by one.  For one time (a scalar or one element) the
        Timeline is this contact's own for that time, shared by every call at it (its
        tau is a read-only copy)."""
        return self._timeline(as_reals(tau, "tau"))

    @cached_property
    def _instants(self) -> tuple[dict[tuple, Timeline], dict[bytes, dict]]:
        """The Timelines of single times asked so far (at most `INSTANTS`), by the time's
        shape and bytes, and the passes (`Timeline.passes`) that those of one time share,
        by the time's bytes."""
        return {}, {}

    def _timeline(self, tau: NDArray[np.float64]) -> Timeline:
        """``at`` of times already validated.  A view asks for many quantities at one
        time, one method at a time (the phase, the radii, the forces, the pressure and
        the traction at the time shown): each quantity of one time is computed once.
        (Threads may share a contact: every step here is one operation on a dict.)"""
        if tau.size != 1:
            return Timeline(tau, self.psi, self._half_e[0], upper_share=self.upper_share)
        lines, passes = self._instants
        time = tau.tobytes()
        line = lines.get((tau.shape, time))
        if line is None:
            if len(lines) >= INSTANTS:
                lines.clear()
                passes.clear()
            held = np.array(tau, dtype=np.float64)
            held.setflags(write=False)
            line = lines[tau.shape, time] = Timeline(held, self.psi, self._half_e[0],
                                                     passes.setdefault(time, {}),
                                                     self.upper_share)
        return line

    def _along(self, tau: ArrayLike, name: str) -> NDArray:
        """Quantity ``name`` of ``at(tau)``."""
        return getattr(self._timeline(as_reals(tau, "tau")), name)

    def phase(self, tau: ArrayLike) -> NDArray[np.int_]:
        """Phase code at each tau: 0 no contact, 1 full stick (psi <= 1), 2 slip while
        loading, 3 partial stick, 4 counter-slip (``core.Phase``)."""
        return self._along(tau, "phase")

    def approach(self, tau: ArrayLike) -> NDArray[np.float64]:
        """alpha / (H - h), the approach of the sphere centres (eq 8)."""
        return self._along(tau, "approach")

    def normal_force(self, tau: ArrayLike) -> NDArray[np.float64]:
        """P / P0 = (sin tau - sin tau0)^(3/2) (eq 9); also mu P / T0."""
        return self._along(tau, "normal_force")

    def tangential_force(self, tau: ArrayLike) -> NDArray[np.float64]:
        """T / T0 (eqs 38, 39): force on the upper sphere, positive along the drive."""
        return self._along(tau, "tangential_force")

    def contact_radius(self, tau: ArrayLike) -> NDArray[np.float64]:
        """a / a* (eq 7, 8)."""
        return self._along(tau, "contact_radius")

    def stick_radius(self, tau: ArrayLike) -> NDArray[np.float64]:
        """b / a* (eq 30): a in full stick, the shrinking stick disc in partial stick,
        0 in the slip phases and outside contact."""
        return self._along(tau, "stick_radius")

    @staticmethod
    def _radii(r: ArrayLike) -> NDArray[np.float64]:
        """|r| validated, capped at 2: every contact lies within r = 1 (a <= a*), so the
        cap changes no result and r^2 cannot overflow."""
        return np.minimum(np.abs(as_reals(r, "r")), 2.0)

    def pressure(self, r: ArrayLike, tau: ArrayLike) -> NDArray[np.float64]:
        """p / p* at radius r (units of a*) and time tau (eq 6); r broadcasts against tau."""
        r = self._radii(r)
        r, a2 = np.broadcast_arrays(r, self._timeline(as_reals(tau, "tau")).approach)
        return hertz.pressure(r, a2)

    def traction(self, r: ArrayLike, tau: ArrayLike) -> NDArray[np.float64]:
        """tau_u / (mu p*) on the upper sphere at radius r (units of a*) and time tau
        (eqs 18, 24, 33, 36); r broadcasts against tau."""
        r = self._radii(r)
        line = self._timeline(as_reals(tau, "tau"))
        return tangential.traction(r, line.clock, line.approach, line.stick_radius_squared,
                                   self.psi)

    def centre_displacement(self, tau: ArrayLike) -> NDArray[np.float64]:
        """u2 / u0, displacement of the contact centre of the upper sphere (eq 43)."""
        return self._along(tau, "centre_displacement")

    def centre_velocity(self, tau: ArrayLike) -> NDArray[np.float64]:
        """v2 / (omega u0), velocity of the contact centre of the upper sphere (eq 42)."""
        return self._along(tau, "centre_velocity")

    def lower_centre_displacement(self, tau: ArrayLike) -> NDArray[np.float64]:
        """u1 / u0, elastic displacement of the contact centre of the lower body (its
        surface point r = 0 moves by u_x0 + u1); -u2 for identical bodies."""
        return self._along(tau, "lower_centre_displacement")

    def lower_centre_velocity(self, tau: ArrayLike) -> NDArray[np.float64]:
        """du1/dt / (omega u0), elastic velocity of the contact centre of the lower body;
        -v2 for identical bodies."""
        return self._along(tau, "lower_centre_velocity")

    @staticmethod
    def drive_displacement(tau: ArrayLike) -> NDArray[np.float64]:
        """u_x0 / u0 = sin tau (eq 3)."""
        return np.sin(as_reals(tau, "tau"))

    @staticmethod
    def drive_velocity(tau: ArrayLike) -> NDArray[np.float64]:
        """(du_x0/dt) / (omega u0) = cos tau (eq 3)."""
        return np.cos(as_reals(tau, "tau"))



def impulse_ratio(
    psi: ArrayLike, tau0: ArrayLike, mu: ArrayLike = 0.2, nu: ArrayLike = 0.3
) -> NDArray[np.float64]:
    """T_imp / (mu P_imp) (eq 41) element-wise over psi and tau0 (arrays broadcast; one
    tau0 and many psi is the curve of Fig. 8).

    Independent of mu and nu (accepted for symmetry with ``Contact``, validated and part
    of the broadcast shape). Every argument is validated element-wise against
    ``core.DOMAIN``: ints or floats (TypeError for any other dtype), ValueError naming the
    first element out of range, nan or inf.
    """
    psi, tau0 = as_reals(psi, "psi"), as_reals(tau0, "tau0")
    shape = common_shape(psi=psi, tau0=tau0, mu=as_reals(mu, "mu"), nu=as_reals(nu, "nu"))
    if tau0.ndim == 0:  # one tau0 (the curve of Fig. 8): J(m0) once
        s, c = half_sines(float(tau0))
        out = tangential.impulse_ratio_of_psis(np.ascontiguousarray(psi), s * s,
                                               c * c).reshape(psi.shape)
    else:
        s, c = kernels.half_sines_of(np.ascontiguousarray(tau0))
        out = np.asarray(tangential.impulse_ratio(psi, s * s, c * c))
    return out if out.shape == shape else np.broadcast_to(out, shape).copy()


_PSI, _TAU0 = DOMAIN["psi"].closed_bounds, DOMAIN["tau0"].closed_bounds


def curve(psi: float, tau0: float, n: int = 200) -> tuple[NDArray[np.float64], float]:
    """One contact in one compiled call: (rows, ratio) with rows = (tau, T / T0, b / a*)
    on ``Contact(psi, tau0).tau_grid(n)`` (a 3 x ~n array) and ratio = T_imp / (mu P_imp)
    (eq 41). The same values, bit for bit, as ``Contact``'s; psi, tau0 and n are checked
    as there (a float in range takes a fast path)."""
    if not (type(psi) is float and _PSI[0] <= psi <= _PSI[1]):
        psi = check_param("psi", psi)
    if not (type(tau0) is float and _TAU0[0] <= tau0 <= _TAU0[1]):
        tau0 = check_param("tau0", tau0)
    if not (type(n) is int and 2 <= n <= MAX_GRID):
        n = _grid_size(n)
    return kernels.curve(psi, tau0, n)
