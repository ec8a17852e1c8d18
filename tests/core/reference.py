"""High-precision references written straight from the paper's formulas (docs/physics.md), in
mpmath at 60 digits (more where eq 11 itself cancels). Float inputs are taken as exact."""

from __future__ import annotations

import mpmath as mp

DPS = 60


def _f(x: float) -> mp.mpf:
    return mp.mpf(float(x))


def reduced(tau: float, tau0: float) -> mp.mpf:
    """tau moved by whole periods into [tau0, tau0 + 2 pi), exactly."""
    with mp.workdps(DPS):
        t, t0 = _f(tau), _f(tau0)
        while t < t0:
            t += 2 * mp.pi
        while t >= t0 + 2 * mp.pi:
            t -= 2 * mp.pi
        return t


def in_contact(tau: float, tau0: float) -> bool:
    with mp.workdps(DPS):
        return reduced(tau, tau0) <= mp.pi - _f(tau0)


def sin_tau1(psi: float, tau0: float) -> mp.mpf:
    s0 = mp.sin(_f(tau0))
    return 1 - 2 * (1 - s0) / (_f(psi) + 1)


def tau1(psi: float, tau0: float) -> mp.mpf:
    """Eq 31: the root of b(tau) in (pi/2, pi - tau0)."""
    with mp.workdps(DPS):
        return mp.pi - mp.asin(sin_tau1(psi, tau0))


def F_of_m(m: mp.mpf) -> mp.mpf:
    """Eq 11 with k0^2 = m = (1 - sin tau0) / 2, at a precision that survives its own
    cancellation as m -> 0."""
    with mp.workdps(DPS + int(2 * abs(mp.log10(m)))):
        s = 1 - 2 * m
        return (1 + s) * (1 + 3 * s) * mp.ellipk(m) - 8 * s * mp.ellipe(m)


def F(s: mp.mpf) -> mp.mpf:
    """Eq 11 with sin tau0 = s (s computed at the caller's precision)."""
    return F_of_m((1 - s) / 2)


def F0(tau0: float) -> mp.mpf:
    with mp.workdps(DPS):
        return F(mp.sin(_f(tau0)))


def impulse_ratio(psi: float, tau0: float) -> mp.mpf:
    """Eq 41."""
    with mp.workdps(DPS):
        psi_ = _f(psi)
        if psi_ <= 1:
            return psi_
        return ((psi_ + 1) / 2) ** mp.mpf(1.5) * F(sin_tau1(psi, tau0)) / F(mp.sin(_f(tau0)))


def phase(psi: float, tau: float, tau0: float) -> int:
    if not in_contact(tau, tau0):
        return 0
    if psi <= 1:
        return 1
    with mp.workdps(DPS):
        t = reduced(tau, tau0)
        if t <= mp.pi / 2:
            return 2
        return 3 if t < tau1(psi, tau0) else 4


def tangential_force(psi: float, tau: float, tau0: float) -> mp.mpf:
    """T / T0, eqs 38, 39."""
    ph = phase(psi, tau, tau0)
    with mp.workdps(DPS):
        if ph == 0:
            return mp.mpf(0)
        d = mp.sin(reduced(tau, tau0)) - mp.sin(_f(tau0))
        d32 = d ** mp.mpf(1.5)
        if ph == 1:
            return _f(psi) * d32
        if ph == 2:
            return d32
        if ph == 4:
            return -d32
        d1 = mp.sin(reduced(tau, tau0)) - sin_tau1(psi, tau0)
        return -d32 + 2 * ((_f(psi) + 1) / 2) ** mp.mpf(1.5) * d1 ** mp.mpf(1.5)


def radii_squared(psi: float, tau: float, tau0: float) -> tuple[mp.mpf, mp.mpf]:
    """(a / a*)^2 and (b / a*)^2 from eqs 7, 8, 22 and 30, a*^2 = R (H - h) / 2."""
    ph = phase(psi, tau, tau0)
    with mp.workdps(DPS):
        if ph == 0:
            return mp.mpf(0), mp.mpf(0)
        s0 = mp.sin(_f(tau0))
        a2 = (mp.sin(reduced(tau, tau0)) - s0) / (1 - s0)
        if ph == 1:
            return a2, a2
        if ph != 3:
            return a2, mp.mpf(0)
        b2 = (_f(psi) + 1) / 2 * (mp.sin(reduced(tau, tau0)) - sin_tau1(psi, tau0)) / (1 - s0)
        return a2, b2


def traction(psi: float, r: float, tau: float, tau0: float) -> mp.mpf:
    """tau_u / (mu p*), eqs 18, 24, 33, 36."""
    ph = phase(psi, tau, tau0)
    a2, b2 = radii_squared(psi, tau, tau0)
    with mp.workdps(DPS):
        r2 = _f(r) ** 2
        p = mp.sqrt(a2 - r2) if r2 < a2 else mp.mpf(0)
        if ph in (0, 2):
            return p
        if ph == 1:
            return _f(psi) * p
        if ph == 4:
            return -p
        return -p + (2 * mp.sqrt(b2 - r2) if r2 < b2 else 0)


def centre_displacement(psi: float, tau: float, tau0: float) -> mp.mpf:
    """u2 / u0, eq 43."""
    ph = phase(psi, tau, tau0)
    with mp.workdps(DPS):
        s, s0, p = mp.sin(reduced(tau, tau0)), mp.sin(_f(tau0)), _f(psi)
        if ph == 0:
            return mp.mpf(0)
        if ph == 1:
            return (s - s0) / 2
        if ph == 3:
            return (p * s + 1 - p - s0) / (2 * p)
        return (1 if ph == 2 else -1) * (s - s0) / (2 * p)


def centre_velocity(psi: float, tau: float, tau0: float) -> mp.mpf:
    """v2 / (omega u0), eq 42 (cos tau / 2 in full stick)."""
    ph = phase(psi, tau, tau0)
    with mp.workdps(DPS):
        c, p = mp.cos(reduced(tau, tau0)), _f(psi)
        if ph in (1, 3):
            return c / 2
        if ph == 0:
            return mp.mpf(0)
        return (1 if ph == 2 else -1) * c / (2 * p)
