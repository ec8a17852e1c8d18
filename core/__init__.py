"""Exact solution of Zharii (1996) for two elastic spheres in intermittent oblique frictional
contact, and (``core.numerics``) independent numerical methods for the same problem.

One public route per quantity: ``Contact``'s methods and properties, which document each
quantity once (definition, units, domain, tested accuracy). The others are thin and refer
there, returning the same values bit for bit: ``Contact.at(tau)`` (the functions of time
at one array of times, each computed once), ``core.batch`` (the functions of time over
arrays of contacts), ``core.impulse_ratio`` (eq 41 over arrays of psi and tau0) and
``core.curve`` (T, b and eq 41 of one contact in one compiled call).

    >>> from core import Contact
    >>> c = Contact(psi=2.414213562373095, tau0=0.5235987755982988)
    >>> round(c.tau1 / 3.141592653589793, 12)   # tau1 = 3 pi / 4 (Fig. 4b)
    0.75
"""

from core import batch
from core.contact import Contact, curve, impulse_ratio
from core.coulomb import CoulombReport, coulomb_certificate
from core.materials import DRY_MU, MATERIALS, MOTOR_MATERIALS, Material
from core.physical import PhysicalInputs, Scales, dundurs_beta, equivalent_pair
from core.tangential import PHASE_NAMES, Phase
from core.validation import DOMAIN, MOTOR_DOMAIN, PSI_MAX, Interval

__all__ = [
    "DOMAIN",
    "DRY_MU",
    "MATERIALS",
    "MOTOR_DOMAIN",
    "MOTOR_MATERIALS",
    "PHASE_NAMES",
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
