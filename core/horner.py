"""Horner's rule over a tuple of coefficients, compiled inline (numba).

``horner(x, coeffs)`` is the polynomial c0 x^(n-1) + ... + c(n-1) of coeffs = (c0, ...,
c(n-1)), highest power first, by n - 1 multiply-adds in that order (no fused multiply-add:
the rounding is that of the written sum). Inlined into its callers, with the coefficients
a module-level tuple, the loop is unrolled at compile time and a loop over many x calling
it compiles to SIMD code. The series of ``core.clock.sine`` and ``core.elliptic``'s J use it.
"""

from __future__ import annotations

from numba import njit


@njit(cache=True, inline="always")
def horner(x: float, coeffs: tuple[float, ...]) -> float:
    """sum coeffs[k] x^(n-1-k) by Horner's rule (highest power first), n >= 2."""
    acc = coeffs[0]
    for c in coeffs[1:]:
        acc = acc * x + c
    return acc
