"""The motor under a load (core.motor.load) and Archard wear (core.motor.wear): the
operating point against the thrust-speed curve, the start-up's energy balance, wear
against the exact dissipation and against the MDR's friction loss."""

import math

import numpy as np
import pytest

from core.motor import (
    Motor,
    Rod,
    moving_rotor,
    moving_wear_rate,
    no_load_speed,
    operating_point,
    operating_speed,
    start_up,
    wear_along_rod,
    wear_depth,
)

ROD = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
MOTOR = Motor(ROD, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05)
X0 = -0.2e-3  # psi = 1.361, tau0 = 0.528


def test_operating_speed_inverts_the_thrust_speed_curve() -> None:
    psi, tau0 = 2.414, 0.5236
    assert operating_speed(psi, tau0, 0.0) == pytest.approx(no_load_speed(psi, tau0), abs=1e-8)
    r = float(moving_rotor(psi, tau0, 0.15).thrust_ratio)
    assert operating_speed(psi, tau0, r) == pytest.approx(0.15, abs=1e-8)
    stall = float(moving_rotor(psi, tau0, 0.0).thrust_ratio)
    with pytest.raises(ValueError, match="exceeds the stall thrust ratio"):
        operating_speed(psi, tau0, stall + 1e-3)


def test_operating_point_in_si() -> None:
    op = operating_point(MOTOR, X0, 4e-3)
    scale = ROD.omega * abs(float(ROD.u0(X0)))
    assert op.speed == pytest.approx(op.v * scale, rel=1e-15)
    assert op.output_power == op.speed * 4e-3  # V F_L, by definition
    assert op.efficiency == pytest.approx(op.output_power / op.input_power, rel=1e-3)
    assert op.input_power == pytest.approx(op.output_power + op.friction_loss, rel=1e-3)
    assert 0.0 < op.speed < no_load_speed(float(MOTOR.psi(X0)), float(MOTOR.tau0(X0))) * scale
    with pytest.raises(ValueError, match=r"load = 0\.0095 N exceeds the stall thrust"):
        operating_point(MOTOR, X0, 9.5e-3)  # stall thrust 9.17 mN
    with pytest.raises(ValueError, match="largest thrust mu N"):
        operating_point(MOTOR, X0, 0.02)
    with pytest.raises(ValueError, match="load = -1 is outside"):
        operating_point(MOTOR, X0, -1.0)


def test_start_up_energy_balance_and_final_speed() -> None:
    su = start_up(MOTOR, X0, mass=0.01, load=4e-3)
    assert su.speed[0] == 0.0 and np.all(np.diff(su.speed) >= 0.0)
    assert abs(su.energy_residual).max() <= 1e-4 * su.work_thrust[-1]
    assert su.speed[-1] == pytest.approx(su.operating_speed, rel=2e-3)
    assert su.operating_speed == pytest.approx(operating_point(MOTOR, X0, 4e-3).speed,
                                               rel=2e-3)
    assert 0.0 < su.t90 < su.t99 < su.t[-1]
    v90 = np.interp(su.t90, su.t, su.speed)
    assert v90 == pytest.approx(0.9 * su.operating_speed, rel=2e-3)
    twice = start_up(MOTOR, X0, mass=0.02, load=4e-3)  # m dV/dt: time scales with m
    assert twice.t99 == pytest.approx(2 * su.t99, rel=1e-9)
    with pytest.raises(ValueError, match="does not start"):
        start_up(MOTOR, X0, mass=0.01, load=9.5e-3)
    with pytest.raises(ValueError, match="mass = 0 is outside"):
        start_up(MOTOR, X0, mass=0.0)


@pytest.mark.parametrize("load", [0.0, 4e-3, 8e-3])
def test_start_up_runs_to_the_operating_point_and_its_times_converge(load: float) -> None:
    """start_up's operating speed is operating_point's (the same brentq on the MDR's r),
    and t90, t99 converge as the curve's speeds grow: the defaults (48) within 2e-5 of
    192 speeds, 4 times closer than 12 speeds."""
    su = start_up(MOTOR, X0, mass=0.01, load=load)
    assert su.operating_speed == operating_point(MOTOR, X0, load).speed
    fine = start_up(MOTOR, X0, mass=0.01, load=load, n=192)
    coarse = start_up(MOTOR, X0, mass=0.01, load=load, n=12)
    for name in ("t90", "t99"):
        error = abs(getattr(su, name) / getattr(fine, name) - 1)
        assert error < 2e-5, name
        assert abs(getattr(coarse, name) / getattr(fine, name) - 1) > 4 * error, name


def test_wear_along_the_rod_from_the_exact_dissipation() -> None:
    k, hard = 1e-6, 2e9
    x0 = np.array([-0.01, -0.002, -2e-5, 0.0, 2e-5, 0.002, 0.01])
    w = wear_along_rod(MOTOR, x0, k, hard)
    per_hour = 3600 * ROD.frequency * k / (MOTOR.mu * hard)
    for i, x in enumerate(x0):
        c = MOTOR.contact(float(x))
        D = c.dissipated_energy * c.scales.energy
        assert w.dissipated_energy[i] == pytest.approx(D, rel=1e-12, abs=0)
        assert w.volume_rate[i] == pytest.approx(D * per_hour, rel=1e-12, abs=0)
        r = np.linspace(0, 1, 513)
        depth = wear_depth(c, r, k, hard) * 3600 / c.scales.period
        assert w.peak_depth_rate[i] == pytest.approx(depth.max(), rel=1e-12, abs=0)
    np.testing.assert_allclose(w.volume_rate, w.volume_rate[::-1], rtol=1e-13)
    assert w.volume_rate[3] == 0.0  # the centre: psi = 0, full stick, no slip
    # the depth integrated over the patch is the volume (per contact)
    c = MOTOR.contact(-0.002)
    r = np.linspace(0, 1, 20001)
    depth = wear_depth(c, r, k, hard)
    volume = np.trapezoid(depth * 2 * np.pi * r, r) * c.scales.a_star**2
    assert volume == pytest.approx(k * c.dissipated_energy * c.scales.energy / (0.2 * hard),
                                   rel=1e-6)


def test_moving_wear_at_stall_meets_the_closed_form() -> None:
    x = -0.002
    psi, tau0 = float(MOTOR.psi(x)), float(MOTOR.tau0(x))
    held = moving_rotor(psi, tau0, [0.0, 0.1])
    rate = moving_wear_rate(MOTOR, x, held, 1e-6, 2e9)
    exact = float(wear_along_rod(MOTOR, x, 1e-6, 2e9).volume_rate)
    assert rate[0] == pytest.approx(exact, rel=2e-4)  # the MDR against the closed form
    assert rate[1] > 0.0


@pytest.mark.parametrize(("name", "value"), [("wear_coefficient", -1.0),
                                             ("wear_coefficient", math.nan),
                                             ("hardness", 0.0), ("hardness", "hard")])
def test_wear_arguments_are_validated(name: str, value: object) -> None:
    kwargs = {"wear_coefficient": 1e-6, "hardness": 2e9, name: value}
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        wear_along_rod(MOTOR, 0.001, **kwargs)
