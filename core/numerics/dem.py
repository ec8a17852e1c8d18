"""Discrete-element tangential spring models, scalar and undamped, as the codes run them;
compiled with numba.

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
When the cap is exceeded the force is scaled onto it and the history is reset to the
elastic part of the capped force. Damping is zero (quasi-static problem).

Rules and sources (one kernel per code, written in that code's arithmetic):

* ``lammps_mindlin``: history xi += v dt, F = -k_t a xi. LAMMPS
  src/GRANULAR/gran_sub_mod_tangential.cpp, GranSubModTangentialMindlin::calculate_forces
  (mindlin_force = mindlin_rescale = 0): if |F| > Fscrit, F *= Fscrit / |F| and
  xi = -F / (k_t a).
* ``lammps_mindlin_force``: the history is the force, F += -k_t a v dt
  (``mindlin/force``: mindlin_force = 1).
* ``lammps_mindlin_rescale``: as mindlin, but before the update the history is scaled
  by a / a_prev whenever a < a_prev (history[3] holds the previous contact radius).
* ``lammps_mindlin_rescale_force``: force history, rescaled by a / a_prev on unloading.
* ``lammps_linear_history``: GranSubModTangentialLinearHistory: as mindlin with a
  constant k_t instead of k_t a (the same file: "the same as the base Mindlin
  calculation except k isn't scaled by contact radius"). k_t is a user input in LAMMPS;
  here it is the Mindlin stiffness at the largest contact radius, 8 G_eff a*, i.e.
  (3/2) psi sqrt(1 - s0) in T0 / u0.
* ``liggghts_history``: LIGGGHTS-PUBLIC src/tangential_model_history.h with the Hertz
  normal model src/normal_model_hertz.h (kt = 8 Geff sqrt(reff deltan)): shear += vtr dt,
  Ft = -kt shear; if kt |shear| > xmu Fn, Ft *= xmu Fn / (kt |shear|) and
  shear = -Ft / kt. The rule is LAMMPS mindlin's; the arithmetic is LIGGGHTS'.
* ``direnzo``: Di Renzo & Di Maio, Chem. Eng. Sci. 60 (2005) 1303-1312, "An improved
  integral non-linear model for the contact of particles in distinct element
  simulations": F = (2/3) k_t a xi (the secant of Mindlin's no-slip loading curve),
  capped at mu P with the history rescaled as in the codes above.

Sign: the history here holds the drive displacement xi = -(relative velocity) dt of the
codes, so that F = +k_t a xi is the force on the upper sphere (eq 37's sign).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numba import njit
from numpy.typing import NDArray

from core.numerics.result import ContactLike, check_resolution, contact_parameters

DESCRIPTIONS: dict[str, str] = {
    "lammps_mindlin": "LAMMPS granular mindlin: F = -k_t a xi, capped at mu P",
    "lammps_mindlin_force": "LAMMPS granular mindlin/force: dF = -k_t a dxi, capped at mu P",
    "lammps_mindlin_rescale": "LAMMPS mindlin_rescale: xi scaled by a/a_prev on unloading",
    "lammps_mindlin_rescale_force": "LAMMPS mindlin_rescale/force: F scaled by a/a_prev "
                                    "on unloading",
    "lammps_linear_history": "LAMMPS granular linear_history: F = -k_t xi with constant "
                             "k_t = 8 G_eff a*, capped at mu P",
    "liggghts_history": "LIGGGHTS tangential_model_history with Hertz kt = 8 G_eff a",
    "direnzo": "Di Renzo & Di Maio (2005): F = -(2/3) k_t a xi, capped at mu P",
}

# model codes of the compiled driver
LAMMPS_MINDLIN, LAMMPS_FORCE, LAMMPS_RESCALE, LAMMPS_RESCALE_FORCE, LAMMPS_LINEAR = range(5)
LIGGGHTS, DIRENZO = 5, 6
MODELS: dict[str, int] = {
    "lammps_mindlin": LAMMPS_MINDLIN,
    "lammps_mindlin_force": LAMMPS_FORCE,
    "lammps_mindlin_rescale": LAMMPS_RESCALE,
    "lammps_mindlin_rescale_force": LAMMPS_RESCALE_FORCE,
    "lammps_linear_history": LAMMPS_LINEAR,
    "liggghts_history": LIGGGHTS,
    "direnzo": DIRENZO,
}


@njit(cache=True, nogil=True)
def lammps(psi, tau0, tau, force_history, rescale, constant_k):
    """LAMMPS granular tangential models (mindlin, mindlin/force, mindlin_rescale,
    mindlin_rescale/force, linear_history) over the times ``tau``; returns F / T0 and the
    Coulomb limit mu P / T0 the rule used at each time."""
    s0 = math.sin(tau0)
    kfac = 1.5 * psi
    k_const = kfac * math.sqrt(1.0 - s0)
    hist = 0.0
    a_prev = 0.0  # history[3]
    out = np.zeros(tau.size)
    lim = np.zeros(tau.size)
    for k in range(1, tau.size):
        delta = max(math.sin(tau[k]) - s0, 0.0)
        if delta <= 0.0:  # out of contact: the codes delete the history
            hist, a_prev = 0.0, 0.0
            continue
        a = math.sqrt(delta)  # a / a* up to the constant sqrt(1 - s0), absorbed in kfac
        k_scaled = k_const if constant_k else kfac * a
        fscrit = delta * a  # mu P / T0 = delta^{3/2}
        lim[k] = fscrit
        if rescale and a < a_prev:
            hist *= a / a_prev
        dxi = math.cos(0.5 * (tau[k] + tau[k - 1])) * (tau[k] - tau[k - 1])
        if force_history:
            hist += k_scaled * dxi
        else:
            hist += dxi
        if rescale:
            a_prev = a
        fs = hist if force_history else k_scaled * hist
        magfs = abs(fs)
        if magfs > fscrit:
            fs *= fscrit / magfs
            hist = fs if force_history else fs / k_scaled
        out[k] = fs
    return out, lim


@njit(cache=True, nogil=True)
def liggghts(psi, tau0, tau):
    """LIGGGHTS-PUBLIC tangential_model_history (Hertz kt) over ``tau``; returns F / T0
    and mu P / T0."""
    s0 = math.sin(tau0)
    kfac = 1.5 * psi
    shear = 0.0
    out = np.zeros(tau.size)
    lim = np.zeros(tau.size)
    for k in range(1, tau.size):
        deltan = max(math.sin(tau[k]) - s0, 0.0)
        if deltan <= 0.0:  # surfacesClose: shear = 0
            shear = 0.0
            continue
        a = math.sqrt(deltan)
        kt = kfac * a
        shear -= math.cos(0.5 * (tau[k] + tau[k - 1])) * (tau[k] - tau[k - 1])  # vtr dt
        shrmag = abs(shear)
        ft = -(kt * shear)
        ft_shear = kt * shrmag
        ft_friction = deltan * a  # xmu |Fn|
        lim[k] = ft_friction
        if ft_shear > ft_friction:
            if shrmag != 0.0:
                ft *= ft_friction / ft_shear
                shear = -ft / kt
            else:
                ft = 0.0
        out[k] = ft
    return out, lim


@njit(cache=True, nogil=True)
def direnzo(psi, tau0, tau):
    """Di Renzo & Di Maio (2005): F = (2/3) k_t a xi, capped; returns F / T0 and
    mu P / T0."""
    s0 = math.sin(tau0)
    kfac = psi  # (2/3) (3/2) psi
    xi = 0.0
    out = np.zeros(tau.size)
    lim = np.zeros(tau.size)
    for k in range(1, tau.size):
        delta = max(math.sin(tau[k]) - s0, 0.0)
        if delta <= 0.0:
            xi = 0.0
            continue
        a = math.sqrt(delta)
        kt = kfac * a
        xi += math.cos(0.5 * (tau[k] + tau[k - 1])) * (tau[k] - tau[k - 1])
        force = kt * xi
        cap = delta * a
        lim[k] = cap
        if abs(force) > cap:
            force = math.copysign(cap, force)
            xi = force / kt
        out[k] = force
    return out, lim


@njit(cache=True, nogil=True)
def forces(model, psi, tau0, tau):
    """(F / T0, mu P / T0) of ``model`` (a code of ``MODELS``) over the times ``tau``."""
    if model == LIGGGHTS:
        return liggghts(psi, tau0, tau)
    if model == DIRENZO:
        return direnzo(psi, tau0, tau)
    return lammps(psi, tau0, tau, model == LAMMPS_FORCE or model == LAMMPS_RESCALE_FORCE,
                  model == LAMMPS_RESCALE or model == LAMMPS_RESCALE_FORCE,
                  model == LAMMPS_LINEAR)


@njit(cache=True, nogil=True)
def contact(model, psi, tau0, steps):
    """One contact from (psi, tau0) with ``steps`` equal time steps over
    [tau0, pi - tau0]: returns (tau, F / T0, impulse ratio by the trapezoid rule)."""
    tau = np.linspace(tau0, np.pi - tau0, steps + 1)
    F, P = forces(model, psi, tau0, tau)
    f_sum = 0.5 * (F[0] + F[steps])  # equal steps: the trapezoid's dtau cancels
    p_sum = 0.5 * (P[0] + P[steps])
    for k in range(1, steps):
        f_sum += F[k]
        p_sum += P[k]
    return tau, F, f_sum / p_sum


def dem_time_grid(tau0: float, steps: int) -> NDArray[np.float64]:
    """steps + 1 equal time steps over the contact [tau0, pi - tau0] (eq 4)."""
    return np.linspace(tau0, np.pi - tau0, steps + 1)


def make_solver(name: str) -> Callable[[ContactLike, int], tuple]:
    """Solver for one DEM model: (contact, steps) -> (tau, T, None, impulse ratio)."""
    model = MODELS[name]

    def solve(contact_: ContactLike, resolution: int) -> tuple:
        steps = check_resolution(resolution, maximum=10**7)
        psi, tau0 = contact_parameters(contact_)
        tau, T, ratio = contact(model, psi, tau0, steps)
        return tau, T, None, ratio

    solve.__doc__ = f"{DESCRIPTIONS[name]} (resolution = number of equal time steps)"
    return solve


SOLVERS: dict[str, Callable[[ContactLike, int], tuple]] = {n: make_solver(n) for n in MODELS}
