"""The classical cases the solver is checked against: Cattaneo-Mindlin's monotonic shift of
a Hertz contact and Spence's compression of dissimilar bodies.

Units: lengths in the Hertz radius a of the (frictionless) normal load, tractions in its
peak pressure p0 (the normal load is 2 pi / 3), displacements in a^2 / R_e.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from core.bem.convolution import Operators
from core.bem.grid import Grid, check_across
from core.bem.march import DEFAULT, State, StepSettings, step, stick_mask
from core.bem.pair import LOAD_RANGE, Pair, hertz_load, rigid_indenter_nu
from core.validation import DOMAIN


def hertz_gap(grid: Grid) -> np.ndarray:
    """The undeformed gap r^2 / 2 of a Hertz contact (units a^2 / R_e, r in a)."""
    x, y = grid.xy
    return 0.5 * (x * x + y * y)


def mindlin_shift(load: float, mu: float, pair: Pair) -> float:
    """Mindlin's relative shift of the two bodies under Q / (mu P) = load:
    mu kappa [1 - (1 - load)^(2/3)] (units a^2 / R_e; ../shared/physics.md, 3D boundary
    elements, with P = 4 E* a^3 / (3 R_e))."""
    return mu * pair.kappa * (1.0 - (1.0 - load) ** (2.0 / 3.0))


def stick_radius(state: State, mu: float, settings: StepSettings) -> float:
    """c / a of the equal-area circles: sqrt(stuck elements / elements in contact)."""
    contact = int((state.p > 0.0).sum())
    thr = max(10.0 * settings.slip_tol, 1e-6 * float(np.hypot(state.sx, state.sy).max()))
    stuck = int(stick_mask(state, mu, thr).sum())
    return math.sqrt(stuck / contact) if contact else 0.0


@dataclass(frozen=True)
class CattaneoResult:
    """Cattaneo-Mindlin's shift on a grid: shift_ratio (shift over Mindlin's),
    stick_radius (c / a, equal-area), transverse_fraction (sum |q_y| dA / |F_x|), the shift
    itself (units a^2 / R_e), elements_across, seconds, and the final ``state``."""

    shift_ratio: float
    stick_radius: float
    transverse_fraction: float
    shift: float
    elements_across: int
    seconds: float
    state: State
    grid: Grid


def cattaneo(nu: float, load: float, grid: int, *, mu: float = 0.4, steps: int = 1,
             settings: StepSettings = DEFAULT) -> CattaneoResult:
    """A Hertz contact of identical bodies (Poisson ratio nu) compressed, then sheared
    monotonically to F_x = load mu P in ``steps`` equal force steps (the rigid shift of
    each step found by Brent's method), as Kalker's and CONTACT's Cattaneo problem.

    Parameters
    ----------
    nu : float
        Poisson ratio, in [0, 0.5).
    load : float
        Q / (mu P), in [0, 1).
    grid : int
        Elements across the contact diameter.
    mu : float
        Friction coefficient (the results scale out of it for identical bodies).
    steps : int
        Force steps (1: one shift from the unloaded state, as CONTACT does).

    Returns
    -------
    CattaneoResult
    """
    pair = Pair(nu)
    load = LOAD_RANGE.check("load", load)
    mu = DOMAIN["mu"].check("mu", mu)
    if isinstance(steps, bool) or not isinstance(steps, int) or not 1 <= steps <= 10**4:
        raise ValueError(f"steps must be an integer in [1, 10000], got {steps!r}")
    t0 = time.perf_counter()
    g = Grid(check_across(grid))
    op = Operators(g, pair.nu, 0.0)
    h0 = hertz_gap(g)
    P = hertz_load()
    state = step(op, h0, State.unloaded(h0.shape), mu, (0.0, 0.0), load=P,
                 settings=settings)
    W = 0.0
    scale = mu * pair.kappa
    for k in range(1, steps + 1):
        target = load * mu * P * k / steps
        prev = state
        trial: dict[float, State] = {}

        def excess(w: float, prev: State = prev, trial: dict = trial,
                   target: float = target, w0: float = W) -> float:
            s = step(op, h0, prev, mu, (w - w0, 0.0), load=P, settings=settings)
            trial[w] = s
            return float(s.qx.sum()) * g.area - target

        if target == 0.0:
            continue
        w_prev = W
        W = brentq(excess, w_prev, w_prev + 2.0 * scale, xtol=1e-13 * scale, rtol=1e-13)
        state = trial[W] if W in trial else step(op, h0, prev, mu, (W - w_prev, 0.0),
                                                 load=P, settings=settings)
    fx = float(state.qx.sum()) * g.area
    shift_m = mindlin_shift(load, mu, pair)
    return CattaneoResult(
        shift_ratio=W / shift_m if shift_m > 0 else math.nan,
        stick_radius=stick_radius(state, mu, settings) if load > 0 else 1.0,
        transverse_fraction=float(np.abs(state.qy).sum()) * g.area / abs(fx) if fx else 0.0,
        shift=W, elements_across=g.elements_across,
        seconds=time.perf_counter() - t0, state=state, grid=g)


@dataclass(frozen=True)
class SpenceResult:
    """Spence's compression on a grid: stick_radius (c / a, equal-area, at the last
    stage), elements_across, stages, seconds, the final ``state``."""

    stick_radius: float
    elements_across: int
    stages: int
    seconds: float
    state: State
    grid: Grid


def spence(beta: float, mu: float, grid: int, *, nu: float | None = None,
           stages: int | None = None,
           settings: StepSettings = DEFAULT) -> SpenceResult:
    """Dissimilar bodies compressed by a growing normal load without shift, in ``stages``
    load stages P_k = (2 pi / 3)(k / stages)^3 (the contact radius grows evenly to 1), as
    CONTACT's example spence35. Spence (1975): c / a settles to a constant that depends on
    beta and mu.

    Parameters
    ----------
    beta : float
        Dundurs' beta, in (-0.5, 0.5).
    mu : float
        Friction coefficient.
    grid : int
        Elements across the final contact diameter.
    nu : float, optional
        Effective Poisson ratio; default that of an elastic body under a rigid one with
        this |beta| (``rigid_indenter_nu``; 0 for beta -> 1/2, CONTACT's example).
    stages : int, optional
        Load stages; default ``grid`` (the radius grows by half an element per stage).
    """
    beta = Pair(0.0, beta).beta
    mu = DOMAIN["mu"].check("mu", mu)
    pair = Pair(rigid_indenter_nu(beta) if nu is None else nu, beta)
    g = Grid(check_across(grid))
    stages = g.elements_across if stages is None else stages
    if isinstance(stages, bool) or not isinstance(stages, int) or not 1 <= stages <= 10**4:
        raise ValueError(f"stages must be an integer in [1, 10000], got {stages!r}")
    t0 = time.perf_counter()
    op = Operators(g, pair.nu, pair.beta)
    h0 = hertz_gap(g)
    state = State.unloaded(h0.shape)
    for k in range(1, stages + 1):
        state = step(op, h0, state, mu, (0.0, 0.0), load=hertz_load() * (k / stages) ** 3,
                     settings=settings)
    return SpenceResult(stick_radius(state, mu, settings), g.elements_across, stages,
                        time.perf_counter() - t0, state, g)
