"""The motor under a load: the steady operating point for a load force, and the rotor's
start-up from rest (docs/physics.md, section 11.3).

A load force F_L opposes the rotor's motion. In steady motion the mean thrust balances
it, mu N r(psi, tau0, v) = F_L, with r the moving rotor's thrust ratio
(``core.motor.moving_rotor``): one speed v in [0, v0] since r falls monotonically from
r(0) (stall, eq 41) to 0 at the no-load speed v0; none if F_L exceeds the stall thrust
mu N r(0). A rotor of (equivalent translational) mass m starts from rest as

    m dV/dt = mu N r(v) - F_L,        V = v omega |u0|,

each period's thrust taken from the steady thrust-speed curve: valid while V changes
little over one period (``StartUp.periods_per_unit``: periods in one time unit
m omega |u0| / (mu N)). In that time unit and v, dv/dt' = r(v) - l, l = F_L / (mu N);
energies in m (omega u0)^2: d(v^2/2)/dt' = r v - l v (thrust work = kinetic energy + work
against the load).

The start-up's operating speed is ``operating_speed``'s (the MDR's r, solved by brentq),
the same as ``operating_point``'s. Its thrust curve is the MDR's r at ``n`` equally spaced
speeds in [0, v_op) and ``REFINE`` more that halve the distance to v_op each time, joined
at (v_op, l) and interpolated monotonically (PCHIP): near v_op, where the run-up is slow
(dt' = dv / (r(v) - l) grows as 1 / (v_op - v)), the nodes are as close as the distance to
it, so r(v) - l keeps its relative accuracy there. The start-up integrates the ODE on it
(``scipy.integrate.solve_ivp``, rtol 1e-10) and the times to 90 % and 99 % of v_op by
quadrature of dt' = dv / (r(v) - l); with the defaults t90 and t99 are within 2e-5 of
runs with 4 times the curve's speeds (``tests/core/test_motor_load.py``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import cumulative_trapezoid, quad, solve_ivp
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from core.frozen import freeze
from core.motor.motor import Motor
from core.motor.moving_rotor import (
    SPRINGS,
    STEPS,
    _check_contact,
    _count,
    _efficiency,
    _one,
    _resolution,
    full_slip_speed,
    moving_rotor,
    thrust_speed_curve,
)
from core.validation import MOTOR_DOMAIN, shown

#: Speeds on the thrust-speed curve the start-up interpolates (equally spaced), and the
#: speeds added towards the operating speed v_op (at v_op (1 - 2^-k), k = 1 .. REFINE).
CURVE_POINTS = 48
REFINE = 14


def _load_ratio(value: object) -> float:
    return MOTOR_DOMAIN["load_ratio"].check("load_ratio", value)


def operating_speed(psi: float, tau0: float, load_ratio: float, *, springs: int = SPRINGS,
                    steps: int = STEPS, xtol: float = 1e-9) -> float:
    """The steady speed v = V / (omega u0) at which the thrust ratio equals the load
    ratio l = F_L / (mu N) in [0, 1]: r(v) = l (brentq on the MDR's r between 0 and the
    full-slip speed). ValueError if l exceeds the stall thrust ratio r(0) (the rotor
    cannot move: it is stalled, and a larger load would drive it backwards)."""
    psi, tau0 = _check_contact(psi, tau0, 0.2, 0.3)
    load = _load_ratio(load_ratio)
    springs, steps = _resolution(springs, steps)
    xtol = MOTOR_DOMAIN["xtol"].check("xtol", xtol)
    stall = _one(psi, tau0, 0.0, springs, steps)[0]
    if load > stall:
        raise ValueError(f"load_ratio = {shown(load)} exceeds the stall thrust ratio "
                         f"r(0) = {stall:.6g} of this contact: the rotor cannot move")
    if load == stall:
        return 0.0
    return float(brentq(lambda s: _one(psi, tau0, s, springs, steps)[0] - load, 0.0,
                        full_slip_speed(psi, tau0), xtol=xtol))


@dataclass(frozen=True)
class OperatingPoint:
    """The steady operating point of the motor at x0 under a load force (SI): load (N),
    speed V (m/s) and v = V / (omega |u0|), output power V F_L (exactly: 0 at zero
    load), input power, friction loss (W, means over a period) and efficiency (output /
    input, ``operating_efficiency``)."""

    x0: float
    load: float
    v: float
    speed: float
    output_power: float
    input_power: float
    friction_loss: float
    efficiency: float


def _contact_at(motor: Motor, x0: float) -> tuple[float, float, float]:
    """(psi, tau0, omega |u0|) at one point x0, or ValueError where the contact never
    opens or psi is outside the moving rotor's range."""
    x = motor.rod.check_x0(x0)
    if x.ndim != 0:
        raise ValueError(f"x0 must be one number, got shape {x.shape}")
    p = motor.profile(x)
    if not p.opens:
        raise ValueError(f"x0 = {shown(float(x))}: the contact never opens there (Phi = "
                         f"{float(p.load_factor):.3g} >= 8), the model does not apply")
    psi, tau0 = _check_contact(float(p.psi), float(p.tau0), motor.mu, 0.3)
    return psi, tau0, motor.rod.omega * abs(float(p.u0))


def operating_point(motor: Motor, x0: float, load: float, *, springs: int = SPRINGS,
                    steps: int = STEPS) -> OperatingPoint:
    """The motor's steady state at contact point x0 (m) under a load force ``load`` (N, in
    [0, 1e6]) opposing the rotor: speed, powers and efficiency. ValueError naming the
    load if it exceeds the stall thrust mu N r(0) there."""
    load = MOTOR_DOMAIN["load"].check("load", load)
    psi, tau0, scale = _contact_at(motor, x0)
    mu_n = motor.mu * motor.preload
    if load > mu_n:
        raise ValueError(f"load = {shown(load)} N exceeds the largest thrust mu N = "
                         f"{mu_n:.6g} N: the rotor cannot move")
    try:
        v = operating_speed(psi, tau0, load / mu_n, springs=springs, steps=steps)
    except ValueError as err:
        stall = _one(psi, tau0, 0.0, *_resolution(springs, steps))[0] * mu_n
        raise ValueError(f"load = {shown(load)} N exceeds the stall thrust {stall:.6g} N at "
                         f"x0 = {shown(float(x0))} m: the rotor cannot move") from err
    res = moving_rotor(psi, tau0, v, springs=springs, steps=steps)
    power = mu_n * scale  # W per unit of the dimensionless powers
    speed = v * scale
    return OperatingPoint(
        x0=float(x0), load=load, v=v, speed=speed, output_power=load * speed,
        input_power=float(res.input_power) * power,
        friction_loss=float(res.friction_loss) * power,
        efficiency=operating_efficiency(psi, v, load / mu_n, float(res.friction_loss)))


def operating_efficiency(psi: float, v: float, load_ratio: float, friction_loss: float
                         ) -> float:
    """The efficiency of an operating point: its output power F_L V over its input
    power, l v / (l v + p_loss) in the dimensionless powers of ``MovingRotor`` (the
    input power by the energy balance, ``moving_rotor``'s evaluation of eta), with the
    output power l v, not v r(v): r(v) = l only to the speed solver's tolerance, and at
    zero load the output power, and so the efficiency, are exactly 0. At v = 0 (a load
    equal to the stall thrust) the limit v -> 0+ of ``moving_rotor``: 1 for psi <= 1,
    0 above.

    Parameters
    ----------
    psi : float
        psi of eq 23.
    v : float
        The operating speed V / (omega |u0|).
    load_ratio : float
        l = F_L / (mu N).
    friction_loss : float
        The frictional dissipation at v, p_loss (units of ``MovingRotor``).

    Returns
    -------
    float

    See Also
    --------
    operating_point, core.motor.moving_rotor
    """
    return float(_efficiency(psi, np.array(v), np.array(load_ratio * v),
                             np.array(friction_loss)))


@dataclass(frozen=True)
class StartUp:
    """The rotor's start-up from rest at x0 under a load (SI; read-only arrays over the
    time samples t).

    Attributes:
        t: time (s); speed: V (m/s); thrust: mu N r(v) (N).
        work_thrust, kinetic_energy, work_load: cumulative work of the thrust, kinetic
            energy m V^2 / 2 and cumulative work against the load (J), each from the
            samples (trapezoid rule), so that their balance checks the integration.
        operating_speed: the steady speed (m/s), ``operating_point``'s.
        t90, t99: times to 90 % and 99 % of it (s).
        time_unit: m omega |u0| / (mu N) (s); periods_per_unit: rod periods in it (the
            model wants many).
    """

    t: NDArray[np.float64]
    speed: NDArray[np.float64]
    thrust: NDArray[np.float64]
    work_thrust: NDArray[np.float64]
    kinetic_energy: NDArray[np.float64]
    work_load: NDArray[np.float64]
    operating_speed: float
    t90: float
    t99: float
    time_unit: float
    periods_per_unit: float

    def __post_init__(self) -> None:
        freeze(self, arrays_only=True)

    @property
    def energy_residual(self) -> NDArray[np.float64]:
        """work_thrust - kinetic_energy - work_load (J): zero for the exact motion."""
        return self.work_thrust - self.kinetic_energy - self.work_load


def thrust_curve(psi: float, tau0: float, n: int = CURVE_POINTS, *, springs: int = SPRINGS,
                 steps: int = STEPS) -> PchipInterpolator:
    """r(v) as a monotone (PCHIP) interpolant of the MDR's thrust-speed curve at n speeds
    from 0 to the full-slip speed; r = -1 beyond (the curve is flat there). (The start-up
    runs on ``start_up_curve``, refined towards its operating speed.)"""
    curve = thrust_speed_curve(psi, tau0, n, springs=springs, steps=steps)
    return PchipInterpolator(curve.v, curve.thrust_ratio, extrapolate=True)


def start_up_curve(psi: float, tau0: float, load_ratio: float, n: int = CURVE_POINTS, *,
                   springs: int = SPRINGS, steps: int = STEPS
                   ) -> tuple[float, PchipInterpolator]:
    """(v_op, r): the operating speed of ``operating_speed`` and the thrust curve r(v) over
    [0, v_op] the start-up runs on, the MDR's r at n equal speeds and ``REFINE`` speeds
    towards v_op, through r(v_op) = l exactly (module docstring)."""
    v_op = operating_speed(psi, tau0, load_ratio, springs=springs, steps=steps)
    x = np.unique(np.concatenate([np.linspace(0.0, 1.0, n, endpoint=False),
                                  1.0 - 2.0 ** -np.arange(1.0, REFINE + 1.0)]))
    v = x * v_op
    r = moving_rotor(psi, tau0, v, springs=springs, steps=steps).thrust_ratio
    return v_op, PchipInterpolator(np.append(v, v_op), np.append(r, load_ratio),
                                   extrapolate=True)


def start_up(motor: Motor, x0: float, mass: float, load: float = 0.0, *,
             samples: int = 400, n: int = CURVE_POINTS, springs: int = SPRINGS,
             steps: int = STEPS) -> StartUp:
    """The start-up from rest of a rotor of (equivalent translational) mass ``mass`` (kg,
    in [1e-9, 1e6]) at contact point x0 (m) under a load force ``load`` (N, in [0, 1e6]):
    m dV/dt = mu N r(v) - F_L on the thrust-speed curve of ``start_up_curve`` (n equal
    speeds; module docstring), sampled at ``samples`` times from 0 to 1.5 t99.
    ValueError if the load stalls the rotor."""
    mass = MOTOR_DOMAIN["mass"].check("mass", mass)
    load = MOTOR_DOMAIN["load"].check("load", load)
    count = _count("n", samples)
    n = _count("n", n)
    springs, steps = _resolution(springs, steps)
    psi, tau0, scale = _contact_at(motor, x0)
    mu_n = motor.mu * motor.preload
    ell = load / mu_n
    stall = _one(psi, tau0, 0.0, springs, steps)[0]
    if ell >= stall:
        raise ValueError(f"load = {shown(load)} N is not below the stall thrust "
                         f"{stall * mu_n:.6g} N at x0 = {shown(float(x0))} m: the "
                         "rotor does not start")
    v_op, r = start_up_curve(psi, tau0, ell, n, springs=springs, steps=steps)

    def time_to(fraction: float) -> float:
        end = fraction * v_op
        nodes = r.x[(r.x > 0.0) & (r.x < end)]  # the pieces of the curve: smooth inside
        return quad(lambda s: 1.0 / (float(r(s)) - ell), 0.0, end, points=nodes,
                    epsabs=0.0, epsrel=1e-11, limit=200 + 2 * nodes.size)[0]

    t90, t99 = time_to(0.9), time_to(0.99)
    t = np.linspace(0.0, 1.5 * t99, count)
    sol = solve_ivp(lambda _, y: [float(r(y[0])) - ell], (0.0, t[-1]), [0.0],
                    t_eval=t, rtol=1e-10, atol=1e-13, method="DOP853")
    v = sol.y[0]
    rv = r(v)
    unit = mass * scale / mu_n  # s per time unit
    energy = mass * scale * scale  # J per unit of v^2
    return StartUp(
        t=t * unit, speed=v * scale, thrust=rv * mu_n,
        work_thrust=energy * cumulative_trapezoid(rv * v, t, initial=0.0),
        kinetic_energy=0.5 * energy * v * v,
        work_load=energy * ell * cumulative_trapezoid(v, t, initial=0.0),
        operating_speed=v_op * scale, t90=t90 * unit, t99=t99 * unit, time_unit=unit,
        periods_per_unit=unit * motor.rod.frequency)


__all__ = ["OperatingPoint", "StartUp", "operating_point", "operating_speed", "start_up",
           "start_up_curve", "thrust_curve"]
