"""The common result type of every numerical method and the checks on its resolution.

Units (used by every module of ``core.numerics``): time is tau = omega t (radians),
lengths are in units of a* = sqrt(R (H - h) / 2) (the largest contact radius, eq 7 at
tau = pi / 2), tangential force in units of T0 (eq 37), normal force in units of
P0 = T0 / mu, so that the Coulomb limit mu P / T0 equals P / P0.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import NDArray

MAX_WORK = 10**7
"""Largest allowed memory/work product (springs or rings times time steps)."""


class ContactLike(Protocol):
    """What a method needs from ``core.Contact``: the four dimensionless parameters."""

    psi: float
    tau0: float
    mu: float
    nu: float


@dataclass(frozen=True)
class MethodResult:
    """Output of one numerical method on one contact.

    Attributes:
        method: registry name of the method (see ``core.numerics.METHODS``).
        resolution: springs, rings, time steps or quadrature nodes, as the method defines.
        tau: times tau = omega t (rad) over the contact, increasing.
        T: tangential force on the upper sphere T / T0 at ``tau`` (eq 37 units).
        b: stick radius b / a* at ``tau``, or None when the method has no stick zone.
        impulse_ratio: T_imp / (mu P_imp) (eq 41) from the method's own quadrature.
        wall_time: seconds spent solving (``time.perf_counter``).
    """

    method: str
    resolution: int
    tau: NDArray[np.float64]
    T: NDArray[np.float64]
    b: NDArray[np.float64] | None
    impulse_ratio: float
    wall_time: float


def check_resolution(resolution: object, *, minimum: int = 2, maximum: int = MAX_WORK,
                     name: str = "resolution") -> int:
    """Return ``resolution`` as an int, or raise ValueError naming value and allowed range.

    Booleans, floats (even integral ones), strings and numbers outside
    [minimum, maximum] are rejected.
    """
    if isinstance(resolution, bool) or not isinstance(resolution, (int, np.integer)):
        raise ValueError(
            f"{name} must be an integer in [{minimum}, {maximum}], got {resolution!r} "
            f"of type {type(resolution).__name__}"
        )
    value = int(resolution)
    if not minimum <= value <= maximum:
        raise ValueError(f"{name} must be an integer in [{minimum}, {maximum}], got {value}")
    return value


def contact_parameters(contact: ContactLike) -> tuple[float, float]:
    """(psi, tau0) of a contact, checked: psi > 0 finite, -pi/2 < tau0 < pi/2."""
    psi = float(contact.psi)
    tau0 = float(contact.tau0)
    if not (np.isfinite(psi) and psi > 0.0):
        raise ValueError(f"psi must be a finite positive number, got {psi!r}")
    if not (np.isfinite(tau0) and -np.pi / 2 < tau0 < np.pi / 2):
        raise ValueError(f"tau0 must lie in (-pi/2, pi/2), got {tau0!r}")
    return psi, tau0


@dataclass(frozen=True)
class Params:
    """Stand-in for ``core.Contact`` when only (psi, tau0, mu, nu) are at hand."""

    psi: float
    tau0: float
    mu: float = 0.2
    nu: float = 0.3
