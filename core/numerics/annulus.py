"""Annulus discretisation with time stepping (Maw, Barber & Fawcett, "The oblique impact
of elastic spheres", Wear 38 (1976) 101-114).

The contact disc r < a* is split into n equal rings carrying uniform tangential
tractions tau_i. Tangential compliance: the axisymmetric part of Cerruti's point-force
solution (the non-axisymmetric terms dropped as in eqs 13-14, docs/physics.md), i.e. a
surface kernel (2 - nu) / (4 pi G rho) per body. Its ring integrals are the classical
uniform-disc results (Johnson, Contact Mechanics, eq 3.30 with (1 - nu^2)/E replaced by
(2 - nu)/(4 G)): a unit traction on the disc r < c displaces the surface of each body by

    (2 - nu)/(4 G) (4/pi) c E(r/c)                           r <= c,
    (2 - nu)/(4 G) (4/pi) r [E(c/r) - (1 - c^2/r^2) K(c/r)]  r > c      (E, K: modulus).

Normal pressure: Hertz (eq 6), averaged exactly over each ring. At each time step the
drive displacement increment d(u0 sin tau) is imposed and Coulomb's law ring by ring
(active-set iteration): stick rings have no relative displacement increment at their
centre; slip rings carry |tau_i| = mu p_i opposing the relative velocity (the traction on
the upper sphere has the sign of the slip increment of the lower surface); rings leaving
the contact drop their traction; entering rings start from zero traction.

Dimensionless form: r in a*, tau_i in mu p* (p* the Hertz peak at a = a*), relative
displacement in U = mu p* a* (2 - nu)/(2 G); the drive is
delta = (pi/2) psi sin tau / (1 - s0) and T / T0 = (3 / (2 pi)) (1 - s0)^{3/2} sum tau_i A_i.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit
from numpy.typing import NDArray
from scipy.special import ellipe, ellipk

from core.numerics.loading import (
    drive_grid,
    one_minus_s0,
    relative_drive,
    rise,
    time_grid,
    trapezoid,
)
from core.numerics.result import ContactLike, check_resolution, contact_parameters

NAME = "annulus"
DESCRIPTION = ("Annulus discretisation (Maw, Barber & Fawcett 1976): n rings, Coulomb per "
               "ring (compiled)")
MAX_SWEEPS = 60
MAX_RINGS = 400
"""Largest ring count: one dense solve per sweep and step costs O(n^3)."""
STICK_TOL = 1e-9
"""Relative slack of the stick test |tau| <= mu p (psi = 1 rides the limit exactly)."""


def disc_displacement(r: NDArray[np.float64], c: NDArray[np.float64]) -> NDArray[np.float64]:
    """Relative tangential displacement at radius r (units U) of a unit traction (mu p*)
    on the disc of radius c (units a*), axisymmetric approximation; broadcasts."""
    r, c = np.broadcast_arrays(np.asarray(r, float), np.asarray(c, float))
    out = np.zeros(r.shape)
    inner = (r <= c) & (c > 0)
    outer = (r > c) & (c > 0)
    out[inner] = c[inner] * ellipe((r[inner] / c[inner]) ** 2)
    q = (c[outer] / r[outer]) ** 2
    out[outer] = r[outer] * (ellipe(q) - (1.0 - q) * ellipk(q))
    return 4.0 / np.pi * out


def compliance_matrix(edges: NDArray[np.float64]) -> NDArray[np.float64]:
    """C[j, i]: displacement at the centre of ring j from unit traction on ring i."""
    centres = 0.5 * (edges[1:] + edges[:-1])
    disc = disc_displacement(centres[:, None], edges[None, :])
    return disc[:, 1:] - disc[:, :-1]


@lru_cache(maxsize=32)
def compliance(n: int) -> NDArray[np.float64]:
    """The compliance matrix of n equal rings on [0, 1]: geometry only, so it is built
    once per ring count (scipy's K and E) and reused for every contact."""
    C = compliance_matrix(np.linspace(0.0, 1.0, n + 1))
    C.setflags(write=False)
    return C


@njit(cache=True, nogil=True)
def ring_pressure(edges: NDArray[np.float64], a: float) -> NDArray[np.float64]:
    """Ring averages of the Hertz pressure p / p* = sqrt(a^2 - r^2)_+ (eq 6)."""
    n = edges.size - 1
    out = np.empty(n)
    cap_lo = max(a * a - edges[0] * edges[0], 0.0) ** 1.5
    for i in range(n):
        cap_hi = max(a * a - edges[i + 1] * edges[i + 1], 0.0) ** 1.5
        out[i] = (2.0 / 3.0) * (cap_lo - cap_hi) / (edges[i + 1] ** 2 - edges[i] ** 2)
        cap_lo = cap_hi
    return out


@njit(cache=True, nogil=True)
def _lu(A):
    """In-place LU factorisation with partial pivoting; returns the pivot rows."""
    m = A.shape[0]
    piv = np.arange(m)
    for j in range(m):
        p = j
        big = abs(A[j, j])
        for i in range(j + 1, m):
            if abs(A[i, j]) > big:
                big = abs(A[i, j])
                p = i
        if p != j:
            for c in range(m):
                A[j, c], A[p, c] = A[p, c], A[j, c]
            piv[j], piv[p] = piv[p], piv[j]
        inv = 1.0 / A[j, j]
        for i in range(j + 1, m):
            f = A[i, j] * inv
            A[i, j] = f
            if f != 0.0:
                for c in range(j + 1, m):
                    A[i, c] -= f * A[j, c]
    return piv


@njit(cache=True, nogil=True)
def _lu_solve(LU, piv, rhs):
    m = rhs.size
    y = np.empty(m)
    for i in range(m):
        s = rhs[piv[i]]
        for c in range(i):
            s -= LU[i, c] * y[c]
        y[i] = s
    for i in range(m - 1, -1, -1):
        s = y[i]
        for c in range(i + 1, m):
            s -= LU[i, c] * y[c]
        y[i] = s / LU[i, i]
    return y


@njit(cache=True, nogil=True)
def coulomb_step(C, tau_old, stick, p, d_delta, cache_idx, cache_lu, cache_piv):
    """Tractions after one step by an active-set iteration on Coulomb's law.

    stick: initial guess of the stick rings (entering rings included; updated in place);
    rings with p = 0 end with zero traction. A stick ring has no relative displacement
    increment at its centre; a slip ring carries sign * p with the sign of its slip.
    The LU factors of C[stick, stick] are kept in (cache_idx, cache_lu, cache_piv) and
    reused while the stick set is unchanged (it changes O(n) times per contact).
    Returns (new tractions, cache).
    """
    n = p.size
    sign = np.empty(n)
    for i in range(n):
        sign[i] = 1.0 if tau_old[i] >= 0.0 else -1.0
        if p[i] <= 0.0:
            stick[i] = False
    new = np.zeros(n)
    flip = np.zeros(n, dtype=np.bool_)
    for _ in range(MAX_SWEEPS):
        for i in range(n):
            new[i] = sign[i] * p[i] if (p[i] > 0.0 and not stick[i]) else 0.0
        idx = np.flatnonzero(stick)
        m = idx.size
        if m:
            same = cache_idx.size == m
            if same:
                for j in range(m):
                    if cache_idx[j] != idx[j]:
                        same = False
                        break
            if not same:
                A = np.empty((m, m))
                for r in range(m):
                    for c in range(m):
                        A[r, c] = C[idx[r], idx[c]]
                cache_piv = _lu(A)
                cache_lu = A
                cache_idx = idx
            rhs = np.empty(m)
            for r in range(m):
                acc = d_delta
                row = idx[r]
                for i in range(n):
                    if not stick[i]:
                        acc -= C[row, i] * (new[i] - tau_old[i])
                rhs[r] = acc
            x = _lu_solve(cache_lu, cache_piv, rhs)
            for r in range(m):
                new[idx[r]] = tau_old[idx[r]] + x[r]
        changed = False
        tol = 1e-14 * max(abs(d_delta), 1e-300)
        for j in range(n):
            flip[j] = False
            if p[j] > 0.0 and not stick[j]:
                # a slip ring whose slip increment opposes its traction sticks instead
                inc = d_delta
                for i in range(n):
                    inc -= C[j, i] * (new[i] - tau_old[i])
                flip[j] = sign[j] * inc < -tol
        for i in range(n):
            if stick[i] and abs(new[i]) > p[i] * (1.0 + STICK_TOL):
                # a stick ring over the Coulomb limit slips, in the direction of its traction
                sign[i] = 1.0 if new[i] > 0.0 else (-1.0 if new[i] < 0.0 else 0.0)
                stick[i] = False
                changed = True
            elif flip[i]:
                stick[i] = True
                changed = True
        if not changed:
            return new, cache_idx, cache_lu, cache_piv
    return new, cache_idx, cache_lu, cache_piv


@njit(cache=True, nogil=True)
def march(C, edges, a_all, delta, scale):
    """March the rings over the contact radii ``a_all`` (a / a*) and the drive ``delta``
    (both per time step); returns (T / T0, b / a*)."""
    n = edges.size - 1
    nt = a_all.size
    area = np.empty(n)
    for i in range(n):
        area[i] = np.pi * (edges[i + 1] ** 2 - edges[i] ** 2)
    traction = np.zeros(n)
    stick = np.zeros(n, dtype=np.bool_)
    was_inside = np.zeros(n, dtype=np.bool_)
    cache_idx = np.empty(0, dtype=np.int64)
    cache_lu = np.empty((0, 0))
    cache_piv = np.empty(0, dtype=np.int64)
    T = np.zeros(nt)
    b = np.zeros(nt)
    for k in range(1, nt):
        p = ring_pressure(edges, a_all[k])
        for i in range(n):
            inside = p[i] > 0.0
            stick[i] = stick[i] or (inside and not was_inside[i])
            was_inside[i] = inside
        traction, cache_idx, cache_lu, cache_piv = coulomb_step(
            C, traction, stick, p, delta[k] - delta[k - 1], cache_idx, cache_lu, cache_piv)
        total = 0.0
        for i in range(n):
            total += traction[i] * area[i]
        T[k] = scale * total
        b[k] = _stick_radius(edges, stick, was_inside, a_all[k])
    return T, b


@njit(cache=True, nogil=True)
def _stick_radius(edges, stick, inside, a):
    """Outer edge of the central block of stick rings (a when every ring sticks)."""
    m = 0
    for i in range(inside.size):
        if inside[i]:
            m += 1
    if m == 0 or not stick[0]:
        return 0.0
    for i in range(m):
        if not stick[i]:
            return edges[i]
    return a


@njit(cache=True, nogil=True)
def contact(psi, tau0, C, steps):
    """One contact from (psi, tau0) with the compliance C of n rings and about ``steps``
    time steps on ``loading.time_grid``: returns (tau, T / T0, b / a*, impulse ratio)."""
    n = C.shape[0]
    s0 = math.sin(tau0)
    tau = time_grid(psi, tau0, steps)
    nt = tau.size
    edges = np.linspace(0.0, 1.0, n + 1)
    a_all = np.empty(nt)
    delta = np.empty(nt)
    P = np.empty(nt)
    end = np.pi - tau0
    for k in range(nt):
        s = math.sin(tau[k])
        ap = max(s - s0, 0.0) if (tau[k] >= tau0 and tau[k] <= end) else 0.0
        a_all[k] = math.sqrt(ap / (1.0 - s0))
        delta[k] = 0.5 * np.pi * psi * s / (1.0 - s0)
        P[k] = ap ** 1.5
    T, b = march(C, edges, a_all, delta, 1.5 / np.pi * (1.0 - s0) ** 1.5)
    return tau, T, b, trapezoid(T, tau) / trapezoid(P, tau)


def run(psi: float, tau0: float, tau: NDArray[np.float64], n: int
        ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """March n rings over the given times ``tau``; returns (T / T0, b / a*)."""
    s0 = np.sin(tau0)
    tau = np.asarray(tau, dtype=float)
    inside = (tau >= tau0) & (tau <= np.pi - tau0)
    ap = np.where(inside, np.maximum(np.sin(tau) - s0, 0.0), 0.0)
    a_all = np.sqrt(ap / (1.0 - s0))
    delta = 0.5 * np.pi * psi * np.sin(tau) / (1.0 - s0)
    return march(compliance(n), np.linspace(0.0, 1.0, n + 1), a_all, delta,
                 1.5 / np.pi * (1.0 - s0) ** 1.5)


def moving(psi: float, tau0: float, v: float, n: int, steps: int
           ) -> tuple[NDArray[np.float64], ...]:
    """One contact under the drive relative to a rotor moving at V = v omega u0,
    u_x0 = u0 sin tau - (V / omega)(tau - tau0) (``loading.relative_drive``), with n
    rings over about ``steps`` time steps of ``loading.drive_grid`` (the grid of
    ``mdr.moving``). v = 0 is eq 3. Arguments are not checked.

    Returns (tau, T / T0, mu P / T0), P the exact Hertz force (eq 9).
    """
    tau = drive_grid(psi, tau0, v, steps)
    c0 = one_minus_s0(tau0)
    ap = np.maximum(rise(tau, tau0), 0.0)
    ap[0] = ap[-1] = 0.0
    delta = 0.5 * np.pi * psi / c0 * relative_drive(tau, tau0, v)
    T, _ = march(compliance(n), np.linspace(0.0, 1.0, n + 1), np.sqrt(ap / c0), delta,
                 1.5 / np.pi * c0 ** 1.5)
    return tau, T, ap ** 1.5


def default_steps(n: int) -> int:
    """Default time steps for n rings: max(60, 4 n) (the convergence orders of
    docs/numerics.md are measured with this coupling)."""
    return max(4 * n, 60)


def solve(contact_: ContactLike, resolution: int, steps: int | None = None) -> tuple:
    """``resolution`` rings and ``steps`` time steps (``default_steps`` when None) on
    ``loading.time_grid``. Returns (tau, T, b, impulse ratio)."""
    n = check_resolution(resolution, maximum=MAX_RINGS)
    m = default_steps(n) if steps is None else check_resolution(steps, maximum=10**6,
                                                                 name="steps")
    psi, tau0 = contact_parameters(contact_)
    check_resolution(n * m, name="rings * time steps")
    tau, T, b, ratio = contact(psi, tau0, compliance(n), m)
    return tau, T, b, ratio
