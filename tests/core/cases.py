"""The hard corners of the parameter domain, shared by the core tests."""

import math

PSIS = [
    0.0,
    0.4,
    1.0 - 1e-12,
    1.0,
    1.0 + 1e-12,
    1.0 + 1e-6,
    math.sqrt(2) + 1,
    6.46,
    28.35,
    1e3,
    1e6,
    1e12,
]
TAU0S = [
    math.pi / 6,
    0.0,
    1.5,
    -0.9,
    math.pi / 2 - 1e-8,
    -math.pi / 2 + 1e-8,
    math.pi / 2 - 1e-4,
    -1.5,
]
