"""Chung & Ooi's impacts in the real LAMMPS (Debian's ``lmp``, ``make lammps``) against the
exact reference: a few incidences, two tangential models (~20 s)."""

from __future__ import annotations

import math
import shutil
import subprocess

import numpy as np
import pytest

from core.dem_check import impact as bench
from core.dem_check.impact_cases import impact_test
from core.dem_check.impact_data import published

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(shutil.which("lmp") is None,
                                 reason="LAMMPS' lmp is not installed (make lammps)")]

MU = 0.092


@pytest.fixture(scope="module")
def test4() -> dict[tuple[str, float], tuple[bench.Rebound, bench.Rebound]]:
    out = {}
    for th in (5.0, 60.0):
        imp = impact_test(4).impact("alumina", th)
        ex = bench.exact(imp)
        for model in ("mindlin", "mindlin/force"):
            out[model, th] = (ex, bench.run(imp, model))
    return out


def test_normal_restitution_is_calibrated(test4):
    for ex, lm in test4.values():
        assert ex.normal_cor == pytest.approx(0.98, abs=1e-7)
        assert lm.normal_cor == pytest.approx(0.98, abs=2e-5)
        assert lm.contact_time == pytest.approx(ex.contact_time, rel=2e-3)


@pytest.mark.parametrize("model", ["mindlin", "mindlin/force"])
def test_gross_sliding_follows_the_rigid_body_law(test4, model):
    ex, lm = test4[model, 60.0]
    th = math.radians(60.0)
    assert lm.tangential_cor == pytest.approx(1 - MU * (1 + lm.normal_cor) / math.tan(th),
                                              abs=2e-4)
    assert lm.tangential_cor == pytest.approx(ex.tangential_cor, abs=5e-4)
    # LAMMPS' torque arm is R - delta/2: its spin is a few 1e-4 below the reference's
    assert lm.rebound_spin == pytest.approx(ex.rebound_spin, rel=3e-3)


def test_small_incidence_separates_the_models_from_the_reference(test4):
    ex, mindlin = test4["mindlin", 5.0]
    _, force = test4["mindlin/force", 5.0]
    # the exact history: 0.737; mindlin's total-displacement rule
    # is too stiff (0.953, +4.2 deg), mindlin/force in between (0.893)
    assert ex.tangential_cor == pytest.approx(0.7369, abs=2e-3)
    assert mindlin.tangential_cor - ex.tangential_cor > 0.15
    assert ex.tangential_cor < force.tangential_cor < mindlin.tangential_cor
    # Kharaz et al.'s measurement at 4.2 deg (0.746) sides with the reference
    inc, val = published("tangential_cor", "experiment")
    measured = float(val[np.argmin(abs(inc - 4.2))])
    assert abs(measured - ex.tangential_cor) < 0.02 < abs(measured - mindlin.tangential_cor)


def test_opposite_spins_do_not_interact_in_lammps():
    imp = impact_test(7).impact("aluminium_alloy", 45.0)
    lm = bench.run(imp, "mindlin")
    assert lm.rebound_spin == pytest.approx(imp.w, rel=1e-9)
    assert lm.w2 == pytest.approx(imp.w2, rel=1e-9)
    assert lm.normal_cor == pytest.approx(0.5, abs=1e-4)


def test_the_shipped_deck_runs_as_it_is(tmp_path):
    # defaults: test 4's alumina at 45 deg, elastic: gross sliding, e_t = 1 - 2 mu
    (tmp_path / "impact_deck.in").write_text(bench.template())
    subprocess.run(["lmp", "-in", "impact_deck.in", "-log", "none", "-nocite"], cwd=tmp_path,
                   check=True, capture_output=True, timeout=120)
    last = np.loadtxt(tmp_path / "impact.txt", comments="#")[-1]
    assert last[3] / (3.9 * math.sin(math.pi / 4)) == pytest.approx(1 - 2 * MU, abs=5e-4)
