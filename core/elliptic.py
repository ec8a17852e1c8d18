"""The elliptic factor F of the normal impulse (eq 11), evaluated without cancellation.

The paper writes

    F(tau0) = (1 + s)(1 + 3 s) K(k) - 8 s E(k),   s = sin tau0,  k^2 = m = (1 - s) / 2,

whose two terms both tend to 4 pi as s -> 1 while F ~ (9 pi / 16)(1 - s)^2: the form
loses every digit for grazing contact and, through F(tau1), for large psi. We use instead

    F = 12 m^2 J(m),   J(m) = int_0^{pi/2} cos^4(phi) / sqrt(1 - m sin^2 phi) dphi
                            = (3 pi / 16) 2F1(1/2, 1/2; 3; m),

which follows from the substitution sin(x/2) = k sin(phi) in
int (sin tau - s)^{3/2} dtau = (2 sqrt 2 / 3) F. J is smooth on [0, 1] (J(0) = 3 pi / 16,
J(1) = 2 / 3). For m < 0.2 we sum the hypergeometric series (24 terms, truncation below
1e-18); for m >= 0.2 the closed form in K and E cancels by less than a factor 50 and is
used with K taken from the complementary parameter (``ellipkm1``), so that m -> 1
(deep preload) keeps its digits.

Domain: 0 <= m <= 1 with mc = 1 - m supplied separately (mc is what loses digits when
m is near 1). Tested accuracy: relative error below 2e-15 against 50-digit mpmath over
the whole domain, m from 1e-300 to 1 - 1e-17 (tests/core/test_accuracy.py).
"""

from __future__ import annotations

import math

import llvmlite.binding as llvm
import numpy as np
from numba import float64, njit, types, vectorize
from numba.extending import get_cython_function_address
from numpy.typing import ArrayLike, NDArray

SERIES_LIMIT = 0.2
_N_TERMS = 24

# scipy's own ellipe and ellipkm1 (cephes), called from compiled code by symbol name, so
# that the kernels that use them can be cached on disk
for _name in ("ellipe", "ellipkm1"):
    llvm.add_symbol(f"zharii_{_name}",
                    get_cython_function_address("scipy.special.cython_special", _name))
_ellipe = types.ExternalFunction("zharii_ellipe", float64(float64))
_ellipkm1 = types.ExternalFunction("zharii_ellipkm1", float64(float64))


def _series_coefficients(n: int) -> tuple[float, ...]:
    """Coefficients of 2F1(1/2, 1/2; 3; m) = sum c_k m^k, times 3 pi / 16, highest first."""
    c = [3.0 * math.pi / 16.0]
    for k in range(n - 1):
        c.append(c[k] * (k + 0.5) ** 2 / ((k + 3.0) * (k + 1.0)))
    return tuple(c[::-1])


# the 24 coefficients, highest power first, as named constants: the polynomial below is
# written out term by term (a loop over a tuple keeps numba from vectorising its callers)
(_C23, _C22, _C21, _C20, _C19, _C18, _C17, _C16, _C15, _C14, _C13, _C12, _C11, _C10, _C9,
 _C8, _C7, _C6, _C5, _C4, _C3, _C2, _C1, _C0) = _series_coefficients(_N_TERMS)


@njit(cache=True, inline="always")
def quartic_series(m: float) -> float:
    """J(m) by its hypergeometric series (Horner, 24 terms), for 0 <= m <= SERIES_LIMIT:
    straight-line code with no branch, so that loops over many m compile to SIMD code."""
    acc = _C23
    acc = acc * m + _C22
    acc = acc * m + _C21
    acc = acc * m + _C20
    acc = acc * m + _C19
    acc = acc * m + _C18
    acc = acc * m + _C17
    acc = acc * m + _C16
    acc = acc * m + _C15
    acc = acc * m + _C14
    acc = acc * m + _C13
    acc = acc * m + _C12
    acc = acc * m + _C11
    acc = acc * m + _C10
    acc = acc * m + _C9
    acc = acc * m + _C8
    acc = acc * m + _C7
    acc = acc * m + _C6
    acc = acc * m + _C5
    acc = acc * m + _C4
    acc = acc * m + _C3
    acc = acc * m + _C2
    acc = acc * m + _C1
    return acc * m + _C0


@njit(cache=True)
def quartic_integral_float(m: float, mc: float) -> float:
    """J(m) for one float m, with mc = 1 - m given (see ``quartic_integral``)."""
    if m < SERIES_LIMIT:
        return quartic_series(m)
    k, e = _ellipkm1(mc), _ellipe(m)
    return (2.0 * (2.0 * m - 1.0) * e + mc * (2.0 - 3.0 * m) * k) / (3.0 * m * m)


@vectorize([float64(float64, float64)], cache=True)
def _quartic_integral(m: float, mc: float) -> float:
    return quartic_integral_float(m, mc)


@vectorize([float64(float64, float64)], cache=True)
def _impulse_factor(m: float, mc: float) -> float:
    return 12.0 * m * m * quartic_integral_float(m, mc)


def quartic_integral(m: ArrayLike, mc: ArrayLike | None = None) -> NDArray[np.float64]:
    """J(m) = int_0^{pi/2} cos^4 phi / sqrt(1 - m sin^2 phi) dphi, for 0 <= m <= 1
    (arrays broadcast).

    ``mc`` is 1 - m; pass it whenever m is close to 1 (it is computed as 1 - m otherwise).
    """
    m = np.asarray(m, dtype=float)
    return np.asarray(_quartic_integral.ufunc(m, 1.0 - m if mc is None else mc))


def impulse_factor(m: ArrayLike, mc: ArrayLike | None = None) -> NDArray[np.float64]:
    """F of eq 11 as a function of m = (1 - sin tau0) / 2 (and mc = 1 - m): F = 12 m^2 J(m).

    Dimensionless. F(tau0) itself is ``impulse_factor(sin(e/2)**2, cos(e/2)**2)`` with
    e = pi/2 - tau0; F(tau1) is the same with tau1 in place of tau0.
    """
    m = np.asarray(m, dtype=float)
    return np.asarray(_impulse_factor.ufunc(m, 1.0 - m if mc is None else mc))
