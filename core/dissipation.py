"""Friction dissipation of one contact with the rotor held (the paper's problem), exact.

Over one contact the normal force does no net work (Hertz contact is elastic and ends
unloaded) and the tangential elastic energy is zero at both ends, so the work of the
drive on the held body, D = int T du_x0, is all dissipated by slip (docs/physics.md,
section 11.2). With T from eqs 38, 39 and s = sin tau:

    D / (T0 u0) = int (T / T0) cos tau dtau = (4/5) (1 - s0)^(5/2) (psi - 1) / (psi + 1)

for psi > 1, and 0 for psi <= 1 (full stick: the loading and unloading halves cancel).
Locally, the friction work per unit area is q(r) = int |tau_u| |s_dot| dt, s_dot the slip
velocity (the two surfaces' tangential velocities' difference, eqs 14, 21, 27; zero in
the stick disc). Each phase gives (r in a*, rho = r^2, kappa = (psi - 1)/(psi + 1) the
squared radius still in contact at tau1, k^2 = 2 / (psi + 1), c = 1 - s0):

    slip (tau0 .. pi/2):   the whole contact slips at (psi - 1) omega u0 cos tau / psi:
                            (psi - 1) (1 - rho)^(3/2)
    partial stick:          the annulus b < r < a at (psi + 1) (2/pi) arccos(b/r) omega u0
                            |cos tau| / psi; in the time variable b^2 the integral is
        rho < kappa:        (4 / (pi k^2)) (kappa (1 - rho))^(3/2) Delta(m'),
                            m' = k^2 rho / (kappa (1 - rho)),
                            Delta(m) = int_0^(pi/2) (1 - m sin^2)^(3/2) dphi - (pi/2)(1 - m)^(3/2)
        rho >= kappa:       k r^3 F(m) / (3 pi),  m = kappa (1 - rho) / (k^2 rho),
                            F = 12 m^2 J(m) the impulse factor of eq 11 (``core.elliptic``)
    counter-slip:           (psi + 1) (kappa - rho)_+^(3/2)

    q(r) / (T0 u0 / (pi a*^2)) = c^(5/2) / psi x (sum of the three),  0 for r >= 1,

so that int_0^1 q 2 r dr = D / (T0 u0). Delta is its series (pi/2) sum_n>=1
(-3/2)_n / n! ((1/2)_n / n! - 1) m^n below m = 1/4 (it starts at 3 pi m / 8: the closed
form (2 (2 - m) E(m) - (1 - m) K(m)) / 3 - (pi/2)(1 - m)^(3/2) cancels there), the closed
form above, with K from the complementary parameter. Every term is positive: no
cancellation. c = 2 sin^2(e/2), e = pi/2 - tau0 (``core.clock.half_sines``), keeps
grazing contacts' digits.

The friction power per unit area at (r, tau), ``rate``, in T0 u0 omega / (pi a*^2):
(3/2) c^(3/2) / psi |cos tau| (a^2 - r^2)_+^(1/2) times psi - 1 (slip), (psi + 1) (2/pi)
arccos(b/r) for r > b (partial stick; 0 in the stick disc), psi + 1 (counter-slip), 0 in
full stick; its integral over the contact is q(r).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import ellipe, ellipkm1

from core.elliptic import impulse_factor
from core.tangential import Phase

#: Below this m, Delta(m) by its series.
DELTA_SERIES_BELOW = 0.25
_SQRT32 = 4.0 * math.sqrt(2.0)  # 2^(5/2): c^(5/2) = 2^(5/2) sin^5(e/2)


def _delta_coefficients(n: int) -> tuple[float, ...]:
    """(pi/2) (-3/2)_j / j! ((1/2)_j / j! - 1) for j = 1 .. n, highest first (Horner),
    each the float nearest its exact rational value times pi / 2."""
    from fractions import Fraction

    out, a, b = [], Fraction(1), Fraction(1)  # (-3/2)_j / j!, (1/2)_j / j!
    for j in range(n):
        a *= Fraction(-3, 2) + j
        a /= j + 1
        b *= Fraction(1, 2) + j
        b /= j + 1
        out.append(float(a * (b - 1)) * (math.pi / 2))
    return tuple(out[::-1])


_DELTA = _delta_coefficients(30)  # terms beyond the 30th: < 1e-19 of Delta at m = 1/4


def excess_integral(m: NDArray[np.float64], mc: NDArray[np.float64]) -> NDArray[np.float64]:
    """Delta(m) = int_0^(pi/2) (1 - m sin^2 phi)^(3/2) dphi - (pi/2)(1 - m)^(3/2), for
    0 <= m < 1 with mc = 1 - m given (dimensionless)."""
    m, mc = np.broadcast_arrays(np.asarray(m, dtype=float), np.asarray(mc, dtype=float))
    out = np.empty(m.shape)
    small = m < DELTA_SERIES_BELOW
    ms = m[small]
    acc = np.full(ms.shape, _DELTA[0])
    for coef in _DELTA[1:]:
        acc = acc * ms + coef
    out[small] = acc * ms
    big = ~small
    mb, mcb = m[big], mc[big]
    out[big] = ((2.0 * (1.0 + mcb) * ellipe(mb) - mcb * ellipkm1(mcb)) / 3.0
                - (math.pi / 2) * mcb * np.sqrt(mcb))
    return out


def energy(psi: ArrayLike, half_sine: ArrayLike) -> NDArray[np.float64]:
    """D / (T0 u0) = (4/5) (1 - s0)^(5/2) (psi - 1)/(psi + 1) for psi > 1, else 0, with
    1 - s0 = 2 sin^2(e/2) and half_sine = sin(e/2), e = pi/2 - tau0. Element-wise."""
    psi, s = np.asarray(psi, dtype=float), np.asarray(half_sine, dtype=float)
    with np.errstate(invalid="ignore"):
        d = (0.8 * _SQRT32) * s**5 * ((psi - 1.0) / (psi + 1.0))
    return np.where(psi > 1.0, d, 0.0)


def density(r: ArrayLike, psi: float, half_sine: float) -> NDArray[np.float64]:
    """q(r) / (T0 u0 / (pi a*^2)), the friction work per unit area over one contact at
    radius |r| (units of a*; 0 for |r| >= 1 and for psi <= 1). See the module docstring."""
    r = np.minimum(np.abs(np.asarray(r, dtype=float)), 1.0)
    if psi <= 1.0:
        return np.zeros(r.shape)
    rho = r * r
    kappa = (psi - 1.0) / (psi + 1.0)
    one = 1.0 - rho
    slip = ((psi - 1.0) / psi) * one * np.sqrt(one)
    back = np.maximum(kappa - rho, 0.0)
    counter = ((psi + 1.0) / psi) * back * np.sqrt(back)
    partial = np.zeros(r.shape)
    inner = rho < kappa
    if inner.any():
        ri, oi = rho[inner], one[inner]
        m = 2.0 * ri / ((psi - 1.0) * oi)  # k^2 rho / (kappa (1 - rho))
        mc = (kappa - ri) / (kappa * oi)
        ko = kappa * oi
        partial[inner] = (2.0 * (psi + 1.0) / (math.pi * psi)) * ko * np.sqrt(ko) * (
            excess_integral(m, mc))
    outer = ~inner & (rho < 1.0)
    if outer.any():
        ro, oo = rho[outer], one[outer]
        m = (psi - 1.0) * oo / (2.0 * ro)  # kappa (1 - rho) / (k^2 rho)
        mc = (psi + 1.0) * (ro - kappa) / (2.0 * ro)
        k = math.sqrt(2.0 / (psi + 1.0))
        partial[outer] = (k / (3.0 * math.pi * psi)) * ro * np.sqrt(ro) * impulse_factor(m, mc)
    return (_SQRT32 * half_sine**5) * (slip + partial + counter)


def rate(r: NDArray[np.float64], tau: NDArray[np.float64], phase: NDArray[np.int_],
         a2: NDArray[np.float64], b2: NDArray[np.float64], psi: float, half_sine: float
         ) -> NDArray[np.float64]:
    """Friction power per unit area at radius r (a*, >= 0) and time tau, in units of
    T0 u0 omega / (pi a*^2), from the phase, a^2 and b^2 (a*^2) at tau (arrays broadcast).
    Zero outside the contact, in full stick and in the stick disc r <= b."""
    c = 2.0 * half_sine * half_sine
    factor = np.select(
        [phase == Phase.SLIP, phase == Phase.PARTIAL_STICK, phase == Phase.COUNTER_SLIP],
        [psi - 1.0, 0.0, psi + 1.0], 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        cos_b = np.where(r > 0.0, np.sqrt(b2) / np.where(r > 0.0, r, 1.0), 1.0)
    annulus = (psi + 1.0) * (2.0 / math.pi) * np.arccos(np.minimum(cos_b, 1.0))
    factor = np.where(phase == Phase.PARTIAL_STICK, annulus, factor)
    gap = np.maximum(a2 - r * r, 0.0)
    return (1.5 * c * math.sqrt(c) / psi) * np.abs(np.cos(tau)) * np.sqrt(gap) * factor
