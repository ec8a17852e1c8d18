"""Method of dimensionality reduction (Popov & Hess, "Method of Dimensionality Reduction
in Contact Mechanics and Friction", Springer 2015, ch. 2-3 and 8).

The 3D contact of two spheres is replaced by a row of N independent springs on a rigid
1D profile g(x) = x^2 / R* (R* = R / 2), normal stiffness E* dx with E* = G / (1 - nu),
tangential stiffness G* dx with G* = 2 G / (2 - nu) (two identical bodies; physics.md).
The indentation d = alpha (eq 8) gives the spring compressions w(x) = d - g(x) and the
contact radius a^2 = R* d (eq 7). The tangential rule, per spring and time step:

* a spring that enters the contact carries the drive displacement accumulated since it
  touched (u0 (sin tau - sin tau_touch)),
* a spring already in contact follows the increment of u_x0 = u0 sin tau (stick),
* |G* u| is then capped at mu E* w(x) (slide at the Coulomb limit),
* a spring leaves the contact (w <= 0) with zero displacement.

Dimensionless form (lengths in a*, w in alpha* = H - h, u in mu E* alpha* / G*):
w(x) = (sin tau - s0) / (1 - s0) - x^2, drive increment du = psi d(sin tau) / (1 - s0)
(psi from eq 23), cap |u| <= w, and

    T / T0 = (3/4) (1 - s0)^{3/2} int u dx,      P / P0 = (3/4) (1 - s0)^{3/2} int w dx,

(eqs 9, 37). The same axisymmetric approximation underlies the paper, so the method
converges to eq 39; the spring values are exact at every time step once tau = pi / 2 (the
only reversal of the drive) is on the grid, so the error is that of the midpoint rule in
x: ~N^-2. 3D tractions follow from the inverse transform
q(r) = -(1/pi) int_r^a q1'(x) / sqrt(x^2 - r^2) dx (``traction``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from core.numerics.loading import approach, impulse_ratio_trapezoid, time_grid
from core.numerics.result import ContactLike, check_resolution, contact_parameters

NAME = "mdr"
STICK_TOL = 1e-9
"""Slack of the stick test, relative to the largest compression a^2."""
DESCRIPTION = "Method of dimensionality reduction (Popov & Hess): N springs, stick/slide"


def spring_positions(n: int) -> NDArray[np.float64]:
    """Midpoints x_i / a* of n equal cells on [0, 1] (the row is symmetric in x)."""
    return (np.arange(n) + 0.5) / n


def step_springs(u: NDArray[np.float64], w: NDArray[np.float64], w_prev: NDArray[np.float64],
                 du: float, psi: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """One time step of the spring rule; returns (new u, stick margin w - |u_trial|).

    u: spring displacements before the step; w, w_prev: compressions after and before;
    du: drive increment psi d(sin tau) / (1 - s0). Entering springs (w_prev <= 0 < w)
    carry psi w, the drive since they touched; leaving ones are set to zero.
    """
    inside = w > 0.0
    entering = inside & (w_prev <= 0.0)
    trial = np.where(entering, psi * w, u + du)
    margin = w - np.abs(trial)
    u_new = np.where(inside, np.clip(trial, -w, w), 0.0)
    return u_new, margin


def stick_radius(x: NDArray[np.float64], margin: NDArray[np.float64], a: float) -> float:
    """Radius b / a* of the central stick zone from the stick margins of the springs.

    The margin w - |u_trial| is smooth (a concave quadratic in x) across the stick
    boundary, so the linear interpolation of its root keeps the O(N^-2) accuracy; when
    every spring in contact sticks, the root is extrapolated from the last two springs
    and capped at a (full stick gives b = a). A slipping centre gives b = 0.
    """
    inside = x < a
    m = margin[inside]
    tol = STICK_TOL * max(a * a, 1e-300)  # psi = 1 rides the Coulomb limit exactly
    if m.size == 0 or m[0] < -tol:
        return 0.0
    neg = np.flatnonzero(m < -tol)
    if neg.size == 0:
        if m.size < 2 or m[-1] <= tol or m[-2] <= m[-1]:
            return a
        k = m.size - 1
    else:
        k = neg[0]
    x0, x1, m0, m1 = x[k - 1], x[k], m[k - 1], m[k]
    return float(min(x0 + (x1 - x0) * m0 / (m0 - m1), a))


def run(psi: float, tau0: float, tau: NDArray[np.float64], n: int
        ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64],
                   NDArray[np.float64]]:
    """March the springs over the times ``tau``; returns (T/T0, P/P0, b/a*, final u).

    ``tau`` must start at or before contact and hold pi / 2 if it passes it.
    """
    s0 = np.sin(tau0)
    x = spring_positions(n)
    h = 1.0 / n
    scale = 0.75 * (1.0 - s0) ** 1.5 * 2.0 * h  # both halves of the symmetric row
    d = approach(tau, tau0) / (1.0 - s0)
    drive = psi * np.sin(tau) / (1.0 - s0)
    u = np.zeros(n)
    w_prev = np.full(n, -1.0)
    T = np.zeros(tau.size)
    P = np.zeros(tau.size)
    b = np.zeros(tau.size)
    for k in range(tau.size):
        w = d[k] - x * x
        du = drive[k] - drive[k - 1] if k else 0.0
        u, margin = step_springs(u, w, w_prev, du, psi)
        T[k] = scale * u.sum()
        P[k] = scale * np.maximum(w, 0.0).sum()
        b[k] = stick_radius(x, margin, np.sqrt(d[k])) if d[k] > 0.0 else 0.0
        w_prev = w
    return T, P, b, u


def solve(contact: ContactLike, resolution: int) -> tuple[NDArray[np.float64], ...]:
    """MDR with ``resolution`` springs on each half of the row and as many time steps
    (at least 60), on the grid of ``loading.time_grid``. Returns (tau, T, b, ratio)."""
    n = check_resolution(resolution, maximum=10**6)
    psi, tau0 = contact_parameters(contact)
    tau = time_grid(psi, tau0, max(n, 60))
    check_resolution(n * tau.size, maximum=10**9, name="springs * time steps")
    T, P, b, _ = run(psi, tau0, tau, n)
    return tau, T, b, impulse_ratio_trapezoid(tau, T, P)


def traction(contact: ContactLike, tau: float, r: ArrayLike, n: int = 2000
             ) -> NDArray[np.float64]:
    """Traction on the upper sphere tau_u(r, tau) / (mu p*) by the MDR inverse transform.

    q(r) = -(1/pi) int_r^a q1'(x) / sqrt(x^2 - r^2) dx with the line load q1 = G* u; in
    these units tau_u / (mu p*) = -(1/2) int_r^a u'(x) / sqrt(x^2 - r^2) dx (p* is the
    Hertz peak pressure at a = a*, eq 6). u is taken piecewise linear between the springs
    (u(a) = 0, u'(0) = 0) and each segment is integrated exactly:
    int dx / sqrt(x^2 - r^2) = log(x + sqrt(x^2 - r^2)).
    """
    n = check_resolution(n, maximum=10**6, name="n")
    psi, tau0 = contact_parameters(contact)
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
