"""Figures of merit of many motor designs in one call: the batched form of the moving
rotor's scalar API (docs/study.md; the physics is docs/physics.md, sections 10.4 and 11).

For each design (a ``Motor`` and a contact point x0, with a load force, Archard's
coefficient and a hardness) this module returns, in SI units:

    stall_thrust       |Motor.stall_thrust(x0)|                          N   (eq 41)
    no_load_speed      no_load_speed(psi, tau0) omega |u0|              m/s
    best_efficiency    best_efficiency(psi, tau0).efficiency             1
    best_speed         best_efficiency(psi, tau0).v omega |u0|          m/s
    best_thrust        best_efficiency(psi, tau0).thrust_ratio mu N      N
    load_speed         operating_point(motor, x0, load).speed           m/s
    load_efficiency    operating_point(motor, x0, load).efficiency       1
    load_power         operating_point(motor, x0, load).output_power     W
    wear_rate          moving_wear_rate(motor, x0, moving_rotor(psi, tau0,
                       operating_point(...).v), k, hardness)            m^3/h

and it returns them equal to those scalar functions: the same thrust-speed evaluations
(the MDR march of ``core.numerics.mdr`` on the grid of ``core.numerics.loading``), the
same root finder and minimiser (scipy's ``brentq`` and bounded ``minimize_scalar``, their
iterations written out below step for step), so the same iterates and the same results,
bit for bit on a machine where numpy's and numba's sin, cos and dot agree (they call the
same libm and OpenBLAS here; ``tests/core/test_motor_batch.py`` compares the two APIs
over random designs of ``core.MOTOR_DOMAIN``).

It is cheaper per design than a loop over the scalar API because (a) a design's
evaluations r(v), p_loss(v) are made once and shared by its merits (the scalar
API makes the no-load solve twice, the stall thrust r(0) three times and the full-slip
end twice, and evaluates the operating speed and the best point again), and (b) each
evaluation runs compiled from end to end (``nogil``): the drive grid, the march and the
integrals, with no Python between the designs of a block.

Where a scalar function raises, the merit is nan: where the contact never opens
(Phi >= 8) every merit is nan; where psi is outside the moving rotor's range
(``MOTOR_DOMAIN["psi_moving"]``, e.g. x0 = 0) all but the stall thrust; where the load
exceeds the stall thrust (mu N r(0)) the load's merits and the wear rate.

    from core.motor import Motor, Rod
    from core.motor.designs import design_merits
    rod = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
    m = Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05)
    out = design_merits(m, x0=[-0.2e-3, -1e-3], load=4e-3)
    out.no_load_speed, out.best_efficiency, out.load_speed   # arrays over the designs
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numba import njit
from numpy.typing import ArrayLike, NDArray

from core.frozen import freeze
from core.motor.motor import Motor
from core.motor.moving_rotor import PSI, SPRINGS, STEPS, _resolution
from core.motor.wear import HOUR
from core.numerics.loading import partial_stick_estimate, trapezoid
from core.numerics.mdr import march_into
from core.validation import DOMAIN, MOTOR_DOMAIN, Interval

#: The figures of merit of ``DesignMerits``: name -> (SI unit, description).
MERITS: dict[str, tuple[str, str]] = {
    "stall_thrust": ("N", "thrust on the held rotor, mu N T_imp / (mu P_imp) (eq 41)"),
    "no_load_speed": ("m/s", "rotor surface speed at which the thrust vanishes"),
    "best_efficiency": ("1", "largest efficiency between stall and no load"),
    "best_speed": ("m/s", "speed at the best efficiency"),
    "best_thrust": ("N", "thrust at the best efficiency"),
    "load_speed": ("m/s", "steady speed under the load force"),
    "load_efficiency": ("1", "efficiency under the load force"),
    "load_power": ("W", "output power under the load force, V F_L"),
    "wear_rate": ("m^3/h", "Archard wear volume per hour under the load force"),
}

#: Tolerances of the scalar API (``no_load_speed`` and ``operating_speed``: brentq's
#: xtol; ``best_efficiency``: the bounded minimiser's xatol) and scipy's defaults.
XTOL_ROOT = 1e-9
XTOL_BEST = 1e-6
_RTOL = 4.0 * np.finfo(float).eps  # scipy.optimize.brentq's default rtol
_ROOT_ITER = 100  # brentq's default maxiter
_BEST_MAXFUN = 500  # minimize_scalar(method="bounded")'s default maxiter
#: Evaluations remembered per design (a design needs ~30-60).
_CACHE = 1024

# Columns of the kernel's output, per contact (dimensionless).
_R0, _V0, _VB, _EB, _RB, _VL, _EL, _PL, _LL, _NE, _OK = range(11)
_COLUMNS = 11
# status bits (column _OK): 1 no-load solved, 2 best solved, 4 load solved
_NOLOAD_OK, _BEST_OK, _LOAD_OK = 1, 2, 4


# ---- one evaluation, compiled: moving_rotor._one bit for bit ------------------------
@njit(cache=True, nogil=True)
def _block(a, lo, n):
    """numpy's sum of a block a[lo:lo + n], n <= 128: eight accumulators (n >= 8)."""
    if n < 8:
        res = -0.0
        for i in range(lo, lo + n):
            res += a[i]
        return res
    r0, r1, r2, r3 = a[lo], a[lo + 1], a[lo + 2], a[lo + 3]
    r4, r5, r6, r7 = a[lo + 4], a[lo + 5], a[lo + 6], a[lo + 7]
    i = 8
    top = n - n % 8
    while i < top:
        j = lo + i
        r0 += a[j]
        r1 += a[j + 1]
        r2 += a[j + 2]
        r3 += a[j + 3]
        r4 += a[j + 4]
        r5 += a[j + 5]
        r6 += a[j + 6]
        r7 += a[j + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        res += a[lo + i]
        i += 1
    return res


@njit(cache=True, nogil=True)
def _pairwise(a):
    """numpy's pairwise sum of a 1-d array (``ndarray.sum``'s order): blocks of at most
    128 summed by ``_block``, longer runs split at n // 2 rounded down to a multiple of
    8, the halves added. The tree is walked with a stack (numba's cache cannot hold a
    recursive function)."""
    n = a.size
    if n <= 128:
        return _block(a, 0, n)
    lo_s = np.empty(128, dtype=np.int64)
    n_s = np.empty(128, dtype=np.int64)
    done_s = np.zeros(128, dtype=np.bool_)
    vals = np.empty(128)
    top, nv = 1, 0
    lo_s[0], n_s[0] = 0, n
    while top:
        top -= 1
        lo, m = lo_s[top], n_s[top]
        if m <= 128:
            vals[nv] = _block(a, lo, m)
            nv += 1
        elif done_s[top]:  # both halves summed: add them
            nv -= 1
            vals[nv - 1] = vals[nv - 1] + vals[nv]
        else:
            half = m // 2
            half -= half % 8
            done_s[top] = True  # the node stays, below its halves
            top += 1
            lo_s[top], n_s[top], done_s[top] = lo + half, m - half, False
            top += 1
            lo_s[top], n_s[top], done_s[top] = lo, half, False  # summed first
            top += 1
    return vals[0]


@njit(cache=True, nogil=True)
def _sum(a):
    """``a.sum()`` of a 1-d float array, in numpy's order."""
    return 0.0 + _pairwise(a)


@njit(cache=True, nogil=True)
def _drive_grid(psi, tau0, v, n):
    """``core.numerics.loading.drive_grid`` compiled, the same times bit for bit: tau0,
    the end, the reversals, the switches and the ends of the partial-stick windows held,
    the pieces between them sized as there."""
    n = max(n, 4)
    end = math.pi - tau0
    rev = np.empty(2)
    n_rev = 0
    if v < 1.0:
        a = math.acos(v)
        for t in (-a, a):
            if tau0 < t < end:
                rev[n_rev] = t
                n_rev += 1
    sw = np.empty(4)
    n_sw = 0
    c1 = (psi * v / (psi - 1.0)) if psi != 1.0 else math.inf
    c2 = psi * v / (psi + 1.0)
    for c in (c1, c2):
        if abs(c) <= 1.0:
            a = math.acos(c)
            for t in (-a, a):
                if tau0 < t < end:
                    seen = False
                    for j in range(n_rev):
                        if rev[j] == t:
                            seen = True
                    if not seen:
                        sw[n_sw] = t
                        n_sw += 1
    w_lo = np.empty(2)
    w_hi = np.empty(2)
    for j in range(n_rev):
        t = rev[j]
        w_lo[j] = t
        top = t + 1.5 * partial_stick_estimate(psi, tau0, t)
        w_hi[j] = end if end < top else top
    held_all = np.empty(2 + n_rev + n_sw + n_rev)
    held_all[0] = tau0
    held_all[1] = end
    k = 2
    for j in range(n_rev):
        held_all[k] = rev[j]
        k += 1
    for j in range(n_sw):
        held_all[k] = sw[j]
        k += 1
    for j in range(n_rev):
        held_all[k] = w_hi[j]
        k += 1
    held_all.sort()
    held = np.empty(held_all.size)
    n_held = 0
    for j in range(held_all.size):  # the set: equal times once
        if n_held == 0 or held_all[j] != held[n_held - 1]:
            held[n_held] = held_all[j]
            n_held += 1
    n_pieces = 0
    p_lo = np.empty(n_held)
    p_hi = np.empty(n_held)
    for j in range(n_held - 1):
        if held[j + 1] > held[j]:
            p_lo[n_pieces] = held[j]
            p_hi[n_pieces] = held[j + 1]
            n_pieces += 1
    flags = np.zeros(n_pieces, dtype=np.bool_)
    lengths = np.empty(n_pieces)
    n_w = 0
    for j in range(n_pieces):
        a, b = p_lo[j], p_hi[j]
        lengths[j] = b - a
        for i in range(n_rev):
            if w_lo[i] <= a and b <= w_hi[i]:
                flags[j] = True
        if flags[j]:
            n_w += 1
    in_w = np.empty(n_w)
    out_w = np.empty(n_pieces - n_w)
    iw = io = 0
    for j in range(n_pieces):
        if flags[j]:
            in_w[iw] = lengths[j]
            iw += 1
        else:
            out_w[io] = lengths[j]
            io += 1
    total_w, total_o = _sum(in_w), _sum(out_w)
    share_w = n // 3 if total_o > 0.0 else n
    share_o = n - share_w if total_w > 0.0 else n
    counts = np.empty(n_pieces, dtype=np.int64)
    size = 0
    for j in range(n_pieces):
        q = (share_w / total_w) if flags[j] else (share_o / total_o)
        c = int(np.rint(q * lengths[j]))
        counts[j] = c if c > 1 else 1
        size += counts[j]
    out = np.empty(size + 1)
    pos = 0
    for j in range(n_pieces):
        a, b, c = p_lo[j], p_hi[j], counts[j]
        for i in range(c):
            out[pos + i] = a + (b - a) * (i / c)
        pos += c
    out[size] = end
    return out


@njit(cache=True, nogil=True)
def _evaluate(psi, tau0, v, xx, springs, steps):
    """(r, p_loss) of one contact at speed v: ``core.motor.moving_rotor._one``
    (``core.numerics.mdr.moving`` and its integrals), the same operations in the same
    order, compiled; the input power p_in, which no merit reads, is not formed."""
    tau = _drive_grid(psi, tau0, v, steps)
    nt = tau.size
    c0 = 2.0 * math.sin(0.5 * (math.pi / 2 - tau0)) ** 2  # loading.one_minus_s0
    to_u = psi / c0
    d = np.empty(nt)
    drive = np.empty(nt)
    for k in range(nt):
        t = tau[k]
        rise = 2.0 * math.cos(0.5 * (t + tau0)) * math.sin(0.5 * (t - tau0))
        d[k] = (rise if rise >= 0.0 else 0.0) / c0  # np.maximum(rise, 0.0)
        drive[k] = to_u * (rise - v * (t - tau0))
    d[0] = 0.0
    d[nt - 1] = 0.0
    scale = 0.75 * c0 ** 1.5 * 2.0 / springs
    T, P, S = np.empty(nt), np.empty(nt), np.empty(nt)
    # no stick radius (b None): the positions x are not read, their squares xx are
    march_into(xx, xx, d, drive, scale, np.zeros(springs), T, P, S, None)
    impulse = trapezoid(P, tau)
    for k in range(nt):
        S[k] = S[k] / to_u
    return trapezoid(T, tau) / impulse, _sum(S) / impulse


# ---- the scalar API's solvers, on cached evaluations --------------------------------
@njit(cache=True, nogil=True)
def _cached(psi, tau0, v, xx, springs, steps, cache, count):
    """Row of the cache holding the evaluation at v (computed if new): cache[j] =
    (v, r, p_loss), count[0] rows used. -1 if the cache is full."""
    for j in range(count[0]):
        if cache[j, 0] == v:
            return j
    j = count[0]
    if j >= cache.shape[0]:
        return -1
    r, loss = _evaluate(psi, tau0, v, xx, springs, steps)
    cache[j, 0], cache[j, 1], cache[j, 2] = v, r, loss
    count[0] = j + 1
    return j


@njit(cache=True, nogil=True)
def _thrust_minus(psi, tau0, v, shift, xx, springs, steps, cache, count):
    """r(v) - shift (nan if the cache is full)."""
    j = _cached(psi, tau0, v, xx, springs, steps, cache, count)
    return math.nan if j < 0 else cache[j, 1] - shift


@njit(cache=True, nogil=True)
def _brentq(psi, tau0, shift, xa, xb, xtol, xx, springs, steps, cache, count):
    """The root of r(v) = shift in [xa, xb] by scipy's brentq (scipy/optimize/Zeros/
    brentq.c, step for step: rtol 4 eps, 100 iterations); nan where scipy raises (no
    sign change, no convergence, a nan value)."""
    xpre, xcur = xa, xb
    xblk = 0.0
    fblk = 0.0
    spre = 0.0
    scur = 0.0
    fpre = _thrust_minus(psi, tau0, xpre, shift, xx, springs, steps, cache, count)
    fcur = _thrust_minus(psi, tau0, xcur, shift, xx, springs, steps, cache, count)
    if math.isnan(fpre) or math.isnan(fcur) or fpre * fcur > 0:
        return math.nan
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    for _ in range(_ROOT_ITER):
        if fpre * fcur < 0:
            xblk = xpre
            fblk = fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre = xcur
            xcur = xblk
            xblk = xpre
            fpre = fcur
            fcur = fblk
            fblk = fpre
        delta = (xtol + _RTOL * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre = scur
                scur = stry
            else:
                spre = sbis
                scur = sbis
        else:
            spre = sbis
            scur = sbis
        xpre = xcur
        fpre = fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0 else -delta
        fcur = _thrust_minus(psi, tau0, xcur, shift, xx, springs, steps, cache, count)
        if math.isnan(fcur):
            return math.nan
    return math.nan


@njit(cache=True, nogil=True)
def _efficiency(psi, v, p_out, loss):
    """``moving_rotor._efficiency`` of one speed."""
    if v == 0.0:
        return 1.0 if psi <= 1.0 else 0.0
    if p_out > 0.0:
        return p_out / (p_out + loss)
    return 0.0 if p_out == 0.0 else math.nan


@njit(cache=True, nogil=True)
def _minus_eta(psi, tau0, s, xx, springs, steps, cache, count):
    """-eta(s), the function ``best_efficiency`` minimises (nan if the cache is full)."""
    j = _cached(psi, tau0, s, xx, springs, steps, cache, count)
    if j < 0:
        return math.nan
    return -_efficiency(psi, s, s * cache[j, 1], cache[j, 2])


@njit(cache=True, nogil=True)
def _sign(a):
    """np.sign of a float."""
    if a > 0.0:
        return 1.0
    if a < 0.0:
        return -1.0
    return a  # 0.0, -0.0 or nan


@njit(cache=True, nogil=True)
def _fminbound(psi, tau0, x1, x2, xatol, xx, springs, steps, cache, count):
    """(x, f) of the minimum of -eta over [x1, x2] by scipy's
    ``_minimize_scalar_bounded`` (scipy/optimize/_optimize.py, step for step; 500
    evaluations at most), returned whatever its status, as ``best_efficiency`` uses
    them."""
    sqrt_eps = math.sqrt(2.2e-16)
    golden_mean = 0.5 * (3.0 - math.sqrt(5.0))
    a, b = x1, x2
    fulc = a + golden_mean * (b - a)
    nfc, xf = fulc, fulc
    rat = e = 0.0
    xv = xf
    fx = _minus_eta(psi, tau0, xv, xx, springs, steps, cache, count)
    num = 1
    fu = math.inf
    ffulc = fnfc = fx
    xm = 0.5 * (a + b)
    tol1 = sqrt_eps * abs(xf) + xatol / 3.0
    tol2 = 2.0 * tol1
    while abs(xf - xm) > (tol2 - 0.5 * (b - a)):
        golden = True
        if abs(e) > tol1:
            golden = False
            r = (xf - nfc) * (fx - ffulc)
            q = (xf - fulc) * (fx - fnfc)
            p = (xf - fulc) * q - (xf - nfc) * r
            q = 2.0 * (q - r)
            if q > 0.0:
                p = -p
            q = abs(q)
            r = e
            e = rat
            if (abs(p) < abs(0.5 * q * r)) and (p > q * (a - xf)) and (p < q * (b - xf)):
                rat = (p + 0.0) / q
                xv = xf + rat
                if ((xv - a) < tol2) or ((b - xv) < tol2):
                    si = _sign(xm - xf) + (1.0 if (xm - xf) == 0 else 0.0)
                    rat = tol1 * si
            else:
                golden = True
        if golden:
            if xf >= xm:
                e = a - xf
            else:
                e = b - xf
            rat = golden_mean * e
        si = _sign(rat) + (1.0 if rat == 0 else 0.0)
        step = abs(rat)
        if not (step >= tol1 or math.isnan(step)):  # np.maximum, nan propagating
            step = tol1
        xv = xf + si * step
        fu = _minus_eta(psi, tau0, xv, xx, springs, steps, cache, count)
        num += 1
        if fu <= fx:
            if xv >= xf:
                a = xf
            else:
                b = xf
            fulc, ffulc = nfc, fnfc
            nfc, fnfc = xf, fx
            xf, fx = xv, fu
        else:
            if xv < xf:
                a = xv
            else:
                b = xv
            if (fu <= fnfc) or (nfc == xf):
                fulc, ffulc = nfc, fnfc
                nfc, fnfc = xv, fu
            elif (fu <= ffulc) or (fulc == xf) or (fulc == nfc):
                fulc, ffulc = xv, fu
        xm = 0.5 * (a + b)
        tol1 = sqrt_eps * abs(xf) + xatol / 3.0
        tol2 = 2.0 * tol1
        if num >= _BEST_MAXFUN:
            break
    return xf, fx


@njit(cache=True, nogil=True)
def _contact(psi, tau0, load, springs, steps, xtol, xatol, xx, cache, count, out):
    """Every merit of one contact (dimensionless) into ``out`` (columns _R0 ...): the
    no-load solve, the best efficiency and the operating point under the load ratio
    ``load`` (nan: none), sharing the cached evaluations."""
    count[0] = 0
    out[:] = math.nan
    status = 0
    v_full = (1.0 + 1.0 / psi) * math.cos(tau0 if tau0 >= 0.0 else 0.0)  # full_slip_speed
    v0 = _brentq(psi, tau0, 0.0, 0.0, v_full, xtol, xx, springs, steps, cache, count)
    j = _cached(psi, tau0, 0.0, xx, springs, steps, cache, count)
    if j >= 0:
        out[_R0] = cache[j, 1]
    if not math.isnan(v0):
        out[_V0] = v0
        status |= _NOLOAD_OK
    if psi <= 1.0:
        if j >= 0:
            out[_VB], out[_EB], out[_RB] = 0.0, 1.0, cache[j, 1]
            status |= _BEST_OK
    elif not math.isnan(v0):
        s, f = _fminbound(psi, tau0, 0.0, v0, xatol, xx, springs, steps, cache, count)
        if not math.isnan(s):
            k = _cached(psi, tau0, s, xx, springs, steps, cache, count)
            if k >= 0:
                out[_VB], out[_EB], out[_RB] = s, -f, cache[k, 1]
                status |= _BEST_OK
    stall = out[_R0]
    if not math.isnan(load) and not math.isnan(stall) and load <= stall:
        v = 0.0 if load == stall else _brentq(psi, tau0, load, 0.0, v_full, xtol, xx,
                                               springs, steps, cache, count)
        k = -1 if math.isnan(v) else _cached(psi, tau0, v, xx, springs, steps, cache, count)
        if k >= 0:
            p_out = load * v  # F_L V (load.operating_efficiency): 0 at zero load
            out[_VL] = v
            out[_EL] = _efficiency(psi, v, p_out, cache[k, 2])
            out[_PL] = p_out
            out[_LL] = cache[k, 2]
            status |= _LOAD_OK
    out[_NE] = count[0]
    out[_OK] = status


@njit(cache=True, nogil=True)
def _contacts(psi, tau0, load, springs, steps, xtol, xatol):
    """``_contact`` for each point of the 1-d arrays psi, tau0, load: (n, _COLUMNS)."""
    n = psi.size
    out = np.empty((n, _COLUMNS))
    xx = (np.arange(springs) + 0.5) / springs  # mdr.spring_positions, squared
    xx *= xx
    cache = np.empty((_CACHE, 3))
    count = np.zeros(1, dtype=np.int64)
    for i in range(n):
        _contact(psi[i], tau0[i], load[i], springs, steps, xtol, xatol, xx, cache, count,
                 out[i])
    return out


# ---- the dimensionless API -----------------------------------------------------------
@dataclass(frozen=True)
class ContactMerits:
    """The moving rotor's figures of merit of many contacts (psi, tau0) (read-only
    arrays of one shape; dimensionless, in the units of ``core.motor.MovingRotor``).

    Attributes:
        psi, tau0: the contacts (eq 23; rad).
        load_ratio: l = F_L / (mu N) of each contact's operating point (nan: none).
        stall_ratio: the MDR's thrust ratio of the held rotor r(0) (eq 41 to ~1e-5).
        no_load_speed: v0 with r(v0) = 0 (``no_load_speed``).
        best_speed, best_efficiency, best_thrust_ratio: ``best_efficiency``'s v,
            efficiency and thrust_ratio.
        load_speed, load_efficiency, load_output_power, load_friction_loss: v, eta,
            p_out = l v and p_loss at the operating point r(v) = l (``operating_speed``,
            ``moving_rotor``, ``operating_efficiency``); nan where l > r(0) (the rotor
            is stalled).
        evaluations: thrust-speed evaluations (MDR contacts) made for the contact.
    Every merit is nan where its scalar function raises.
    """

    psi: NDArray[np.float64]
    tau0: NDArray[np.float64]
    load_ratio: NDArray[np.float64]
    stall_ratio: NDArray[np.float64]
    no_load_speed: NDArray[np.float64]
    best_speed: NDArray[np.float64]
    best_efficiency: NDArray[np.float64]
    best_thrust_ratio: NDArray[np.float64]
    load_speed: NDArray[np.float64]
    load_efficiency: NDArray[np.float64]
    load_output_power: NDArray[np.float64]
    load_friction_loss: NDArray[np.float64]
    evaluations: NDArray[np.int64]

    def __post_init__(self) -> None:
        freeze(self)


def _reals(name: str, value: ArrayLike) -> NDArray[np.float64]:
    """value as a float array (ValueError naming ``name`` for anything else)."""
    try:
        raw = np.asarray(value)
    except (ValueError, TypeError) as err:
        raise ValueError(f"{name} must be real numbers: {err}") from err
    if raw.dtype.kind not in "iuf":
        raise ValueError(f"{name} must be real numbers, got dtype {raw.dtype}")
    return raw.astype(np.float64)


def _broadcast(**values: ArrayLike) -> tuple[NDArray[np.float64], ...]:
    """The arguments, by name, as float arrays broadcast together (read-only views of
    one shape; ValueError naming an argument that is not real numbers, or the shapes
    that do not broadcast)."""
    arrays = [_reals(name, value) for name, value in values.items()]
    try:
        return tuple(np.broadcast_arrays(*arrays))
    except ValueError as err:
        shapes = ", ".join(f"{name} {a.shape}" for name, a in zip(values, arrays, strict=True))
        raise ValueError(f"the shapes of {shapes} do not broadcast together") from err


def _check_all(name: str, values: NDArray[np.float64], row: Interval) -> None:
    """ValueError naming the first element of ``values`` outside ``row`` (nan, inf
    included), its value and the range."""
    lo, hi = row.closed_bounds
    with np.errstate(invalid="ignore"):
        bad = ~(np.isfinite(values) & (values >= lo) & (values <= hi))
    if bad.any():
        first = np.unravel_index(np.flatnonzero(bad)[0], values.shape)
        label = name if values.ndim == 0 else f"{name}[{', '.join(str(int(i)) for i in first)}]"
        row.check(label, values[first])


def contact_merits(psi: ArrayLike, tau0: ArrayLike, load_ratio: ArrayLike = np.nan, *,
                   springs: int = SPRINGS, steps: int = STEPS) -> ContactMerits:
    """Stall thrust, no-load speed, best efficiency and the operating point under a load
    ratio of each contact (psi, tau0) (arrays, broadcast together with ``load_ratio``;
    ``ContactMerits``), equal to ``no_load_speed``, ``best_efficiency`` and
    ``operating_speed`` + ``moving_rotor`` called per contact with the same springs and
    steps.

    Parameters
    ----------
    psi : array_like
        psi of eq 23, each in [1e-5, 1e12] (``MOTOR_DOMAIN["psi_moving"]``).
    tau0 : array_like
        Start of contact (rad), each in (-pi/2, pi/2).
    load_ratio : array_like
        l = F_L / (mu N) in [0, 1] (``MOTOR_DOMAIN["load_ratio"]``), or nan for no
        operating point.
    springs, steps : int
        MDR resolution (``moving_rotor``'s; the defaults converge r to 1e-4).

    Returns
    -------
    ContactMerits

    Raises
    ------
    ValueError
        Naming the first element outside its range, or a resolution beyond
        ``MOTOR_DOMAIN``.

    See Also
    --------
    design_merits : the same for motors and contact points, in SI units.
    core.motor.best_efficiency, core.motor.no_load_speed, core.motor.operating_speed
    """
    p, t, ell = _broadcast(psi=psi, tau0=tau0, load_ratio=load_ratio)
    _check_all("psi", p, PSI)
    _check_all("psi", p, MOTOR_DOMAIN["psi_moving"])
    _check_all("tau0", t, DOMAIN["tau0"])
    given = ~np.isnan(ell)
    _check_all("load_ratio", np.where(given, ell, 0.0), MOTOR_DOMAIN["load_ratio"])
    n, m = _resolution(springs, steps)
    out = _contacts(np.ascontiguousarray(p.ravel()), np.ascontiguousarray(t.ravel()),
                    np.ascontiguousarray(ell.ravel()), n, m, XTOL_ROOT, XTOL_BEST)
    out = out.reshape(*p.shape, _COLUMNS)
    return ContactMerits(
        psi=p, tau0=t, load_ratio=ell, stall_ratio=out[..., _R0],
        no_load_speed=out[..., _V0], best_speed=out[..., _VB],
        best_efficiency=out[..., _EB], best_thrust_ratio=out[..., _RB],
        load_speed=out[..., _VL], load_efficiency=out[..., _EL],
        load_output_power=out[..., _PL], load_friction_loss=out[..., _LL],
        evaluations=out[..., _NE].astype(np.int64))


# ---- the SI API ----------------------------------------------------------------------
@dataclass(frozen=True)
class DesignMerits:
    """The figures of merit of many designs (read-only arrays over the designs; SI, as
    ``MERITS`` lists them), with the contact of each design: psi, tau0 (rad), the
    scale omega |u0| (m/s per unit of the dimensionless speed v) and mu N (N)."""

    stall_thrust: NDArray[np.float64]
    no_load_speed: NDArray[np.float64]
    best_efficiency: NDArray[np.float64]
    best_speed: NDArray[np.float64]
    best_thrust: NDArray[np.float64]
    load_speed: NDArray[np.float64]
    load_efficiency: NDArray[np.float64]
    load_power: NDArray[np.float64]
    wear_rate: NDArray[np.float64]
    psi: NDArray[np.float64]
    tau0: NDArray[np.float64]
    speed_scale: NDArray[np.float64]
    coulomb_force: NDArray[np.float64]
    evaluations: NDArray[np.int64]

    def __post_init__(self) -> None:
        freeze(self)


def _as_motors(motor: Motor | Sequence[Motor], size: int) -> list[Motor]:
    if isinstance(motor, Motor):
        return [motor] * size
    motors = list(motor)
    if len(motors) != size or not all(isinstance(m, Motor) for m in motors):
        raise ValueError(f"motor must be a core.motor.Motor or a sequence of {size} of "
                         "them (one per design)")
    return motors


def design_merits(motor: Motor | Sequence[Motor], x0: ArrayLike, load: ArrayLike = 0.0,
                  wear_coefficient: ArrayLike = 1e-6, hardness: ArrayLike = 2e9, *,
                  springs: int = SPRINGS, steps: int = STEPS) -> DesignMerits:
    """Every figure of merit of ``MERITS`` for the designs (motor, x0, load,
    wear_coefficient, hardness), in one call.

    Parameters
    ----------
    motor : Motor or sequence of Motor
        One motor for every design, or one per design (x0 then 1-d, of its length).
    x0 : array_like
        Contact points (m), |x0| < L of each design's rod.
    load : array_like
        Load force opposing the rotor (N), each in [0, 1e6] (``MOTOR_DOMAIN["load"]``).
    wear_coefficient : array_like
        Archard's k, in [0, 1].
    hardness : array_like
        Hardness of the softer body (Pa), in [1e3, 1e12].
    springs, steps : int
        MDR resolution, as for ``moving_rotor``.

    Returns
    -------
    DesignMerits
        Arrays of the broadcast shape of x0, load, wear_coefficient and hardness; equal
        to the scalar API (module docstring) design by design.

    Raises
    ------
    ValueError
        Naming the argument and its first element out of range.

    See Also
    --------
    contact_merits : the dimensionless kernel, over contacts (psi, tau0).
    core.motor.operating_point, core.motor.moving_wear_rate
    """
    x, ld, k, hard = _broadcast(x0=x0, load=load, wear_coefficient=wear_coefficient,
                                hardness=hardness)
    _check_all("load", ld, MOTOR_DOMAIN["load"])
    _check_all("wear_coefficient", k, MOTOR_DOMAIN["wear_coefficient"])
    _check_all("hardness", hard, MOTOR_DOMAIN["hardness"])
    n, m = _resolution(springs, steps)
    shape = x.shape
    motors = _as_motors(motor, x.size)
    if not isinstance(motor, Motor) and x.ndim != 1:
        raise ValueError(f"x0 must be 1-d with one motor per design, got shape {shape}")
    x, ld, k, hard = (np.ascontiguousarray(a.ravel()) for a in (x, ld, k, hard))
    size = x.size
    psi, tau0, u0 = np.full(size, np.nan), np.full(size, np.nan), np.full(size, np.nan)
    stall = np.full(size, np.nan)
    omega, mu, mu_n = np.empty(size), np.empty(size), np.empty(size)
    groups: dict[Motor, list[int]] = {}
    for i, mot in enumerate(motors):
        groups.setdefault(mot, []).append(i)
    for mot, index in groups.items():
        idx = np.array(index)
        inside = Interval(-mot.rod.half_length, mot.rod.half_length, lo_open=True,
                          hi_open=True)
        bad = ~(np.abs(x[idx]) < mot.rod.half_length)
        if bad.any():
            first = int(idx[np.flatnonzero(bad)[0]])
            inside.check("x0" if x.size == 1 and not shape else f"x0[{first}]", x[first])
        prof = mot.profile(x[idx])
        psi[idx], tau0[idx], u0[idx] = prof.psi, prof.tau0, prof.u0
        stall[idx] = np.abs(prof.stall_thrust)
        omega[idx], mu[idx], mu_n[idx] = mot.rod.omega, mot.mu, mot.mu * mot.preload
    scale = omega * np.abs(u0)
    lo, hi = MOTOR_DOMAIN["psi_moving"].closed_bounds
    t_lo, t_hi = DOMAIN["tau0"].closed_bounds
    with np.errstate(invalid="ignore"):  # moving_rotor's _check_contact
        moving = (psi >= lo) & (psi <= hi) & (tau0 >= t_lo) & (tau0 <= t_hi)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(ld <= mu_n, ld / mu_n, np.nan)  # operating_point: load > mu N
    out = np.full((size, _COLUMNS), np.nan)
    out[:, _NE] = 0.0
    if moving.any():
        out[moving] = _contacts(np.ascontiguousarray(psi[moving]),
                                np.ascontiguousarray(tau0[moving]),
                                np.ascontiguousarray(ratio[moving]), n, m, XTOL_ROOT,
                                XTOL_BEST)
    loss = out[:, _LL] * (mu_n * scale)  # moving_wear_rate's friction power (W)
    wear = HOUR * k * loss / (mu * hard)

    def shaped(a: NDArray) -> NDArray:
        return a.reshape(shape)

    return DesignMerits(
        stall_thrust=shaped(stall), no_load_speed=shaped(out[:, _V0] * scale),
        best_efficiency=shaped(out[:, _EB]), best_speed=shaped(out[:, _VB] * scale),
        best_thrust=shaped(out[:, _RB] * mu_n), load_speed=shaped(out[:, _VL] * scale),
        load_efficiency=shaped(out[:, _EL]), load_power=shaped(ld * (out[:, _VL] * scale)),
        wear_rate=shaped(wear), psi=shaped(psi), tau0=shaped(tau0),
        speed_scale=shaped(scale), coulomb_force=shaped(mu_n),
        evaluations=shaped(out[:, _NE].astype(np.int64)))


__all__ = ["MERITS", "ContactMerits", "DesignMerits", "contact_merits", "design_merits"]
