"""The closed form against 60-digit mpmath references of the paper's own formulas, at the
hard corners of the domain: psi within 1e-12 of 1, psi = 1e12, tau0 within 1e-8 of both
ends, and tau exactly at tau0, pi/2, tau1 and pi - tau0."""

import math

import mpmath as mp
import numpy as np
import pytest

from core import Contact, impulse_ratio
from core.elliptic import impulse_factor
from tests.core import reference as ref
from tests.core.cases import PSIS, TAU0S

TOL = 1e-13
CASES = [(psi, tau0) for psi in PSIS for tau0 in TAU0S]


def times(c: Contact) -> np.ndarray:
    """Breakpoints exactly, interior points, points outside contact and a later period."""
    marks = [c.tau0, math.pi / 2, c.tau_end]
    if c.psi > 1:
        marks.append(c.tau1)
        marks += list(math.pi / 2 + (c.tau1 - math.pi / 2) * np.array([0.1, 0.5, 0.9]))
    inner = list(np.linspace(c.tau0, c.tau_end, 9)[1:-1])
    outside = [c.tau_end + 1e-3, c.tau0 - 1e-3] if c.tau0 > -1.5 else []
    # Whole periods away, off the jumps of b at pi/2 and tau1 (a shifted float lands ulps off).
    later = [t + 2 * math.pi for t in inner[:2]] + [t - 4 * math.pi for t in inner[5:7]]
    return np.array(marks + inner + outside + later)


def rel(x: float, r: mp.mpf) -> float:
    """Relative error of x against r (absolute where r is exactly 0)."""
    return float(abs(mp.mpf(x) - r) / (abs(r) or 1))


@pytest.mark.parametrize(("psi", "tau0"), CASES)
def test_scalars_match_reference(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    assert rel(c.F0, ref.F0(tau0)) < TOL
    assert rel(c.impulse_ratio, ref.impulse_ratio(psi, tau0)) < TOL
    if psi > 1:
        assert rel(c.tau1, ref.tau1(psi, tau0)) < TOL
        assert math.pi / 2 < c.tau1 <= c.tau_end
    else:
        assert math.isnan(c.tau1)


@pytest.mark.parametrize(("psi", "tau0"), CASES)
def test_functions_of_time_match_reference(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    tau = times(c)
    T = c.tangential_force(tau)
    a, b = c.contact_radius(tau), c.stick_radius(tau)
    a2_num, P = c.approach(tau), c.normal_force(tau)
    u2, v2 = c.centre_displacement(tau), c.centre_velocity(tau)
    u2_scale = float(max(abs(ref.centre_displacement(psi, t, tau0)) for t in tau)) or 1.0
    for i, t in enumerate(tau):
        a2, b2 = ref.radii_squared(psi, t, tau0)
        assert abs(T[i] - float(ref.tangential_force(psi, t, tau0))) < TOL, t
        assert abs(P[i] - float(ref.tangential_force(0.5, t, tau0)) * 2) < TOL, t
        assert abs(a2_num[i] - float(a2)) < TOL, t
        assert abs(a[i] ** 2 - float(a2)) < TOL and abs(b[i] ** 2 - float(b2)) < TOL, t
        # Radii themselves: exact away from their square-root zeros (documented exception).
        if a2 > 1e-4:
            assert abs(a[i] - float(mp.sqrt(a2))) < TOL, t
        if b2 > 1e-4:
            assert abs(b[i] - float(mp.sqrt(b2))) < TOL, t
        assert abs(u2[i] - float(ref.centre_displacement(psi, t, tau0))) < TOL * u2_scale, t
        if c.phase(t) == ref.phase(psi, t, tau0):  # v2 jumps where the phase changes
            assert abs(v2[i] - float(ref.centre_velocity(psi, t, tau0))) < TOL, t


@pytest.mark.parametrize(("psi", "tau0"), CASES[::3])
def test_traction_matches_reference(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    tau = times(c)
    r = np.linspace(-1.0, 1.0, 23)
    tr = c.traction(r[None, :], tau[:, None])
    pr = c.pressure(r[None, :], tau[:, None])
    assert tr.shape == pr.shape == (tau.size, r.size)
    for i, t in enumerate(tau):
        a2, b2 = ref.radii_squared(psi, t, tau0)
        for j, x in enumerate(r):
            zeros = [a2, b2] if 3 in (c.phase(t), ref.phase(psi, t, tau0)) else [a2]
            if min(abs(z - x * x) for z in zeros) < 1e-6:
                continue  # square-root zero: float64 limits the traction to ~1e-8 there
            assert abs(tr[i, j] - float(ref.traction(psi, x, t, tau0))) < TOL, (t, x)
            expected_p = float(mp.sqrt(a2 - x * x)) if x * x < a2 else 0.0
            assert abs(pr[i, j] - expected_p) < TOL


def test_impulse_ratio_vectorised_matches_reference() -> None:
    psi = np.concatenate([np.linspace(0, 30, 31), [1 - 1e-12, 1 + 1e-12, 1e6, 1e12]])
    for tau0 in (math.pi / 6, 1.5 - 1e-9, -1.5):
        got = impulse_ratio(psi, tau0)
        assert got.shape == psi.shape
        for g, p in zip(got, psi, strict=True):
            assert rel(g, ref.impulse_ratio(p, tau0)) < TOL


def test_impulse_factor_whole_domain() -> None:
    """F(m) relative error < 1e-14 from m = 1e-150 (grazing) to 1 - 1e-16 (deep preload)."""
    ms = np.concatenate([np.logspace(-150, -1, 40), np.linspace(0.01, 0.99, 99)])
    worst = 0.0
    for m in ms:
        with mp.workdps(80):
            mc = 1 - mp.mpf(m)
            got = impulse_factor(m, float(mc))
            worst = max(worst, rel(float(got), ref.F_of_m(mp.mpf(m))))
    assert worst < 1e-14
    mc = 1e-17  # m = 1 - 1e-17 is not a float: only mc carries it
    with mp.workdps(80):
        assert rel(float(impulse_factor(1.0, mc)), ref.F_of_m(1 - mp.mpf(mc))) < 1e-14


def test_textbook_F_really_fails_where_the_stable_one_does_not() -> None:
    """The reason for core.elliptic: eq 11 as written loses all digits near s0 = 1."""
    from scipy.special import ellipe, ellipk

    tau0 = math.pi / 2 - 1e-4
    s0 = math.sin(tau0)
    m = (1 - s0) / 2
    textbook = (1 + s0) * (1 + 3 * s0) * ellipk(m) - 8 * s0 * ellipe(m)
    exact = ref.F0(tau0)
    assert rel(textbook, exact) > 1e-3
    assert rel(Contact(1.0, tau0).F0, exact) < TOL


def test_the_series_of_J_about_one_tenth() -> None:
    """J(m) for m < 0.2 (``quartic_series``): its 14 coefficients are the Taylor
    coefficients of (3 pi/16) 2F1(1/2, 1/2; 3; m) about 0.1 to within 1-2 ulp, the first
    omitted term is below 1e-17 J on the whole range, and the sum is within 3e-16 of J
    at 2001 points of [0, 0.2] and at its ends (where |m - 0.1| is largest)."""
    from core.elliptic import (
        _N_TERMS,
        SERIES_CENTRE,
        SERIES_LIMIT,
        _series_coefficients,
        quartic_series,
    )

    half, three = mp.mpf(1) / 2, mp.mpf(3)

    def coefficient(k: int) -> mp.mpf:
        return (3 * mp.pi / 16 * mp.rf(half, k) ** 2 / (mp.rf(three, k) * mp.factorial(k))
                * mp.hyp2f1(half + k, half + k, three + k, mp.mpf(SERIES_CENTRE)))

    def J(m: float) -> mp.mpf:
        return 3 * mp.pi / 16 * mp.hyp2f1(half, half, three, mp.mpf(m))

    with mp.workdps(50):
        got = _series_coefficients(_N_TERMS, SERIES_CENTRE)[::-1]
        assert max(rel(a, coefficient(k)) for k, a in enumerate(got)) < 3e-16
        radius = mp.mpf(SERIES_LIMIT - SERIES_CENTRE)
        assert coefficient(_N_TERMS) * radius**_N_TERMS < 1e-17 * J(SERIES_LIMIT)
        ms = [0.0, 1e-300, *np.linspace(0.0, SERIES_LIMIT, 2001)[1:-1],
              np.nextafter(SERIES_LIMIT, 0.0)]
        assert max(rel(quartic_series(m), J(m)) for m in ms) < 3e-16
