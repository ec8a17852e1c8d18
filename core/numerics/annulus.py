"""Annulus discretisation with time stepping (Maw, Barber & Fawcett, "The oblique impact
of elastic spheres", Wear 38 (1976) 101-114).

The contact disc r < a* is split into n equal rings carrying uniform tangential
tractions tau_i. Tangential compliance: the axisymmetric part of Cerruti's point-force
solution (the non-axisymmetric terms dropped as in eqs 13-14, physics.md), i.e. a
surface kernel (2 - nu) / (4 pi G rho) per body. Its ring integrals are the classical
uniform-disc results (Johnson, Contact Mechanics, eq 3.30 with (1 - nu^2)/E replaced by
(2 - nu)/(4 G)): a unit traction on the disc r < c displaces the surface of each body by

    (2 - nu)/(4 G) (4/pi) c E(r/c)                           r <= c,
    (2 - nu)/(4 G) (4/pi) r [E(c/r) - (1 - c^2/r^2) K(c/r)]  r > c      (E, K: modulus).

Normal pressure: Hertz (eq 6), averaged exactly over each ring. At each time step the
drive displacement increment d(u0 sin tau) is imposed and Coulomb's law ring by ring
(active-set iteration): stick rings have no relative displacement increment at their
centre; slip rings carry |tau_i| = mu p_i opposing the relative velocity (the traction on
the upper sphere has the sign of the slip increment of the lower surface); rings leaving
the contact drop their traction; entering rings start from zero traction.

Dimensionless form: r in a*, tau_i in mu p* (p* the Hertz peak at a = a*), relative
displacement in U = mu p* a* (2 - nu)/(2 G); the drive is
delta = (pi/2) psi sin tau / (1 - s0) and T / T0 = (3 / (2 pi)) (1 - s0)^{3/2} sum tau_i A_i.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import solve as dense_solve
from scipy.special import ellipe, ellipk

from core.numerics.loading import approach, impulse_ratio_trapezoid, time_grid
from core.numerics.result import ContactLike, check_resolution, contact_parameters

NAME = "annulus"
DESCRIPTION = "Annulus discretisation (Maw, Barber & Fawcett 1976): n rings, Coulomb per ring"
MAX_SWEEPS = 60
MAX_RINGS = 400
"""Largest ring count: one dense solve per sweep and step costs O(n^3)."""
STICK_TOL = 1e-9
"""Relative slack of the stick test |tau| <= mu p (psi = 1 rides the limit exactly)."""


def disc_displacement(r: NDArray[np.float64], c: NDArray[np.float64]) -> NDArray[np.float64]:
    """Relative tangential displacement at radius r (units U) of a unit traction (mu p*)
    on the disc of radius c (units a*), axisymmetric approximation; broadcasts."""
    r, c = np.broadcast_arrays(np.asarray(r, float), np.asarray(c, float))
    out = np.zeros(r.shape)
    inner = (r <= c) & (c > 0)
    outer = (r > c) & (c > 0)
    out[inner] = c[inner] * ellipe((r[inner] / c[inner]) ** 2)
    q = (c[outer] / r[outer]) ** 2
    out[outer] = r[outer] * (ellipe(q) - (1.0 - q) * ellipk(q))
    return 4.0 / np.pi * out


def compliance_matrix(edges: NDArray[np.float64]) -> NDArray[np.float64]:
    """C[j, i]: displacement at the centre of ring j from unit traction on ring i."""
    centres = 0.5 * (edges[1:] + edges[:-1])
    disc = disc_displacement(centres[:, None], edges[None, :])
    return disc[:, 1:] - disc[:, :-1]


def ring_pressure(edges: NDArray[np.float64], a: float) -> NDArray[np.float64]:
    """Ring averages of the Hertz pressure p / p* = sqrt(a^2 - r^2)_+ (eq 6)."""
    cap = np.maximum(a * a - edges**2, 0.0) ** 1.5
    return (2.0 / 3.0) * (cap[:-1] - cap[1:]) / np.diff(edges**2)


def coulomb_step(C: NDArray[np.float64], tau_old: NDArray[np.float64],
                 stick: NDArray[np.bool_], p: NDArray[np.float64], d_delta: float
                 ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Tractions after one step by an active-set iteration on Coulomb's law.

    stick: initial guess of the stick rings (entering rings included); rings with p = 0
    end with zero traction. Returns (new tractions, stick flags).
    """
    inside = p > 0.0
    stick = stick & inside
    sign = np.where(tau_old >= 0.0, 1.0, -1.0)
    new = np.zeros_like(tau_old)
    for _ in range(MAX_SWEEPS):
        new[:] = 0.0
        slip = inside & ~stick
        new[slip] = sign[slip] * p[slip]
        if stick.any():
            rhs = d_delta - C[np.ix_(stick, ~stick)] @ (new[~stick] - tau_old[~stick])
            new[stick] = tau_old[stick] + dense_solve(C[np.ix_(stick, stick)], rhs,
                                                      assume_a="gen", check_finite=False)
        over = stick & (np.abs(new) > p * (1.0 + STICK_TOL))
        slip_inc = d_delta - C @ (new - tau_old)
        wrong = slip & (sign * slip_inc < -1e-14 * max(abs(d_delta), 1e-300))
        if not over.any() and not wrong.any():
            return new, stick
        sign[over] = np.sign(new[over])
        stick = (stick & ~over) | wrong
    return new, stick


def run(psi: float, tau0: float, tau: NDArray[np.float64], n: int
        ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """March n rings over the times ``tau``; returns (T / T0, b / a*)."""
    s0 = np.sin(tau0)
    edges = np.linspace(0.0, 1.0, n + 1)
    area = np.pi * np.diff(edges**2)
    C = compliance_matrix(edges)
    scale = 1.5 / np.pi * (1.0 - s0) ** 1.5
    a_all = np.sqrt(approach(tau, tau0) / (1.0 - s0))
    delta = 0.5 * np.pi * psi * np.sin(tau) / (1.0 - s0)
    traction = np.zeros(n)
    stick = np.zeros(n, dtype=bool)
    was_inside = np.zeros(n, dtype=bool)
    T = np.zeros(tau.size)
    b = np.zeros(tau.size)
    for k in range(1, tau.size):
        p = ring_pressure(edges, a_all[k])
        inside = p > 0.0
        guess = stick | (inside & ~was_inside)
        traction, stick = coulomb_step(C, traction, guess, p, delta[k] - delta[k - 1])
        was_inside = inside
        T[k] = scale * traction @ area
        b[k] = stick_radius(edges, stick, inside, a_all[k])
    return T, b


def stick_radius(edges: NDArray[np.float64], stick: NDArray[np.bool_],
                 inside: NDArray[np.bool_], a: float) -> float:
    """Outer edge of the central block of stick rings (a when every ring sticks)."""
    m = int(inside.sum())
    if m == 0 or not stick[0]:
        return 0.0
    block = int(np.argmin(stick[:m])) if not stick[:m].all() else m
    return a if block == m else float(edges[block])


def solve(contact: ContactLike, resolution: int) -> tuple:
    """``resolution`` rings and 4 * resolution time steps (at least 60) on
    ``loading.time_grid``. Returns (tau, T, b, impulse ratio)."""
    n = check_resolution(resolution, maximum=MAX_RINGS)
    psi, tau0 = contact_parameters(contact)
    tau = time_grid(psi, tau0, max(4 * n, 60))
    check_resolution(n * tau.size, name="rings * time steps")
    T, b = run(psi, tau0, tau, n)
    return tau, T, b, impulse_ratio_trapezoid(tau, T, approach(tau, tau0) ** 1.5)
