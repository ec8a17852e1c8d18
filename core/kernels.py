"""Compiled loops of the closed form over times and contacts (numba, ``@njit(cache=True)``).

The formulas are those of ``core.clock``, ``core.hertz`` and ``core.tangential`` (each
written once, as a kernel of one float); this module only loops them over arrays, one
pass per quantity with no temporaries, in a form the compiler turns into SIMD code.
Callers validate; ``Contact``, ``core.batch`` and ``core.curve`` are the public faces.

Layout of ``rows``: contact r (psi[r], sin_half_e[r]) at the times tau[r] (or tau[0] for
every contact when tau has one row), written to out[r]; all arrays C-contiguous.
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


@njit(cache=True)
def rows(q: int, tau: np.ndarray, psi: np.ndarray, sin_half_e: np.ndarray,
         out: np.ndarray) -> None:
    """Quantity q (a code above) of contact r at times tau[r] (or tau[0]) into out[r]."""
    n = out.shape[1]
    for r in range(out.shape[0]):
        p = psi[r]
        inv_s = 1.0 / sin_half_e[r]
        k = stick_clock(p)
        scale = force_scale(sin_half_e[r])
        t = tau[r if tau.shape[0] > 1 else 0]
        o = out[r]
        if q == TANGENTIAL_FORCE:
            for j in range(n):
                o[j] = _tangential(t[j], p, inv_s, k, scale)
        elif q == NORMAL_FORCE:
            for j in range(n):
                o[j] = normal_force(cube(one_minus_square(clock(t[j], inv_s))), scale)
        elif q == STICK_RADIUS:
            for j in range(n):
                o[j] = math.sqrt(stick_radius_squared(clock(t[j], inv_s), p, k))
        elif q == STICK_RADIUS_SQUARED:
            for j in range(n):
                o[j] = stick_radius_squared(clock(t[j], inv_s), p, k)
        elif q == CONTACT_RADIUS:
            for j in range(n):
                o[j] = math.sqrt(one_minus_square(clock(t[j], inv_s)))
        elif q == APPROACH:
            for j in range(n):
                o[j] = one_minus_square(clock(t[j], inv_s))
        elif q == CLOCK:
            for j in range(n):
                o[j] = clock(t[j], inv_s)
        else:
            for j in range(n):
                o[j] = phase(clock(t[j], inv_s), p, k)


@njit(cache=True)
def half_sines_of(tau0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(sin(e/2), cos(e/2)) of every element of tau0 (``core.clock.half_sines``), as two
    arrays of tau0's shape."""
    s = np.empty(tau0.shape)
    c = np.empty(tau0.shape)
    flat, fs, fc = tau0.reshape(-1), s.reshape(-1), c.reshape(-1)
    for i in range(flat.size):
        fs[i], fc[i] = half_sines(flat[i])
    return s, c


@njit(cache=True)
def tau_grid(psi: float, tau0: float, t1: float, n: int) -> np.ndarray:
    """About n sorted times over [tau0, pi - tau0] holding tau0, pi/2, tau1 (= t1, when
    psi > 1) and pi - tau0 exactly, uniform on each phase, with n/8 extra points in
    partial stick. Piece [a, b) of k points is a + i (b - a)/k, i = 0 ... k - 1."""
    tau_end = math.pi - tau0
    half = n // 2
    ends = np.empty(4)
    counts = np.empty(3, dtype=np.int64)
    ends[0], ends[1] = tau0, HALF_PI_HI
    if psi <= 1.0:
        ends[2] = tau_end
        counts[0], counts[1] = half, n - half
        pieces = 2
    else:
        share = round((t1 - HALF_PI_HI) / (tau_end - HALF_PI_HI) * (n - half))
        ends[2], ends[3] = t1, tau_end
        counts[0], counts[1], counts[2] = half, share + max(n // 8, 8), n - half - share
        pieces = 3
    size = 1
    for i in range(pieces):
        counts[i] = max(counts[i], 1) if ends[i + 1] > ends[i] else 0
        size += counts[i]
    out = np.empty(size)
    pos = 0
    for i in range(pieces):
        a, k = ends[i], counts[i]
        step = (ends[i + 1] - a) / k if k else 0.0
        for j in range(k):
            out[pos + j] = j * step + a
        pos += k
    out[size - 1] = tau_end
    return out


@njit(cache=True)
def curve(psi: float, tau0: float, n: int) -> tuple[np.ndarray, float]:
    """One contact in one call: rows (tau, T / T0, b / a*) on ``tau_grid`` of about n
    points, and the impulse ratio T_imp / (mu P_imp) (eq 41)."""
    s, c = half_sines(tau0)
    t1 = min(tau1(psi, s, c), math.pi - tau0)
    tau = tau_grid(psi, tau0, t1, n)
    out = np.empty((3, tau.size))
    inv_s = 1.0 / s
    k = stick_clock(psi)
    scale = force_scale(s)
    for j in range(tau.size):
        w = clock(tau[j], inv_s)
        b2 = stick_radius_squared(w, psi, k)
        out[0, j] = tau[j]
        out[1, j] = tangential_force(cube(one_minus_square(w)), cube(b2), w, psi, scale)
        out[2, j] = math.sqrt(b2)
    return out, impulse_ratio_float(psi, s * s, c * c)
