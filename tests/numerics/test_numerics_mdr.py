"""Method of dimensionality reduction against the closed form."""

from __future__ import annotations

import numpy as np
import pytest
from numerics_helpers import max_error, slope

from core import Contact
from core.numerics import mdr, solve

CASES = [(0.4, np.pi / 6), (2.414, np.pi / 6), (28.35, -0.9), (1000.0, 0.5)]


@pytest.mark.parametrize(("psi", "tau0"), CASES)
def test_second_order_convergence(psi, tau0):
    c = Contact(psi, tau0)
    ns = [100, 200, 400, 800]
    errors = [max_error(c, solve("mdr", c, n)) for n in ns]
    order = -slope(ns, errors)
    assert 1.7 < order < 2.4, (errors, order)
    assert errors[-1] < 5e-6


def test_impulse_ratio_converges():
    c = Contact(2.414, np.pi / 6)
    errs = [abs(solve("mdr", c, n).impulse_ratio - c.impulse_ratio) for n in (50, 400)]
    assert errs[1] < errs[0] / 20 and errs[1] < 1e-6


@pytest.mark.parametrize(("psi", "tau0"), [(2.414, np.pi / 6), (28.35, 0.0)])
def test_stick_radius(psi, tau0):
    c = Contact(psi, tau0)
    res = solve("mdr", c, 400)
    away = np.abs(res.tau - np.pi / 2) > 1e-9  # b jumps from 0 to a* at pi/2
    err = np.max(np.abs(res.b - c.stick_radius(res.tau))[away])
    assert err < 5e-3
    partial = (res.tau > np.pi / 2 + 1e-9) & (res.tau < c.tau1)
    assert partial.sum() > 10 and np.all(res.b[partial] > 0)


def test_full_stick_radius_is_contact_radius():
    c = Contact(0.6, 0.2)
    res = solve("mdr", c, 100)
    np.testing.assert_allclose(res.b, c.contact_radius(res.tau), atol=1e-7)


@pytest.mark.parametrize("tau", [np.pi / 3, 7 * np.pi / 12, 17 * np.pi / 24])
def test_traction_by_inverse_transform(tau):
    c = Contact(2.414, np.pi / 6)
    a = float(c.contact_radius(tau))
    r = np.linspace(0.0, 0.98 * a, 25)
    q = mdr.traction(c, tau, r, n=1500)
    np.testing.assert_allclose(q, c.traction(r, tau), atol=3e-3)


def test_time_grid_holds_the_reversal_and_resolves_partial_stick():
    c = Contact(1000.0, np.pi / 6)
    res = solve("mdr", c, 90)
    assert np.any(res.tau == np.pi / 2)
    assert np.sum((res.tau > np.pi / 2) & (res.tau < c.tau1)) >= 15
