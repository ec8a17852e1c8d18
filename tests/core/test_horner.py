"""core.horner: the polynomial of a tuple of coefficients, highest power first, in the
rounding of the written Horner sum (numpy.polyval's order), bit for bit."""

import numpy as np

from core.horner import horner


def test_horner_is_polyval_bit_for_bit() -> None:
    rng = np.random.default_rng(7)
    for n in (2, 10, 14):
        coeffs = tuple(float(c) for c in rng.normal(size=n))
        for x in rng.uniform(-2.0, 2.0, 50):
            assert horner(x, coeffs) == np.polyval(coeffs, x)
    assert horner(3.0, (1.0, 2.0, 3.0)) == 18.0  # 9 + 6 + 3
