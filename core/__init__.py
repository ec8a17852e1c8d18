"""Exact solution of Zharii (1996) for two elastic spheres in intermittent oblique frictional
contact, and (``core.numerics``) independent numerical methods for the same problem.

    >>> from core import Contact
    >>> c = Contact(psi=2.414213562373095, tau0=0.5235987755982988)
    >>> round(c.tau1 / 3.141592653589793, 12)   # tau1 = 3 pi / 4 (Fig. 4b)
    0.75
"""

from core import batch
from core.contact import Contact, curve, impulse_ratio
from core.coulomb import CoulombReport, coulomb_certificate
from core.materials import PRESETS, Material
from core.physical import MATERIALS, PhysicalInputs, Scales, dundurs_beta, equivalent_pair
from core.tangential import PHASE_NAMES, Phase
from core.validation import DOMAIN, MOTOR_DOMAIN, PSI_MAX, Interval

__all__ = [
    "DOMAIN",
    "MATERIALS",
    "MOTOR_DOMAIN",
    "PHASE_NAMES",
    "PRESETS",
    "PSI_MAX",
    "Contact",
    "CoulombReport",
    "Interval",
    "Material",
    "Phase",
    "PhysicalInputs",
    "Scales",
    "batch",
    "coulomb_certificate",
    "curve",
    "dundurs_beta",
    "equivalent_pair",
    "impulse_ratio",
]
