"""core.dem_check: the cases, the exact reference and the scorer against the closed form,
an independent closed form of the dissipated energy and constructed histories."""

from __future__ import annotations

import math

import numpy as np
import pytest

from core import Contact
from core.dem_check import CASES, Case, dissipated_energy, exact, score


def closed_dissipation(psi: float, tau0: float) -> float:
    """Eq 39 integrated in s = sin tau: (4/5)(1 - s0)^{5/2}(psi - 1)/(psi + 1) for psi > 1."""
    return 0.0 if psi <= 1 else 0.8 * (1 - math.sin(tau0)) ** 2.5 * (psi - 1) / (psi + 1)


def test_case_validates_each_parameter_by_name() -> None:
    for kwargs, name in [({"psi": -1, "tau0": 0}, "psi"), ({"psi": 1, "tau0": 2}, "tau0"),
                         ({"psi": 1, "tau0": 0, "mu": 0}, "mu"),
                         ({"psi": 1, "tau0": 0, "nu": 0.6}, "nu")]:
        with pytest.raises(ValueError, match=name):
            Case(**kwargs)


def test_fig7_cases_end_partial_stick_where_the_paper_says() -> None:
    for name, tau1 in [("fig7_psi2.41", 3 * math.pi / 4), ("fig7_psi6.46", 2 * math.pi / 3),
                       ("fig7_psi28.35", 7 * math.pi / 12)]:
        assert CASES[name].contact.tau1 == pytest.approx(tau1, abs=1e-13)
    assert [round(CASES[n].psi, 2) for n in ("fig7_psi2.41", "fig7_psi6.46",
                                             "fig7_psi28.35")] == [2.41, 6.46, 28.35]


@pytest.mark.parametrize("name", list(CASES))
def test_dissipated_energy_is_the_closed_form(name: str) -> None:
    c = CASES[name]
    assert dissipated_energy(c) == pytest.approx(closed_dissipation(c.psi, c.tau0),
                                                 rel=1e-12, abs=1e-18)


def test_reference_is_core_on_its_grid() -> None:
    c = CASES["fig7_psi2.41"]
    ref = exact(c)
    con = Contact(c.psi, c.tau0)
    np.testing.assert_array_equal(ref.T, con.tangential_force(ref.tau))
    np.testing.assert_array_equal(ref.P, con.normal_force(ref.tau))
    assert ref.impulse_ratio == con.impulse_ratio == pytest.approx(0.7580806319327227)
    assert set(np.unique(ref.phase)) == {2, 3, 4}
    # the trapezoid of the work on 2000 points is D to 1e-6
    assert ref.work[-1] == pytest.approx(ref.dissipated_energy, rel=1e-6)
    assert ref.work.min() >= 0


@pytest.mark.parametrize("name", list(CASES))
def test_score_of_the_exact_history_is_clean(name: str) -> None:
    c = CASES[name]
    ref = exact(c, 4000)
    s = score(c, ref.tau, ref.T, ref.P)
    assert s.max_T_error == 0 and s.max_P_error == 0 and s.coulomb_excess == 0
    assert abs(s.impulse_ratio_error) < 3e-8
    assert abs(s.energy_error) < 1e-7 * c.loading_work / 0.07
    assert s.energy_gain < 1e-15


def test_score_finds_an_error_where_it_is() -> None:
    c = CASES["fig7_psi2.41"]
    ref = exact(c)
    T = ref.T.copy()
    k = int(np.searchsorted(ref.tau, 2.5))  # counter-slip: tau1 = 2.356 < 2.5
    T[k] -= 0.125  # beyond the bound: counter-slip has T = -P
    s = score(c, ref.tau, T, ref.P)
    assert s.max_T_error == pytest.approx(0.125)
    assert s.worst_tau == ref.tau[k] and s.worst_phase == "counter-slip"
    assert s.coulomb_excess == pytest.approx(0.125)


def test_time_reversed_history_gains_what_the_contact_dissipates() -> None:
    """T(pi - tau) runs the exact contact backwards (the drive sin tau is symmetric about
    pi/2): the drive gets back D."""
    c = Case(psi=2.0, tau0=0.0)
    tau = np.linspace(0.0, math.pi, 8001)
    s = score(c, tau, c.contact.tangential_force(math.pi - tau), c.contact.normal_force(tau))
    D = closed_dissipation(2.0, 0.0)
    assert s.dissipated_energy == pytest.approx(-D, rel=1e-5)
    assert s.energy_gain == pytest.approx(D, rel=1e-5)
    assert s.impulse_ratio == pytest.approx(c.contact.impulse_ratio, rel=1e-6)


def test_full_stick_with_a_stiffer_spring_dissipates_nothing_but_is_wrong() -> None:
    """mindlin's stick: 3/2 the exact T, a function of the drive alone, so W returns to 0."""
    c = CASES["full_stick"]
    ref = exact(c)
    s = score(c, ref.tau, 1.5 * ref.T, ref.P)
    assert s.impulse_ratio == pytest.approx(0.6, rel=1e-6)
    assert s.max_T_error == pytest.approx(0.5 * c.psi * (1 - math.sin(c.tau0)) ** 1.5)
    assert abs(s.energy_error) < 1e-15 and s.energy_gain < 1e-15


@pytest.mark.parametrize(("tau", "T", "P", "match"), [
    ([0.0, 1.0], [0.0], [0.0, 0.0], "one length"),
    ([0.0, np.nan, 3.2], [0, 0, 0], [0, 0, 0], r"tau\[1\]"),
    ([0.0, 1.0, 3.2], [0, np.inf, 0], [0, 0, 0], r"T\[1\]"),
    ([0.0, 2.0, 1.0, 3.2], [0] * 4, [0] * 4, r"tau\[2\]"),
    ([0.5, 3.2], [0, 0], [0, 0], "cover the contact"),
    ([[0.0, 3.2]], [[0, 0]], [[0, 0]], "one-dimensional"),
    (["a", "b"], [0, 0], [0, 0], "tau must be a sequence"),
])
def test_score_names_what_is_malformed(tau, T, P, match) -> None:
    with pytest.raises(ValueError, match=match):
        score(Case(psi=2.0, tau0=0.0), tau, T, P)
