"""The normal contact problem on the grid by Polonsky & Keer's constrained conjugate
gradient (Polonsky & Keer, Wear 231 (1999) 206-219).

Find p >= 0 with gap g = A p + h >= 0 and p g = 0 element by element (A the normal
operator of ``core.bem.convolution``, h the undeformed gap with every other term: rigid
approach, the shear tractions' coupling). Either the total load sum(p) h_e^2 = P is given
(load control: the approach is the unknown, the mean gap over the contact, as in the
paper), or the approach is inside h (displacement control: plain projected CG). The
iteration is conjugate gradient on the contact set with projection onto p >= 0 and
re-entry of penetrating elements (steepest-descent restart), converging in about
sqrt(condition number) ~ sqrt(M) iterations per decade; it stops when the relative change
of p falls below ``tol``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from core.bem.convolution import Operators

Array = NDArray[np.float64]


@dataclass(frozen=True)
class NormalSolution:
    """p (units p*), gap (units a^2 / R_e), approach (the rigid approach when the load was
    given, else nan), iterations."""

    p: Array
    gap: Array
    approach: float
    iterations: int


def solve_normal(op: Operators, h: Array, *, load: float | None = None,
                 p0: Array | None = None, tol: float = 1e-11,
                 max_iter: int = 2000) -> NormalSolution:
    """Polonsky & Keer's CG for the frictionless (or shear-loaded) normal problem.

    Parameters
    ----------
    op : Operators
    h : ndarray (M, M)
        Undeformed gap plus every displacement not from p (units a^2 / R_e). With
        ``load`` None it includes the rigid approach (gap = A p + h).
    load : float, optional
        Total force sum(p) h_e^2 (units p* a^2); None for displacement control.
    p0 : ndarray, optional
        Warm start (any shape-matching array; negative values are clipped).
    tol : float
        Stop when sum |p_k - p_(k-1)| <= tol sum p_k.

    Returns
    -------
    NormalSolution
    """
    area = op.grid.area
    if p0 is None:
        p = np.where(h < 0.0, -h, 0.0) if load is None else np.where(h <= h.min() + 1e-300,
                                                                     1.0, 0.0)
        if load is None and not p.any():
            return NormalSolution(np.zeros_like(h), h.copy(), np.nan, 0)
        if load is not None:
            p = np.maximum(h.max() - h, 0.0)
    else:
        p = np.maximum(p0, 0.0)
    if load is not None:
        if load <= 0.0:
            return NormalSolution(np.zeros_like(h), h - h.min(), float(h.min()), 0)
        p *= load / (p.sum() * area)
    t = np.zeros_like(p)
    g_old, delta = 1.0, 0.0
    it = 0
    while it < max_iter:
        it += 1
        gap = op.normal(p) + h
        contact = p > 0.0
        if not contact.any():
            p = np.where(gap < 0.0, -gap, 0.0)
            if not p.any():
                break
            continue
        if load is not None:
            gap -= gap[contact].mean()
        G = float(np.dot(gap[contact], gap[contact]))
        t = np.where(contact, gap + (delta * G / g_old) * t, 0.0)
        g_old = G if G > 0.0 else 1.0
        r = op.normal(t)
        if load is not None:
            r -= r[contact].mean()
        denom = float(np.dot(r[contact], t[contact]))
        # a contact set already at equilibrium: only re-entry can change p (a gradient
        # step of length 1 / lambda_max for the penetrating elements)
        step = (float(np.dot(gap[contact], t[contact])) / denom if denom > 0.0
                else 1.0 / op.normal_bound)
        p_old = p
        p = np.maximum(p - step * t, 0.0)
        overlap = (p == 0.0) & (gap < 0.0)
        if overlap.any():
            delta = 0.0
            p[overlap] -= step * gap[overlap]
        else:
            delta = 1.0
        if load is not None:
            p *= load / (p.sum() * area)
        change = float(np.abs(p - p_old).sum())
        if change <= tol * max(float(p.sum()), 1e-300):
            break
    gap = op.normal(p) + h
    approach = np.nan
    if load is not None:
        contact = p > 0.0
        approach = float(gap[contact].mean()) if contact.any() else float(h.min())
        gap = gap - approach
    return NormalSolution(p, gap, approach, it)
