"""Annulus (Maw, Barber & Fawcett) scheme: compliance and convergence."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from numerics_helpers import max_error, slope

from core import Contact
from core.numerics import annulus, solve


def test_compliance_reproduces_the_hertz_type_displacement():
    # A traction of Hertz shape sqrt(a^2 - r^2) displaces the surface (relative, units U)
    # by (pi / 4)(2 a^2 - r^2) inside r < a (the basis of eqs 13-14, 36).
    edges = np.linspace(0.0, 1.0, 401)
    centres = 0.5 * (edges[1:] + edges[:-1])
    a = 0.8
    u = annulus.compliance_matrix(edges) @ annulus.ring_pressure(edges, a)
    inside = centres < 0.95 * a
    np.testing.assert_allclose(u[inside], np.pi / 4 * (2 * a * a - centres[inside] ** 2),
                               rtol=2e-3)


def test_ring_pressure_integrates_to_the_hertz_force():
    edges = np.linspace(0.0, 1.0, 37)
    a = 0.731
    total = annulus.ring_pressure(edges, a) @ (np.pi * np.diff(edges**2))
    assert total == pytest.approx(2 * np.pi / 3 * a**3, rel=1e-12)


@pytest.mark.parametrize(("psi", "tau0"), [(0.4, np.pi / 6), (2.414, np.pi / 6),
                                           (28.35, -0.9)])
def test_converges_as_rings_and_steps_grow(psi, tau0):
    c = Contact(psi, tau0)
    errors = [max_error(c, solve("annulus", c, n)) for n in (8, 16, 32, 64)]
    assert all(e2 < e1 for e1, e2 in itertools.pairwise(errors)), errors
    assert errors[-1] < errors[0] / 5
    assert errors[-1] < 3e-3


@pytest.mark.parametrize(("psi", "tau0", "lo", "hi"), [
    (0.4, np.pi / 6, 0.8, 1.1), (0.4, -0.9, 0.8, 1.1),  # entering rings stick a whole step
    (1.0, np.pi / 6, 1.15, 1.4), (1.0, -0.9, 1.15, 1.4),
    (2.414, np.pi / 6, 1.75, 2.0), (28.35, -0.9, 1.75, 2.0),  # full-slip loading exact
])
def test_convergence_order(psi, tau0, lo, hi):
    c = Contact(psi, tau0)
    ns = [8, 16, 32, 64]
    errors = [max_error(c, solve("annulus", c, n)) for n in ns]
    assert lo < -slope(ns, errors) < hi, errors


def test_full_slip_loading_is_exact():
    # psi > 1: every ring slides at mu p during loading, so T = mu P there (eq 18).
    c = Contact(5.0, 0.2)
    res = solve("annulus", c, 10)
    load = res.tau <= np.pi / 2
    np.testing.assert_allclose(res.T[load], c.tangential_force(res.tau[load]), atol=1e-12)


def test_impulse_ratio_approaches_the_closed_form():
    c = Contact(2.414, np.pi / 6)
    errs = [abs(solve("annulus", c, n).impulse_ratio - c.impulse_ratio) for n in (8, 48)]
    assert errs[1] < errs[0] / 5 and errs[1] < 1e-3
