"""Quadrature of the closed-form forces against the elliptic impulse formula (eq 41)."""

from __future__ import annotations

import numpy as np
import pytest
from numerics_helpers import slope

from core import Contact
from core.numerics import solve, textbook

CASES = [(0.4, np.pi / 6), (1.0, 0.0), (2.414, np.pi / 6), (28.35, -0.9), (1000.0, 1.5)]


@pytest.mark.parametrize(("psi", "tau0"), CASES)
def test_quad_matches_eq41(psi, tau0):
    c = Contact(psi, tau0)
    assert solve("quad", c, 100).impulse_ratio == pytest.approx(c.impulse_ratio, rel=1e-10)


@pytest.mark.parametrize(("psi", "tau0"), [(1.5, 0.2), (2.414, np.pi / 6), (28.35, -0.9),
                                           (1000.0, 0.5)])
def test_gauss_legendre_converges_algebraically_for_psi_above_one(psi, tau0):
    # T has (tau - tau0)^{3/2} ends and a jump of T'' at tau1: algebraic convergence,
    # order above 2 in the fit, not monotone from one n to the next
    c = Contact(psi, tau0)
    ns = [32, 64, 128, 256, 512]
    errs = [abs(solve("gauss_legendre", c, n).impulse_ratio - c.impulse_ratio) for n in ns]
    assert 2.0 < -slope(ns, errs) < 3.6, errs
    assert errs[-1] < errs[0] / 100 and errs[-1] < 3e-5


@pytest.mark.parametrize(("psi", "tau0"), [(0.4, np.pi / 6), (1.0, 0.0)])
def test_gauss_legendre_is_exact_for_psi_up_to_one(psi, tau0):
    # T = psi P (eq 38): any rule gives the ratio psi
    c = Contact(psi, tau0)
    assert solve("gauss_legendre", c, 8).impulse_ratio == pytest.approx(psi, rel=1e-14)


def test_textbook_agrees_where_it_is_well_conditioned():
    c = Contact(2.414, np.pi / 6)
    assert textbook.impulse_ratio(2.414, np.pi / 6) == pytest.approx(c.impulse_ratio,
                                                                    rel=1e-12)
    tau = np.linspace(c.tau0, np.pi - c.tau0, 50)
    np.testing.assert_allclose(textbook.tangential_force(2.414, np.pi / 6, tau),
                               c.tangential_force(tau), atol=1e-13)


def test_textbook_loses_digits_for_grazing_contact():
    tau0 = 1.5605  # s0 = 1 - 5e-5: both terms of eq 11 ~ 4 pi, F ~ 1e-8
    c = Contact(3.0, tau0)
    err = abs(textbook.impulse_ratio(3.0, tau0) / c.impulse_ratio - 1)
    assert err > 1e-8
