"""The prescribed loading history and Hertz geometry, in the units of ``result.py``.

Only the data of the problem enter here, never its solution: the drive
u_x0 = u0 sin tau, u_z0 = H sin tau (eq 3), contact for sin tau > s0 = sin tau0 (eq 4),
the approach alpha = H (sin tau - s0) (eq 8), a^2 = R alpha / 2 (eq 7) and the Hertz
force P / P0 = (sin tau - s0)^{3/2} (eq 9).

``time_grid`` and ``trapezoid`` are compiled (numba): the time-stepping kernels call
them; they are plain callables from Python too.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import ArrayLike, NDArray


def contact_window(tau0: float) -> tuple[float, float]:
    """Start and end of contact, (tau0, pi - tau0) (eq 4)."""
    return tau0, np.pi - tau0


def approach(tau: ArrayLike, tau0: float) -> NDArray[np.float64]:
    """(sin tau - s0)_+, the approach alpha / H (eq 8); zero outside contact."""
    tau = np.asarray(tau, dtype=float)
    inside = (tau >= tau0) & (tau <= np.pi - tau0)
    return np.where(inside, np.maximum(np.sin(tau) - np.sin(tau0), 0.0), 0.0)


def contact_radius_sq(tau: ArrayLike, tau0: float) -> NDArray[np.float64]:
    """(a / a*)^2 = (sin tau - s0)_+ / (1 - s0) (eq 7 divided by a*^2)."""
    return approach(tau, tau0) / (1.0 - np.sin(tau0))


def hertz_force(tau: ArrayLike, tau0: float) -> NDArray[np.float64]:
    """Normal force P / P0 = (sin tau - s0)_+^{3/2} (eq 9); equals mu P / T0."""
    return approach(tau, tau0) ** 1.5


@njit(cache=True)
def partial_stick_estimate(psi: float, tau0: float) -> float:
    """Rough length of the partial-stick phase, 2 sqrt((1 - s0) / psi) (eq 35 asymptote).

    Only used to place time steps; never as part of a solution.
    """
    return 2.0 * math.sqrt((1.0 - math.sin(tau0)) / psi)


@njit(cache=True)
def time_grid(psi: float, tau0: float, n: int) -> NDArray[np.float64]:
    """About ``n`` + 1 times over [tau0, pi - tau0] holding tau0, pi/2 and pi - tau0.

    For psi <= 1 the two halves get n // 2 and n - n // 2 equal steps. For psi > 1 a
    third of the steps go to [pi/2, pi/2 + L] with
    L = min(1.5 * partial_stick_estimate, pi/2 - tau0), so the short partial-stick phase
    (~psi^-1/2 long) stays resolved however large psi is; a third to the loading and
    the rest to the counter-slip. n < 4 counts as 4.
    """
    start = tau0
    end = np.pi - tau0
    mid = np.pi / 2
    half = mid - start
    n = max(n, 4)
    if psi <= 1.0:
        n1 = max(n // 2, 1)
        n2 = max(n - n // 2, 1)
        grid = np.empty(n1 + n2 + 1)
        grid[: n1 + 1] = np.linspace(start, mid, n1 + 1)
        grid[n1:] = np.linspace(mid, end, n2 + 1)
    else:
        length = min(1.5 * partial_stick_estimate(psi, tau0), half)
        n1 = max(n // 3, 1)
        if length >= half * (1 - 1e-12):
            n2 = max(n - n1, 1)
            grid = np.empty(n1 + n2 + 1)
            grid[: n1 + 1] = np.linspace(start, mid, n1 + 1)
            grid[n1:] = np.linspace(mid, end, n2 + 1)
        else:
            n2 = max(n // 3, 1)
            n3 = max(n - n1 - n2, 1)
            grid = np.empty(n1 + n2 + n3 + 1)
            grid[: n1 + 1] = np.linspace(start, mid, n1 + 1)
            grid[n1: n1 + n2 + 1] = np.linspace(mid, mid + length, n2 + 1)
            grid[n1 + n2:] = np.linspace(mid + length, end, n3 + 1)
    grid[0] = start
    grid[-1] = end
    return grid


@njit(cache=True)
def trapezoid(y: NDArray[np.float64], x: NDArray[np.float64]) -> float:
    """Trapezoid rule of y(x) on an increasing grid."""
    total = 0.0
    for k in range(1, x.size):
        total += 0.5 * (y[k] + y[k - 1]) * (x[k] - x[k - 1])
    return total


def impulse_ratio_trapezoid(tau: NDArray[np.float64], T: NDArray[np.float64],
                            P: NDArray[np.float64]) -> float:
    """T_imp / (mu P_imp) from sampled T / T0 and mu P / T0 by the trapezoid rule (eq 41)."""
    return trapezoid(T, tau) / trapezoid(P, tau)
