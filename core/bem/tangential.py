"""The tangential contact problem of one time step with Coulomb's law in every element.

With the pressure p fixed, the traction q = (q_x, q_y) on body 1 and the slip of the step
s = (u_t(q) - u_t at the previous step) - (rigid shift increment) are related affinely,
s = T q + b (T the symmetric positive definite tangential operator of
``core.bem.convolution``; b holds the previous displacement, the shift increment and the
pressure's coupling term). Coulomb's law per element, |q| <= mu p, s = 0 where |q| < mu p,
s = -lambda q / |q| (lambda >= 0) where |q| = mu p, is exactly the optimality condition of

    minimise  (1/2) q . T q + b . q   over   |q_i| <= mu p_i  (a disc per element),

a strictly convex quadratic programme (the incremental form of Kalker's variational
principle): its minimiser exists, is unique, and is the step's solution.

Method: accelerated projected gradient (FISTA, Beck & Teboulle 2009) with the projection
onto the discs (radial scaling), step 1 / L with L the operator's largest eigenvalue bound
(``Operators.tangential_bound``), and O'Donoghue & Candes' (2015) gradient restart. Each
iteration costs one application of T (two forward and two inverse FFTs). It converges for
every problem (a projected gradient method on a convex QP), linearly with rate about
1 - 1/sqrt(kappa) (kappa ~ M the condition number of T on the stick set). It stops when the
gradient mapping L |y - P(y - s / L)| (the slip a stuck element would still have, units of
displacement) is below ``tol`` in every element. Warm starts from the previous step's
traction make most steps cheap.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from core.bem.convolution import Operators

Array = NDArray[np.float64]


@dataclass(frozen=True)
class TangentialSolution:
    """Traction (qx, qy) on body 1 (units p*), the step's slip (sx, sy) (units of
    displacement), the solver's last residual and iteration count."""

    qx: Array
    qy: Array
    sx: Array
    sy: Array
    residual: float
    iterations: int


def project(qx: Array, qy: Array, bound: Array) -> tuple[Array, Array]:
    """(qx, qy) scaled onto the discs |q| <= bound, element by element."""
    mag = np.hypot(qx, qy)
    f = np.where(mag > bound, bound / np.where(mag > 0.0, mag, 1.0), 1.0)
    return qx * f, qy * f


def contact_norm(op: Operators, contact: NDArray[np.bool_], iterations: int = 12,
                 safety: float = 1.1) -> float:
    """A step length's Lipschitz constant for the elements in contact: ``safety`` times
    the power-iteration estimate of the largest eigenvalue of T restricted to them (much
    below ``Operators.tangential_bound`` for a small contact: the largest eigenvalue of
    the 1/r kernel on a disc grows with its radius), capped at that bound."""
    bound = op.tangential_bound
    if not contact.any():
        return bound
    vx = np.where(contact, 1.0, 0.0)
    vy = 0.5 * vx
    lam = 0.0
    for _ in range(iterations):
        norm = math.sqrt(float(np.sum(vx * vx + vy * vy)))
        vx, vy = vx / norm, vy / norm
        ux, uy = op.tangential(vx, vy)
        ux, uy = np.where(contact, ux, 0.0), np.where(contact, uy, 0.0)
        lam = float(np.sum(vx * ux + vy * uy))
        vx, vy = ux, uy
    return min(safety * lam, bound)


def solve_tangential(op: Operators, bound: Array, bx: Array, by: Array, *,
                     q0: tuple[Array, Array] | None = None, tol: float = 1e-10,
                     max_iter: int = 20000) -> TangentialSolution:
    """The step's traction: the minimiser of (1/2) q.Tq + b.q over |q| <= bound.

    Parameters
    ----------
    op : Operators
    bound : ndarray (M, M)
        mu p per element (units p*), >= 0.
    bx, by : ndarray (M, M)
        The affine part of the slip, s = T q + b (units a^2 / R_e).
    q0 : (ndarray, ndarray), optional
        Warm start (projected first).
    tol : float
        Largest remaining slip of the gradient mapping (units a^2 / R_e).

    Returns
    -------
    TangentialSolution
    """
    if not bound.any():
        z = np.zeros_like(bound)
        return TangentialSolution(z, z.copy(), bx.copy(), by.copy(), 0.0, 0)
    lip = contact_norm(op, bound > 0.0)
    if q0 is None:
        xx, xy = project(-bx * (bound > 0) * 0.0, -by * 0.0, bound)
    else:
        xx, xy = project(q0[0], q0[1], bound)
    yx, yy = xx, xy
    t = 1.0
    res = np.inf
    it = 0
    while it < max_iter:
        it += 1
        ux, uy = op.tangential(yx, yy)
        nx, ny = project(yx - (ux + bx) / lip, yy - (uy + by) / lip, bound)
        dx, dy = yx - nx, yy - ny
        res = lip * float(np.sqrt((dx * dx + dy * dy).max()))
        if res <= tol:
            xx, xy = nx, ny
            break
        if float(np.sum(dx * (nx - xx)) + np.sum(dy * (ny - xy))) > 0.0:
            t = 1.0  # restart: the momentum points uphill
        t_new = 0.5 * (1.0 + np.sqrt(1.0 + 4.0 * t * t))
        w = (t - 1.0) / t_new
        yx, yy = nx + w * (nx - xx), ny + w * (ny - xy)
        xx, xy, t = nx, ny, t_new
    ux, uy = op.tangential(xx, xy)
    return TangentialSolution(xx, xy, ux + bx, uy + by, res, it)
