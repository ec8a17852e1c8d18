"""Compiled loops of the closed form over times and contacts (numba, ``@njit``, cached,
releasing the GIL).

The formulas are those of ``core.clock``, ``core.hertz`` and ``core.tangential`` (each
written once, as a kernel of one float); this module only loops them over arrays, one
pass per quantity with no temporaries, in a form the compiler turns into SIMD code.
Callers validate; ``Contact``, ``core.batch`` and ``core.curve`` are the public faces.

Layout of ``rows``: contact r (psi[r], sin_half_e[r]) at the times tau[r] (or tau[0] for
every contact when tau has one row), written to out[r]; all arrays C-contiguous.

Two habits for speed on short rows (a contact on a few tens of points, as a DEM rule
computes it): arrays are indexed in place, never sliced into views (a view costs two
reference-count updates, as much as a few points); and a loop over times whose
formula branches on psi <= 1 is written twice under one test of psi, so that each copy
compiles without the other's terms (full stick then skips partial stick's division and
second square root). The values are the same, bit for bit.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from core.clock import HALF_PI_HI, clock, half_sines, one_minus_square
from core.hertz import cube, force_scale, normal_force
from core.tangential import (
    impulse_ratio_float,
    phase,
    stick_clock,
    stick_radius_squared,
    tangential_force,
    tau1,
)

# quantity codes of ``rows``
CLOCK, APPROACH, CONTACT_RADIUS, NORMAL_FORCE, STICK_RADIUS_SQUARED, STICK_RADIUS, \
    TANGENTIAL_FORCE, PHASE = range(8)


@njit(cache=True, inline="always")
def _tangential(tau: float, psi: float, inv_s: float, k: float, scale: float) -> float:
    """T / T0 at one time (eqs 38, 39)."""
    w = clock(tau, inv_s)
    a3 = cube(one_minus_square(w))
    return tangential_force(a3, cube(stick_radius_squared(w, psi, k)), w, psi, scale)


@njit(cache=True, nogil=True)
def rows(q: int, tau: np.ndarray, psi: np.ndarray, sin_half_e: np.ndarray,
         out: np.ndarray) -> None:
    """Quantity q (a code above) of contact r at times tau[r] (or tau[0]) into out[r]."""
    n = out.shape[1]
    for r in range(out.shape[0]):
        p = psi[r]
        inv_s = 1.0 / sin_half_e[r]
        k = stick_clock(p)
        scale = force_scale(sin_half_e[r])
        i = r if tau.shape[0] > 1 else 0
        if q == TANGENTIAL_FORCE:
            if p <= 1.0:  # the same loop twice (module docstring)
                for j in range(n):
                    out[r, j] = _tangential(tau[i, j], p, inv_s, k, scale)
            else:
                for j in range(n):
                    out[r, j] = _tangential(tau[i, j], p, inv_s, k, scale)
        elif q == NORMAL_FORCE:
            for j in range(n):
                out[r, j] = normal_force(cube(one_minus_square(clock(tau[i, j], inv_s))), scale)
        elif q == STICK_RADIUS:
            for j in range(n):
                out[r, j] = math.sqrt(stick_radius_squared(clock(tau[i, j], inv_s), p, k))
        elif q == STICK_RADIUS_SQUARED:
            for j in range(n):
                out[r, j] = stick_radius_squared(clock(tau[i, j], inv_s), p, k)
        elif q == CONTACT_RADIUS:
            for j in range(n):
                out[r, j] = math.sqrt(one_minus_square(clock(tau[i, j], inv_s)))
        elif q == APPROACH:
            for j in range(n):
                out[r, j] = one_minus_square(clock(tau[i, j], inv_s))
        elif q == CLOCK:
            for j in range(n):
                out[r, j] = clock(tau[i, j], inv_s)
        else:
            for j in range(n):
                out[r, j] = phase(clock(tau[i, j], inv_s), p, k)


@njit(cache=True, nogil=True)
def half_sines_of(tau0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(sin(e/2), cos(e/2)) of every element of tau0 (``core.clock.half_sines``), as two
    arrays of tau0's shape."""
    s = np.empty(tau0.shape)
    c = np.empty(tau0.shape)
    flat, fs, fc = tau0.reshape(-1), s.reshape(-1), c.reshape(-1)
    for i in range(flat.size):
        fs[i], fc[i] = half_sines(flat[i])
    return s, c


@njit(cache=True, inline="always")
def _grid_pieces(psi: float, tau0: float, t1: float, n: int
                 ) -> tuple[float, float, float, float, int, int, int, int]:
    """The pieces of ``tau_grid``: ends (tau0, pi/2, ..., pi - tau0), the number of points
    on each phase, and the total size."""
    tau_end = math.pi - tau0
    half = n // 2
    if psi <= 1.0:
        e2, e3 = tau_end, tau_end
        c0, c1, c2 = half, n - half, 0
    else:
        share = round((t1 - HALF_PI_HI) / (tau_end - HALF_PI_HI) * (n - half))
        e2, e3 = t1, tau_end
        c0, c1, c2 = half, share + max(n // 8, 8), n - half - share
    # a piece of zero length gets no point, any other at least one
    c0 = max(c0, 1) if HALF_PI_HI > tau0 else 0
    c1 = max(c1, 1) if e2 > HALF_PI_HI else 0
    c2 = max(c2, 1) if e3 > e2 else 0
    return tau0, e2, e3, tau_end, c0, c1, c2, c0 + c1 + c2 + 1


@njit(cache=True, inline="always")
def _fill_grid(tau0: float, e2: float, e3: float, tau_end: float, c0: int, c1: int,
               c2: int, out: np.ndarray) -> None:
    """``tau_grid`` into out[0, :c0 + c1 + c2 + 1]: piece [a, b) of k points is
    a + i (b - a)/k, i = 0 ... k - 1, then pi - tau0."""
    pos = 0
    for a, b, k in ((tau0, HALF_PI_HI, c0), (HALF_PI_HI, e2, c1), (e2, e3, c2)):
        step = (b - a) / k if k else 0.0
        for j in range(k):
            out[0, pos + j] = j * step + a
        pos += k
    out[0, pos] = tau_end


@njit(cache=True, nogil=True)
def tau_grid(psi: float, tau0: float, t1: float, n: int) -> np.ndarray:
    """About n sorted times over [tau0, pi - tau0] holding tau0, pi/2, tau1 (= t1, when
    psi > 1) and pi - tau0 exactly, uniform on each phase, with n/8 extra points in
    partial stick."""
    a, e2, e3, end, c0, c1, c2, size = _grid_pieces(psi, tau0, t1, n)
    out = np.empty((1, size))
    _fill_grid(a, e2, e3, end, c0, c1, c2, out)
    return out[0]


@njit(cache=True, inline="always")
def _force_and_radius(out: np.ndarray, psi: float, inv_s: float, k: float,
                      scale: float) -> None:
    """T / T0 and b / a* (rows 1, 2 of out) at the times of row 0."""
    for j in range(out.shape[1]):
        w = clock(out[0, j], inv_s)
        b2 = stick_radius_squared(w, psi, k)
        out[1, j] = tangential_force(cube(one_minus_square(w)), cube(b2), w, psi, scale)
        out[2, j] = math.sqrt(b2)


@njit(cache=True, nogil=True)
def curve(psi: float, tau0: float, n: int) -> tuple[np.ndarray, float]:
    """One contact in one call: rows (tau, T / T0, b / a*) on ``tau_grid`` of about n
    points (written straight into the first row), and the impulse ratio
    T_imp / (mu P_imp) (eq 41)."""
    s, c = half_sines(tau0)
    t1 = min(tau1(psi, s, c), math.pi - tau0)
    a, e2, e3, end, c0, c1, c2, size = _grid_pieces(psi, tau0, t1, n)
    out = np.empty((3, size))
    _fill_grid(a, e2, e3, end, c0, c1, c2, out)
    inv_s = 1.0 / s
    k = stick_clock(psi)
    scale = force_scale(s)
    if psi <= 1.0:  # the same loop twice (module docstring)
        _force_and_radius(out, psi, inv_s, k, scale)
    else:
        _force_and_radius(out, psi, inv_s, k, scale)
    return out, impulse_ratio_float(psi, s * s, c * c)
