"""Registry, result type and validation of resolutions."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from core import Contact
from core.numerics import INTERACTIVE_RESOLUTION, METHODS, MethodResult, solve

NAMES = ["mdr", "annulus", "lammps_mindlin", "lammps_mindlin_force", "lammps_mindlin_rescale",
         "lammps_mindlin_rescale_force", "lammps_linear_history", "liggghts_history", "direnzo",
         "quad",
         "gauss_legendre"]


def test_registry_names_match_the_contract():
    assert sorted(METHODS) == sorted(NAMES)
    assert sorted(INTERACTIVE_RESOLUTION) == sorted(NAMES)
    assert all(isinstance(v, str) and v for v in METHODS.values())


@pytest.mark.parametrize("name", NAMES)
def test_result_fields(name):
    c = Contact(2.414, np.pi / 6)
    res = solve(name, c, 16)
    assert isinstance(res, MethodResult)
    assert dataclasses.is_dataclass(res)
    with pytest.raises(dataclasses.FrozenInstanceError):
        res.method = "x"  # type: ignore[misc]
    assert res.method == name and res.resolution == 16
    assert res.tau.shape == res.T.shape and res.tau.size >= 2
    assert np.all(np.diff(res.tau) > 0)
    assert res.tau[0] >= c.tau0 - 1e-12 and res.tau[-1] <= np.pi - c.tau0 + 1e-12
    assert res.wall_time > 0
    assert 0.0 < res.impulse_ratio < 1.5
    if res.b is not None:
        assert res.b.shape == res.tau.shape


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("bad", [0, 1, -3, 2.0, 10.5, True, "100", None, 10**8])
def test_bad_resolution_raises(name, bad):
    with pytest.raises(ValueError, match="resolution"):
        solve(name, Contact(1.0, 0.3), bad)


def test_huge_work_is_refused_with_the_limit_named():
    with pytest.raises(ValueError, match=r"\[2, 400\]"):
        solve("annulus", Contact(2.0, 0.0), 5000)


def test_unknown_method():
    with pytest.raises(KeyError, match="unknown method"):
        solve("euler", Contact(1.0, 0.3), 10)


@pytest.mark.parametrize("name", ["mdr", "annulus"])
@pytest.mark.parametrize("bad", [0, 1, 2.0, True, "10"])
def test_bad_steps_raise(name, bad):
    with pytest.raises(ValueError, match="steps"):
        solve(name, Contact(2.0, 0.3), 10, steps=bad)


def test_steps_only_for_stepped_methods():
    with pytest.raises(ValueError, match="steps"):
        solve("lammps_mindlin", Contact(2.0, 0.3), 100, steps=100)


def test_steps_set_the_time_grid():
    c = Contact(2.0, 0.3)
    assert solve("mdr", c, 40, steps=300).tau.size > solve("mdr", c, 40, steps=30).tau.size
