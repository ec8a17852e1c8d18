"""Discrete-element tangential spring models, scalar and undamped, as the codes run them.

Every model integrates the same prescribed drive with a fixed time step. The relative
tangential velocity of the contact is that of the lower sphere's centre,
u0 omega cos tau (eq 3; the upper sphere is held), taken at the half step as in
velocity-Verlet codes, so the history increment of step k is
dxi = u0 cos(tau_{k-1/2}) dtau. The contact radius a = sqrt(R* delta), R* = R / 2,
and the Hertz force P are those of eqs 7-9. Stiffness k_t a with k_t = 8 G_eff,
G_eff = G / (2 (2 - nu)) for two identical spheres (the codes' mixing rule), i.e.
k_t a = 2 G* a with G* = 2 G / (2 - nu). In units of T0 / u0 (eqs 23, 37):

    k_t a = (3/2) psi sqrt(sin tau - s0).

Force on the upper sphere F (units T0), Coulomb cap |F| <= mu P = T0 (sin tau - s0)^{3/2}.
When the cap is hit, the force is scaled to the cap and the history is reset to the
elastic part of the capped force (xi = F / (k_t a), or the force itself).

Rules and sources:

* ``lammps_mindlin``: F = k_t a xi, xi += dxi. LAMMPS src/GRANULAR/gran_sub_mod_tangential.cpp,
  GranSubModTangentialMindlin::calculate_forces (mindlin_force = mindlin_rescale = 0).
* ``lammps_mindlin_force``: history is the force, F += k_t a dxi (mindlin_force = 1,
  ``hist_increment = -k_scaled * dt * vtr``).
* ``lammps_mindlin_rescale``: as mindlin, but before the update the history is scaled by
  a / a_prev whenever a < a_prev (history[3] holds the previous contact radius).
* ``lammps_mindlin_rescale_force``: force history, rescaled by a / a_prev on unloading.
* ``liggghts_history``: LIGGGHTS-PUBLIC src/tangential_model_history.h with the Hertz
  normal model src/normal_model_hertz.h (kt = 8 Geff sqrt(reff deltan)): shear += vtr dt,
  F = -kt shear, capped at xmu Fn with shear = -F / kt. For this scalar undamped loading
  it performs the same arithmetic as ``lammps_mindlin``.
* ``direnzo``: Di Renzo & Di Maio, Chem. Eng. Sci. 60 (2005) 1303-1312, "An improved
  integral non-linear model for the contact of particles in distinct element
  simulations": F = (2/3) k_t a xi (the secant of Mindlin's no-slip loading curve),
  capped at mu P with the history rescaled as in the codes above.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from core.numerics.loading import hertz_force, impulse_ratio_trapezoid
from core.numerics.result import ContactLike, check_resolution, contact_parameters

DESCRIPTIONS: dict[str, str] = {
    "lammps_mindlin": "LAMMPS granular mindlin: F = -k_t a xi, capped at mu P",
    "lammps_mindlin_force": "LAMMPS granular mindlin/force: dF = -k_t a dxi, capped at mu P",
    "lammps_mindlin_rescale": "LAMMPS mindlin_rescale: xi scaled by a/a_prev on unloading",
    "lammps_mindlin_rescale_force": "LAMMPS mindlin_rescale/force: F scaled by a/a_prev "
                                    "on unloading",
    "liggghts_history": "LIGGGHTS tangential_model_history with Hertz kt = 8 G_eff a",
    "direnzo": "Di Renzo & Di Maio (2005): F = -(2/3) k_t a xi, capped at mu P",
}

# (force_history, rescale, stiffness factor) per model
_RULES: dict[str, tuple[bool, bool, float]] = {
    "lammps_mindlin": (False, False, 1.0),
    "lammps_mindlin_force": (True, False, 1.0),
    "lammps_mindlin_rescale": (False, True, 1.0),
    "lammps_mindlin_rescale_force": (True, True, 1.0),
    "liggghts_history": (False, False, 1.0),
    "direnzo": (False, False, 2.0 / 3.0),
}


def dem_time_grid(tau0: float, steps: int) -> NDArray[np.float64]:
    """steps + 1 equal time steps over the contact [tau0, pi - tau0] (eq 4)."""
    return np.linspace(tau0, np.pi - tau0, steps + 1)


def integrate(psi: float, tau0: float, tau: NDArray[np.float64], *, force_history: bool,
              rescale: bool, factor: float = 1.0) -> NDArray[np.float64]:
    """March one spring model over the times ``tau``; returns F / T0 at each time.

    force_history: the history is the force (``/force`` variants) instead of the
    displacement xi / u0; rescale: scale the history by a / a_prev when a shrinks;
    factor: multiplies k_t a (2/3 for Di Renzo & Di Maio).
    """
    s0 = math.sin(tau0)
    kfac = 1.5 * psi * factor
    hist = 0.0
    a_prev = 0.0
    out = np.zeros(tau.size)
    for k in range(1, tau.size):
        delta = max(math.sin(tau[k]) - s0, 0.0)
        a = math.sqrt(delta)  # a / a* up to the constant sqrt(1 - s0), absorbed in kfac
        if delta <= 0.0:
            hist, a_prev = 0.0, 0.0
            continue
        kt_a = kfac * a
        cap = delta * a  # mu P / T0 = delta^{3/2}
        if rescale and a < a_prev:
            hist *= a / a_prev
        dxi = math.cos(0.5 * (tau[k] + tau[k - 1])) * (tau[k] - tau[k - 1])
        if force_history:
            hist += kt_a * dxi
            force = hist
        else:
            hist += dxi
            force = kt_a * hist
        if abs(force) > cap:
            force = math.copysign(cap, force)
            hist = force if force_history else force / kt_a
        a_prev = a
        out[k] = force
    return out


def make_solver(name: str) -> Callable[[ContactLike, int], tuple]:
    """Solver for one DEM model: (contact, steps) -> (tau, T, None, impulse ratio)."""
    force_history, rescale, factor = _RULES[name]

    def solve(contact: ContactLike, resolution: int) -> tuple:
        steps = check_resolution(resolution, maximum=10**7)
        psi, tau0 = contact_parameters(contact)
        tau = dem_time_grid(tau0, steps)
        T = integrate(psi, tau0, tau, force_history=force_history, rescale=rescale,
                      factor=factor)
        return tau, T, None, impulse_ratio_trapezoid(tau, T, hertz_force(tau, tau0))

    solve.__doc__ = f"{DESCRIPTIONS[name]} ({steps_doc})"
    return solve


steps_doc = "resolution = number of equal time steps over the contact"
SOLVERS: dict[str, Callable[[ContactLike, int], tuple]] = {n: make_solver(n) for n in _RULES}
