"""The vibrating rod of the motor (Fig. 1, eqs 1, 2): how a point of its top face moves.

A piezo rod of length 2L (-L < x < L) and thickness delta vibrates in its first
longitudinal mode at angular frequency omega = 2 pi f:

    u_x = A sin(pi x / 2L) sin(omega t)                                        (eq 1)
    u_y = -nu_rod (delta / 2) du_x/dx
        = -nu_rod (pi delta / 4L) A cos(pi x / 2L) sin(omega t)                  (eq 2)

(u_y on the top face y = delta / 2, from the Poisson contraction.) With the time origin
moved by half a period, so that the face rises while sin(omega t) > 0, the point x0
moves as the lower sphere of eq 3, u_x0 = u0 sin(omega t), u_z0 = H sin(omega t), with

    H(x0)  = nu_rod (pi delta / 4L) A cos(pi x0 / 2L)       > 0 for |x0| < L
    u0(x0) = -A sin(pi x0 / 2L)                             > 0 for x0 < 0

(For an auxetic rod, nu_rod < 0, the face rises without the time shift: H takes
|nu_rod| and u0 the opposite sign, +A sin(pi x0 / 2L). For nu_rod = 0 the face does not
rise at all, H = 0, and no contact ever opens.)

cos(pi x0 / 2L) is evaluated as sin(pi (L - |x0|) / 2L), which keeps its relative
accuracy up to the ends, where the textbook form loses it (cos of an argument near pi/2).
Lengths in m, frequency in Hz, omega in rad/s. See docs/physics.md, "The motor".
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from core.validation import DOMAIN, MOTOR_DOMAIN, Interval

#: Lengths, amplitude, frequency and preload: any positive finite number.
POSITIVE = Interval(0.0, None, lo_open=True)
#: The rod's Poisson ratio has the range of core's nu, (-1, 0.5].
POISSON = DOMAIN["nu"]


@dataclass(frozen=True)
class Rod:
    """The rod of Fig. 1: half-length L = ``half_length`` (m), thickness delta =
    ``thickness`` (m), Poisson ratio ``nu_rod``, longitudinal amplitude A = ``amplitude``
    at x = L (m) and vibration ``frequency`` f (Hz).

    Validated (ValueError names the parameter, its value and the allowed range):
    half_length, thickness, amplitude, frequency > 0 and within their rows of
    ``core.validation.MOTOR_DOMAIN`` (L in [1e-6, 100] m, delta in [1e-9, 100] m,
    A in [1e-12, 0.1] m, f in [1e-3, 1e9] Hz), where every drive amplitude is finite;
    nu_rod in (-1, 0.5]. The model (eq 2: strain uniform across the thickness) assumes
    delta << L; it is not enforced.
    """

    half_length: float
    thickness: float
    nu_rod: float
    amplitude: float
    frequency: float

    def __post_init__(self) -> None:
        for name in ("half_length", "thickness", "amplitude", "frequency"):
            value = POSITIVE.check(name, getattr(self, name))
            object.__setattr__(self, name, MOTOR_DOMAIN[name].check(name, value))
        object.__setattr__(self, "nu_rod", POISSON.check("nu_rod", self.nu_rod))

    @property
    def omega(self) -> float:
        """Angular frequency 2 pi f (rad/s)."""
        return 2.0 * math.pi * self.frequency

    @property
    def period(self) -> float:
        """One period of the vibration, 1 / f (s)."""
        return 1.0 / self.frequency

    @property
    def vertical_amplitude(self) -> float:
        """nu_rod (pi delta / 4L) A (m): H at the centre x0 = 0, its largest value (eq 2).
        Negative for an auxetic rod (nu_rod < 0): the face then rises where the
        longitudinal strain is compressive, and H(x0) below takes its absolute value."""
        return self.nu_rod * math.pi * self.thickness * self.amplitude / (4.0 * self.half_length)

    def check_x0(self, x0: ArrayLike) -> NDArray[np.float64]:
        """x0 as a float array, or ValueError if any element is not a finite real number
        with |x0| < L (the first offending value is named)."""
        L = self.half_length
        inside = Interval(-L, L, lo_open=True, hi_open=True)
        try:
            raw = np.asarray(x0)
        except (ValueError, TypeError) as err:  # e.g. ragged nested lists
            raise ValueError(f"x0 must be real numbers in {inside.describe()} (m): {err}") from err
        if raw.dtype.kind not in "iuf":
            raise ValueError(
                f"x0 must be real numbers in {inside.describe()} (m), got dtype {raw.dtype}"
            )
        arr = raw.astype(np.float64)
        bad = ~(np.abs(arr) < L)  # also nan
        if bad.any():
            first = np.unravel_index(np.flatnonzero(bad)[0], arr.shape)
            label = "x0" if arr.ndim == 0 else f"x0[{', '.join(str(int(i)) for i in first)}]"
            inside.check(label, arr[first])  # raises, naming the value and the range
        return arr

    def drive(self, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(u0, H) in m at already checked points x (``check_x0``): the amplitudes below,
        from one sine each."""
        q = math.pi / (2.0 * self.half_length)
        u0 = np.sin(q * x)
        u0 *= self.amplitude if self.nu_rod < 0.0 else -self.amplitude
        H = np.sin(q * (self.half_length - np.abs(x)))  # cos(q x), accurate near the ends
        H *= abs(self.vertical_amplitude)
        return u0, H

    def u0(self, x0: ArrayLike) -> NDArray[np.float64]:
        """u0(x0) = -A sin(pi x0 / 2L) (m): amplitude of the tangential drive at x0 (eq 1,
        eq 3), signed: along +x (positive) for x0 < 0. (+A sin(pi x0 / 2L) if nu_rod < 0.)"""
        return self.drive(self.check_x0(x0))[0]

    def H(self, x0: ArrayLike) -> NDArray[np.float64]:
        """H(x0) = |nu_rod| (pi delta / 4L) A cos(pi x0 / 2L) (m): amplitude of the normal
        drive at x0 (eq 2, eq 3); largest at the centre, 0 in the limit |x0| -> L."""
        return self.drive(self.check_x0(x0))[1]

    def tan_theta(self, x0: ArrayLike) -> NDArray[np.float64]:
        """tan theta(x0) = |u0| / H = (4L / (|nu_rod| pi delta)) |tan(pi x0 / 2L)|, the
        tangent of the angle of incidence at x0 (dimensionless; inf for nu_rod = 0)."""
        u0, H = self.drive(self.check_x0(x0))
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            return np.abs(u0) / H
