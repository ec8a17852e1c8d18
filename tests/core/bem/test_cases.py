"""Cattaneo-Mindlin and Spence: the closed form at nu = 0, CONTACT's documented examples
(Vollebregt's CONTACT, open source, github.com/eve70a/CONTACT: examples/cattaneo.inp with
its reference output examples/cattaneo.ref_out, and examples/spence35.inp with
spence35.ref_out, the case of Kalker 1990, section 5.2.1.1 and Figure 5.25), Coulomb's law
on every solution, symmetry."""

from __future__ import annotations

import math

import numpy as np
import pytest

from core.bem.cases import cattaneo, mindlin_shift, spence
from core.bem.march import DEFAULT
from core.bem.pair import Pair

# CONTACT's Cattaneo example: polyethylene on polyethylene, G = 200 MPa, nu = 0.42,
# mu = 0.4, R = 50 mm (curvatures 0.01 / mm), Fn = 9.195 N giving a = 1 mm, Fx = -7/8 mu Fn,
# 19 x 19 elements of 0.1333 mm (15 across the contact diameter), one shift step.
CONTACT_SHIFT_MM = 8.155e-3  # "SHIFT X" of case 2
CONTACT_ELEMENTS = 177  # NCON
CONTACT_ADHESION = 45  # NADH
# |p_t| (N/mm^2) at element centres (x, y) in mm, from the "ABS(PT)" column of case 2
CONTACT_TRACTIONS = [((0.0, -0.4), 1.10), ((0.0, -0.2667), 0.948),
                     ((-0.2667, -0.2667), 1.05), ((0.0, -0.9333), 0.575),
                     ((-0.4, -0.8), 0.798), ((-0.5334, -0.6667), 0.923)]


def mindlin_shift_mm() -> float:
    """Mindlin's shift 3 mu P (2 - nu) / (8 G a) [1 - (1 - 7/8)^(2/3)] in mm."""
    return 3 * 0.4 * 9.195 * (2 - 0.42) / (8 * 200.0 * 1.0) * (1 - (1 / 8) ** (2 / 3))


def test_contact_cattaneo_example():
    r = cattaneo(0.42, 0.875, 15, mu=0.4)
    # the same shift as CONTACT's to its four printed digits
    assert r.shift_ratio == pytest.approx(CONTACT_SHIFT_MM / mindlin_shift_mm(), abs=2e-4)
    contact = int((r.state.p > 0).sum())
    assert contact == CONTACT_ELEMENTS
    assert round(r.stick_radius**2 * contact) == CONTACT_ADHESION
    p0 = 3 * 9.195 / (2 * math.pi)  # N/mm^2: the Hertz peak pressure, p* of the model
    mag = np.hypot(r.state.qx, r.state.qy) * p0
    c = r.grid.centres
    for (x, y), ref in CONTACT_TRACTIONS:
        i, j = np.argmin(np.abs(c - x)), np.argmin(np.abs(c - y))
        assert mag[i, j] == pytest.approx(ref, abs=6e-3)  # CONTACT prints 3 digits


def check_coulomb(state, mu, tol=DEFAULT.slip_tol):
    """Coulomb's law element by element on a step's solution."""
    bound = mu * state.p
    q = np.hypot(state.qx, state.qy)
    s = np.hypot(state.sx, state.sy)
    assert np.all(q <= bound * (1 + 1e-12) + 1e-300)
    assert np.all(q[state.p == 0] == 0)
    slipping = (state.p > 0) & (s > 100 * tol)
    # slip opposite to the traction, and only at the bound
    cos = (state.qx * state.sx + state.qy * state.sy)[slipping] / (q * s)[slipping]
    assert np.all(cos < -1 + 1e-6)
    assert np.all(q[slipping] >= bound[slipping] * (1 - 1e-9))
    # where the traction is below the bound the element sticks
    inside = (state.p > 0) & (q < bound * (1 - 1e-6))
    assert np.all(s[inside] <= 100 * tol)


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.49])
def test_coulomb_law_and_symmetry_in_cattaneo(nu):
    r = cattaneo(nu, 0.6, 16, mu=0.3, steps=2)
    check_coulomb(r.state, 0.3)
    qx, qy = r.state.qx, r.state.qy
    # indexed [ix, iy] on a grid symmetric about both axes: p_y odd in y (and in x),
    # p_x even in both
    np.testing.assert_allclose(qy, -qy[:, ::-1], atol=1e-9)
    np.testing.assert_allclose(qy, -qy[::-1, :], atol=1e-9)
    np.testing.assert_allclose(qx, qx[:, ::-1], atol=1e-9)
    assert abs(qy.sum()) < 1e-9
    if nu == 0:
        assert np.abs(qy).max() == 0.0  # Cattaneo-Mindlin is exact: no transverse traction
    else:
        assert r.transverse_fraction > 0.005 * nu


def test_cattaneo_nu0_shift_is_mindlins():
    for n in (16, 24):
        r = cattaneo(0.0, 0.5, n)
        assert abs(r.shift_ratio - 1) < 4e-3
        assert abs(r.stick_radius - 0.5 ** (1 / 3)) < 2.5 / n  # one element or so


@pytest.mark.slow
def test_cattaneo_nu0_grid_order():
    # Mindlin's shift is exact at nu = 0; the referee's error falls as h^p with p >= 1.5
    # (measured: about 2 to 4 through the sign changes of the stick boundary's
    # discretisation; docs/bem.md)
    grids = np.array([12, 16, 20, 24, 28, 32])
    err = np.array([abs(cattaneo(0.0, 0.5, int(n)).shift_ratio - 1) for n in grids])
    slope = np.polyfit(np.log(2.0 / grids), np.log(err), 1)[0]
    assert slope > 1.5
    assert err[-1] < 5e-4


def test_mindlin_shift_formula():
    # identical bodies: mu kappa [1 - (1 - Q)^(2/3)], kappa = (2 - nu) / (2 (1 - nu))
    assert mindlin_shift(0.875, 0.4, Pair(0.42)) == pytest.approx(
        0.4 * 1.58 / 1.16 * 0.75, rel=1e-14)


def test_spence_small_grid():
    # CONTACT's spence35 on 15 elements across: c / a near Spence's 1/2
    r = spence(0.49999, 0.2986, 15)
    assert r.stick_radius == pytest.approx(0.4943, abs=0.03)
    check_coulomb(r.state, 0.2986)
    q = r.state
    # the square grid's symmetries of a radial field: q_x odd in x, even in y, and
    # q_y(x, y) = q_x(y, x); no net force
    np.testing.assert_allclose(q.qx, -q.qx[::-1, :], atol=1e-9)
    np.testing.assert_allclose(q.qx, q.qx[:, ::-1], atol=1e-9)
    np.testing.assert_allclose(q.qy, q.qx.T, atol=1e-9)
    assert abs(q.qx.sum()) < 1e-7 and abs(q.qy.sum()) < 1e-7  # solver tolerance
    assert np.abs(q.qx).max() > 0.05  # the coupling does shear the contact


@pytest.mark.slow
def test_contact_spence35_example():
    # spence35: nu = 0 on a rigid plane (beta = 0.5 - 5e-6), mu = 0.2986, 35 load stages
    # growing the contact to 35 elements across; CONTACT's last stage: 921 elements in
    # contact, 225 in adhesion (c / a = sqrt(225 / 921) = 0.494)
    G1, G2 = 0.5, 1e5
    beta = ((1 / G1) - (1 / G2)) / (2 * (1 / G1 + 1 / G2))
    r = spence(beta, 0.2986, 35, nu=0.0)
    contact = int((r.state.p > 0).sum())
    stuck = round(r.stick_radius**2 * contact)
    assert abs(contact - 921) <= 6
    assert abs(stuck - 225) <= 4
