"""DEM spring models: their impulse ratios reproduced from their rules by hand, their
convergence in dt for psi <= 1 (mindlin/force first order, Di Renzo second order), and
mindlin/force low for psi > 1.

The hand integrations below solve each rule in the limit dt -> 0 at psi = 2, tau0 = 0
(s = sin tau, P / P0 = s^{3/2}, k_t a = (3/2) psi sqrt(s) = 3 sqrt(s) in T0 / u0,
xi: drive displacement). During loading every model sits at the cap F = s^{3/2}. After
pi / 2 the drive goes back (dxi = ds < 0) and:

* mindlin / LIGGGHTS: xi = 1/3 at s = 1 (cap), xi = s - 2/3, F = 3 sqrt(s)(s - 2/3)
  until F = -s^{3/2}, i.e. s = 1/2;
* linear_history (k_t = 3 constant, the Mindlin stiffness at a*): capped while loading,
  xi = 1/3 at s = 1, F = 3 s - 2 until F = -s^{3/2};
* mindlin/force: dF = 3 sqrt(s) ds, F = 2 s^{3/2} - 1 until s = 3^{-2/3};
* mindlin_rescale: dxi = ds + xi ds / (2 s) -> xi = 2 s - (5/3) sqrt(s),
  F = 6 s^{3/2} - 5 s until s = 25/49;
* mindlin_rescale/force: dF = 3 sqrt(s) ds + F ds / (2 s) -> F = 3 s^{3/2} - 2 sqrt(s)
  until s = 1/2;
* Di Renzo: k = (2/3) 3 sqrt(s): xi = 1/2 at s = 1, F = 2 sqrt(s)(s - 1/2) until s = 1/3;

then counter-slip F = -s^{3/2} to the end.
"""

from __future__ import annotations

import numpy as np
import pytest
from numerics_helpers import max_error, slope
from scipy.integrate import quad
from scipy.optimize import brentq

from core import Contact
from core.numerics import solve

HAND = {
    "lammps_mindlin": (lambda s: 3 * np.sqrt(s) * (s - 2 / 3), 0.5),
    "liggghts_history": (lambda s: 3 * np.sqrt(s) * (s - 2 / 3), 0.5),
    "lammps_mindlin_force": (lambda s: 2 * s**1.5 - 1, 3 ** (-2 / 3)),
    "lammps_mindlin_rescale": (lambda s: 6 * s**1.5 - 5 * s, 25 / 49),
    "lammps_mindlin_rescale_force": (lambda s: 3 * s**1.5 - 2 * np.sqrt(s), 0.5),
    "lammps_linear_history": (lambda s: 3 * s - 2,
                              brentq(lambda s: 3 * s - 2 + s**1.5, 0.3, 0.7)),
    "direnzo": (lambda s: 2 * np.sqrt(s) * (s - 0.5), 1 / 3),
}


def hand_ratio(unload, s_cross: float) -> float:
    """T_imp / (mu P_imp) of a rule at psi = 2, tau0 = 0 by direct quadrature."""
    t_cross = np.pi - np.arcsin(s_cross)
    load = quad(lambda t: np.sin(t) ** 1.5, 0, np.pi / 2)[0]
    back = quad(lambda t: unload(np.sin(t)), np.pi / 2, t_cross)[0]
    counter = quad(lambda t: np.sin(t) ** 1.5, t_cross, np.pi)[0]
    total = quad(lambda t: np.sin(t) ** 1.5, 0, np.pi)[0]
    return (load + back - counter) / total


@pytest.mark.parametrize("name", sorted(HAND))
def test_impulse_ratio_from_the_rule(name):
    expected = hand_ratio(*HAND[name])
    res = solve(name, Contact(2.0, 0.0), 8000)
    assert res.impulse_ratio == pytest.approx(expected, abs=2e-4)
    # and none of them is the exact answer (eq 41)
    assert abs(res.impulse_ratio - Contact(2.0, 0.0).impulse_ratio) > 5e-3


def test_rescale_force_traces_mindlin_and_the_others_differ():
    # mindlin and mindlin_rescale/force follow the same curve 3 s^{3/2} - 2 sqrt(s) in
    # unloading (d(F/a) = k_t dxi); every other rule gives its own curve
    c = Contact(2.0, 0.0)
    runs = {name: solve(name, c, 8000) for name in HAND}
    same = np.max(np.abs(runs["lammps_mindlin"].T - runs["lammps_mindlin_rescale_force"].T))
    assert same < 2e-3
    ratios = sorted(r.impulse_ratio for n, r in runs.items()
                    if n not in ("lammps_mindlin_rescale_force", "liggghts_history"))
    assert min(np.diff(ratios)) > 5e-3


@pytest.mark.parametrize(("psi", "tau0"), [(0.3, 0.0), (0.8, np.pi / 6), (0.9, -0.9),
                                           (0.5, 1.3)])
def test_mindlin_force_is_exact_for_psi_up_to_one(psi, tau0):
    c = Contact(psi, tau0)
    errs = []
    for steps in (1000, 4000, 16000):
        res = solve("lammps_mindlin_force", c, steps)
        errs.append(np.max(np.abs(res.T - c.tangential_force(res.tau))))
    # first order in the time step: error / 4 per step refinement by 4
    assert errs[2] < errs[1] / 3 < errs[0] / 9
    t_max = psi * (1 - np.sin(tau0)) ** 1.5  # largest T / T0 (eq 38)
    assert errs[2] < 10 * t_max / 16000  # first order in the 16000 steps
    res = solve("lammps_mindlin_force", c, 16000)
    assert res.impulse_ratio == pytest.approx(psi, rel=5e-4)


def test_mindlin_force_at_psi_one_rides_the_cap_exactly():
    c = Contact(1.0, -0.9)
    res = solve("lammps_mindlin_force", c, 300)
    np.testing.assert_allclose(res.T, c.tangential_force(res.tau), atol=1e-12)


@pytest.mark.parametrize("psi", [1.5, 2.414, 10.0])
def test_mindlin_force_is_low_for_psi_above_one(psi):
    c = Contact(psi, np.pi / 6)
    res = solve("lammps_mindlin_force", c, 8000)
    exact = c.tangential_force(res.tau)
    partial = (res.tau > np.pi / 2) & (res.tau < c.tau1)
    assert np.all(res.T[partial] <= exact[partial] + 1e-9)
    assert np.max(exact[partial] - res.T[partial]) > 1e-2
    assert res.impulse_ratio < c.impulse_ratio - 1e-3


@pytest.mark.parametrize(("psi", "tau0"), [(3.0, 0.2), (0.5, -0.9), (1000.0, 1.5)])
def test_liggghts_and_lammps_kernels_agree_to_rounding(psi, tau0):
    # two kernels, each in its code's arithmetic (LIGGGHTS caps kt |shear|, LAMMPS |F|),
    # of the same rule
    c = Contact(psi, tau0)
    a = solve("lammps_mindlin", c, 500)
    b = solve("liggghts_history", c, 500)
    np.testing.assert_allclose(b.T, a.T, rtol=0, atol=1e-13 * np.max(np.abs(a.T)))


def test_mindlin_overshoots_full_stick_by_one_half():
    # total-displacement form F = k_t a xi with the current a: 3/2 of eq 38 while loading
    c = Contact(0.5, 0.0)
    res = solve("lammps_mindlin", c, 2000)
    load = (res.tau > 0.2) & (res.tau < np.pi / 2)
    np.testing.assert_allclose(res.T[load], 1.5 * c.tangential_force(res.tau[load]),
                               rtol=2e-3)


@pytest.mark.parametrize(("psi", "tau0"), [(0.7, 0.3), (0.4, -0.9), (1.0, 0.0)])
def test_direnzo_converges_at_second_order_for_psi_up_to_one(psi, tau0):
    # the secant (2/3) k_t a xi is Mindlin's no-slip curve; xi from the midpoint
    # velocity is the only error: O(dt^2)
    c = Contact(psi, tau0)
    steps = [100, 200, 400, 800]
    errs = [max_error(c, solve("direnzo", c, n)) for n in steps]
    assert 1.9 < -slope(steps, errs) < 2.1, errs


@pytest.mark.parametrize(("psi", "tau0", "low"), [(0.4, np.pi / 6, 1e-2), (0.4, -0.9, 5e-2)])
def test_mindlin_force_is_not_exact_after_30_steps(psi, tau0, low):
    c = Contact(psi, tau0)
    assert max_error(c, solve("lammps_mindlin_force", c, 30)) > low


def test_linear_history_has_a_constant_stiffness():
    # psi = 0.2, tau0 = 0: k_t = 0.3. The cap s^{3/2} grows slower than 0.3 s until
    # s = 0.04 (where d(s^{3/2}) / ds = 0.3): xi = s^{3/2} / 0.3 up to there, then the
    # spring sticks, F = 0.3 (s - 0.04) + 0.04^{3/2}, until pi / 2
    c = Contact(0.2, 0.0)
    res = solve("lammps_linear_history", c, 4000)
    s = np.sin(res.tau)
    stick = (res.tau < np.pi / 2) & (s > 0.05)
    np.testing.assert_allclose(res.T[stick], 0.3 * (s[stick] - 0.04) + 0.008, rtol=1e-3)
