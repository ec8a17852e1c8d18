"""One contact at an array of times: each quantity computed on first use, kept for reuse.

``Contact.at(tau)`` returns a ``Timeline``; ``Contact``'s functions of time are this
class used once, and are where each quantity is documented. The clock, phase, approach,
radii and forces are each one compiled pass over the times (``core.kernels.rows``: the
clock w, one sine per time, and the formulas of w fused, without temporaries); the
centre's motion is numpy, from the clock, a^2 and the phase already computed
(``core.kinematics``). Arrays have the shape of tau, are zero (never nan) outside
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
    float64 array): what ``Contact.at`` returns.

    Each attribute is the Contact method of the same name at ``tau`` (definitions, units and
    accuracy are documented there), computed on first use and kept.

    ``tau`` is held, not copied: change it and ask again, and the quantities already
    computed will not follow (make a new Timeline instead).  ``passes`` holds each pass
    made, flat, by quantity code: Timelines of the same times in other shapes may share
    it (``Contact.at`` does, for one time). ``upper_share`` is ``Contact.upper_share``.

    See Also
    --------
    Contact.at : the public way to make one.
    """

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
        """w = sin((tau - pi/2)/2) / sin(e/2) (``core.clock``): -1 at tau0, 0 at pi/2, +1 at
        pi - tau0."""
        return self._pass(kernels.CLOCK)

    @cached_property
    def phase(self) -> NDArray[np.int_]:
        """``Contact.phase`` at ``tau``."""
        return _fixed(self._pass(kernels.PHASE).astype(int))

    @cached_property
    def approach(self) -> NDArray[np.float64]:
        """``Contact.approach`` at ``tau``."""
        return self._pass(kernels.APPROACH)

    @cached_property
    def contact_radius(self) -> NDArray[np.float64]:
        """``Contact.contact_radius`` at ``tau``."""
        return self._pass(kernels.CONTACT_RADIUS)

    @cached_property
    def stick_radius_squared(self) -> NDArray[np.float64]:
        """(b / a*)^2 (eq 30), the square of ``stick_radius``, exact to ~1e-16."""
        return self._pass(kernels.STICK_RADIUS_SQUARED)

    @cached_property
    def stick_radius(self) -> NDArray[np.float64]:
        """``Contact.stick_radius`` at ``tau``."""
        return self._pass(kernels.STICK_RADIUS)

    @cached_property
    def normal_force(self) -> NDArray[np.float64]:
        """``Contact.normal_force`` at ``tau``."""
        return self._pass(kernels.NORMAL_FORCE)

    @cached_property
    def tangential_force(self) -> NDArray[np.float64]:
        """``Contact.tangential_force`` at ``tau``."""
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
        """``Contact.centre_displacement`` at ``tau``."""
        return _fixed(kinematics.own_motion(self._half_relative_displacement,
                                            self.upper_share))

    @cached_property
    def centre_velocity(self) -> NDArray[np.float64]:
        """``Contact.centre_velocity`` at ``tau``."""
        return _fixed(kinematics.own_motion(self._half_relative_velocity, self.upper_share))

    @cached_property
    def lower_centre_displacement(self) -> NDArray[np.float64]:
        """``Contact.lower_centre_displacement`` at ``tau``."""
        return _fixed(0.0 - kinematics.own_motion(self._half_relative_displacement,
                                                  1.0 - self.upper_share))

    @cached_property
    def lower_centre_velocity(self) -> NDArray[np.float64]:
        """``Contact.lower_centre_velocity`` at ``tau``."""
        return _fixed(0.0 - kinematics.own_motion(self._half_relative_velocity,
                                                  1.0 - self.upper_share))
