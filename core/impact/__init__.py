"""The exact oblique impact of a sphere on a flat or a second sphere: Hertz normal
contact, the Mindlin-Deresiewicz tangential history (``core.numerics.mdr``'s springs) and
the rigid-body motion, integrated with error control (docs/impact.md).

    >>> from core.impact import Impact, Material, solve
    >>> alumina = Material("alumina", E=380e9, nu=0.23, density=4000.0)
    >>> import math
    >>> th = math.radians(45.0)
    >>> r = solve(Impact(radius=2.5e-3, material=alumina, mu=0.092,
    ...                  vx=3.9 * math.sin(th), vz=-3.9 * math.cos(th)))
    >>> round(r.tangential_cor, 4), round(r.normal_cor, 6)   # gross sliding: 1 - 2 mu
    (0.816, 1.0)
"""

from core.impact.bodies import Impact, Material, Target
from core.impact.normal import dashpot, tsuji_coefficient
from core.impact.solve import ImpactResult, Normalised, normalised, solve

__all__ = ["Impact", "ImpactResult", "Material", "Normalised", "Target", "dashpot",
           "normalised", "solve", "tsuji_coefficient"]
