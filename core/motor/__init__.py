"""The motor of the paper's Fig. 1: a rod vibrating in its first longitudinal mode
(eqs 1, 2) drives a rotor through the intermittent frictional contact that the rest of
``core`` solves. Beyond the paper; the physics is docs/physics.md, section 10.

One concept per module:

- ``rod``: the rod and how a point x0 of its top face moves (``Rod``: u0(x0), H(x0)).
- ``balance``: the preload fixes the start of contact, F(tau0) = Phi (eq 10), by a
  vectorised bracketed Newton solve on core's F; nan where the contact never opens.
- ``thrust``: the stall thrust mu N T_imp / (mu P_imp) (eq 41) with its sign.
- ``motor``: ``Motor`` (rod + rotor + preload), vectorised over x0; ``MotorProfile``.

Planned: ``moving_rotor``, the rotor turning at a steady surface speed V (section 10.4):
thrust ratio, input and output power, friction loss and efficiency per point x0. It
needs from the method of dimensionality reduction (``core.numerics``): a solve for an
arbitrary tangential drive history u_x0(tau) = u0 sin tau - (V / omega)(tau - tau0)
(not only eq 3's u0 sin tau), returning T(tau) on the solver's own time grid (for
T_imp = int T dt and W_in = int T du_x0), vectorised or cheap enough for ~1e3 points
x0 times ~1e2 speeds V, with its convergence order in the number of springs (N^-2 at
V = 0) so that a tolerance can be asked for.

    from core.motor import Rod, Motor
    rod = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
    m = Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05)
    m.psi(x0), m.tau0(x0), m.stall_thrust(x0)
"""

from core.motor.balance import PHI_MAX
from core.motor.motor import Motor, MotorProfile
from core.motor.rod import Rod

__all__ = ["PHI_MAX", "Motor", "MotorProfile", "Rod"]
