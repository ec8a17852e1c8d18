"""Archard wear from the exact friction dissipation (docs/physics.md, section 11.2).

Archard's law, worn volume = k F s / H_hard (k dimensionless, F the normal force, s the
sliding distance, H_hard the hardness of the softer body), applied locally: the friction
work per unit area is mu p ds, so the worn depth is

    depth(r) = k q(r) / (mu H_hard)       per contact,    volume = k D / (mu H_hard),

with q and D the exact dissipation density and energy of the held contact
(``core.Contact.dissipation_density``, ``dissipated_energy``), one contact per period of
the rod: multiply by 3600 f for one hour. For a moving rotor the friction loss of the MDR
(``MovingRotor.friction_loss``, in mu N omega |u0|) drives the volume the same way:
k P_loss / (mu H_hard) per second. Limits: k is an empirical constant of the pair and the
conditions (1e-8 to 1e-3 for dry sliding); the contact's geometry is not updated as it
wears (valid while the depth is small against the approach H - h), and only slip wears
(a contact in full stick, psi <= 1 at stall, does not).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from core import dissipation
from core.contact import Contact
from core.frozen import freeze
from core.motor.motor import Motor
from core.motor.moving_rotor import MovingRotor
from core.physical import SQRT8
from core.validation import MOTOR_DOMAIN

HOUR = 3600.0
#: Radii (units of a*) on which the peak of the dissipation density is sought.
PEAK_RADII = np.linspace(0.0, 1.0, 513)


def _archard(wear_coefficient: object, hardness: object) -> tuple[float, float]:
    return (MOTOR_DOMAIN["wear_coefficient"].check("wear_coefficient", wear_coefficient),
            MOTOR_DOMAIN["hardness"].check("hardness", hardness))


def wear_depth(contact: Contact, r: ArrayLike, wear_coefficient: float, hardness: float
               ) -> NDArray[np.float64]:
    """Archard's worn depth (m) per contact at radius r (units of a*) of a contact built
    with SI scales (``Contact.from_physical`` or ``Motor.contact``):
    k q(r) / (mu H_hard). Multiply by 3600 / ``contact.scales.period`` for one hour."""
    if contact.scales is None:
        raise ValueError("wear_depth needs SI scales: build the contact with "
                         "Contact.from_physical or Motor.contact")
    k, hard = _archard(wear_coefficient, hardness)
    q = contact.dissipation_density(r) * contact.scales.energy_density
    return k * q / (contact.mu * hard)


@dataclass(frozen=True)
class WearProfile:
    """Archard wear along the rod with the rotor held (read-only arrays over x0; nan
    where the contact never opens). SI: x0 (m); dissipated_energy per contact (J);
    friction_power, its mean over a period (W); volume_rate (m^3 per hour of operation);
    peak_depth_rate, the largest depth rate over the contact patch (m per hour, the
    maximum of the density over 513 radii); centre_depth_rate, at r = 0 (m/h)."""

    x0: NDArray[np.float64]
    dissipated_energy: NDArray[np.float64]
    friction_power: NDArray[np.float64]
    volume_rate: NDArray[np.float64]
    peak_depth_rate: NDArray[np.float64]
    centre_depth_rate: NDArray[np.float64]

    def __post_init__(self) -> None:
        freeze(self)  # (copies, also of 0-d results)


def wear_along_rod(motor: Motor, x0: ArrayLike, wear_coefficient: float, hardness: float
                   ) -> WearProfile:
    """Which contact points wear most: the exact dissipation of the held contact at each
    x0 (m, |x0| < L) and Archard's wear rates for the coefficient k = ``wear_coefficient``
    (in [0, 1]) and the softer body's ``hardness`` (Pa, in [1e3, 1e12])."""
    k, hard = _archard(wear_coefficient, hardness)
    p = motor.profile(x0)
    R, G, nu = motor.equivalent
    m0 = np.where(p.opens, p.m0, np.nan)
    half = np.sqrt(m0)  # sin(e / 2)
    with np.errstate(invalid="ignore", over="ignore"):
        T0 = motor.mu * SQRT8 * G / (3.0 * (1.0 - nu)) * np.sqrt(R) * p.H * np.sqrt(p.H)
        energy = T0 * np.abs(p.u0)  # T0 u0 (J)
        density = energy / (np.pi * R * p.H * m0)  # T0 u0 / (pi a*^2), a*^2 = R H m0
    D = np.where(p.opens, energy * dissipation.energy(np.where(p.opens, p.psi, 0.0),
                                                      np.where(p.opens, half, 0.0)), np.nan)
    peak, centre = np.full(p.x0.shape, np.nan), np.full(p.x0.shape, np.nan)
    for i in zip(*np.nonzero(p.opens), strict=True) if p.x0.ndim else ([()] if p.opens else []):
        q = dissipation.density(PEAK_RADII, float(p.psi[i]), float(half[i]))
        peak[i], centre[i] = q.max() * density[i], q[0] * density[i]
    per_hour = HOUR * motor.rod.frequency * k / (motor.mu * hard)
    return WearProfile(x0=p.x0, dissipated_energy=D,
                       friction_power=D * motor.rod.frequency, volume_rate=D * per_hour,
                       peak_depth_rate=peak * per_hour, centre_depth_rate=centre * per_hour)


def moving_wear_rate(motor: Motor, x0: float, result: MovingRotor, wear_coefficient: float,
                     hardness: float) -> NDArray[np.float64]:
    """Archard's worn volume per hour (m^3/h) of a moving rotor at contact point x0 (m),
    from the MDR's friction loss of ``result`` (``moving_rotor`` at that point's psi and
    tau0; one value per speed): k P_loss / (mu H_hard), P_loss = friction_loss mu N omega
    |u0(x0)| (W)."""
    k, hard = _archard(wear_coefficient, hardness)
    scale = motor.rod.omega * abs(float(motor.rod.u0(x0)))
    power = np.asarray(result.friction_loss) * (motor.mu * motor.preload * scale)
    return HOUR * k * power / (motor.mu * hard)
