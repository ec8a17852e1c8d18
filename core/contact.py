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
    """Two elastic spheres in one intermittent oblique contact (Zharii 1996): the primary
    route to every quantity of the closed form.

    Parameters
    ----------
    psi : float
        Drive ratio 2 (1 - nu) u0 / (mu (2 - nu) H) = tan theta / tan theta0 (eq 23), in
        [0, 1e12]; psi <= 1 is full stick, psi > 1 slip, partial stick and counter-slip.
    tau0 : float
        Start of contact, sin tau0 = h / H (eq 4), in (-pi/2, pi/2); tau0 < 0 is a preload.
    mu : float
        Friction coefficient, in (0, 1e3].
    nu : float
        Poisson ratio, in (-1, 0.5] (of the equivalent pair for dissimilar bodies).
    scales : Scales or None
        The SI values of the scales below, set by ``from_physical``; not compared.
    upper_share : float
        The upper body's share of the relative tangential displacement, in (0, 1): 1/2 (the
        default) for the paper's identical spheres (``core.physical.upper_share``, set by
        ``from_physical``). It enters only each body's centre motion.

    Raises
    ------
    ValueError
        A parameter outside its range of ``core.DOMAIN``, named with its value and range.

    See Also
    --------
    Contact.at : the functions of time at one array of times, each computed once.
    core.batch : the functions of time over arrays of contacts.
    core.curve : T and b on ``tau_grid`` with the impulse ratio, one compiled call.
    core.impulse_ratio : eq 41 over arrays of psi and tau0.

    Notes
    -----
    This class documents each quantity once: its definition, units, domain and tested
    accuracy. The other routes return the same values, bit for bit, and refer here.

    Times tau = omega t (rad) are taken modulo 2 pi; radii r are in units of a*. Both may be
    Python or numpy ints and floats of any precision, alone, in lists or in arrays; any other
    dtype (bool, complex, str, bytes, object, datetime) raises TypeError, and nan or inf
    raises ValueError naming the first such element: no result is ever nan (but ``tau1``
    for psi <= 1). Every function of time returns a read-only array of tau's shape (r
    broadcast against tau), zero outside contact: copy one to modify it.

    Units: forces in T0 (eq 37) or P0 = T0 / mu; radii in a* = sqrt(R (H - h) / 2); pressure
    in p* = 4 G a* / ((1 - nu) pi R); tractions in mu p*; the centre's motion in u0 and
    omega u0; energies in T0 u0.

    Accuracy, stated on each method: against 60-digit mpmath evaluations of the paper's
    formulas at the corners of the domain (psi within 1e-12 of 1, psi = 1e12, tau0 within
    1e-8 of +-pi/2, tau exactly at tau0, pi/2, tau1, pi - tau0 and periods away;
    ``tests/core/test_accuracy.py``).
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
        """The contact of SI inputs, with ``scales`` set.

        Parameters
        ----------
        R, G, nu : float
            Radius (m), shear modulus (Pa) and Poisson ratio of body 1, the upper body (the
            rotor), each in its range of ``core.DOMAIN``.
        mu : float
            Friction coefficient.
        H, u0 : float
            Normal and tangential drive amplitudes of eq 3 (m).
        h : float
            Gap at t = 0 (m), in (-H, H); h < 0 is a preload.
        omega : float
            Angular frequency of the drive (rad/s).
        R2, G2, nu2 : float or None
            Body 2, the lower, driven body (the rod): R2 in m (inf for a flat face), G2 in Pa,
            nu2; None (each): body 1's value, the paper's identical spheres.

        Returns
        -------
        Contact
            psi and tau0 of eqs 23 and 4, and ``scales``. A dissimilar body 2 enters under
            Goodman's approximation: the contact is that of the equivalent identical pair
            (``core.physical.equivalent_pair``), so ``nu`` is its effective nu_eq,
            psi = 4 G* u0 / (mu E* H), ``scales`` (also Dundurs' ``beta``) are the pair's, and
            ``upper_share`` is body 1's share of the compliance (docs/physics.md, section 11.1).

        Raises
        ------
        ValueError
            An input outside its range, h outside (-H, H), or psi outside [0, 1e12]; every scale
            is finite otherwise.
        """
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
        """End of contact, pi - tau0 (rad)."""
        return math.pi - self.tau0

    @cached_property
    def tau1(self) -> float:
        """End of partial stick (eq 31), in (pi/2, pi - tau0] (rad); nan when psi <= 1.

        Within 1e-13 relative of mpmath; the first float at which the phase reads counter-slip.
        (For psi within ~1e-12 of 1 and grazing contact, tau1 and pi - tau0 round to the same
        float; tau1 is then reported as pi - tau0.)
        """
        return min(tangential.tau1(self.psi, *self._half_e), self.tau_end)

    @cached_property
    def F0(self) -> float:
        """F(tau0) of eq 11 (dimensionless), the elliptic factor of the normal impulse (eq 10).

        Relative error below 1e-13 (1e-14 for ``core.elliptic.impulse_factor`` over
        m = 1e-150 ... 1 - 1e-17), where eq 11 as printed loses every digit at grazing contact.
        """
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
        """T_imp / (mu P_imp) (eq 41) element-wise over psi and tau0.

        Parameters
        ----------
        psi, tau0 : array_like
            Drive ratios and starts of contact (``Contact``'s ranges), broadcast; one tau0 and
            many psi is the curve of Fig. 8 (J(m0) computed once).
        mu, nu : array_like, optional
            Validated and part of the broadcast shape; the ratio does not depend on them.

        Returns
        -------
        ndarray
            ``Contact(psi, tau0).impulse_ratio`` element-wise, bit for bit, of the broadcast shape.

        Raises
        ------
        TypeError, ValueError
            A dtype that is not int or float; an element out of range, nan or inf (named).

        See Also
        --------
        Contact.impulse_ratio : the definition and tested accuracy.
        """
        s, c = self._half_e
        return tangential.impulse_ratio_float(self.psi, s * s, c * c)

    # ---- friction dissipation (core.dissipation) --------------------------------------
    @cached_property
    def dissipated_energy(self) -> float:
        """D / (T0 u0): the work of the drive on the held body over one contact, all of it
        dissipated by slip (docs/physics.md, section 11.2).

        (4/5)(1 - sin tau0)^(5/2)(psi - 1)/(psi + 1) for psi > 1, 0 for psi <= 1;
        ``scales.energy`` is T0 u0 (J). Within 1e-10 relative of a quadrature of T d(sin tau)
        (``tests/core/test_dissipation.py``).
        """
        return float(dissipation.energy(self.psi, self._half_e[0]))

    def dissipation_density(self, r: ArrayLike) -> NDArray[np.float64]:
        """Friction work per unit area over one contact, q(r) (docs/physics.md, section 11.2).

        Parameters
        ----------
        r : array_like
            Radii (units of a*; the sign is ignored).

        Returns
        -------
        ndarray
            q / (T0 u0 / (pi a*^2)), of r's shape: exact, in elliptic integrals; 0 for psi <= 1
            and for r >= 1. int_0^1 q(r) 2 r dr = ``dissipated_energy``; ``scales.energy_density``
            is T0 u0 / (pi a*^2) (J/m^2).

        See Also
        --------
        dissipation_rate : its integrand in time.

        Notes
        -----
        Within 1e-9 relative of a 30-digit quadrature in time, and its integral over r within
        1e-10 of ``dissipated_energy`` (``tests/core/test_dissipation.py``).
        """
        return dissipation.density(self._radii(r), self.psi, self._half_e[0])

    def dissipation_rate(self, r: ArrayLike, tau: ArrayLike) -> NDArray[np.float64]:
        """Friction power per unit area at (r, tau): |tau_u| times the slip speed (eqs 14, 21, 27).

        Parameters
        ----------
        r : array_like
            Radii (units of a*; the sign is ignored), broadcast against tau.
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            In units of T0 u0 omega / (pi a*^2), of the broadcast shape: 0 in the stick zone, in
            full stick and outside contact. Its integral over tau is ``dissipation_density``.

        See Also
        --------
        dissipation_density : its integral over one contact.

        Notes
        -----
        Within 1e-12 relative of |traction| times the slip velocity built from eq 14
        (``tests/core/test_dissipation.py``).
        """
        r, tau = self._radii(r), as_reals(tau, "tau")
        line = self._timeline(tau)
        if self.psi <= 1.0:
            return np.zeros(np.broadcast_shapes(r.shape, tau.shape))
        return dissipation.rate(r, tau, line.phase, line.approach, line.stick_radius_squared,
                                self.psi, self._half_e[0])

    # ---- time grid -------------------------------------------------------------------
    def tau_grid(self, n: int = 400) -> NDArray[np.float64]:
        """A time grid for plotting or integrating one contact.

        Parameters
        ----------
        n : int
            About how many times, in [2, 1e8].

        Returns
        -------
        ndarray
            About n sorted times over [tau0, pi - tau0] that hold tau0, pi/2, tau1 and pi - tau0
            exactly, uniform on each phase, with n/8 extra points in partial stick (short for
            large psi).

        See Also
        --------
        core.curve : T and b on this grid, one compiled call.
        """
        return kernels.tau_grid(self.psi, self.tau0, self.tau1, _grid_size(n))

    # ---- functions of time -----------------------------------------------------------
    def at(self, tau: ArrayLike) -> Timeline:
        """Every function of time below at the times tau, each computed on first use and kept.

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        Timeline
            Attributes named as the methods (``phase``, ``tangential_force``, ...), read-only
            arrays of tau's shape, the same values bit for bit (``core.timeline``). For one
            time (a scalar or one element) the Timeline is this contact's own for that time,
            shared by every call at it (its tau is a read-only copy).

        See Also
        --------
        Contact.tangential_force : and the other methods: definitions, units, accuracy.

        Notes
        -----
        Ask it for several quantities on the same times rather than calling the methods one by
        one: the clock is evaluated once.
        """
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
        """Phase of the contact at each time (``core.Phase``).

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray of int
            0 no contact, 1 full stick (psi <= 1), 2 slip while loading, 3 partial stick,
            4 counter-slip.

        See Also
        --------
        at : ``at(tau).phase``, with the other quantities of the same times.
        core.batch.phase : the same over arrays of contacts.

        Notes
        -----
        At the breakpoints by one rule: tau0 and pi - tau0 are in contact, pi/2 is slip,
        tau1 is counter-slip and the float before it partial stick.
        """
        return self._along(tau, "phase")

    def approach(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Approach of the sphere centres, alpha / (H - h) (eq 8).

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            alpha / (H - h) = (sin tau - sin tau0) / (1 - sin tau0), equal to (a / a*)^2.

        See Also
        --------
        at : ``at(tau).approach``, with the other quantities of the same times.

        Notes
        -----
        Within 1e-13 of mpmath, without cancellation at both ends of contact (``core.clock``).
        """
        return self._along(tau, "approach")

    def normal_force(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Normal force, P / P0 = (sin tau - sin tau0)^(3/2) (eq 9); also mu P / T0.

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            P / P0.

        See Also
        --------
        at : ``at(tau).normal_force``, with the other quantities of the same times.
        core.batch.normal_force : the same over arrays of contacts.

        Notes
        -----
        Within 1e-13 of mpmath.
        """
        return self._along(tau, "normal_force")

    def tangential_force(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Tangential force on the upper body, T / T0 (eqs 38, 39), positive along the drive.

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            T / T0.

        See Also
        --------
        at : ``at(tau).tangential_force``, with the other quantities of the same times.
        core.batch.tangential_force : the same over arrays of contacts.
        core.curve : T and b on ``tau_grid`` with the impulse ratio, one compiled call.

        Notes
        -----
        Within 1e-13 (of T0) of mpmath.
        """
        return self._along(tau, "tangential_force")

    def contact_radius(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Radius of the contact disc, a / a* (eqs 7, 8).

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            a / a*.

        See Also
        --------
        at : ``at(tau).contact_radius``, with the other quantities of the same times.
        core.batch.contact_radius : the same over arrays of contacts.

        Notes
        -----
        Within 1e-13 of mpmath where (a / a*)^2 > 1e-4, and its square everywhere; within
        ~1e-8 of the ends of contact a is a square root of a number known to ~1e-16.
        """
        return self._along(tau, "contact_radius")

    def stick_radius(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Radius of the stick disc, b / a* (eq 30).

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            b / a*: a in full stick, the shrinking stick disc in partial stick, 0 in the slip
            phases and outside contact.

        See Also
        --------
        at : ``at(tau).stick_radius``, with the other quantities of the same times.
        core.batch.stick_radius : the same over arrays of contacts.
        core.curve : T and b on ``tau_grid`` with the impulse ratio, one compiled call.

        Notes
        -----
        Within 1e-13 of mpmath where (b / a*)^2 > 1e-4, and its square everywhere.
        """
        return self._along(tau, "stick_radius")

    @staticmethod
    def _radii(r: ArrayLike) -> NDArray[np.float64]:
        """|r| validated, capped at 2: every contact lies within r = 1 (a <= a*), so the
        cap changes no result and r^2 cannot overflow."""
        return np.minimum(np.abs(as_reals(r, "r")), 2.0)

    def pressure(self, r: ArrayLike, tau: ArrayLike) -> NDArray[np.float64]:
        """Contact pressure, p / p* (eq 6).

        Parameters
        ----------
        r : array_like
            Radii (units of a*; the sign is ignored), broadcast against tau.
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            p / p* = sqrt((a / a*)^2 - r^2) inside the contact, 0 outside, of the broadcast
            shape.

        See Also
        --------
        traction : the tangential traction on the same grid.

        Notes
        -----
        Within 1e-13 of mpmath, but within ~1e-6 (in r^2) of r = a (a square-root zero).
        """
        r = self._radii(r)
        r, a2 = np.broadcast_arrays(r, self._timeline(as_reals(tau, "tau")).approach)
        return hertz.pressure(r, a2)

    def traction(self, r: ArrayLike, tau: ArrayLike) -> NDArray[np.float64]:
        """Tangential traction on the upper body, tau_u / (mu p*) (eqs 18, 24, 33, 36).

        Parameters
        ----------
        r : array_like
            Radii (units of a*; the sign is ignored), broadcast against tau.
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            tau_u / (mu p*), of the broadcast shape; 0 outside the contact.

        See Also
        --------
        pressure : the normal pressure on the same grid.

        Notes
        -----
        Within 1e-13 of mpmath, but within ~1e-6 (in r^2) of r = a and r = b.
        """
        r = self._radii(r)
        line = self._timeline(as_reals(tau, "tau"))
        return tangential.traction(r, line.clock, line.approach, line.stick_radius_squared,
                                   self.psi)

    def centre_displacement(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Displacement of the contact centre r = 0 of the upper body, u2 / u0 (eq 43).

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            u2 / u0: eq 43 for identical bodies, 2 ``upper_share`` times it for dissimilar ones
            (docs/physics.md, section 11.1); 0 at both ends of contact and outside it.

        See Also
        --------
        lower_centre_displacement : the lower body's.
        at : ``at(tau).centre_displacement``, with the other quantities of the same times.

        Notes
        -----
        Within 1e-13 of its largest value over the contact against mpmath; for dissimilar
        bodies within 1e-12 of a quadrature of Cerruti's displacement under ``traction``
        (``tests/core/test_dissimilar.py``).
        """
        return self._along(tau, "centre_displacement")

    def centre_velocity(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Velocity of the contact centre r = 0 of the upper body, v2 / (omega u0) (eq 42).

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            v2 / (omega u0): eq 42 for identical bodies, 2 ``upper_share`` times it for dissimilar
            ones; it jumps at tau0, tau1 and pi - tau0 (inertia neglected).

        See Also
        --------
        lower_centre_velocity : the lower body's.
        at : ``at(tau).centre_velocity``, with the other quantities of the same times.

        Notes
        -----
        Within 1e-13 of mpmath away from its jumps.
        """
        return self._along(tau, "centre_velocity")

    def lower_centre_displacement(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Elastic displacement of the lower body's contact centre, u1 / u0.

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            u1 / u0 = -2 (1 - ``upper_share``) times eq 43; -u2 / u0 for identical bodies. The
            lower body's surface point r = 0 moves by u_x0 + u1.

        See Also
        --------
        centre_displacement : the upper body's (definition and accuracy).
        """
        return self._along(tau, "lower_centre_displacement")

    def lower_centre_velocity(self, tau: ArrayLike) -> NDArray[np.float64]:
        """Elastic velocity of the lower body's contact centre, (du1/dt) / (omega u0).

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            -2 (1 - ``upper_share``) times eq 42; -v2 / (omega u0) for identical bodies.

        See Also
        --------
        centre_velocity : the upper body's (definition and accuracy).
        """
        return self._along(tau, "lower_centre_velocity")

    @staticmethod
    def drive_displacement(tau: ArrayLike) -> NDArray[np.float64]:
        """Drive of the lower body's centre, u_x0 / u0 = sin tau (eq 3).

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            sin tau.

        See Also
        --------
        drive_velocity : its rate.
        """
        return np.sin(as_reals(tau, "tau"))

    @staticmethod
    def drive_velocity(tau: ArrayLike) -> NDArray[np.float64]:
        """Velocity of the drive, (du_x0/dt) / (omega u0) = cos tau (eq 3).

        Parameters
        ----------
        tau : array_like
            Times omega t (rad), taken modulo 2 pi.

        Returns
        -------
        ndarray
            cos tau.

        See Also
        --------
        drive_displacement : the drive itself.
        """
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
    """One contact in one compiled call: T and b on the contact's time grid, and eq 41.

    Parameters
    ----------
    psi, tau0 : float
        As ``Contact``'s (a float in range takes a fast path past the checks).
    n : int
        As ``Contact.tau_grid``'s.

    Returns
    -------
    rows : ndarray
        3 x ~n: tau = ``Contact(psi, tau0).tau_grid(n)``, T / T0 and b / a* on it.
    ratio : float
        T_imp / (mu P_imp) (eq 41).

    See Also
    --------
    Contact.tangential_force, Contact.stick_radius, Contact.impulse_ratio : the same values,
        bit for bit; their definitions and tested accuracy.
    """
    if not (type(psi) is float and _PSI[0] <= psi <= _PSI[1]):
        psi = check_param("psi", psi)
    if not (type(tau0) is float and _TAU0[0] <= tau0 <= _TAU0[1]):
        tau0 = check_param("tau0", tau0)
    if not (type(n) is int and 2 <= n <= MAX_GRID):
        n = _grid_size(n)
    return kernels.curve(psi, tau0, n)
