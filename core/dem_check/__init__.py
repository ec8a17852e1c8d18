"""The DEM modeller's bench: exact test vectors of the paper's loading, a scorer for any
DEM code's force history over one contact, and the real LAMMPS run on the same cases.

    >>> import math
    >>> from core.dem_check import Case, exact, score
    >>> case = Case(psi=2.414, tau0=math.pi / 6, mu=0.2, nu=0.3)
    >>> ref = exact(case)
    >>> round(ref.impulse_ratio, 4), round(ref.dissipated_energy, 5)
    (0.7581, 0.05856)
    >>> s = score(case, ref.tau, ref.T, ref.P)
    >>> s.max_T_error, s.energy_gain
    (0.0, 0.0)

``lammps.run(case, model, steps)`` runs Debian's ``lmp`` (docs/dem_check.md);
``python -m core.dem_check`` exports the vectors, scores a CSV file and runs LAMMPS.
"""

from core.dem_check import lammps
from core.dem_check.case import CASES, Case, case_named
from core.dem_check.exact import Reference, dissipated_energy, drive_work, exact
from core.dem_check.score import DemScore, score

__all__ = [
    "CASES",
    "Case",
    "DemScore",
    "Reference",
    "case_named",
    "dissipated_energy",
    "drive_work",
    "exact",
    "lammps",
    "score",
]
