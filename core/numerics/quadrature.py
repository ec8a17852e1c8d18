"""Impulses by numerical quadrature of the closed-form forces (eqs 9, 39 -> eq 41).

These two methods do not solve the contact: they integrate ``core``'s T(tau) and P(tau)
and so test the elliptic closed form of the impulses (eqs 10, 11, 41) rather than the
traction solution. The ratio is T_imp / (mu P_imp) = int T / T0 dtau / int P / P0 dtau.

* ``quad``: scipy.integrate.quad (QUADPACK QAGP) with ``limit = resolution``
  subintervals (at least one more than the breakpoints), breakpoints at pi/2 (and tau1
  for psi > 1) where T'' jumps.
* ``gauss_legendre``: one fixed ``resolution``-point Gauss-Legendre rule over the whole
  contact [tau0, pi - tau0]; its algebraic convergence shows the kinks of T.
"""

from __future__ import annotations

import warnings
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import IntegrationWarning, quad
from scipy.special import roots_legendre

from core.numerics.result import ContactLike, check_resolution

DESCRIPTIONS: dict[str, str] = {
    "quad": "scipy.integrate.quad of the closed-form T(tau) and P(tau) (impulses only)",
    "gauss_legendre": "fixed n-point Gauss-Legendre of the closed-form T(tau) and P(tau)",
}


def _contact(contact: ContactLike):
    """A ``core.Contact`` for these parameters (built if a plain parameter set is given)."""
    from core import Contact

    if isinstance(contact, Contact):
        return contact
    return Contact(contact.psi, contact.tau0, mu=contact.mu, nu=contact.nu)


def solve_quad(contact: ContactLike, resolution: int) -> tuple:
    """Adaptive QUADPACK with at most ``resolution`` subintervals.

    Returns (tau, T, None, ratio) with tau the sorted abscissae quad evaluated T at.
    """
    limit = check_resolution(resolution, maximum=10**5)
    c = _contact(contact)
    start, end = float(c.tau0), float(np.pi - c.tau0)
    points = [np.pi / 2]
    if c.psi > 1 and np.isfinite(c.tau1) and start < c.tau1 < end:
        points.append(float(c.tau1))
    limit = max(limit, len(points) + 1)  # QUADPACK needs more subintervals than breaks
    seen: list[float] = []

    def t_of(x: float) -> float:
        seen.append(x)
        return float(c.tangential_force(x))

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        t_imp = quad(t_of, start, end, points=points, limit=limit, epsabs=0.0,
                     epsrel=2e-14)[0]
        p_imp = quad(lambda x: float(c.normal_force(x)), start, end, points=points[:1],
                     limit=limit, epsabs=0.0, epsrel=2e-14)[0]
    tau = np.unique(np.asarray(seen, dtype=float))
    return tau, np.asarray(c.tangential_force(tau), dtype=float), None, t_imp / p_imp


@lru_cache(maxsize=64)
def _legendre(n: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Nodes and weights on [-1, 1], computed once per n."""
    return roots_legendre(n)


def gauss_legendre_nodes(start: float, end: float, n: int
                         ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Nodes and weights of the n-point Gauss-Legendre rule on [start, end]
    (scipy.special.roots_legendre, O(n), computed once per n and cached)."""
    x, w = _legendre(n)
    half = 0.5 * (end - start)
    return start + half * (x + 1.0), half * w


def solve_gauss_legendre(contact: ContactLike, resolution: int) -> tuple:
    """``resolution``-point Gauss-Legendre; returns (nodes, T at nodes, None, ratio)."""
    n = check_resolution(resolution, maximum=10**5)
    c = _contact(contact)
    tau, w = gauss_legendre_nodes(float(c.tau0), float(np.pi - c.tau0), n)
    T = np.asarray(c.tangential_force(tau), dtype=float)
    P = np.asarray(c.normal_force(tau), dtype=float)
    return tau, T, None, float(w @ T / (w @ P))


SOLVERS = {"quad": solve_quad, "gauss_legendre": solve_gauss_legendre}
