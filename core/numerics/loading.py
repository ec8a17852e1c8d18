"""The prescribed loading history and Hertz geometry, in the units of ``result.py``.

Only the data of the problem enter here, never its solution: the drive
u_x0 = u0 sin tau, u_z0 = H sin tau (eq 3), contact for sin tau > s0 = sin tau0 (eq 4),
the approach alpha = H (sin tau - s0) (eq 8), a^2 = R alpha / 2 (eq 7) and the Hertz
force P / P0 = (sin tau - s0)^{3/2} (eq 9); for a rotor moving at a steady surface speed
V, the tangential drive relative to it, u_x0 = u0 sin tau - (V / omega)(tau - tau0)
(docs/physics.md, section 10.4), and a time grid for it (``drive_grid``).

``time_grid`` and ``trapezoid`` are compiled (numba): the time-stepping kernels call
them; they are plain callables from Python too.
"""

from __future__ import annotations

import itertools
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


@njit(cache=True, nogil=True)
def partial_stick_estimate(psi: float, tau0: float, reversal: float = np.pi / 2) -> float:
    """Rough length of the partial-stick phase that follows a reversal of the tangential
    drive at tau = ``reversal``: 2 sqrt((sin tau_r - s0) / (psi |sin tau_r|)), the time
    the drive (curvature psi |sin tau_r| in units of u0 / (1 - s0)) takes to move the
    centre of the contact from one Coulomb bound to the other (2 w, w = (sin tau_r - s0)
    / (1 - s0)). For eq 3 the reversal is pi / 2 and this is 2 sqrt((1 - s0) / psi), the
    asymptote of eq 35.

    Only used to place time steps; never as part of a solution.
    """
    s = math.sin(reversal)
    return 2.0 * math.sqrt((s - math.sin(tau0)) / (psi * abs(s)))


@njit(cache=True, nogil=True)
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


@njit(cache=True, nogil=True)
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


def rise(tau: ArrayLike, tau0: float) -> NDArray[np.float64]:
    """sin tau - sin tau0 = 2 cos((tau + tau0) / 2) sin((tau - tau0) / 2) (dimensionless),
    in the product form, which keeps its relative accuracy near grazing contact
    (tau0 -> pi / 2), where both sines are close to 1. Not clipped: negative outside
    the contact window."""
    tau = np.asarray(tau, dtype=float)
    return 2.0 * np.cos(0.5 * (tau + tau0)) * np.sin(0.5 * (tau - tau0))


def one_minus_s0(tau0: float) -> float:
    """1 - sin tau0 = 2 sin^2((pi/2 - tau0) / 2), accurate up to grazing contact."""
    return 2.0 * math.sin(0.5 * (math.pi / 2 - tau0)) ** 2


def relative_drive(tau: ArrayLike, tau0: float, v: float) -> NDArray[np.float64]:
    """Tangential drive of the lower sphere relative to a rotor whose surface moves at
    the steady speed V = v omega u0, in units of u0 and measured from its value at
    tau0 (only its increments act on the contact):

        u_x0 / u0 - sin tau0 = (sin tau - sin tau0) - v (tau - tau0)   (section 10.4)

    v = 0 is eq 3's drive u0 sin tau (shifted by the constant u0 sin tau0)."""
    tau = np.asarray(tau, dtype=float)
    return rise(tau, tau0) - v * (tau - tau0)


def drive_switches(psi: float, tau0: float, v: float) -> tuple[list[float], list[float]]:
    """Times inside the contact (tau0, pi - tau0) where the drive of ``relative_drive``
    changes what the springs of a contact can do: (reversals, switches).

    reversals: d(drive)/dtau = cos tau - v = 0, tau = +-arccos v for 0 <= v < 1 (pi / 2
    for eq 3; -arccos v only under a preload deep enough, tau0 < -arccos v). switches:
    the drive rate equals the rate of the Coulomb bound, psi (cos tau - v) = +-cos tau,
    cos tau = psi v / (psi -+ 1):
    there a point sliding at the bound sticks again, remembering where (its value there
    is a minimum of bound minus drive: on the grid it is exact). Sorted, each list."""
    end = math.pi - tau0
    reversals: list[float] = []
    switches: list[float] = []
    if v < 1.0:
        for t in (-math.acos(v), math.acos(v)):
            if tau0 < t < end:
                reversals.append(t)
    for c in ((psi * v / (psi - 1.0)) if psi != 1.0 else math.inf, psi * v / (psi + 1.0)):
        if abs(c) <= 1.0:
            for t in (-math.acos(c), math.acos(c)):
                if tau0 < t < end and t not in reversals:
                    switches.append(t)
    return reversals, sorted(set(switches))


def drive_grid(psi: float, tau0: float, v: float, n: int) -> NDArray[np.float64]:
    """About ``n`` + 1 increasing times over [tau0, pi - tau0] for the drive of
    ``relative_drive``, holding tau0, pi - tau0, every reversal and switch time
    (``drive_switches``).

    After each reversal the partial-stick phase (``partial_stick_estimate``, 1.5 times
    it, within the contact) gets a share of n // 3 of the steps (split evenly between
    reversals); the remaining steps are spread over the rest of the contact in
    proportion to length. Every piece between two held times gets at least one step.
    For v = 0 this is ``time_grid``'s layout (tau0, pi/2, the partial-stick window, the
    end) with its pieces sized in proportion to their length. n < 4 counts as 4.
    """
    n = max(int(n), 4)
    end = math.pi - tau0
    reversals, switches = drive_switches(psi, tau0, v)
    windows = [(t, min(t + 1.5 * partial_stick_estimate(psi, tau0, t), end))
               for t in reversals]
    held = sorted({tau0, end, *reversals, *switches, *(b for _, b in windows)})
    pieces = [(a, b) for a, b in itertools.pairwise(held) if b > a]
    in_window = [any(lo <= a and b <= hi for lo, hi in windows) for a, b in pieces]
    lengths = np.array([b - a for a, b in pieces])
    flags = np.array(in_window)
    total_w, total_o = lengths[flags].sum(), lengths[~flags].sum()
    share_w = n // 3 if total_o > 0.0 else n
    share_o = n - share_w if total_w > 0.0 else n
    counts = [max(round((share_w / total_w if f else share_o / total_o) * L), 1)
              for f, L in zip(flags, lengths, strict=True)]
    out = np.empty(sum(counts) + 1)
    pos = 0
    for (a, b), k in zip(pieces, counts, strict=True):
        out[pos:pos + k] = a + (b - a) * (np.arange(k) / k)
        pos += k
    out[-1] = end
    return out
