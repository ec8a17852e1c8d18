"""The paper's loading by the referee: equal to the closed form at nu = 0 (where
Cattaneo-Mindlin is exact) within the discretisation error and converging with the grid;
the energy balance over a contact; Coulomb's law along the march; bad input refused."""

from __future__ import annotations

import math

import numpy as np
import pytest

from core.bem.__main__ import main
from core.bem.cases import cattaneo, spence
from core.bem.grid import Grid
from core.bem.loading import PaperLoading
from core.bem.pair import Pair
from core.bem.paper import run_paper

from .test_cases import check_coulomb

PSI, TAU0 = 1 + math.sqrt(2), math.pi / 6  # Fig. 4b: tau1 = 3 pi / 4


@pytest.fixture(scope="module")
def nu0_16():
    return run_paper(PSI, TAU0, 0.0, grid=16, steps=50, snapshots=(2.0, 2.3))


def test_nu0_equals_the_closed_form(nu0_16):
    r = nu0_16
    assert r.worst_T_error < 1e-3
    assert abs(r.impulse_ratio - r.impulse_ratio_closed) < 2e-4
    assert abs(r.dissipation_ratio - 1) < 5e-3
    np.testing.assert_allclose(r.P, r.closed.normal_force(r.tau), atol=3e-3)
    assert np.abs(r.Ty).max() < 1e-12  # no transverse force at nu = 0


def test_coulomb_law_along_the_march(nu0_16):
    assert set(nu0_16.snapshots) == {2.0, 2.3}
    for state in nu0_16.snapshots.values():
        check_coulomb(state, 0.2)


def test_partial_stick_zone_follows_eq_30(nu0_16):
    r = nu0_16
    phase3 = r.closed.phase(r.tau) == 3
    assert phase3.sum() > 5
    # equal-area stick radius within about an element of b(tau)
    assert r.worst_stick_error < 2.5 * r.grid.h


@pytest.mark.slow
def test_energy_balance_over_a_contact():
    # friction work summed element by element = the drive's work int T du_x0 (the
    # elastic energy is zero at both ends), both -> the closed form's D at nu = 0
    coarse = run_paper(PSI, TAU0, 0.0, grid=12, steps=40)
    fine = run_paper(PSI, TAU0, 0.0, grid=12, steps=160)
    gap = [abs(r.friction_work - r.dissipation) / r.dissipation for r in (coarse, fine)]
    assert gap[1] < gap[0] / 8  # about second order in the time step (measured: / 29)
    assert gap[1] < 1e-3
    assert fine.dissipation == pytest.approx(fine.closed.dissipated_energy, rel=5e-3)


@pytest.mark.slow
def test_full_stick_psi_below_one_dissipates_nothing():
    # psi <= 1: T = psi mu P (eq 38). On the grid, elements leaving the shrinking contact
    # drop their traction within one step, a spurious slip that vanishes with the step
    runs = [run_paper(0.8, TAU0, 0.0, grid=12, steps=n) for n in (40, 160)]
    err = [abs(r.impulse_ratio - 0.8) for r in runs]
    assert err[1] < err[0] / 2 and err[1] < 6e-3
    assert runs[1].friction_work < runs[0].friction_work / 10
    for r in runs:
        assert abs(r.dissipation) < 1e-8  # the drive's work cancels over the contact
        assert math.isnan(r.dissipation_ratio)


@pytest.mark.slow
def test_nu0_grid_convergence():
    e = [run_paper(PSI, TAU0, 0.0, grid=n, steps=50).worst_T_error for n in (12, 24)]
    assert e[1] < e[0] / 2.5  # order > 1.3 (measured about 1.7; docs/bem.md)


@pytest.mark.parametrize(("call", "name"), [
    (lambda: Pair(0.5), "nu"),
    (lambda: Pair(-0.1), "nu"),
    (lambda: Pair(0.3, 0.5), "beta"),
    (lambda: Pair(0.3, float("nan")), "beta"),
    (lambda: Grid(3), "grid"),
    (lambda: Grid(16.0), "grid"),
    (lambda: cattaneo(0.3, 1.0, 16), "load"),
    (lambda: cattaneo(0.3, -0.1, 16), "load"),
    (lambda: cattaneo(0.3, 0.5, 2000), "grid"),
    (lambda: spence(0.2, 0.0, 16), "mu"),
    (lambda: PaperLoading(-1.0, TAU0, 0.2, Pair(0.3)), "psi"),
    (lambda: PaperLoading(1.0, 2.0, 0.2, Pair(0.3)), "tau0"),
    (lambda: PaperLoading(1.0, TAU0, 0.2, Pair(0.3), steps=51), "steps"),
    (lambda: run_paper(1.0, TAU0, 0.3, beta=0.6, grid=8, steps=8), "beta"),
])
def test_bad_input_is_refused_naming_the_argument(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_cli_json_and_exit_codes(capsys):
    assert main(["cattaneo", "--nu", "0", "--load", "0.5", "--grid", "8", "--json"]) == 0
    out = capsys.readouterr().out
    import json

    d = json.loads(out)
    assert set(d) >= {"shift_ratio", "stick_radius", "transverse_fraction",
                      "elements_across", "seconds"}
    assert d["elements_across"] == 8
    assert main(["cattaneo", "--nu", "0.7", "--load", "0.5", "--grid", "8"]) == 2
    assert "nu" in capsys.readouterr().err
    with pytest.raises(SystemExit) as e:
        main(["paper", "--psi", "x", "--tau0", "0.5", "--nu", "0", "--grid", "8"])
    assert e.value.code == 2
