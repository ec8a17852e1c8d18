"""The real LAMMPS (Debian's ``lmp``, ``make lammps``) on the paper's loading: the harness
reproduces the normal force and the issue's hand-checked impulse ratio, each numba copy
of ``core.numerics.dem`` traces LAMMPS' own model to the time-step error, and mindlin/force
converges to the exact solution in full stick. A few thousand steps a run (~0.5 s each)."""

from __future__ import annotations

import numpy as np
import pytest

from core.dem_check import CASES, Case, lammps, score
from core.numerics.dem import MODELS as COPIES
from core.numerics.dem import contact


@pytest.fixture(scope="module")
def runs() -> dict[str, lammps.LammpsRun]:
    case = CASES["partial_stick"]
    return {m: lammps.run(case, m, steps=2000) for m in lammps.MODELS}


def test_issue_check_mindlin_at_psi_2414() -> None:
    """The issue: mindlin, psi = 2.414, tau0 = 0, 4000 steps: 0.6921766 (exact 0.7490),
    from the raw x and z forces. Split along the tilted line of centres it is 0.69217674,
    the numba copy's value to 1e-8 (the raw split lets 1.3e-7 of P into T)."""
    case = Case(psi=2.414, tau0=0.0)
    run = lammps.run(case, "mindlin", steps=4000)
    s = score(case, run.tau, run.T, run.P)
    assert s.impulse_ratio == pytest.approx(0.6921766, abs=2e-7)
    assert s.impulse_ratio == pytest.approx(0.69217674, abs=1e-8)
    assert s.exact_impulse_ratio == pytest.approx(0.7490, abs=1e-4)
    assert run.version.startswith("29 Sep 2021")
    assert s.max_P_error < 2e-8  # Hertz from E and nu, P0 = 1: the geometry is exact
    assert run.tau[0] == case.tau0 and run.tau[-1] == pytest.approx(case.tau_end)


def test_each_numba_copy_traces_lammps(runs) -> None:
    case = CASES["partial_stick"]
    for model, run in runs.items():
        tau, T, ratio = contact(COPIES[lammps.MODELS[model]], case.psi, case.tau0, 2000)
        np.testing.assert_allclose(run.tau, tau, atol=1e-14)
        assert np.max(np.abs(run.T - T)) < 2e-7, model
        assert score(case, run.tau, run.T, run.P).impulse_ratio == pytest.approx(ratio,
                                                                                 abs=2e-8)


def test_models_differ_where_they_should(runs) -> None:
    """All ride the cap in loading; mindlin and mindlin_rescale/force trace one curve
    (physics of the rules), the others differ after the reversal at pi/2."""
    T = {m: r.T for m, r in runs.items()}
    load = runs["mindlin"].tau < 1.5
    for m in T:
        np.testing.assert_allclose(T[m][load], runs[m].P[load], atol=1e-7)
    assert np.max(np.abs(T["mindlin"] - T["mindlin_rescale/force"])) < 1e-12
    assert np.max(np.abs(T["mindlin"] - T["mindlin/force"])) > 0.05
    assert np.max(np.abs(T["mindlin"] - T["mindlin_rescale"])) > 0.05


def test_mindlin_force_converges_in_full_stick_at_first_order() -> None:
    case = CASES["full_stick"]
    err = [score(case, r.tau, r.T, r.P).max_T_error
           for r in (lammps.run(case, "mindlin/force", steps=n) for n in (500, 2000))]
    assert err[0] < 2e-3 and 3.2 < err[0] / err[1] < 4.8


def test_without_lmp_the_error_says_how_to_install() -> None:
    with pytest.raises(lammps.LammpsNotFound, match="make lammps"):
        lammps.run(CASES["full_stick"], lmp="/nonexistent/lmp")
