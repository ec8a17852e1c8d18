"""The motor of the paper's Fig. 1: a rod vibrating in its first longitudinal mode
(eqs 1, 2) drives a rotor through the intermittent frictional contact that the rest of
``core`` solves. Beyond the paper; the physics is docs/physics.md, section 10.

One concept per module:

- ``rod``: the rod and how a point x0 of its top face moves (``Rod``: u0(x0), H(x0)).
- ``balance``: the preload fixes the start of contact, F(tau0) = Phi (eq 10), by a
  vectorised bracketed Newton solve on core's F; nan where the contact never opens.
- ``thrust``: the stall thrust mu N T_imp / (mu P_imp) (eq 41) with its sign.
- ``motor``: ``Motor`` (rod + rotor + preload), vectorised over x0; ``MotorProfile``.

- ``load``: the operating point under a load force and the start-up from rest
  (``operating_point``, ``operating_speed``, ``start_up``).
- ``wear``: Archard wear from the exact friction dissipation, per contact
  (``wear_depth``), along the rod (``wear_along_rod``) and for a moving rotor
  (``moving_wear_rate``).

- ``designs``: the figures of merit of many designs in one call (``design_merits``,
  SI; ``contact_merits``, dimensionless), equal to the scalar API design by design.
- ``moving_rotor``: the rotor turning at a steady surface speed V (section 10.4): thrust
  ratio, input and output power, friction loss and efficiency per contact (psi, tau0),
  by the method of dimensionality reduction (``core.numerics.mdr``) under the drive
  relative to the rotor; the thrust-speed curve, the no-load speed and the point of best
  efficiency.

    from core.motor import Rod, Motor
    rod = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
    m = Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05)
    m.psi(x0), m.tau0(x0), m.stall_thrust(x0)
    res = moving_rotor(float(m.psi(-0.01)), float(m.tau0(-0.01)), v=[0.0, 0.1, 0.2])
    res.thrust_ratio, res.efficiency
"""

from core.motor.balance import PHI_MAX
from core.motor.designs import ContactMerits, DesignMerits, contact_merits, design_merits
from core.motor.load import OperatingPoint, StartUp, operating_point, operating_speed, start_up
from core.motor.motor import Motor, MotorProfile
from core.motor.moving_rotor import (
    BestEfficiency,
    MovingRotor,
    best_efficiency,
    full_slip_speed,
    moving_rotor,
    no_load_speed,
    thrust_speed_curve,
)
from core.motor.rod import Rod
from core.motor.wear import WearProfile, moving_wear_rate, wear_along_rod, wear_depth

__all__ = [
    "PHI_MAX",
    "BestEfficiency",
    "ContactMerits",
    "DesignMerits",
    "Motor",
    "MotorProfile",
    "MovingRotor",
    "OperatingPoint",
    "Rod",
    "StartUp",
    "WearProfile",
    "best_efficiency",
    "contact_merits",
    "design_merits",
    "full_slip_speed",
    "moving_rotor",
    "moving_wear_rate",
    "no_load_speed",
    "operating_point",
    "operating_speed",
    "start_up",
    "thrust_speed_curve",
    "wear_along_rod",
    "wear_depth",
]
