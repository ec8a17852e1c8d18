"""The closed form over many contacts at once: arrays of psi and tau0 (and mu, nu)
broadcast against the times tau, for users who evaluate many contacts (a motor along its
rod, a parameter sweep).

    from core import batch
    T = batch.tangential_force(psi[:, None], tau0[:, None], tau)   # one row per contact

Each function validates every element against ``core.DOMAIN`` (TypeError for a dtype
that is not int or float, ValueError naming the argument and the first element that is
nan, infinite or out of range, or the shapes that do not broadcast) and returns a new
array of the broadcast shape of (psi, tau0, tau, mu, nu). Values, units and accuracy are
those of the same quantity of ``Contact(psi, tau0, mu, nu)`` at tau, bit for bit: the
same compiled formulas (``core.kernels``) run over all contacts in one pass. mu and nu
do not enter these dimensionless results. The impulse ratio over arrays of psi and tau0
is ``core.impulse_ratio``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from core import kernels
from core.validation import as_reals, common_shape


def _evaluate(q: int, psi: ArrayLike, tau0: ArrayLike, tau: ArrayLike, mu: ArrayLike,
              nu: ArrayLike) -> NDArray[np.float64]:
    """Quantity code q of ``core.kernels`` for the broadcast contacts and times."""
    psi, tau0, tau = as_reals(psi, "psi"), as_reals(tau0, "tau0"), as_reals(tau, "tau")
    shape = common_shape(psi=psi, tau0=tau0, tau=tau, mu=as_reals(mu, "mu"),
                         nu=as_reals(nu, "nu"))
    out = np.empty(shape or (1,))
    if out.size == 0:
        return out
    n = out.shape[-1]
    rows = out.size // n
    P, T0, T = (np.broadcast_to(a, out.shape) for a in (psi, tau0, tau))
    if n == 1 or (P.strides[-1] == 0 and T0.strides[-1] == 0):
        # contacts constant along the last axis: one row of times per contact
        P, T0 = P[..., 0], T0[..., 0]
        times = (np.ascontiguousarray(T[(0,) * (T.ndim - 1)]).reshape(1, n)
                 if all(st == 0 for st in T.strides[:-1])
                 else np.ascontiguousarray(T).reshape(rows, n))
    else:  # contacts change along the last axis: one time per row
        rows, n = out.size, 1
        times = np.ascontiguousarray(T).reshape(rows, 1)
    sin_half_e, _ = kernels.half_sines_of(np.ascontiguousarray(T0).reshape(-1))
    kernels.rows(q, times, np.ascontiguousarray(P).reshape(-1), sin_half_e,
                 out.reshape(rows, n))
    return out.reshape(shape)


def tangential_force(psi: ArrayLike, tau0: ArrayLike, tau: ArrayLike, mu: ArrayLike = 0.2,
                     nu: ArrayLike = 0.3) -> NDArray[np.float64]:
    """T / T0 (eqs 38, 39) of every contact (psi, tau0) at the times tau.

    Parameters
    ----------
    psi, tau0 : array_like
        Contacts' drive ratios and starts of contact (``Contact``'s ranges), element-wise.
    tau : array_like
        Times omega t (rad), taken modulo 2 pi.
    mu, nu : array_like, optional
        Validated and part of the broadcast shape; they do not enter the result.

    Returns
    -------
    ndarray
        ``Contact(psi, tau0, mu, nu).tangential_force(tau)`` element-wise, bit for bit, as a new
        array of the broadcast shape of (psi, tau0, tau, mu, nu).

    See Also
    --------
    core.Contact.tangential_force : the definition, units and tested accuracy.
    """
    return _evaluate(kernels.TANGENTIAL_FORCE, psi, tau0, tau, mu, nu)


def normal_force(psi: ArrayLike, tau0: ArrayLike, tau: ArrayLike, mu: ArrayLike = 0.2,
                 nu: ArrayLike = 0.3) -> NDArray[np.float64]:
    """P / P0 (eq 9) of every contact (psi, tau0) at the times tau.

    Parameters
    ----------
    psi, tau0 : array_like
        Contacts' drive ratios and starts of contact (``Contact``'s ranges), element-wise.
    tau : array_like
        Times omega t (rad), taken modulo 2 pi.
    mu, nu : array_like, optional
        Validated and part of the broadcast shape; they do not enter the result.

    Returns
    -------
    ndarray
        ``Contact(psi, tau0, mu, nu).normal_force(tau)`` element-wise, bit for bit, as a new
        array of the broadcast shape of (psi, tau0, tau, mu, nu).

    See Also
    --------
    core.Contact.normal_force : the definition, units and tested accuracy.
    """
    return _evaluate(kernels.NORMAL_FORCE, psi, tau0, tau, mu, nu)


def contact_radius(psi: ArrayLike, tau0: ArrayLike, tau: ArrayLike, mu: ArrayLike = 0.2,
                   nu: ArrayLike = 0.3) -> NDArray[np.float64]:
    """a / a* (eqs 7, 8) of every contact (psi, tau0) at the times tau.

    Parameters
    ----------
    psi, tau0 : array_like
        Contacts' drive ratios and starts of contact (``Contact``'s ranges), element-wise.
    tau : array_like
        Times omega t (rad), taken modulo 2 pi.
    mu, nu : array_like, optional
        Validated and part of the broadcast shape; they do not enter the result.

    Returns
    -------
    ndarray
        ``Contact(psi, tau0, mu, nu).contact_radius(tau)`` element-wise, bit for bit, as a new
        array of the broadcast shape of (psi, tau0, tau, mu, nu).

    See Also
    --------
    core.Contact.contact_radius : the definition, units and tested accuracy.
    """
    return _evaluate(kernels.CONTACT_RADIUS, psi, tau0, tau, mu, nu)


def stick_radius(psi: ArrayLike, tau0: ArrayLike, tau: ArrayLike, mu: ArrayLike = 0.2,
                 nu: ArrayLike = 0.3) -> NDArray[np.float64]:
    """b / a* (eq 30) of every contact (psi, tau0) at the times tau.

    Parameters
    ----------
    psi, tau0 : array_like
        Contacts' drive ratios and starts of contact (``Contact``'s ranges), element-wise.
    tau : array_like
        Times omega t (rad), taken modulo 2 pi.
    mu, nu : array_like, optional
        Validated and part of the broadcast shape; they do not enter the result.

    Returns
    -------
    ndarray
        ``Contact(psi, tau0, mu, nu).stick_radius(tau)`` element-wise, bit for bit, as a new
        array of the broadcast shape of (psi, tau0, tau, mu, nu).

    See Also
    --------
    core.Contact.stick_radius : the definition, units and tested accuracy.
    """
    return _evaluate(kernels.STICK_RADIUS, psi, tau0, tau, mu, nu)


def phase(psi: ArrayLike, tau0: ArrayLike, tau: ArrayLike, mu: ArrayLike = 0.2,
          nu: ArrayLike = 0.3) -> NDArray[np.int_]:
    """The phase code (``core.Phase``) of every contact (psi, tau0) at the times tau.

    Parameters
    ----------
    psi, tau0 : array_like
        Contacts' drive ratios and starts of contact (``Contact``'s ranges), element-wise.
    tau : array_like
        Times omega t (rad), taken modulo 2 pi.
    mu, nu : array_like, optional
        Validated and part of the broadcast shape; they do not enter the result.

    Returns
    -------
    ndarray
        ``Contact(psi, tau0, mu, nu).phase(tau)`` element-wise, bit for bit, as a new
        array of the broadcast shape of (psi, tau0, tau, mu, nu).

    See Also
    --------
    core.Contact.phase : the definition, units and tested accuracy.
    """
    return _evaluate(kernels.PHASE, psi, tau0, tau, mu, nu).astype(int)


__all__ = ["contact_radius", "normal_force", "phase", "stick_radius", "tangential_force"]
