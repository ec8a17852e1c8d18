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
    # the same 201 times for every N: the error of T at those times is the spring error
    errors = [max_error(c, solve("mdr", c, n, steps=200)) for n in ns]
    order = -slope(ns, errors)
    assert 1.75 < order < 2.25, (errors, order)
    assert errors[-1] < 5e-6


@pytest.mark.parametrize(("psi", "tau0"), [(0.4, np.pi / 6), (28.35, -0.9)])
def test_T_error_does_not_depend_on_the_time_step(psi, tau0):
    # with pi/2 on the grid every spring value is exact at every step: T's error is the
    # spring (midpoint-rule) error of N alone
    c = Contact(psi, tau0)
    fine = solve("mdr", c, 200, steps=2000)
    coarse = solve("mdr", c, 200, steps=40)
    common = np.isin(fine.tau, coarse.tau)
    assert common.sum() >= 3
    np.testing.assert_allclose(fine.T[common], coarse.T[np.isin(coarse.tau, fine.tau)],
                               atol=1e-15)


@pytest.mark.parametrize(("psi", "tau0"), [(2.414, np.pi / 6), (28.35, -0.9)])
def test_impulse_converges_at_second_order_in_the_time_step(psi, tau0):
    c = Contact(psi, tau0)
    steps = [60, 120, 240, 480]
    errs = [abs(solve("mdr", c, 4000, steps=m).impulse_ratio - c.impulse_ratio)
            for m in steps]
    assert 1.7 < -slope(steps, errs) < 2.6, errs


def test_psi_up_to_one_impulse_is_exact_at_any_step():
    c = Contact(0.6, -0.4)  # u = psi w spring by spring: T = psi P at every step
    assert solve("mdr", c, 20, steps=8).impulse_ratio == pytest.approx(0.6, abs=1e-14)


def test_drive_history_is_an_input():
    # march() takes the drive as an array: a drive lagging by a constant never moves the
    # springs after they touch (drive increments are what they follow), and a drive
    # twice as large doubles u wherever the springs stick
    psi = 0.3
    tau = np.linspace(0.0, np.pi, 201)
    d = np.maximum(np.sin(tau), 0.0)
    x = mdr.spring_positions(50)
    base = mdr.march(x, d, psi * np.sin(tau), 1.0, np.zeros(50))[0]
    shifted = mdr.march(x, d, psi * np.sin(tau) + 7.0, 1.0, np.zeros(50))[0]
    double = mdr.march(x, d, 2 * psi * np.sin(tau), 1.0, np.zeros(50))[0]
    np.testing.assert_allclose(shifted, base, atol=1e-12)
    np.testing.assert_allclose(double, 2 * base, atol=1e-12)


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
    res = solve("mdr", c, 90, steps=90)
    assert np.any(res.tau == np.pi / 2)
    assert np.sum((res.tau > np.pi / 2) & (res.tau < c.tau1)) >= 15
