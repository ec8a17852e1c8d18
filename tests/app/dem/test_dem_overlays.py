"""app.dem.overlays: the LAMMPS runs shipped with the card are what LAMMPS gives (a fresh
run of one case and model) and what core.numerics.dem's copies of its rules give (every
case and model), at the same step count."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from app.dem import overlays
from core.dem_check import CASES, lammps
from core.numerics.dem import MODELS as COPIES
from core.numerics.dem import contact


def test_every_case_has_every_model_at_the_documented_steps() -> None:
    for name, case in CASES.items():
        o = overlays.load(name)
        assert o.steps == overlays.STEPS and o.version.startswith("29 Sep 2021")
        assert set(o.T) == set(lammps.MODELS)
        assert o.tau.size == overlays.STEPS // overlays.STRIDE + 1
        assert o.tau[0] == case.tau0 and o.tau[-1] == pytest.approx(case.tau_end, abs=1e-14)
    with pytest.raises(ValueError, match="no case named 'x'"):
        overlays.load("x")


@pytest.mark.skipif(shutil.which("lmp") is None,
                    reason="LAMMPS (lmp) is not installed (`make lammps`): the shipped "
                           "overlays cannot be compared with a fresh run")
def test_the_overlays_are_a_fresh_lammps_run() -> None:
    """Written with 12 significant digits: a fresh run agrees to their rounding."""
    run = lammps.run(CASES["fig7_psi6.46"], "mindlin_rescale", overlays.STEPS)
    o = overlays.load("fig7_psi6.46")
    np.testing.assert_array_equal(o.tau, run.tau[::overlays.STRIDE])
    np.testing.assert_allclose(o.T["mindlin_rescale"], run.T[::overlays.STRIDE],
                               rtol=1e-11, atol=1e-15)


def test_the_overlays_match_the_numba_copies_of_the_rules() -> None:
    """The copies trace LAMMPS to 3.3e-8 T0 at 4000 steps (docs/dem_check.md: the T
    difference falls to the harness's ~5e-8 floor by 8000 steps)."""
    for name, case in CASES.items():
        o = overlays.load(name)
        for model, copy in lammps.MODELS.items():
            tau, T, _ = contact(COPIES[copy], case.psi, case.tau0, overlays.STEPS)
            np.testing.assert_allclose(tau[::overlays.STRIDE], o.tau, rtol=0, atol=1e-14)
            assert np.max(np.abs(T[::overlays.STRIDE] - o.T[model])) < 5e-8, (name, model)


def test_the_file_text_is_what_load_reads(tmp_path, monkeypatch) -> None:
    """`text` of runs, read back by `load`, gives the runs every STRIDE-th step."""
    case = CASES["critical"]
    tau = np.linspace(case.tau0, case.tau_end, 41)
    runs = {m: lammps.LammpsRun(case=case, model=m, steps=40, tau=tau, T=np.sin(tau) * k,
                                P=np.zeros_like(tau), deck="", version="test", seconds=0.0)
            for k, m in enumerate(lammps.MODELS)}
    monkeypatch.setattr(overlays, "DIRECTORY", tmp_path)
    overlays.path("critical").write_text(overlays.text("critical", runs))
    overlays.load.cache_clear()
    try:
        o = overlays.load("critical")
    finally:
        overlays.load.cache_clear()
    np.testing.assert_array_equal(o.tau, tau[::overlays.STRIDE])
    assert o.version == "test" and o.steps == 40
    for k, m in enumerate(lammps.MODELS):
        np.testing.assert_allclose(o.T[m], np.sin(tau[::overlays.STRIDE]) * k, rtol=2e-12)
