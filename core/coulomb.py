"""A computed certificate that a solution obeys Coulomb's law (eqs 16, 17, 25, 26, 32, 34).

The paper proves on paper that its guessed tractions are admissible; here we sample a
solution over r and tau and measure the worst violation of each condition:

1. traction bound: |tau_u| <= mu p everywhere in the contact;
2. form: the traction is kappa_a mu p*(a^2 - r^2)^(1/2) + kappa_b mu p*(b^2 - r^2)_+^(1/2)
   with the phase's constant coefficients (eqs 18, 24, 33, 36);
3. stick: equal surface velocities v1 = v2 for r < b (eqs 17, 25);
4. slip: |tau_u| = mu p and tau_u (v1 - v2) >= 0 for b <= r < a (eqs 16, 26, 32, 34).

Velocities follow from the tractions through the half-space response of eq 14: a traction
q0 (c^2 - r^2)^(1/2) moves the surface with q0 (2 - nu)/(4 G) d(c^2)/dt g(r, c), g = pi/2
for r <= c and arcsin(c/r) outside (eqs 21, 27). With v1 - v2 = du_x0/dt - 2 du2/dt
(eqs 19, 20), d(a^2)/dt from eq 8 and d(b^2)/dt = ((psi + 1)/2) d(a^2)/dt (eq 28), in units
of V = omega u0 / psi:

    (v1 - v2) / V = cos(tau) [psi - (2/pi)(kappa_a g(r, a) + kappa_b (psi + 1)/2 g(r, b))].

The form is compared away from the square-root zeros |r - a|, |r - b| < 1e-6 (there a
rounding of 1e-16 in a^2 or b^2 alone moves the traction by up to 1e-8). Violations are
reported in units of mu p* (tractions), of the drive velocity
max(psi, 1) V (velocities), and of their product (the slip-direction condition).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from core.contact import Contact
from core.tangential import Phase

ZERO_BAND = 1e-6

# (kappa_a, kappa_b) of the traction in each phase; kappa_a of full stick is psi.
_KAPPA = {
    Phase.SLIP: (1.0, 0.0),
    Phase.PARTIAL_STICK: (-1.0, 2.0),
    Phase.COUNTER_SLIP: (-1.0, 0.0),
}


@dataclass(frozen=True)
class CoulombReport:
    """Worst violation of each Coulomb condition (0 means exactly satisfied)."""

    traction_excess: float
    form_residual: float
    stick_velocity: float
    slip_traction: float
    slip_direction: float

    @property
    def worst(self) -> float:
        """The largest of the five violations."""
        return max(
            self.traction_excess,
            self.form_residual,
            self.stick_velocity,
            self.slip_traction,
            self.slip_direction,
        )


def _response(r: NDArray[np.float64], c: NDArray[np.float64]) -> NDArray[np.float64]:
    """g(r, c) of eq 14: pi/2 inside r <= c, arcsin(c/r) outside."""
    ratio = np.divide(c, r, out=np.ones_like(r), where=r > c)
    return np.arcsin(np.minimum(ratio, 1.0))


def _max(x: NDArray[np.float64]) -> float:
    return float(x.max()) if x.size else 0.0


def coulomb_certificate(contact: Contact, n_r: int = 201, n_tau: int = 401) -> CoulombReport:
    """Sample ``contact`` on n_r radii in [0, a*] and about n_tau times of the contact
    (``Contact.tau_grid``) and return the worst violation of each Coulomb condition."""
    psi = contact.psi
    tau = contact.tau_grid(n_tau)[:, None]
    r = np.linspace(0.0, 1.0, n_r)[None, :]
    a = contact.contact_radius(tau)
    b = contact.stick_radius(tau)
    ph = np.broadcast_to(contact.phase(tau), (tau.shape[0], n_r))
    t = contact.traction(r, tau)
    p = contact.pressure(r, tau)
    inside = r < a

    kappa_a = np.full(tau.shape, psi)
    kappa_b = np.zeros(tau.shape)
    for code, (ka, kb) in _KAPPA.items():
        here = contact.phase(tau) == code
        kappa_a[here], kappa_b[here] = ka, kb
    b_form = np.where(ph == Phase.FULL_STICK, 0.0, b)
    form = kappa_a * p + kappa_b * np.sqrt(np.maximum(b_form**2 - r**2, 0.0))

    rel = (
        np.cos(tau)
        * (
            psi
            - (2.0 / np.pi)
            * (
                kappa_a * _response(np.broadcast_to(r, t.shape), np.broadcast_to(a, t.shape))
                + kappa_b
                * (psi + 1.0)
                / 2.0
                * _response(np.broadcast_to(r, t.shape), np.broadcast_to(b_form, t.shape))
            )
        )
        / max(psi, 1.0)
    )

    away_from_zeros = (np.abs(r - a) > ZERO_BAND) & (np.abs(r - b_form) > ZERO_BAND)
    stick = inside & (r < b)
    slip = inside & ~stick
    return CoulombReport(
        traction_excess=_max(np.maximum(np.abs(t) - p, 0.0)[inside]),
        form_residual=_max(np.abs(t - form)[away_from_zeros]),
        stick_velocity=_max(np.abs(rel[stick])),
        slip_traction=_max(np.abs(np.abs(t) - p)[slip]),
        slip_direction=_max(np.maximum(-t * rel, 0.0)[slip]),
    )
