"""The dimensionless impact, compiled: Hertz normal contact and the Mindlin-Deresiewicz
tangential history (``core.numerics.mdr.march``, the method of dimensionality
reduction), coupled to the rigid-body motion, integrated by velocity Verlet with
step-doubling error control.

Units: approach d = alpha / alpha*, time s = t v_n / alpha*, slip D = delta / delta*
with delta* = mu E* alpha* / (4 G_e) (the unit of ``mdr.march``'s spring displacements
for lengths in a* = sqrt(R* alpha*)). With these the equations of motion are

    d'' = -(15/16) P - gamma d^(1/4) d'         d(0) = 0, d'(0) = 1
    D'' = -(15/8) chi T                         D(0) = 0, D'(0) = Psi1

P = (4/3) d^(3/2) the Hertz force in E* alpha* a* (here the springs' sum, which tends to
it as the number of springs grows), T the tangential force in mu E* alpha* a*, opposing D,
each spring bounded by mu times its share of the total normal force (``step``);
chi and Psi1 those of ``bodies.Impact``, gamma the normal dashpot (0 for e = 1,
``normal.dashpot``). The normal force is the springs' own sum, so that the Coulomb bounds
of the springs add up to mu times the force that moves the bodies.

One step of length h (kick-drift-kick): half kicks with the old forces, drift of d and D,
one ``march`` step of the springs from (d, D) to (d_new, D_new), half kicks with the new
forces (the dashpot's velocity term implicit, so the step stays explicit and second
order). Step doubling: a step h and two steps h/2 from the same state (springs copied);
their difference / 3 estimates the error of the two half steps, which are kept when it
is below ``tol`` (an absolute tolerance on d, d' and, divided by max(1, |Psi1|), on D and
D'); the next h is 0.9 (tol / err)^(1/3) times this one, within [0.2, 2]. ``tol <= 0``
gives fixed steps of h0 (for measuring the step's own order).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from core.numerics.mdr import march_into

#: Columns of the history array: time s, d, d', D, D', normal force f (in m_n v_n^2 /
#: alpha*: d'' = -f), tangential force T (mu E* alpha* a*), slip work of the step.
HISTORY_COLUMNS = ("s", "d", "dv", "D", "Dv", "f", "T", "slip_work")


@njit(cache=True, nogil=True)
def _normal(P, d, dv_half, h, gamma):
    """(d' at the step's end, normal force f) from the springs' P at d: the implicit half
    kick dv = dv_half - h/2 f, f = (15/16) P + gamma d^(1/4) dv, with no tension (f >= 0)
    and no force out of contact."""
    if d <= 0.0:
        return dv_half, 0.0
    damp = gamma * d ** 0.25
    dv = (dv_half - 0.5 * h * (15.0 / 16.0) * P) / (1.0 + 0.5 * h * damp)
    f = (15.0 / 16.0) * P + damp * dv
    if f < 0.0:
        return dv_half, 0.0
    return dv, f


@njit(cache=True, nogil=True)
def spring_force(x, d, scale):
    """The springs' normal force, scale * sum of (d - x_i^2)_+ over the row (x increasing),
    summed in the springs' order (``march_into`` sums the same terms in its vector lanes:
    equal to rounding)."""
    s = 0.0
    for i in range(x.size):
        w = d - x[i] * x[i]
        if w <= 0.0:
            break
        s += w
    return scale * s


@njit(cache=True, nogil=True)
def step(h, d, dv, D, Dv, f, T, u, x, xx, scale, chi, gamma, total):
    """One Verlet step of length h from (d, d', D, D') with forces (f, T) there; u (the
    springs) is updated in place. Returns (d, d', D, D', f, T, slip work of the step in
    mu E* alpha* a* delta*). xx: the squares x * x of the positions.

    The Coulomb bound of each spring is mu times its share of the total normal force f
    (elastic plus dashpot), shared like the elastic force: mu k w with k = f / ((15/16) P)
    at the step's end. ``march`` is given the approach k d and the positions k^(1/2) x,
    which scales every spring's bound w = d - x^2 by k without changing which springs
    touch; k = 1 without a dashpot (e = 1) or when ``total`` is False (the bound on the
    elastic force alone, the other model choice)."""
    kt = (15.0 / 8.0) * chi
    dvh = dv - 0.5 * h * f
    Dvh = Dv + 0.5 * h * (-kt * T)
    dn = d + h * dvh
    Dn = D + h * Dvh
    Pn = spring_force(x, max(dn, 0.0), scale)
    dvn, fn = _normal(Pn, dn, dvh, h, gamma)
    k = 1.0
    if total and gamma != 0.0 and Pn > 0.0:
        k = fn / ((15.0 / 16.0) * Pn)
    dd = np.empty(2)
    dr = np.empty(2)
    dd[0] = k * max(d, 0.0)
    dd[1] = k * max(dn, 0.0)
    dr[0] = D
    dr[1] = Dn
    Ts, Ps, Ss = np.empty(2), np.empty(2), np.empty(2)
    if k == 1.0:  # the squares the caller has
        march_into(x, xx, dd, dr, scale, u, Ts, Ps, Ss, None)
    else:
        xs = x * math.sqrt(k)
        march_into(xs, xs * xs, dd, dr, scale, u, Ts, Ps, Ss, None)
    Tn = Ts[1]
    Dvn = Dvh - 0.5 * h * kt * Tn
    return dn, dvn, Dn, Dvn, fn, Tn, Ss[1]


@njit(cache=True, nogil=True)
def impact(psi1, chi, gamma, x, scale, tol, h0, max_steps, total=True):
    """Integrate one impact from first touch (d = 0, d' = 1, D = 0, D' = psi1) until the
    bodies separate (d < 0 moving apart, every spring out of contact). Returns the history
    (rows of ``HISTORY_COLUMNS``, the accepted steps) and the number of rejected steps.
    A negative row count means max_steps was reached first."""
    n = x.size
    out = np.zeros((max_steps + 1, 8))
    u = np.zeros(n)
    d, dv, D, Dv, f, T = 0.0, 1.0, 0.0, psi1, 0.0, 0.0
    s = 0.0
    out[0, 0] = 0.0
    out[0, 2] = 1.0
    out[0, 4] = psi1
    scale_D = max(1.0, abs(psi1))
    h = h0
    k = 0
    rejected = 0
    adaptive = tol > 0.0
    u1 = np.empty(n)
    u2 = np.empty(n)
    xx = x * x
    while k < max_steps:
        if adaptive:
            u1[:] = u
            r1 = step(h, d, dv, D, Dv, f, T, u1, x, xx, scale, chi, gamma, total)
            u2[:] = u
            a = step(0.5 * h, d, dv, D, Dv, f, T, u2, x, xx, scale, chi, gamma, total)
            r2 = step(0.5 * h, a[0], a[1], a[2], a[3], a[4], a[5], u2, x, xx, scale, chi,
                      gamma,
                      total)
            err = max(abs(r1[0] - r2[0]), abs(r1[1] - r2[1]),
                      abs(r1[2] - r2[2]) / scale_D, abs(r1[3] - r2[3]) / scale_D) / 3.0
            if err > tol and h > 1e-14:
                h *= max(0.2, 0.9 * (tol / err) ** (1.0 / 3.0))
                rejected += 1
                continue
            slip = a[6] + r2[6]
            u[:] = u2
            d, dv, D, Dv, f, T = r2[0], r2[1], r2[2], r2[3], r2[4], r2[5]
            s += h
            grow = 2.0 if err == 0.0 else min(2.0, max(0.2, 0.9 * (tol / err) ** (1.0 / 3.0)))
            h_used = h
            h *= grow
        else:
            r = step(h, d, dv, D, Dv, f, T, u, x, xx, scale, chi, gamma, total)
            slip = r[6]
            d, dv, D, Dv, f, T = r[0], r[1], r[2], r[3], r[4], r[5]
            s += h
            h_used = h
        k += 1
        out[k, 0] = s
        out[k, 1] = d
        out[k, 2] = dv
        out[k, 3] = D
        out[k, 4] = Dv
        out[k, 5] = f
        out[k, 6] = T
        out[k, 7] = slip
        if d <= 0.0 and dv < 0.0:
            inside = False
            for i in range(n):
                if u[i] != 0.0:
                    inside = True
                    break
            if not inside:
                return out[: k + 1], rejected
        if h_used <= 0.0:
            break
    return out[: k + 1], -1 - rejected


@njit(cache=True, nogil=True)
def separation_time(s0, d0, v0, s1, d1, v1):
    """The time in [s0, s1] where the cubic Hermite interpolant of d through (d0, d0')
    and (d1, d1') vanishes (d0 > 0 >= d1), by bisection (fourth-order accurate)."""
    h = s1 - s0
    lo, hi = 0.0, 1.0
    for _ in range(60):
        m = 0.5 * (lo + hi)
        h00 = 2 * m ** 3 - 3 * m ** 2 + 1
        h10 = m ** 3 - 2 * m ** 2 + m
        h01 = -2 * m ** 3 + 3 * m ** 2
        h11 = m ** 3 - m ** 2
        val = h00 * d0 + h10 * h * v0 + h01 * d1 + h11 * h * v1
        if val > 0.0:
            lo = m
        else:
            hi = m
    return s0 + 0.5 * (lo + hi) * h


def spring_row(n: int, reach: float = 1.05) -> tuple[np.ndarray, float]:
    """(x, scale): n springs at the midpoints of equal cells of [0, reach] (in a*, reach
    above 1 so that the largest contact radius is always inside the row) and the factor
    2 reach / n from the sum over springs to the force (both halves of the row)."""
    x = (np.arange(n) + 0.5) * (reach / n)
    return x, 2.0 * reach / n

