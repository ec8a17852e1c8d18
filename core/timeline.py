"""One contact at an array of times: each quantity computed on first use, kept for reuse.

``Contact.at(tau)`` returns a ``Timeline``. Each quantity of eqs 6-43 is one compiled
pass over the times (``core.kernels.rows``: the clock w, one sine per time, and the
formulas of w fused, without temporaries); the centre's motion is derived from the
clock, a^2 and the phase already computed. ``Contact``'s single-quantity methods are
this class used once.

Units as in ``Contact``: forces in T0 (eq 37) or P0 = T0 / mu, radii in a*, displacement
in u0, velocity in omega u0. Arrays have the shape of tau, are zero (never nan) outside
contact, and are read-only: they are shared between the quantities derived from them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from core import kernels, kinematics


def _fixed(a: NDArray) -> NDArray:
    """a as a read-only array (numpy scalars, from 0-d inputs, become 0-d arrays)."""
    if not isinstance(a, np.ndarray):
        a = np.asarray(a)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class Timeline:
    """The contact (psi, s = sin(e/2) of ``core.clock``) at the times ``tau`` (radians, a
    float64 array).

    ``tau`` is held, not copied: change it and ask again, and the quantities already
    computed will not follow (make a new Timeline instead).  ``passes`` holds each pass
    made, flat, by quantity code: Timelines of the same times in other shapes may share
    it (``Contact.at`` does, for one time)."""

    tau: NDArray[np.float64]
    psi: float
    sin_half_e: float
    passes: dict[int, NDArray[np.float64]] = field(default_factory=dict, repr=False)
    upper_share: float = 0.5

    def _pass(self, q: int) -> NDArray[np.float64]:
        """Quantity code q of ``core.kernels`` at every time, as a read-only array."""
        flat = self.passes.get(q)
        if flat is None:
            tau = np.ascontiguousarray(self.tau).reshape(1, -1)
            flat = np.empty(tau.size)
            kernels.rows(q, tau, np.array([self.psi]), np.array([self.sin_half_e]),
                         flat.reshape(1, -1))
            self.passes[q] = _fixed(flat)
        return _fixed(flat.reshape(self.tau.shape))

    @cached_property
    def clock(self) -> NDArray[np.float64]:
        """w = sin((tau - pi/2)/2) / sin(e/2): -1 at tau0, 0 at pi/2, +1 at pi - tau0."""
        return self._pass(kernels.CLOCK)

    @cached_property
    def phase(self) -> NDArray[np.int_]:
        """Phase code (``core.Phase``): 0 no contact, 1 full stick, 2 slip, 3 partial
        stick, 4 counter-slip."""
        return _fixed(self._pass(kernels.PHASE).astype(int))

    @cached_property
    def approach(self) -> NDArray[np.float64]:
        """alpha / (H - h) = (sin tau - sin tau0) / (1 - sin tau0) (eq 8); equals a^2 / a*^2."""
        return self._pass(kernels.APPROACH)

    @cached_property
    def contact_radius(self) -> NDArray[np.float64]:
        """a / a* (eqs 7, 8)."""
        return self._pass(kernels.CONTACT_RADIUS)

    @cached_property
    def stick_radius_squared(self) -> NDArray[np.float64]:
        """(b / a*)^2 (eq 30)."""
        return self._pass(kernels.STICK_RADIUS_SQUARED)

    @cached_property
    def stick_radius(self) -> NDArray[np.float64]:
        """b / a* (eq 30): a in full stick, the stick disc in partial stick, else 0."""
        return self._pass(kernels.STICK_RADIUS)

    @cached_property
    def normal_force(self) -> NDArray[np.float64]:
        """P / P0 = (sin tau - sin tau0)^(3/2) (eq 9); also mu P / T0."""
        return self._pass(kernels.NORMAL_FORCE)

    @cached_property
    def tangential_force(self) -> NDArray[np.float64]:
        """T / T0 (eqs 38, 39): force on the upper sphere, positive along the drive."""
        return self._pass(kernels.TANGENTIAL_FORCE)

    @cached_property
    def _half_relative_displacement(self) -> NDArray[np.float64]:
        """Eq 43: u2 / u0 of the equivalent identical pair, half the relative displacement."""
        return _fixed(kinematics.centre_displacement(self.clock, self.approach, self.phase,
                                                     self.psi, self.sin_half_e))

    @cached_property
    def _half_relative_velocity(self) -> NDArray[np.float64]:
        """Eq 42: v2 / (omega u0) of the equivalent identical pair."""
        return _fixed(kinematics.centre_velocity(np.cos(self.tau), self.phase, self.psi))

    @cached_property
    def centre_displacement(self) -> NDArray[np.float64]:
        """u2 / u0, displacement of the contact centre of the upper body (eq 43)."""
        return _fixed(kinematics.own_motion(self._half_relative_displacement,
                                            self.upper_share))

    @cached_property
    def centre_velocity(self) -> NDArray[np.float64]:
        """v2 / (omega u0), velocity of the contact centre of the upper body (eq 42)."""
        return _fixed(kinematics.own_motion(self._half_relative_velocity, self.upper_share))

    @cached_property
    def lower_centre_displacement(self) -> NDArray[np.float64]:
        """u1 / u0, elastic displacement of the lower body's contact centre."""
        return _fixed(0.0 - kinematics.own_motion(self._half_relative_displacement,
                                                  1.0 - self.upper_share))

    @cached_property
    def lower_centre_velocity(self) -> NDArray[np.float64]:
        """v1 / (omega u0) - cos tau, elastic velocity of the lower body's contact centre."""
        return _fixed(0.0 - kinematics.own_motion(self._half_relative_velocity,
                                                  1.0 - self.upper_share))
