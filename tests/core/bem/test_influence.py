"""Influence coefficients: closed forms against quadrature, and the DC-FFT operators
against the direct sum, their symmetry, and Hertz's displacement."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import dblquad

from core.bem.convolution import SCALE, Operators
from core.bem.grid import Grid
from core.bem.influence import ANTIDERIVATIVES, coefficients, rectangle_integral

KERNELS = {
    "inv_r": lambda x, y: 1.0 / math.hypot(x, y),
    "xx": lambda x, y: x * x / math.hypot(x, y) ** 3,
    "yy": lambda x, y: y * y / math.hypot(x, y) ** 3,
    "xy": lambda x, y: x * y / math.hypot(x, y) ** 3,
    "cx": lambda x, y: x / (x * x + y * y),
    "cy": lambda x, y: y / (x * x + y * y),
}


@pytest.mark.parametrize("name", sorted(ANTIDERIVATIVES))
@pytest.mark.parametrize("offset", [(3.0, 2.0), (-1.0, 4.0), (1.0, 0.0)])
def test_closed_form_equals_quadrature_off_the_element(name, offset):
    X, Y = offset
    h = 1.0
    ref, _ = dblquad(lambda y, x: KERNELS[name](x, y), X - h / 2, X + h / 2,
                     Y - h / 2, Y + h / 2, epsabs=1e-13, epsrel=1e-12)
    got = float(rectangle_integral(name, np.array(X), np.array(Y), h))
    assert got == pytest.approx(ref, rel=1e-9, abs=1e-12)


def test_self_element_values():
    # the integral of 1/r over a square of side h about its centre: 4 h ln(1 + sqrt 2)
    c = coefficients(3, 0.5)
    centre = (2, 2)
    assert c["inv_r"][centre] == pytest.approx(4 * 0.5 * math.log(1 + math.sqrt(2)),
                                               rel=1e-14)
    # X^2/r^3 and Y^2/r^3 share it equally; the odd kernels vanish
    assert c["xx"][centre] == pytest.approx(0.5 * c["inv_r"][centre], rel=1e-14)
    for name in ("xy", "cx", "cy"):
        assert abs(c[name][centre]) < 1e-14


def test_dc_fft_equals_the_direct_sum():
    g = Grid(8)
    op = Operators(g, 0.3, 0.2)
    rng = np.random.default_rng(1)
    p, qx, qy = (rng.random((g.size, g.size)) for _ in range(3))
    k = coefficients(g.size, g.h)
    m = g.size
    n = 0.3 / 0.7

    def direct(kern, f):
        out = np.zeros_like(f)
        for i in range(m):
            for j in range(m):
                sub = kern[m - 1 + i - np.arange(m)[:, None], m - 1 + j - np.arange(m)[None, :]]
                out[i, j] = SCALE * np.sum(sub * f)
        return out

    un = op.normal(p) + op.normal_from_shear(qx, qy)
    ref = direct(k["inv_r"], p) + 0.2 * (direct(k["cx"], qx) + direct(k["cy"], qy))
    np.testing.assert_allclose(un, ref, rtol=1e-12, atol=1e-13)
    ux, uy = op.tangential(qx, qy)
    cx, cy = op.shear_from_normal(p)
    refx = (direct(k["inv_r"] + n * k["xx"], qx) + n * direct(k["xy"], qy)
            - 0.2 * direct(k["cx"], p))
    np.testing.assert_allclose(ux + cx, refx, rtol=1e-12, atol=1e-13)
    refy = (direct(k["inv_r"] + n * k["yy"], qy) + n * direct(k["xy"], qx)
            - 0.2 * direct(k["cy"], p))
    np.testing.assert_allclose(uy + cy, refy, rtol=1e-12, atol=1e-13)


def test_the_coupled_operator_is_symmetric():
    g = Grid(10)
    op = Operators(g, 0.25, -0.3)
    rng = np.random.default_rng(2)
    a = [rng.standard_normal((g.size, g.size)) for _ in range(3)]
    b = [rng.standard_normal((g.size, g.size)) for _ in range(3)]

    def apply(p, qx, qy):
        un = op.normal(p) + op.normal_from_shear(qx, qy)
        ux, uy = op.tangential(qx, qy)
        cx, cy = op.shear_from_normal(p)
        return un, ux + cx, uy + cy

    lhs = sum(float(np.sum(x * y)) for x, y in zip(a, apply(*b), strict=True))
    rhs = sum(float(np.sum(x * y)) for x, y in zip(b, apply(*a), strict=True))
    assert lhs == pytest.approx(rhs, rel=1e-12)


def test_hertz_pressure_gives_hertz_displacement():
    # p = sqrt(1 - r^2) (units p*) displaces the surfaces by 1 - r^2 / 2 (units a^2 / R_e)
    g = Grid(64)
    op = Operators(g, 0.0, 0.0)
    x, y = g.xy
    r2 = x * x + y * y
    u = op.normal(np.sqrt(np.clip(1.0 - r2, 0.0, None)))
    inside = r2 < 0.8
    assert np.abs(u - (1.0 - r2 / 2.0))[inside].max() < 3e-3
