"""Every method gives zero force outside the contact window (tau0, pi - tau0)."""

from __future__ import annotations

import numpy as np
import pytest

from core import Contact
from core.numerics import annulus, dem, mdr, solve

# a grid that starts before contact and ends after it
TAU0 = 0.4
GRID = np.concatenate([np.linspace(-0.5, TAU0, 7, endpoint=False),
                       np.linspace(TAU0, np.pi - TAU0, 201),
                       np.linspace(np.pi - TAU0, 3.5, 8)[1:]])
OUTSIDE = (GRID < TAU0) | (GRID > np.pi - TAU0)


@pytest.mark.parametrize("psi", [0.5, 3.0])
def test_mdr_zero_outside(psi):
    T, P, b, _ = mdr.run(psi, TAU0, GRID, 100)
    assert np.all(T[OUTSIDE] == 0.0) and np.all(P[OUTSIDE] == 0.0)
    assert np.all(b[OUTSIDE] == 0.0)
    assert np.abs(T[~OUTSIDE]).max() > 0.05


@pytest.mark.parametrize("psi", [0.5, 3.0])
def test_annulus_zero_outside(psi):
    T, b = annulus.run(psi, TAU0, GRID, 12)
    assert np.all(T[OUTSIDE] == 0.0) and np.all(b[OUTSIDE] == 0.0)
    assert np.abs(T[~OUTSIDE]).max() > 0.05


@pytest.mark.parametrize("name", sorted(dem.MODELS))
@pytest.mark.parametrize("psi", [0.5, 3.0])
def test_dem_zero_outside(name, psi):
    T = dem.forces(dem.MODELS[name], psi, TAU0, GRID)[0]
    assert np.all(T[OUTSIDE] == 0.0)
    assert np.abs(T[~OUTSIDE]).max() > 0.05


@pytest.mark.parametrize("name", ["mdr", "annulus", "lammps_mindlin", "direnzo",
                                  "gauss_legendre"])
def test_results_vanish_at_the_ends_of_contact(name):
    c = Contact(2.0, TAU0)
    res = solve(name, c, 40)
    ends = np.isclose(res.tau, TAU0) | np.isclose(res.tau, np.pi - TAU0)
    assert np.all(np.abs(res.T[ends]) < 1e-12)
