"""The Motor card's CSV files: the explorer's header block (source, version, the inputs
in SI), columns named with units, core's very numbers, file names with the inputs."""

from __future__ import annotations

from importlib.metadata import version

import numpy as np
import pytest
from test_export import Csv, written
from test_motor_scene import SPEED_NAMES, motor_of, wait

from app.motor import MotorScene
from app.motor.data import contact_key, rod_grid, speeds
from core.motor import best_efficiency, moving_rotor, no_load_speed

eq = np.testing.assert_array_equal

THRUST_NAMES = ["x0 (m)", "u0 (m)", "H (m)", "psi", "Phi", "opens", "tau0 (rad)",
                "F_x/(mu N)", "F_x (N)"]
#: The default state's inputs as the header writes them: SI units, the very floats.
DEFAULT_SI = {"L": ("m", 0.02), "delta": ("m", 0.004), "nu_rod": ("", 0.31),
              "A": ("m", 1e-05), "f": ("Hz", 40000.0), "R": ("m", 0.005),
              "G": ("Pa", 79300000000.0), "nu": ("", 0.29), "mu": ("", 0.2),
              "N": ("N", 0.5)}


def inputs_si(s: MotorScene) -> dict[str, tuple[str, float]]:
    """The inputs (SI unit, value) of the core motor built here (`motor_of`), x0 too."""
    m, x0 = motor_of(s)
    r = m.rod
    return {"L": ("m", r.half_length), "delta": ("m", r.thickness), "nu_rod": ("", r.nu_rod),
            "A": ("m", r.amplitude), "f": ("Hz", r.frequency), "R": ("m", m.R),
            "G": ("Pa", m.G), "nu": ("", m.nu), "mu": ("", m.mu), "N": ("N", m.preload),
            "x0": ("m", x0)}


def use_other_state(s: MotorScene) -> None:
    """The alumina rotor, another amplitude, x0 on the other side of the centre."""
    s.rotor_select.value = "alumina"
    s.inputs["A"]._entry.value = "7.25"
    s.inputs["x0"]._entry.value = "3.5"
    wait()


def assert_header(got: Csv, s: MotorScene, key: str) -> None:
    """The explorer's header block: source, version, the inputs in SI (x0 for the curve
    at x0 only)."""
    assert got.comments[0].startswith("Zharii 1996 explorer: the motor of Fig. 1")
    assert any("Zharii" in line and "(1996)" in line for line in got.comments)
    assert f"app: zharii-contact {version('zharii-contact')}" in got.comments
    expected = inputs_si(s)
    if key == "thrust":
        del expected["x0"]
        assert "x0" not in got.parameters
    for name, (unit, value) in expected.items():
        assert got.parameters[name] == (unit, value), name


@pytest.mark.parametrize("other", [False, True])
def test_csv_of_the_rod_is_core_with_units(scene: MotorScene, other: bool) -> None:
    if other:
        use_other_state(scene)
    got = Csv(scene.csv_text("thrust"))  # also: no -0, pandas reads it as it is
    assert got.names == THRUST_NAMES
    assert list(got.descriptions) == THRUST_NAMES
    assert "eq 41" in got.descriptions["F_x/(mu N)"] and "eq 10" in got.descriptions["Phi"]
    assert_header(got, scene, "thrust")
    if not other:
        assert {k: got.parameters[k] for k in DEFAULT_SI} == DEFAULT_SI
    m, _ = motor_of(scene)
    x = rod_grid(m.rod.half_length)
    col = got.columns
    written(col["x0 (m)"], x)
    written(col["u0 (m)"], m.rod.u0(x))
    written(col["H (m)"], m.rod.H(x))
    written(col["psi"], m.psi(x))
    written(col["Phi"], m.load_factor(x))
    eq(col["opens"], m.opens(x))
    written(col["tau0 (rad)"], m.tau0(x))
    written(col["F_x (N)"], m.stall_thrust(x))
    written(col["F_x/(mu N)"], m.stall_thrust(x) / (m.mu * m.preload))
    assert np.isnan(col["F_x (N)"][0]) and col["opens"][0] == 0  # never opens at the ends
    driven = (col["opens"] == 1) & (np.abs(col["x0 (m)"]) > 1e-9)  # + along +x for x0 < 0
    assert driven.sum() > 100
    eq(np.sign(col["F_x (N)"][driven]), -np.sign(col["x0 (m)"][driven]))
    name = scene.csv_file("thrust") and scene.downloads["thrust"].filename
    assert name == scene.csv_filename("thrust")
    if not other:
        assert name == ("zharii_motor_thrust_L20mm_delta4mm_nu_rod0.31_A10um_f40kHz_R5mm"
                        "_G79.3GPa_nu0.29_mu0.2_N0.5N.csv")
    else:
        assert name == ("zharii_motor_thrust_L20mm_delta4mm_nu_rod0.31_A7.25um_f40kHz_R5mm"
                        "_G152GPa_nu0.22_mu0.3_N0.5N.csv")


@pytest.mark.parametrize("other", [False, True])
def test_csv_of_the_curve_at_x0_is_core_with_units(scene: MotorScene, other: bool) -> None:
    if other:
        use_other_state(scene)
    wait()
    got = Csv(scene.csv_text("speed"))
    assert got.names == SPEED_NAMES
    assert list(got.descriptions) == SPEED_NAMES
    assert_header(got, scene, "speed")
    m, x0 = motor_of(scene)
    psi, tau0, mu, nu = contact_key(float(m.psi(x0)), float(m.tau0(x0)), m.mu, m.nu)
    assert got.parameters["psi"] == ("", psi) and got.parameters["tau0"] == ("rad", tau0)
    v0 = no_load_speed(psi, tau0, mu=mu, nu=nu)
    v = speeds(psi, tau0, v0, best_efficiency(psi, tau0, mu=mu, nu=nu).v)
    c = moving_rotor(psi, tau0, v, mu=mu, nu=nu)
    speed = m.rod.omega * abs(float(m.rod.u0(x0)))  # omega |u0|
    force = m.mu * m.preload
    col = got.columns
    assert len(col["V (m/s)"]) == v.size > 60
    written(col["V/(omega u0)"], c.v)
    written(col["F/(mu N)"], c.thrust_ratio)
    written(col["eta"], c.efficiency)
    written(col["P_out/(mu N omega u0)"], c.output_power)
    written(col["P_in/(mu N omega u0)"], c.input_power)
    written(col["P_loss/(mu N omega u0)"], c.friction_loss)
    written(col["V (m/s)"], c.v * speed)
    written(col["F (N)"], c.thrust_ratio * force)
    written(col["P_out (W)"], c.output_power * force * speed)
    written(col["P_in (W)"], c.input_power * force * speed)
    written(col["P_loss (W)"], c.friction_loss * force * speed)
    assert col["V (m/s)"][0] == col["P_out (W)"][0] == 0  # the held rotor
    assert col["F (N)"][0] == pytest.approx(abs(float(m.stall_thrust(x0))), rel=1e-3)
    scene.csv_file("speed")
    name = scene.downloads["speed"].filename
    assert name == scene.csv_filename("speed")
    x0_part = "_x0_3.5mm" if other else "_x0_-5mm"
    assert name.startswith("zharii_motor_speed_L20mm_delta4mm_") and name.endswith(
        f"_N0.5N{x0_part}.csv")


def test_csv_names_the_rods_own_contact_layer(scene: MotorScene) -> None:
    scene.material_select.value = "PZT-4"
    scene.flat_box.value = True
    got = Csv(scene.csv_text("thrust"))
    m, _ = scene.state.motor()
    assert got.parameters["rod_G"] == ("Pa", m.rod_G)
    assert got.parameters["rod_nu"] == ("", m.rod_nu)
    assert got.parameters["rod_R"] == ("m", float("inf"))
    written(got.columns["F_x (N)"], m.stall_thrust(rod_grid(m.rod.half_length)))
