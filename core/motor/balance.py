"""The preload fixes the start of contact: tau0 from the mean-force balance (eq 10).

The rotor rests on the rod with a steady force N (its weight, or a spring). Between
contacts nothing holds it up, so over one period 2 pi / omega the impulse of the contact
force balances that of N: P_imp = 2 pi N / omega, and with eq 10

    F(tau0) = Phi,   Phi = 9 pi (1 - nu) N / (4 G R^(1/2) H^(3/2))      (dimensionless)

(R in m, G in Pa, N in newtons, H in m: the normal drive amplitude of eq 3.) F decreases
monotonically from 8 at tau0 = -pi/2 (contact all period long) to 0 at tau0 = pi/2
(grazing contact), so the balance has exactly one root for 0 < Phi < 8. For Phi >= 8 the
contact never opens: the rotor is pressed on the rod throughout, and the intermittent
model of the paper does not apply; the solver returns nan there, never a number.

We solve in m = (1 - sin tau0) / 2 = sin^2(e / 2), e = pi/2 - tau0, the variable of
``core.elliptic``, where F = 12 m^2 J(m) rises from 0 (m = 0) to 8 (m = 1), and carry
mc = 1 - m alongside, so that deep preload (m near 1) keeps its digits. F itself is
always ``core.elliptic.impulse_factor`` (one source of truth for eq 11); this module adds
only what the root solve needs:

- a starting point from a table of the inverse, built once at import from core's F:
  nodes m = 0.95 i / 192 and mc = 0.05 / 1.1^j (down to 1e-13), with s = sqrt(F / 8)
  and the slope dm/ds, interpolated by cubic Hermite pieces in s (located by
  u = 1 - s, formed as (8 - Phi) / (8 (1 + s)), and interpolated in u where s >= 1/2, so
  that mc keeps its digits near Phi = 8). For Phi < 7.9 the start is good to 1e-8 and
  the slope dF/dm the pieces imply to 3e-7 (both tested);
- the exact slope dF/dm = 2 F / m + 12 m^2 J'(m), with
  J'(m) = ((8 - 7m) E(m) - mc (8 - 3m) K(m)) / (6 m^3) for m >= 0.05 (K, E with
  parameter m) and its hypergeometric series below (the closed form cancels there);
- Newton steps on all points at once, safeguarded by a bracket [lo, hi] that every
  evaluation of F narrows (F is monotone): a step that leaves the bracket is replaced by
  its midpoint. The first step uses the table's slope; a point is done after it if the
  step is below 1e-8 of min(m, mc) and Phi < 7.9 (remaining error < 3e-7 x 1e-8 from
  the slope plus ~1e-16 from the quadratic term). Later steps use the exact slope and
  stop below 1e-7 of min(m, mc) (Newton converges quadratically: dF/dm > 0, d2F/dm2
  bounded up to a mild log at m = 1, so ~1e-14 remains). A point is also done when
  |F - Phi| is at the rounding level of F itself (4e-15 Phi: near Phi = 8 no step can do
  better). In practice one evaluation of F settles all points below Phi = 7.9, and the
  few above take one or two more (only those points are carried on).

tau0 = pi/2 - 2 arcsin(sqrt m) for m <= 1/2, and 2 arcsin(sqrt mc) - pi/2 above, each
exact to rounding. Near Phi = 8 the problem itself is ill-conditioned: F(m) has absolute
error ~1e-15, so mc, and tau0 + pi/2 ~ 2 sqrt(mc), are good to ~1e-16 / mc relative.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import ellipe, ellipkm1

from core.elliptic import impulse_factor

#: F(tau0) at tau0 = -pi/2: the largest mean contact force an intermittent contact can carry,
#: in units of 4 G R^(1/2) H^(3/2) / (9 pi (1 - nu)).
PHI_MAX = 8.0

_G0 = math.sqrt(32.0 / (9.0 * math.pi))  # dm/ds at s = 0: F ~ (9 pi / 4) m^2
_SERIES_BELOW = 0.05
_TOL = 1e-7
_TOL_FIRST = 1e-8  # first step, taken with the table's slope
_TRUSTED = 7.9  # below this Phi the table's dF/dm is within 3e-7 (tests/core/test_motor.py)
_NOISE = 4e-15  # F is known to ~2e-15 relative: a residual below this carries no information
MAX_ITER = 60
_TINY = 1e-300


def _derivative_series(n: int) -> tuple[float, ...]:
    """Coefficients of J'(m) = sum d_k m^k, from J = sum c_k m^k (``core.elliptic``),
    highest first for Horner."""
    c = [3.0 * math.pi / 16.0]
    for k in range(n):
        c.append(c[-1] * (k + 0.5) ** 2 / ((k + 3.0) * (k + 1.0)))
    return tuple((k + 1) * c[k + 1] for k in range(n))[::-1]


_DJ = _derivative_series(9)  # truncation < 0.05^9 relative


def load_factor(
    preload: float, R: float, G: float, nu: float, H: ArrayLike
) -> NDArray[np.float64]:
    """Phi = 9 pi (1 - nu) N / (4 G R^(1/2) H^(3/2)) (dimensionless), the value F(tau0) must
    take for a mean contact force N (eq 10 with P_imp = 2 pi N / omega); inf where H = 0.
    N in newtons, R and H in m, G in Pa."""
    H = np.asarray(H, dtype=float)
    with np.errstate(divide="ignore", over="ignore"):  # H -> 0: Phi = inf, never opens
        return (9.0 * math.pi * (1.0 - nu) * preload / (4.0 * G * math.sqrt(R))) / (H * np.sqrt(H))


def slope(m: NDArray[np.float64], mc: NDArray[np.float64], F: NDArray[np.float64]
          ) -> NDArray[np.float64]:
    """dF/dm at m (with mc = 1 - m and F = F(m) given), 0 < m < 1."""
    out = np.empty_like(m)
    small = m < _SERIES_BELOW
    if small.any():
        ms = m[small]
        dj = np.full(ms.shape, _DJ[0])
        for d in _DJ[1:]:
            dj *= ms
            dj += d
        out[small] = 2.0 * F[small] / ms + 12.0 * ms * ms * dj
    big = ~small
    if big.any():
        mb, mcb = m[big], mc[big]
        k, e = ellipkm1(mcb), ellipe(mb)
        out[big] = 2.0 * (F[big] + (8.0 - 7.0 * mb) * e - mcb * (8.0 - 3.0 * mb) * k) / mb
    return out


def _inverse_table() -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The inverse of s = sqrt(F(m) / 8) as cubic pieces between nodes, F from
    ``core.elliptic``: nodes from m = 0 (s = 0, dm/ds = g0) to m = 1 (s = 1,
    dm/ds = 16 / 18). Returns -u at the nodes (ascending, u = 1 - s, for the search) and
    one column per interval of: s_i, 1 / (s_i+1 - s_i), u_i, 1 / (u_i - u_i+1), m_i, mc_i
    and the coefficients q1, q2, q3 of the cubic Hermite piece in t in [0, 1]:
    m = m_i + t (q1 + t (q2 + t q3)), mc = mc_i - t (q1 + t (q2 + t q3))."""
    m_lin = np.linspace(0.0, 0.95, 193)[1:]
    mc_geo = 0.05 * 1.1 ** -np.arange(1.0, 280.0)  # down to 1e-13 (8 - F: 1.8e-12)
    m = np.concatenate([m_lin, 1.0 - mc_geo])
    mc = np.concatenate([1.0 - m_lin, mc_geo])
    F = impulse_factor(m, mc)
    s = np.sqrt(F / PHI_MAX)
    u = (PHI_MAX - F) / (PHI_MAX * (1.0 + s))
    if not (np.all(np.diff(u) < 0.0) and u[-1] > 0.0):
        raise RuntimeError("core.motor.balance: the inverse table of F is not monotone")
    d = 2.0 * PHI_MAX * s / slope(m, mc, F)
    S, U = np.concatenate([[0.0], s, [1.0]]), np.concatenate([[1.0], u, [0.0]])
    M, MC = np.concatenate([[0.0], m, [1.0]]), np.concatenate([[1.0], mc, [0.0]])
    D = np.concatenate([[_G0], d, [16.0 / 18.0]])
    h = np.diff(S)
    dm = np.diff(M)
    q1, e1 = h * D[:-1], h * D[1:]  # dm/dt at the two ends of each piece
    q2 = 3.0 * dm - 2.0 * q1 - e1
    q3 = q1 + e1 - 2.0 * dm
    columns = np.stack([S[:-1], 1.0 / h, U[:-1], -1.0 / np.diff(U), M[:-1], MC[:-1], q1, q2, q3])
    return -U, columns


def _start(phi: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """Starting point (m, mc) for 0 < phi < 8, and dF/dm there (= 16 s / (dm/ds)), from
    the cubic pieces of the inverse table."""
    s = np.sqrt(phi / PHI_MAX)
    u = (PHI_MAX - phi) / (PHI_MAX * (1.0 + s))  # 1 - s with the digits of 8 - phi
    # located by u (exact to 1e-16 absolute everywhere, and relative near Phi = 8, where
    # the nodes' s values are 1 - 1e-15 apart and round alike)
    i = np.searchsorted(_NEG_U, -u, side="right")
    np.clip(i, 1, _NEG_U.size - 1, out=i)
    i -= 1
    s0, inv_h, u0, inv_hu, m0, mc0, q1, q2, q3 = _COLUMNS.take(i, axis=1)
    t = np.where(s < 0.5, (s - s0) * inv_h, (u0 - u) * inv_hu)
    q = q1 + t * (q2 + t * q3)
    dm_dt = q + t * (q2 + 2.0 * t * q3)
    q *= t
    m, mc = m0 + q, mc0 - q
    np.maximum(mc, _TINY, out=mc)  # in the last piece (Phi within 2e-12 of 8) rounding
    np.maximum(m, _TINY, out=m)  # could reach the ends, where F is not defined
    return m, mc, (2.0 * PHI_MAX) * s / (dm_dt * inv_h)


_NEG_U, _COLUMNS = _inverse_table()


def solve(phi: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(m, mc) with F(m) = phi, m = (1 - sin tau0) / 2 and mc = 1 - m, elementwise;
    nan where phi >= 8 (the contact never opens) or phi is nan. phi must be > 0.

    Raises RuntimeError if some point has not converged after MAX_ITER steps (never
    observed: it would be a bug, not an answer)."""
    phi = np.asarray(phi, dtype=float)
    opens = phi < PHI_MAX
    every = bool(opens.all())
    if not every and not opens.any():
        return np.full(phi.shape, np.nan), np.full(phi.shape, np.nan)
    p = phi.reshape(-1) if every else phi[opens]
    m, mc, d = _start(p)
    trusted = p < _TRUSTED
    lo, lo_c, hi, hi_c = 0.0, 1.0, 1.0, 0.0  # the bracket: F(lo) <= p <= F(hi)
    active = None  # indices of the points still iterating, once some are done
    for it in range(MAX_ITER):
        F = impulse_factor(m, mc)
        f = F - p
        if it:
            d = slope(m, mc, F)
        step = f / d
        m_new, mc_new = m - step, mc + step
        inside = (m_new >= lo) & (mc_new >= hi_c)  # each end compared where it is exact
        if it:
            small = np.abs(step) <= _TOL * np.minimum(m, mc)
        else:  # the table's slope is good to 3e-7 below _TRUSTED: demand a smaller step
            small = (np.abs(step) <= _TOL_FIRST * np.minimum(m, mc)) & trusted
        done = inside & (small | (np.abs(f) <= _NOISE * p))
        if done.all():
            if active is None:
                m_res, mc_res = m_new, mc_new
            else:
                m_res[active], mc_res[active] = m_new, mc_new
            break
        if active is None:
            m_res, mc_res, active = np.empty_like(p), np.empty_like(p), np.arange(p.size)
        below, above = f <= 0.0, f >= 0.0
        lo, lo_c = np.where(below, m, lo), np.where(below, mc, lo_c)
        hi, hi_c = np.where(above, m, hi), np.where(above, mc, hi_c)
        m = np.where(inside, m_new, 0.5 * (lo + hi))
        mc = np.where(inside, mc_new, 0.5 * (lo_c + hi_c))
        m_res[active[done]], mc_res[active[done]] = m[done], mc[done]
        keep = ~done
        active, p, m, mc = active[keep], p[keep], m[keep], mc[keep]
        lo, lo_c, hi, hi_c = lo[keep], lo_c[keep], hi[keep], hi_c[keep]
    else:
        raise RuntimeError(f"tau0: the balance F(tau0) = Phi did not converge in {MAX_ITER} steps")
    if every:
        return m_res.reshape(phi.shape), mc_res.reshape(phi.shape)
    m_out, mc_out = np.full(phi.shape, np.nan), np.full(phi.shape, np.nan)
    m_out[opens], mc_out[opens] = m_res, mc_res
    return m_out, mc_out


def tau0_of(m: ArrayLike, mc: ArrayLike) -> NDArray[np.float64]:
    """tau0 (rad) of m = (1 - sin tau0) / 2 = sin^2(e/2), mc = 1 - m, without cancellation:
    pi/2 - 2 arcsin(sqrt m) for m <= 1/2, 2 arcsin(sqrt mc) - pi/2 otherwise; nan stays nan."""
    m, mc = np.asarray(m, dtype=float), np.asarray(mc, dtype=float)
    low = m <= 0.5
    a = np.arcsin(np.sqrt(np.where(low, m, mc)))
    return np.where(low, math.pi / 2 - 2.0 * a, 2.0 * a - math.pi / 2)
