"""The exact impact reference (core.impact): closed forms, balances, convergence orders,
validation."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from core.impact import Impact, Material, Target, normalised, solve
from core.impact.normal import dashpot, restitution, tsuji_coefficient

ALUMINA = Material("alumina", E=380e9, nu=0.23, density=4000.0)
CHI = (1 - 0.23) * 3.5 / (2 - 0.23)  # MBF's chi of alumina on a rigid flat


def oblique(deg: float, e: float = 1.0, mu: float = 0.092, **kw) -> Impact:
    th = math.radians(deg)
    return Impact(radius=2.5e-3, material=ALUMINA, mu=mu, e=e, vx=3.9 * math.sin(th),
                  vz=-3.9 * math.cos(th), **kw)


def test_normal_incidence_is_hertz_and_spins_nothing():
    r = solve(oblique(0.0))
    i = r.impact
    # Hertz: t_c = 2 (alpha*/v) int_0^1 (1 - x^{5/2})^{-1/2} dx (Johnson eq 11.27)
    integral = quad(lambda x: (1 - x ** 2.5) ** -0.5, 0, 1, limit=200)[0]
    assert r.contact_time == pytest.approx(2 * integral * i.alpha_star / i.v_n, rel=2e-6)
    assert r.normal_cor == pytest.approx(1.0, abs=1e-7)
    assert r.w == 0.0 and r.vx == 0.0 and np.all(r.T == 0.0)
    # the largest force of the elastic impact, (4/3) E* R*^1/2 alpha*^3/2
    assert r.P.max() == pytest.approx(4 / 3 * i.E_star * math.sqrt(i.R_star)
                                      * i.alpha_star ** 1.5, rel=1e-4)


@pytest.mark.parametrize("deg", [40.0, 60.0, 85.0])
def test_gross_sliding_reaches_the_rigid_body_law(deg):
    # tan(theta) >= 3.5 mu (1 + e): slides throughout; e = 1, mu = 0.092
    r = solve(oblique(deg), tol=1e-10)
    th = math.radians(deg)
    assert r.tangential_cor == pytest.approx(1 - 0.092 * 2 / math.tan(th), abs=1e-8)
    assert r.w == pytest.approx(2.5 * 0.092 * 2 * 3.9 * math.cos(th) / 2.5e-3, rel=1e-8)
    assert r.psi2 == pytest.approx(r.psi1 - 4 * CHI, abs=1e-7)


@pytest.mark.parametrize("deg, slack", [(60.0, 1e-6), (85.0, 1e-7)])
def test_gross_sliding_with_the_dashpot_follows_the_law_with_e(deg, slack):
    # Coulomb's bound on the total normal force: J_t = mu (1 + e) m_n v_n, but for the
    # first springs, which stick where the dashpot dominates at first touch (3e-7 at 60)
    r = solve(oblique(deg, e=0.98), tol=1e-10)
    law = 1 - 0.092 * 1.98 / math.tan(math.radians(deg))
    assert r.normal_cor == pytest.approx(0.98, abs=1e-8)
    assert 0.0 <= r.tangential_cor - law < slack


def test_the_bound_choice_matters_only_with_a_dashpot():
    elastic = solve(oblique(20.0, bound="elastic"))
    total = solve(oblique(20.0))
    assert elastic.tangential_cor == total.tangential_cor  # e = 1: one model
    damped = [solve(oblique(20.0, e=0.98, bound=b)).tangential_cor for b in ("total", "elastic")]
    assert damped[0] != damped[1]


def test_sliding_threshold_is_four_chi():
    # just below psi1 = 4 chi the contact sticks at the end and psi2 > psi1 - 4 chi
    below = normalised(4 * CHI * 0.8, CHI)
    assert below.psi2 > below.psi1 - 4 * CHI + 1e-3
    above = normalised(4 * CHI * 1.05, CHI)
    assert above.psi2 == pytest.approx(above.psi1 - 4 * CHI, abs=1e-7)


@pytest.mark.parametrize("psi1", [0.3, 0.83, 2.0, 3.44, 6.0])
def test_energy_balance(psi1):
    # tangential kinetic energy lost = slip work of the springs (they store nothing at
    # the end): psi1^2 - psi2'^2 = (15/4) chi S, to the tolerance
    n = normalised(psi1, CHI, springs=2000, tol=1e-10)
    assert abs(n.energy_balance()) < 1e-6 * max(1.0, psi1 ** 2)
    assert n.slip_work > 1e-2


@pytest.mark.slow
@pytest.mark.parametrize("psi1", [0.83, 3.44])
def test_energy_residual_is_the_integrators(psi1):
    # it falls with the tolerance (not with the springs: the slip work is exact per step)
    coarse = normalised(psi1, CHI, springs=2000, tol=1e-10)
    finer = normalised(psi1, CHI, springs=2000, tol=1e-12)
    assert abs(finer.energy_balance()) < abs(coarse.energy_balance()) / 3


def test_energy_balance_in_si_units():
    r = solve(oblique(20.0), tol=1e-10)
    assert r.dissipated == pytest.approx(r.slip_work, rel=1e-5)
    assert r.dissipated > 0


@pytest.mark.parametrize("deg", [5.0, 20.0, 60.0])
def test_angular_momentum_about_the_contact_point(deg):
    r = solve(oblique(deg, e=0.98))
    L0, L1 = r.angular_momentum_about_contact(False), r.angular_momentum_about_contact(True)
    assert L1 == pytest.approx(L0, rel=1e-12)
    # and the contact point's slip from the bodies is the integrated one
    assert r.slip_velocity == pytest.approx(
        -r.contact_point_cor * r.impact.slip_velocity, rel=1e-12)


@pytest.mark.slow
def test_two_free_spheres_conserve_momentum_and_angular_momentum():
    al = Material("al", 70e9, 0.33, 2700.0)
    R = 0.1
    i = Impact(radius=R, material=al, target=Target(radius=R, material=al, free=True),
               mu=0.4, e=0.5, vx=0.1, vz=-0.2, vz2=0.2, w=3.0, w2=1.0)
    r = solve(i)
    m = i.mass
    inertia = i.inertia
    assert m * r.vx + m * r.vx2 == pytest.approx(m * i.vx + m * i.vx2, abs=1e-15)
    assert m * r.vz + m * r.vz2 == pytest.approx(0.0, abs=1e-14)
    L = lambda vx, w, vx2, w2: inertia * (w + w2) + m * R * (vx - vx2)  # noqa: E731
    assert L(r.vx, r.w, r.vx2, r.w2) == pytest.approx(L(i.vx, i.w, i.vx2, i.w2), rel=1e-12)
    assert r.normal_cor == pytest.approx(0.5, abs=1e-7)


def test_opposite_spins_of_identical_spheres_do_not_interact():
    # Chung & Ooi's test 7 (elastic here, which changes nothing tangentially): the contact
    # points move together, so the spins come back unchanged
    al = Material("al", 70e9, 0.33, 2700.0)
    w = 2.0 / 0.1
    r = solve(Impact(radius=0.1, material=al,
                     target=Target(radius=0.1, material=al, free=True),
                     mu=0.4, e=1.0, vz=-0.2, vz2=0.2, w=w, w2=-w))
    assert r.w == w and r.w2 == -w and r.vx == 0.0 and r.vx2 == 0.0


def test_normal_restitution_is_the_dashpot_model():
    r = solve(oblique(30.0, e=0.98))
    assert r.normal_cor == pytest.approx(0.98, abs=1e-7)
    # LAMMPS' damping tsuji polynomial: e = 0.98 gives a weaker dashpot (e ~ 0.9863)
    assert restitution(tsuji_coefficient(0.98) * math.sqrt(1.25), 2000, 1e-10) == \
        pytest.approx(0.98630, abs=2e-5)
    assert dashpot(1.0, 2000, 1e-9) == 0.0


@pytest.mark.slow
def test_spring_convergence_is_at_least_second_order():
    # measured here: 7.9e-5, 8.4e-6, 7.3e-7 at 32, 64, 128 springs (order ~3.3); below
    # ~1e-7 the integrator's tolerance takes over
    ref = normalised(0.83, CHI, springs=8192, tol=1e-11).psi2
    n = np.array([32, 64, 128])
    err = np.array([abs(normalised(0.83, CHI, springs=int(k), tol=1e-11).psi2 - ref)
                    for k in n])
    order = -np.polyfit(np.log(n), np.log(err), 1)[0]
    assert 2.0 < order < 4.0, (err, order)


@pytest.mark.slow
def test_fixed_step_convergence_is_second_order():
    ref = normalised(0.83, CHI, springs=2000, tol=1e-11).psi2
    h = np.array([0.02, 0.01, 0.005])
    err = np.array([abs(normalised(0.83, CHI, springs=2000, tol=0.0, h0=float(s)).psi2 - ref)
                    for s in h])
    order = np.polyfit(np.log(h), np.log(err), 1)[0]
    assert 1.8 < order < 2.2, (err, order)


@pytest.mark.slow
def test_adaptive_error_follows_the_tolerance():
    # local error control of a second-order step: global error ~ tol^(2/3), steps ~ tol^-1/3
    ref = normalised(3.44, CHI, springs=2000, tol=1e-11)
    runs = [normalised(3.44, CHI, springs=2000, tol=t) for t in (1e-6, 1e-7, 1e-8)]
    err = np.array([abs(r.psi2 - ref.psi2) for r in runs])
    steps = np.array([r.steps for r in runs])
    tol = np.array([1e-6, 1e-7, 1e-8])
    assert np.all(err < 20 * tol ** (2 / 3)), err
    order_in_tol = np.polyfit(np.log(tol), np.log(err), 1)[0]
    order_in_steps = -np.polyfit(np.log(steps), np.log(err), 1)[0]
    assert 0.5 < order_in_tol < 1.0, (err, order_in_tol)
    assert 1.5 < order_in_steps < 2.6, (err, steps)


@pytest.mark.parametrize("kwargs, word", [
    ({"mu": 0.0}, "mu"), ({"e": 1.5}, "e"), ({"radius": -1.0}, "radius"),
    ({"vz": 1.0}, "approach"), ({"vx": math.nan}, "vx"), ({"vx2": 1.0}, "fixed"),
    ({"bound": "viscous"}, "bound"),
])
def test_bad_impacts_are_refused(kwargs, word):
    base = {"radius": 1e-3, "material": ALUMINA, "mu": 0.1, "vz": -1.0}
    base.update(kwargs)
    with pytest.raises(ValueError, match=word):
        Impact(**base)


def test_bad_materials_and_numerics_are_refused():
    with pytest.raises(ValueError, match="E"):
        Material("x", E=-1.0, nu=0.3, density=1.0)
    with pytest.raises(ValueError, match="nu"):
        Material("x", E=1.0, nu=0.5, density=1.0)
    with pytest.raises(ValueError, match="free target"):
        Target(free=True)
    with pytest.raises(ValueError, match="springs"):
        solve(oblique(10.0), springs=3)
    with pytest.raises(ValueError, match="tol"):
        solve(oblique(10.0), tol=1.0)
    with pytest.raises(ValueError, match="impact"):
        solve("not an impact")
