"""Quasi-static time marching of the frictional contact with its history.

One step takes the normal loading (a rigid approach, or a total load) and the increment of
the rigid shift dW of body 2 relative to body 1, and solves for the pressure p and the
traction q on body 1 such that Coulomb's law holds for the step's slip

    s = [u_t(q, p) - u_t(previous step)] - dW

(u_t the displacement of body 1's surface relative to body 2's, ``core.bem.convolution``;
Kalker's shift transient). When beta != 0 the normal and tangential problems are coupled
(the shear moves the surfaces normally, the pressure tangentially) and each step iterates
between them (Panagiotopoulos' process) until p and q change by less than ``outer_tol``;
for beta = 0 one pass is exact.

The friction work of a step is -sum(q_mean . s) h^2, q_mean the mean of the step's two
tractions (trapezoid rule for int q . ds; with the end traction alone every term would be
non-negative by Coulomb's law, but the estimate is only first order in the step).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import NDArray

from core.bem.convolution import Operators
from core.bem.normal import solve_normal
from core.bem.tangential import solve_tangential

Array = NDArray[np.float64]


@dataclass(frozen=True)
class State:
    """The contact after a step: pressure p, traction (qx, qy) on body 1 (units p*), the
    relative tangential displacement (ux, uy) (units a^2 / R_e), the step's slip (sx, sy),
    the rigid approach and the cumulative friction work (units p* a^2 . a^2 / R_e)."""

    p: Array
    qx: Array
    qy: Array
    ux: Array
    uy: Array
    sx: Array
    sy: Array
    approach: float = 0.0
    work: float = 0.0
    iterations: dict = field(default_factory=dict, compare=False)

    @classmethod
    def unloaded(cls, shape: tuple[int, int]) -> State:
        """No contact, no history."""
        z = np.zeros(shape)
        return cls(z, z, z, z, z, z, z)


@dataclass(frozen=True)
class StepSettings:
    """Tolerances: ``normal_tol`` (relative change of p), ``slip_tol`` (largest residual
    slip, units a^2 / R_e), ``outer_tol`` (largest change of p or q between outer
    iterations, units p*), ``max_outer``."""

    normal_tol: float = 1e-8
    slip_tol: float = 1e-8
    outer_tol: float = 1e-8
    max_outer: int = 60


#: The default tolerances.
DEFAULT = StepSettings()


def step(op: Operators, h0: Array, state: State, mu: float, dW: tuple[float, float], *,
         approach: float | None = None, load: float | None = None,
         settings: StepSettings = DEFAULT) -> State:
    """One quasi-static step from ``state``.

    Parameters
    ----------
    op : Operators
    h0 : ndarray (M, M)
        Undeformed gap (units a^2 / R_e), e.g. r^2 / 2 for a Hertz contact.
    state : State
        The previous step (its displacement is the history).
    mu : float
        Friction coefficient.
    dW : (float, float)
        Increment of the rigid shift of body 2 relative to body 1 (units a^2 / R_e).
    approach, load : float
        Exactly one: the rigid approach (units a^2 / R_e) or the total load
        (units p* a^2).

    Returns
    -------
    State
    """
    if (approach is None) == (load is None):
        raise ValueError("give exactly one of approach and load")
    p, qx, qy = state.p, state.qx, state.qy
    h = h0 if approach is None else h0 - approach
    n_iter = t_iter = 0
    outer = 0
    change = np.inf
    while outer < settings.max_outer:
        outer += 1
        # inexact inner solves while the outer iteration is far from converged
        loose = min(1.0, 1e-2 * change) if op.coupled else 0.0
        hn = h + op.normal_from_shear(qx, qy) if op.coupled else h
        ns = solve_normal(op, hn, load=load, p0=p if p.any() else None,
                          tol=max(settings.normal_tol, 1e-2 * loose))
        cx, cy = op.shear_from_normal(ns.p)
        bx = cx - state.ux - dW[0]
        by = cy - state.uy - dW[1]
        ts = solve_tangential(op, mu * ns.p, bx, by, q0=(qx, qy),
                              tol=max(settings.slip_tol, loose * op.grid.h))
        n_iter += ns.iterations
        t_iter += ts.iterations
        change = max(float(np.abs(ns.p - p).max()), float(np.abs(ts.qx - qx).max()),
                     float(np.abs(ts.qy - qy).max()))
        p, qx, qy = ns.p, ts.qx, ts.qy
        if not op.coupled or (change <= settings.outer_tol and loose <= settings.outer_tol):
            break
    area = op.grid.area
    # trapezoid rule in the step for int q . ds (the traction moves from the previous
    # step's to this one's while the slip s accumulates)
    work = -0.5 * float(np.sum((qx + state.qx) * ts.sx + (qy + state.qy) * ts.sy)) * area
    return State(p, qx, qy, ts.sx + state.ux + dW[0], ts.sy + state.uy + dW[1], ts.sx,
                 ts.sy, ns.approach if load is not None else float(approach),
                 state.work + work,
                 {"normal": n_iter, "tangential": t_iter, "outer": outer})


def stick_mask(state: State, mu: float, slip_tol: float) -> NDArray[np.bool_]:
    """Elements in contact (p > 0) whose slip in the last step is below ``slip_tol``."""
    return (state.p > 0.0) & (np.hypot(state.sx, state.sy) <= slip_tol)


def with_history_reset(state: State) -> State:
    """The state with its history cleared (a new contact after separation)."""
    return replace(State.unloaded(state.p.shape), work=state.work)
