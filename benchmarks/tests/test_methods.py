"""benchmarks/core/methods.py's many-contacts-a-call timing: every method's kernel runs once
per contact, with the arguments of the single call, and the count follows one rule."""

from __future__ import annotations

import math

import pytest

from benchmarks.core import methods

RUNS = [("closed_form", 200, None), ("closed_form", 10, None), ("mdr", 12, 8),
        ("annulus", 8, None), ("direnzo", 10, None), ("lammps_mindlin_force", 20, None)]


@pytest.mark.parametrize(("name", "resolution", "steps"), RUNS)
@pytest.mark.parametrize(("psi", "tau0"), [(0.4, math.pi / 6), (28.35, -0.9)])
def test_a_batch_is_count_single_calls(name, resolution, steps, psi, tau0):
    kernel, args, check = methods.compiled(name, psi, tau0, resolution, steps)
    one = check(kernel(*args))
    _, T, _, ratio = methods.as_result(name, kernel(*args))
    assert one == T[-1] + ratio  # check reads the last T and the impulse ratio
    count, call = methods.batched(name, psi, tau0, resolution, steps, 1e-6)
    assert count == 1000
    assert call() == pytest.approx(count * one, rel=1e-12, abs=1e-12)


def test_the_count_rule():
    for seconds, count in [(1e-6, 1000), (3e-7, 3333), (1e-3, 1), (5e-2, 1)]:
        assert methods.batched("direnzo", 0.4, 0.5, 10, None, seconds)[0] == count


def test_the_batch_ratios_of_a_case():
    row = dict(psi=0.4, tau0=0.5, regime="psi <= 1", kind="relative", threshold=1e-2,
               peer="direnzo 10", peer_points=11, peer_time=1.4e-6, cf_time=1.6e-6,
               cf_n=10, cf_points=11, cf_n_time=1.0e-6, peer_batch=0.3e-6,
               cf_batch=0.7e-6, cf_n_batch=0.1e-6)
    (case,) = methods.cases_of([row], "relative")
    best = case["best"][1e-2]
    assert best["ratio"] == pytest.approx(1.4 / 1.6)
    assert best["ratio_points"] == pytest.approx(1.4)
    assert best["ratio_batch"] == pytest.approx(0.3 / 0.7)
    assert best["ratio_points_batch"] == pytest.approx(3.0)
