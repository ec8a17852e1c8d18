"""The elliptic factor F of the normal impulse (eq 11), evaluated without cancellation.

The paper writes

    F(tau0) = (1 + s)(1 + 3 s) K(k) - 8 s E(k),   s = sin tau0,  k^2 = m = (1 - s) / 2,

whose two terms both tend to 4 pi as s -> 1 while F ~ (9 pi / 16)(1 - s)^2: the form
loses every digit for grazing contact and, through F(tau1), for large psi. We use instead

    F = 12 m^2 J(m),   J(m) = int_0^{pi/2} cos^4(phi) / sqrt(1 - m sin^2 phi) dphi
                            = (3 pi / 16) 2F1(1/2, 1/2; 3; m),

which follows from the substitution sin(x/2) = k sin(phi) in
int (sin tau - s)^{3/2} dtau = (2 sqrt 2 / 3) F. J is smooth on [0, 1] (J(0) = 3 pi / 16,
J(1) = 2 / 3). For m < 0.2 we sum its Taylor series about m = 0.1 (14 terms: the series
converges like ((m - 0.1) / 0.9)^k, and on |m - 0.1| <= 0.1 the first omitted term is below
1e-17 J); for m >= 0.2 the closed form in K and E cancels by less than a factor 50 and is
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

from core.horner import horner

SERIES_LIMIT = 0.2
SERIES_CENTRE = 0.1
_N_TERMS = 14

# scipy's own ellipe and ellipkm1 (cephes), called from compiled code by symbol name, so
# that the kernels that use them can be cached on disk
for _name in ("ellipe", "ellipkm1"):
    llvm.add_symbol(f"zharii_{_name}",
                    get_cython_function_address("scipy.special.cython_special", _name))
_ellipe = types.ExternalFunction("zharii_ellipe", float64(float64))
_ellipkm1 = types.ExternalFunction("zharii_ellipkm1", float64(float64))


def _hyp2f1(a: float, b: float, c: float, x: float) -> float:
    """2F1(a, b; c; x) for a, b, c > 0 and 0 <= x <= 1/2 by its series: positive terms,
    the first 1, summed with ``math.fsum`` once they fall below 1e-20 of the sum."""
    terms, j = [1.0], 0
    while terms[-1] > 1e-20:
        terms.append(terms[-1] * (a + j) * (b + j) / ((c + j) * (j + 1.0)) * x)
        j += 1
    return math.fsum(terms)


def _series_coefficients(n: int, centre: float) -> tuple[float, ...]:
    """Coefficients of J(centre + d) = sum a_k d^k, highest power first:
    a_k = J^(k)(centre) / k! = (3 pi / 16) (1/2)_k^2 / ((3)_k k!) 2F1(1/2 + k, 1/2 + k;
    3 + k; centre), the derivatives of 2F1 being 2F1s with shifted parameters."""
    a, rising = [], 1.0  # rising = (1/2)_k^2 / ((3)_k k!)
    for k in range(n):
        a.append(3.0 * math.pi / 16.0 * rising * _hyp2f1(0.5 + k, 0.5 + k, 3.0 + k, centre))
        rising *= (0.5 + k) ** 2 / ((3.0 + k) * (k + 1.0))
    return tuple(a[::-1])


_COEFFICIENTS = _series_coefficients(_N_TERMS, SERIES_CENTRE)


@njit(cache=True, inline="always")
def quartic_series(m: float) -> float:
    """J(m) by its Taylor series about SERIES_CENTRE (Horner, 14 terms), for
    0 <= m <= SERIES_LIMIT: straight-line code with no branch, so that loops over many m
    compile to SIMD code. m - 0.1 is exact for m >= 0.05 (Sterbenz) and within 7e-18
    below, which moves J by less than 1e-17 of itself."""
    return horner(m - SERIES_CENTRE, _COEFFICIENTS)


@njit(cache=True, nogil=True)
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
