"""Influence coefficients of uniform tractions on a square element of an elastic
half-space: the surface displacement at an element centre per unit traction on another
element, in closed form.

The point-force solutions (Johnson, *Contact Mechanics*, sections 3.2 and 3.5;
../shared/physics.md, "Beyond the paper: the model's own error") are, for a half-space of
shear modulus G and Poisson ratio nu, with (X, Y) = field point minus load point and
r = sqrt(X^2 + Y^2) (displacements into the body and in the direction of the load):

    normal force P (Boussinesq):  u_z = (1 - nu) P / (2 pi G r),
                                  u_t = -(1 - 2 nu) P (X, Y) / (4 pi G r^2)
    tangential Q_x (Cerruti):     u_x = Q / (2 pi G) [(1 - nu)/r + nu X^2 / r^3]
                                  u_y = Q / (2 pi G) nu X Y / r^3
                                  u_z = (1 - 2 nu) Q X / (4 pi G r^2)

(the last by Betti's reciprocity from the radial Boussinesq term). For two bodies the
relative displacements add the compliances; in units of 1 / (pi E*) with
1/E* = (1 - nu1)/(2 G1) + (1 - nu2)/(2 G2), the five distinct kernels are

    1/r,   X^2/r^3,   Y^2/r^3,   X Y/r^3   (weight n = E* sum nu_i/(2 G_i) = nu/(1 - nu)),
    X/r^2, Y/r^2                          (weight Dundurs' beta),

nu being the pair's effective Poisson ratio (``core.physical.equivalent_pair``). Each is
integrated over the element [X - h/2, X + h/2] x [Y - h/2, Y + h/2] through an
antiderivative F with d^2 F / dX dY = kernel, evaluated at the four corners (Love 1929 for
1/r; Kalker 1990, chapter 5, for the others):

    1/r:      X asinh(Y/|X|) + Y asinh(X/|Y|)
    X^2/r^3:  Y asinh(X/|Y|)           Y^2/r^3:  X asinh(Y/|X|)
    X Y/r^3:  -r
    X/r^2:    Y ln r + X atan(Y/X)     Y/r^2:    X ln r + Y atan(X/Y)

(terms depending on one corner coordinate only cancel in the corner sum and are dropped).
Element centres lie on a grid of spacing h, so corners sit at half-integer multiples of h
and no corner coordinate is ever 0: the formulas are evaluated without special cases.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

Antiderivative = Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]


def _inv_r(x: NDArray, y: NDArray) -> NDArray:
    return x * np.arcsinh(y / np.abs(x)) + y * np.arcsinh(x / np.abs(y))


def _xx(x: NDArray, y: NDArray) -> NDArray:
    return y * np.arcsinh(x / np.abs(y))


def _yy(x: NDArray, y: NDArray) -> NDArray:
    return x * np.arcsinh(y / np.abs(x))


def _xy(x: NDArray, y: NDArray) -> NDArray:
    return -np.hypot(x, y)


def _cx(x: NDArray, y: NDArray) -> NDArray:
    return y * np.log(np.hypot(x, y)) + x * np.arctan(y / x)


def _cy(x: NDArray, y: NDArray) -> NDArray:
    return x * np.log(np.hypot(x, y)) + y * np.arctan(x / y)


#: name -> antiderivative of each kernel.
ANTIDERIVATIVES: dict[str, Antiderivative] = {
    "inv_r": _inv_r, "xx": _xx, "yy": _yy, "xy": _xy, "cx": _cx, "cy": _cy,
}


def rectangle_integral(kernel: str, X: NDArray[np.float64], Y: NDArray[np.float64],
                       h: float) -> NDArray[np.float64]:
    """The integral of ``kernel`` over the square of side h centred at (X, Y).

    Parameters
    ----------
    kernel : str
        One of ``ANTIDERIVATIVES`` ("inv_r", "xx", "yy", "xy", "cx", "cy").
    X, Y : ndarray
        Field point minus element centre (units of the grid's length), broadcasting.
    h : float
        Element side.

    Returns
    -------
    ndarray
        The integral (units of length for 1/r and the r^-3 kernels' products, dimensionless
        in scale for X/r^2 times length: each kernel integrated over an area).
    """
    F = ANTIDERIVATIVES[kernel]
    a, b = X - h / 2.0, X + h / 2.0
    c, d = Y - h / 2.0, Y + h / 2.0
    return F(b, d) - F(a, d) - F(b, c) + F(a, c)


def offsets(size: int, h: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(X, Y) of every offset between two element centres of an M x M grid,
    k h for k = -(M - 1) .. M - 1, each of shape (2M - 1, 2M - 1)."""
    k = np.arange(-(size - 1), size) * h
    return np.meshgrid(k, k, indexing="ij")


def coefficients(size: int, h: float) -> dict[str, NDArray[np.float64]]:
    """Every kernel of ``ANTIDERIVATIVES`` integrated over one element, at every offset of
    an M x M grid of spacing h (arrays of shape (2M - 1, 2M - 1), offset 0 at the centre).
    Multiply by 1 / (pi E*) (and n or beta) for the displacement per unit traction."""
    X, Y = offsets(size, h)
    return {name: rectangle_integral(name, X, Y, h) for name in ANTIDERIVATIVES}
