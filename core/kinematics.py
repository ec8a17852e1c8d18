"""Motion of the contact-area centre r = 0 of each body (eqs 42, 43), dimensionless.

Eqs 42, 43 are the motion of identical spheres, u2 = -u1: half the relative tangential
displacement u2 - u1 of the two surfaces at r = 0. For dissimilar bodies (Goodman's
approximation, docs/physics.md section 11.1) the relative displacement is the equivalent
pair's, and each body takes its share of it in proportion to its tangential compliance
(2 - nu) / G: the upper body 2 lambda u2, the lower one -2 (1 - lambda) u2, lambda the
upper body's share (``core.physical.upper_share``; ``own_motion``).

Displacement in u0, velocity in omega u0. With s = sin(e/2), a^2 = (1 - w)(1 + w) and
sin tau - sin tau0 = 2 s^2 a^2 (``core.clock``):

    psi <= 1:  u2 = s^2 a^2                      v2 = cos(tau) / 2
    slip:      u2 = s^2 a^2 / psi                v2 = cos(tau) / (2 psi)
    partial:   u2 = s^2 (1/psi - w^2)            v2 = cos(tau) / 2
    counter:   u2 = -s^2 a^2 / psi               v2 = -cos(tau) / (2 psi)

(the partial-stick line is eq 43's u0 (psi sin tau + 1 - psi - sin tau0) / (2 psi),
rewritten without cancellation).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from core.tangential import Phase


def centre_displacement(
    w: NDArray[np.float64], a2: NDArray[np.float64], ph: NDArray[np.int_], psi: float,
    sin_half_e: float,
) -> NDArray[np.float64]:
    """u2 / u0 (eq 43) from the clock w, a2 = (a/a*)^2 and the phase codes ph; 0 outside
    contact and at both contact ends."""
    s2 = sin_half_e**2
    if psi <= 1.0:
        return s2 * a2
    out = np.where(ph == Phase.COUNTER_SLIP, -s2 * a2 / psi, s2 * a2 / psi)
    partial = ph == Phase.PARTIAL_STICK
    out[partial] = s2 * (1.0 / psi - w[partial] ** 2)
    return out


def centre_velocity(
    cos_tau: NDArray[np.float64], ph: NDArray[np.int_], psi: float
) -> NDArray[np.float64]:
    """v2 / (omega u0) (eq 42) from cos(tau) and the phase codes ph; 0 outside contact.
    Jumps at tau0, tau1 and pi - tau0."""
    factor = np.select(
        [
            ph == Phase.FULL_STICK,
            ph == Phase.SLIP,
            ph == Phase.PARTIAL_STICK,
            ph == Phase.COUNTER_SLIP,
        ],
        [0.5, 0.5 / max(psi, 1.0), 0.5, -0.5 / max(psi, 1.0)],
        0.0,
    )
    return factor * cos_tau


def own_motion(half: NDArray[np.float64], share: float) -> NDArray[np.float64]:
    """A body's own motion, 2 share x half, from ``half``, the equivalent pair's u2 or v2
    (half the relative motion), and ``share``, the body's share of the compliance
    (lambda for the upper body, 1 - lambda for the lower one). ``half`` itself, the same
    array, when share = 1/2 (identical bodies: eqs 42, 43 bit for bit)."""
    return half if share == 0.5 else (2.0 * share) * half
