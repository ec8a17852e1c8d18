"""The stall thrust: the mean tangential force on a held rotor (eq 41 along the rod).

With the rotor held (the paper's problem), each contact at x0 is the paper's contact with
psi(x0) and tau0(x0), one contact per period 2 pi / omega, so the mean force is

    F_t = (omega / 2 pi) T_imp = mu N T_imp / (mu P_imp)       (P_imp = 2 pi N / omega)

times the direction of the drive, sign u0(x0). T_imp / (mu P_imp) is eq 41, evaluated by
``core.tangential`` (one source of truth): psi for psi <= 1, k J(k^2 m0) / J(m0) with
k^2 = 2 / (psi + 1) and m0 = (1 - sin tau0) / 2 above. The preload solve gives m0 and
mc0 = 1 - m0 directly (more digits than tau0 near grazing), so this module calls core's
element-wise form of m0, ``core.tangential.impulse_ratio``, on both arrays.
See docs/physics.md, section 10.3.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from core import tangential


def impulse_ratio(
    psi: NDArray[np.float64], m0: NDArray[np.float64], mc0: NDArray[np.float64]
) -> NDArray[np.float64]:
    """T_imp / (mu P_imp) (eq 41, dimensionless, in [0, 1]) elementwise over arrays of psi
    and of m0 = (1 - sin tau0) / 2, mc0 = 1 - m0 (same shape); nan where m0 is nan (the
    contact never opens)."""
    opens = ~np.isnan(m0)  # elsewhere psi may be inf: no arithmetic on it
    ratio = tangential.impulse_ratio(np.where(opens, psi, 0.0), np.where(opens, m0, 0.0),
                                     np.where(opens, mc0, 1.0))
    return np.where(opens, ratio, np.nan)


def stall_thrust(
    ratio: NDArray[np.float64], u0: NDArray[np.float64], mu: float, preload: float
) -> NDArray[np.float64]:
    """F_t = mu N ratio sign(u0) (N): positive along +x on the rotor's bottom surface
    (counter-clockwise rotation of a free rotor, as seen in Fig. 1); +0 where u0 = 0,
    nan where ratio is nan."""
    thrust = (mu * preload) * np.asarray(ratio)
    return np.where(u0 < 0.0, -thrust, thrust)
