"""Method of dimensionality reduction (Popov & Hess, "Method of Dimensionality Reduction
in Contact Mechanics and Friction", Springer 2015, ch. 2-3 and 8), compiled with numba.

The 3D contact of two spheres is replaced by a row of N independent springs on a rigid
1D profile g(x) = x^2 / R* (R* = R / 2), normal stiffness E* dx with E* = G / (1 - nu),
tangential stiffness G* dx with G* = 2 G / (2 - nu) (two identical bodies; docs/physics.md).
The indentation d = alpha (eq 8) gives the spring compressions w(x) = d - g(x) and the
contact radius a^2 = R* d (eq 7). The tangential rule, per spring and time step:

* a spring that enters the contact carries the drive accumulated since it touched,
  drive(t) - drive(t_touch), with drive(t_touch) interpolated linearly in d over the
  step (exact when the drive is an affine function of d over the step, as for eq 3),
* a spring already in contact follows the increment of the drive (stick),
* |G* u| is then capped at mu E* w(x) (slide at the Coulomb limit),
* a spring leaves the contact (w <= 0) with zero displacement.

Dimensionless form (lengths in a*, w in alpha* = H - h, u in mu E* alpha* / G*):
w(x) = d - x^2 with d = (sin tau - s0) / (1 - s0), drive psi sin tau / (1 - s0) (psi from
eq 23), cap |u| <= w, and

    T / T0 = (3/4) (1 - s0)^{3/2} int u dx,      P / P0 = (3/4) (1 - s0)^{3/2} int w dx

(eqs 9, 37). ``march`` takes the approach d and the drive as arrays over time, so any
drive history (a moving rotor: u0 sin tau - (V / omega)(tau - tau0)) runs through the
same kernel. For eq 3 each spring value is exact at every time step once tau = pi / 2
(the only reversal of the drive) is on the grid: T's error is that of the midpoint rule
in x, ~N^-2, whatever the time step. The impulse (trapezoid rule in time) has its own
error ~M^-2 in the number M of time steps, so M is chosen separately (``default_steps``).
Only the springs in contact (a prefix of the row, x < a) are touched at each step.
3D tractions follow from the inverse transform
q(r) = -(1/pi) int_r^a q1'(x) / sqrt(x^2 - r^2) dx (``traction``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import ArrayLike, NDArray

from core.numerics.loading import (
    approach,
    drive_grid,
    one_minus_s0,
    relative_drive,
    rise,
    time_grid,
    trapezoid,
)
from core.numerics.result import ContactLike, check_resolution, contact_parameters

NAME = "mdr"
STICK_TOL = 1e-9
"""Slack of the stick test, relative to the largest compression a^2."""
DESCRIPTION = ("Method of dimensionality reduction (Popov & Hess): N springs, stick/slide "
               "(compiled)")
MIN_STEPS = 32
"""Fewest default time steps (enough to draw T; psi <= 1 needs no more for accuracy)."""


def default_steps(n: int) -> int:
    """Default time steps M for N springs: max(MIN_STEPS, ceil(N / 2)).

    T is exact at every step up to the spring error ~N^-2 whatever M; the impulse adds
    the trapezoid error ~M^-2 for psi > 1 (none for psi <= 1, where T = psi P spring by
    spring). With M = N / 2 the two are about equal in absolute error over the benchmark
    cases; relative error at grazing contact wants M ~ 2-4 N. Pass ``steps`` to choose."""
    return max(MIN_STEPS, (n + 1) // 2)


def spring_positions(n: int) -> NDArray[np.float64]:
    """Midpoints x_i / a* of n equal cells on [0, 1] (the row is symmetric in x)."""
    return (np.arange(n) + 0.5) / n


@njit(cache=True, nogil=True)
def _stick_radius(x, margin, m, d):
    """Radius b / a* of the central stick zone from the stick margins w - |u_trial| of
    the m springs in contact (d = a^2).

    The margin is smooth (a concave quadratic in x) across the stick boundary, so the
    linear interpolation of its root keeps the O(N^-2) accuracy; when every spring in
    contact sticks, the root is extrapolated from the last two springs and capped at a
    (full stick gives b = a). A slipping centre gives b = 0.
    """
    if d <= 0.0:
        return 0.0
    a = math.sqrt(d)
    tol = STICK_TOL * max(d, 1e-300)  # psi = 1 rides the Coulomb limit exactly
    if m == 0 or margin[0] < -tol:
        return 0.0
    k = -1
    for i in range(m):
        if margin[i] < -tol:
            k = i
            break
    if k < 0:
        if m < 2 or margin[m - 1] <= tol or margin[m - 2] <= margin[m - 1]:
            return a
        k = m - 1
    x0, x1, m0, m1 = x[k - 1], x[k], margin[k - 1], margin[k]
    return min(x0 + (x1 - x0) * m0 / (m0 - m1), a)


@njit(cache=True, nogil=True, fastmath={"reassoc"})
def _held(xx, u, held, dk, d_prev, du, margin):
    """One step of the springs 0 .. held - 1, in contact at the previous step (approach
    d_prev) and at this one (dk): each follows the drive increment du (stick) and is
    capped at its Coulomb bound w = dk - x^2 (slide). u is updated in place, margin gets
    the stick margins w - |trial|. Returns the sums over these springs of u, of w and of
    the slip work (``march_into``).

    The springs are independent, so the loop runs in the CPU's vector lanes: each
    spring's value is computed as written (its u bit for bit), only the three sums are
    reassociated (``fastmath={"reassoc"}``: partial sums per lane, added at the end, a
    pairwise-like order at least as accurate as the sequential one). The order is fixed
    by the compiled loop, so every caller of ``march_into`` on one machine gets the same
    floats."""
    t_sum = 0.0
    p_sum = 0.0
    s_sum = 0.0
    for i in range(held):
        x2 = xx[i]
        w = dk - x2
        trial = u[i] + du
        a = abs(trial)
        margin[i] = w - a
        slide = a > w  # the bound cuts off |trial| - w
        slip = 0.5 * (max(d_prev - x2, 0.0) + w) * (a - w)
        s_sum += slip if slide else 0.0
        bound = w if trial > 0.0 else -w
        trial = bound if slide else trial
        u[i] = trial
        t_sum += trial
        p_sum += w
    return t_sum, p_sum, s_sum


@njit(cache=True, nogil=True)
def march_into(x, xx, d, drive, scale, u, T, P, S, b):
    """March the springs at positions ``x`` (increasing; ``xx`` their squares x * x)
    over the approach ``d`` (w = d - x^2) and the tangential ``drive`` (both per time
    step, in the units above), into the arrays T, P, S (and b) of the time steps:
    ``march`` without its allocations, the stick radius optional.

    u: spring displacements before the first step (updated in place; zero for a fresh
    contact). scale: factor from sum over springs to force (both halves of the row).
    T, P: sum of u and of w_+ times scale; S: the slip work of each step, scale times
    the sum over sliding springs of the mean Coulomb bound over the step,
    (w_+(start) + w(end)) / 2, times the slip (the part of the trial displacement the
    bound cut off): the frictional dissipation in units of T0 times the unit of u
    (exact for a spring that slides through the whole step with w linear in time,
    second order otherwise). b: the stick radius b / a* of each step, or None (compiled
    without it; an empty array also means none): the march alone.
    Every reversal of the drive should be a grid point (springs are then exact there).

    The springs held from the previous step (``_held``, in vector lanes) and those
    entering are walked in two loops (no per-spring test of which a spring is); a spring
    slides when |trial| > w (the margin w - |trial| < 0) and its slip is
    |trial| - w = -(w - |trial|), exactly.
    """
    nt = d.size
    n = xx.size
    if b is None:  # compiled apart: no stick radius
        stick = False
    else:
        stick = b.size > 0
    margin = np.empty(n)
    m_prev = 0
    while m_prev < n and u[m_prev] != 0.0:
        m_prev += 1
    d_prev = d[0]
    drive_prev = drive[0]
    for k in range(nt):
        dk = d[k]
        dr = drive[k]
        du = dr - drive_prev
        m = m_prev  # springs in contact: the prefix with d - x^2 > 0
        while m < n and dk - xx[m] > 0.0:
            m += 1
        while m > 0 and dk - xx[m - 1] <= 0.0:
            m -= 1
        for i in range(m, m_prev):  # leaving springs drop their displacement
            u[i] = 0.0
        held = m if m < m_prev else m_prev
        t_sum, p_sum, s_sum = _held(xx, u, held, dk, d_prev, du, margin)
        for i in range(held, m):  # entering: the drive since it touched (d = x^2 here)
            x2 = xx[i]
            w = dk - x2
            frac = (x2 - d_prev) / (dk - d_prev) if dk != d_prev else 0.0
            frac = min(max(frac, 0.0), 1.0)
            trial = dr - (drive_prev + frac * du)
            a = abs(trial)
            margin[i] = w - a
            if a > w:
                s_sum += 0.5 * (max(d_prev - x2, 0.0) + w) * (a - w)
                trial = w if trial > 0.0 else -w
            u[i] = trial
            t_sum += trial
            p_sum += w
        T[k] = scale * t_sum
        P[k] = scale * p_sum
        S[k] = scale * s_sum
        if b is not None:
            if stick:
                b[k] = _stick_radius(x, margin, m, dk)
        m_prev = m
        d_prev = dk
        drive_prev = dr


@njit(cache=True, nogil=True)
def march(x, d, drive, scale, u):
    """March the springs at positions ``x`` (increasing) over the approach ``d`` (w =
    d - x^2) and the tangential ``drive`` (both per time step, in the units above).

    u: spring displacements before the first step (updated in place; zero for a fresh
    contact). scale: factor from sum over springs to force (both halves of the row).
    Returns (T, P, b, S): sum of u and of w_+ times scale, the stick radius b / a*, and
    the slip work of each step (``march_into``, which this allocates for).
    Every reversal of the drive should be a grid point (springs are then exact there).
    """
    nt = d.size
    T = np.zeros(nt)
    P = np.zeros(nt)
    b = np.zeros(nt)
    S = np.zeros(nt)
    march_into(x, x * x, d, drive, scale, u, T, P, S, b)
    return T, P, b, S


@njit(cache=True, nogil=True)
def contact(psi, tau0, n, steps):
    """One contact of eq 3 from (psi, tau0): N = n springs, about ``steps`` time steps on
    ``loading.time_grid``. Returns (tau, T / T0, b / a*, impulse ratio, final u)."""
    s0 = math.sin(tau0)
    tau = time_grid(psi, tau0, steps)
    nt = tau.size
    d = np.empty(nt)
    drive = np.empty(nt)
    end = np.pi - tau0
    for k in range(nt):
        s = math.sin(tau[k])
        inside = tau[k] >= tau0 and tau[k] <= end
        d[k] = max(s - s0, 0.0) / (1.0 - s0) if inside else 0.0
        drive[k] = psi * s / (1.0 - s0)
    x = (np.arange(n) + 0.5) / n
    scale = 0.75 * (1.0 - s0) ** 1.5 * 2.0 / n
    u = np.zeros(n)
    T, P, b, _ = march(x, d, drive, scale, u)
    return tau, T, b, trapezoid(T, tau) / trapezoid(P, tau), u


def run(psi: float, tau0: float, tau: NDArray[np.float64], n: int
        ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64],
                   NDArray[np.float64]]:
    """March N = n springs over the given times ``tau`` (any start, before or inside the
    contact; pi / 2 on the grid if it is passed). Returns (T/T0, P/P0, b/a*, final u)."""
    s0 = np.sin(tau0)
    tau = np.asarray(tau, dtype=float)
    d = approach(tau, tau0) / (1.0 - s0)
    drive = psi * np.sin(tau) / (1.0 - s0)
    u = np.zeros(n)
    T, P, b, _ = march(spring_positions(n), d, drive, 0.75 * (1.0 - s0) ** 1.5 * 2.0 / n, u)
    return T, P, b, u


def moving(psi: float, tau0: float, v: float, n: int, steps: int
           ) -> tuple[NDArray[np.float64], ...]:
    """One contact under the drive relative to a rotor moving at V = v omega u0,
    u_x0 = u0 sin tau - (V / omega)(tau - tau0) (``loading.relative_drive``), with N = n
    springs over about ``steps`` time steps of ``loading.drive_grid`` (every reversal of
    the drive, and every time a sliding spring can stick again, on the grid). v = 0 is
    eq 3. Arguments are not checked (``core.motor.moving_rotor`` does).

    Returns (tau, T / T0, mu P / T0, S): S the slip work of each step (``march``) in
    units of T0 u0; T0 u0 times sum(S) is the frictional dissipation of the contact.
    Approach and drive are formed from ``loading.rise`` and 1 - s0 = 2 sin^2(e / 2), so
    that grazing contacts keep their digits.
    """
    tau = drive_grid(psi, tau0, v, steps)
    c0 = one_minus_s0(tau0)
    d = np.maximum(rise(tau, tau0), 0.0) / c0
    d[0] = d[-1] = 0.0  # the contact window's ends, exactly
    to_u = psi / c0  # u0 in the units of u (mu E* alpha* / G*)
    drive = to_u * relative_drive(tau, tau0, v)
    T, P, _, S = march(spring_positions(n), d, drive, 0.75 * c0 ** 1.5 * 2.0 / n, np.zeros(n))
    return tau, T, P, S / to_u


def solve(contact_: ContactLike, resolution: int, steps: int | None = None
          ) -> tuple[NDArray[np.float64], ...]:
    """MDR with ``resolution`` springs on each half of the row and ``steps`` time steps
    (``default_steps(resolution)`` when None). Returns (tau, T, b, ratio)."""
    n = check_resolution(resolution, maximum=10**6)
    m = default_steps(n) if steps is None else check_resolution(steps, maximum=10**7,
                                                                 name="steps")
    psi, tau0 = contact_parameters(contact_)
    check_resolution(n * m, maximum=10**9, name="springs * time steps")
    tau, T, b, ratio, _ = contact(psi, tau0, n, m)
    return tau, T, b, ratio


def traction(contact_: ContactLike, tau: float, r: ArrayLike, n: int = 2000
             ) -> NDArray[np.float64]:
    """Traction on the upper sphere tau_u(r, tau) / (mu p*) by the MDR inverse transform.

    q(r) = -(1/pi) int_r^a q1'(x) / sqrt(x^2 - r^2) dx with the line load q1 = G* u; in
    these units tau_u / (mu p*) = -(1/2) int_r^a u'(x) / sqrt(x^2 - r^2) dx (p* is the
    Hertz peak pressure at a = a*, eq 6). u is taken piecewise linear between the springs
    (u(a) = 0, u'(0) = 0) and each segment is integrated exactly:
    int dx / sqrt(x^2 - r^2) = log(x + sqrt(x^2 - r^2)).
    """
    n = check_resolution(n, maximum=10**6, name="n")
    psi, tau0 = contact_parameters(contact_)
    if not (tau0 < tau < np.pi - tau0):
        return np.zeros_like(np.asarray(r, dtype=float))
    grid = time_grid(psi, tau0, max(n, 60))
    grid = np.unique(np.concatenate([grid[grid < tau], [tau]]))
    _, _, _, u = run(psi, tau0, grid, n)
    a = float(np.sqrt(approach(tau, tau0) / (1.0 - np.sin(tau0))))
    x = spring_positions(n)
    keep = x < a
    xs = np.concatenate([[0.0], x[keep], [a]])
    us = np.concatenate([[u[keep][0] if keep.any() else 0.0], u[keep], [0.0]])
    slope = np.diff(us) / np.diff(xs)
    r = np.atleast_1d(np.asarray(r, dtype=float))
    out = np.zeros(r.shape)
    for i, r_i in enumerate(r.ravel()):
        if r_i >= a:
            continue
        ri = max(r_i, 1e-300)  # r = 0: the first segment has zero slope, the log stays finite
        lo = np.clip(xs[:-1], ri, None)
        hi = np.clip(xs[1:], ri, None)
        prim_hi = np.log(hi + np.sqrt(np.maximum(hi * hi - ri * ri, 0.0)))
        prim_lo = np.log(lo + np.sqrt(np.maximum(lo * lo - ri * ri, 0.0)))
        seg = np.where(hi > lo, slope * (prim_hi - prim_lo), 0.0)
        out.flat[i] = -0.5 * seg.sum()
    return out.reshape(np.shape(np.asarray(r, dtype=float))) if np.ndim(r) else out
