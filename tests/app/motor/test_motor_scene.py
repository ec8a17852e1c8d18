"""Server-side tests of the Motor card (no browser): inputs in, named sources out.

Every plotted number must be exactly what `core.motor` computes for the card's state;
the background job's results are waited for on the runner (`jobs_helpers.drained`).
"""

from __future__ import annotations

import io
import math
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from jobs_helpers import drained

from app.kit.jobs import RUNNER
from app.motor import FIELDS, MotorScene
from app.motor.data import contact_key, rod_grid, speeds
from app.motor.fields import ROD_PRESETS, ROTOR_PRESETS
from core.motor import (
    Motor,
    Rod,
    best_efficiency,
    moving_rotor,
    no_load_speed,
)

eq = np.testing.assert_array_equal


def wait() -> None:
    """Wait for the runner's jobs (the card's results shown)."""
    assert drained(RUNNER, 60)


def motor_of(s: MotorScene) -> tuple[Motor, float]:
    """The core motor of the state, built here from the display units (mm, µm, kHz,
    GPa, N), independently of the card's own conversion (the paper's identical bodies)."""
    v = s.state
    rod = Rod(half_length=v.L / 1e3, thickness=v.delta / 1e3, nu_rod=v.nu_rod,
              amplitude=v.A / 1e6, frequency=v.f * 1e3)
    return Motor(rod, R=v.R / 1e3, G=v.G * 1e9, nu=v.nu, mu=v.mu, preload=v.N), v.x0 / 1e3


def assert_rod_matches_core(s: MotorScene) -> None:
    m, _ = motor_of(s)
    f = s.figures
    x = np.asarray(f.thrust.data["x"])
    eq(x, rod_grid(m.rod.half_length))
    assert np.all(np.abs(x) < m.rod.half_length)
    d = f.rod.data
    eq(d["x"], x)
    eq(d["u0_um"], m.rod.u0(x) * 1e6)
    eq(d["H_um"], m.rod.H(x) * 1e6)
    d = f.thrust.data
    eq(d["stall_thrust"], m.stall_thrust(x))
    eq(d["thrust_mN"], m.stall_thrust(x) * 1e3)
    eq(d["psi"], m.psi(x))
    eq(d["tau0"], m.tau0(x))
    # the never-opening region: nan from core, and shaded exactly there
    closed = ~m.opens(x)
    eq(np.isnan(np.asarray(d["stall_thrust"])), closed)
    left = np.asarray(f.invalid.data["left"])
    right = np.asarray(f.invalid.data["right"])
    x_mm = x * 1e3
    shaded = ((x_mm[:, None] >= left) & (x_mm[:, None] <= right)).any(axis=1)
    eq(shaded, closed)
    # the optimum: the largest |stall thrust| of the plotted points, both signs
    thrust = m.stall_thrust(x) * 1e3
    assert sorted(f.optimum.data["thrust_mN"]) == [np.nanmin(thrust), np.nanmax(thrust)]


def assert_x0_matches_core(s: MotorScene) -> None:
    m, x0 = motor_of(s)
    f = s.figures
    assert s.x0 == x0
    F = float(m.stall_thrust(x0))
    d = f.x0.data
    assert d["x_mm"] == [x0 * 1e3]
    eq(d["thrust_mN"], [F * 1e3])
    if m.opens(x0):
        assert s.contact == (float(m.psi(x0)), float(m.tau0(x0)))
    else:
        assert s.contact is None
    assert f.rotor.data["x"] == [x0 * 1e3]
    assert f.rotor.data["radius"] == [m.R * 1e3]
    # resting on the rod's drawn top face (H magnified as the rod is drawn)
    k_H = 0.3 * m.rod.thickness / abs(m.rod.vertical_amplitude)
    top = (0.5 * m.rod.thickness + k_H * float(m.rod.H(x0))) * 1e3
    assert f.rotor.data["y"][0] - f.rotor.data["radius"][0] == pytest.approx(top, rel=1e-12)


def assert_curve_matches_core(s: MotorScene) -> None:
    """The background curve, once arrived, is core's moving rotor at the contact, on
    speeds that resolve the efficiency, its best point among them."""
    wait()
    m, x0 = motor_of(s)
    key = contact_key(float(m.psi(x0)), float(m.tau0(x0)), m.mu, m.nu)
    at = s.results.at_x0
    assert at.key == key
    psi, tau0, mu, nu = key
    v0 = no_load_speed(psi, tau0, mu=mu, nu=nu)
    best = best_efficiency(psi, tau0, mu=mu, nu=nu)
    v = speeds(psi, tau0, v0, best.v)
    c = moving_rotor(psi, tau0, v, mu=mu, nu=nu)
    d = s.figures.speed.data
    eq(d["v"], c.v)
    eq(d["thrust_ratio"], c.thrust_ratio)
    eq(d["efficiency"], c.efficiency)
    speed = m.rod.omega * abs(float(m.rod.u0(x0)))
    eq(d["V_mm_s"], c.v * speed * 1e3)
    eq(d["thrust_mN"], c.thrust_ratio * m.mu * m.preload * 1e3)
    marks = s.figures.marks.data
    assert marks["V_mm_s"] == [v0 * speed * 1e3, best.v * speed * 1e3]
    assert marks["efficiency_pct"][1] == best.efficiency * 100.0
    assert marks["thrust_mN"][1] == best.thrust_ratio * m.mu * m.preload * 1e3
    # the efficiency is resolved where it is defined, its maximum the computed best
    assert np.sum((c.v > 0) & (c.v < v0)) >= 40
    assert best.v in c.v
    assert np.nanmax(d["efficiency_pct"]) == best.efficiency * 100.0


def test_default_scene_is_core(scene: MotorScene) -> None:
    assert (scene.state.rod_preset, scene.state.rotor_preset) == ("pzt40", "steel")
    assert_rod_matches_core(scene)
    assert_x0_matches_core(scene)
    assert_curve_matches_core(scene)
    assert len(scene.figures.invalid.data["left"]) == 2  # both ends never open
    assert not scene.progress.busy


def test_x0_move_updates_the_contact_and_the_curve(scene: MotorScene) -> None:
    seen = []
    scene.on_contact(seen.append)
    rod_before = dict(scene.figures.thrust.data)
    scene.inputs["x0"].value = 3.0
    assert scene.state.x0 == 3.0
    assert_x0_matches_core(scene)
    assert seen == [scene.contact]
    assert scene.figures.rotor.data["label"] == ["↻"]  # clockwise for x0 > 0
    assert scene.figures.thrust.data is rod_before or all(
        np.array_equal(scene.figures.thrust.data[k], v, equal_nan=True)
        for k, v in rod_before.items())
    assert_curve_matches_core(scene)
    # typed in the box, as the browser sends it
    scene.inputs["x0"]._entry.value = "-0.2"
    assert scene.state.x0 == -0.2
    assert_x0_matches_core(scene)
    assert_curve_matches_core(scene)


def test_never_opening_x0_has_no_curve_and_says_why(scene: MotorScene) -> None:
    seen = []
    scene.on_contact(seen.append)
    scene.inputs["x0"].value = 19.0
    assert_x0_matches_core(scene)
    assert seen == [None] and scene.contact is None
    assert math.isnan(scene.figures.x0.data["thrust_mN"][0])
    assert scene.figures.rotor.data["label"] == ["never opens"]
    wait()
    assert scene.results.at_x0.key is None and list(scene.figures.speed.data["v"]) == []
    m, _ = motor_of(scene)
    phi = float(m.load_factor(0.019))
    assert scene.status.object == (
        f"The contact never opens at x₀ = 19 mm (Φ = {phi:.3g} ≥ 8): the model does not "
        "apply there, and there is no thrust.")
    assert not scene.progress.busy
    text = scene.csv_text("speed")  # the header block and the column names, no rows
    assert "# no curve: the contact never opens at x0\n" in text
    table = pd.read_csv(io.StringIO(text), comment="#")
    assert list(table.columns) == SPEED_NAMES and len(table) == 0


def test_no_curve_at_the_centre_says_why_in_plain_words(scene: MotorScene) -> None:
    scene.inputs["x0"].value = 0.0  # no tangential drive: no psi, no curve
    wait()
    assert scene.results.at_x0.curve is None and list(scene.figures.speed.data["v"]) == []
    assert "outside the allowed range" not in scene.status.object
    assert scene.status.object == (
        "At x₀ = 0 mm the rod barely moves along x (ψ = 0): at its centre it does not at "
        "all, and drives nothing: move the rotor off the centre.")
    assert not scene.progress.busy
    text = scene.csv_text("speed")
    assert "# no curve: no tangential drive at x0\n" in text
    assert "# x0 (m) = 0.0\n" in text
    assert list(pd.read_csv(io.StringIO(text), comment="#").columns) == SPEED_NAMES
    assert scene.csv_filename("speed").endswith("_N0.5N_x0_0mm.csv")


def test_the_never_opening_ends_are_explained_on_the_plot(scene: MotorScene) -> None:
    f = scene.figures
    left, right = f.invalid.data["left"], f.invalid.data["right"]
    ends = f.ends.data
    assert ends["x_mm"] == pytest.approx([0.5 * (a + b) for a, b in zip(left, right,
                                                                  strict=True)], rel=1e-12)
    assert ends["x_mm"][0] < -15 and ends["x_mm"][1] > 15  # one at each end
    assert ends["text"] == ["contact never opens:\nnormal motion H too small\nfor the "
                            "preload (Φ ≥ 8)"] * 2
    assert f.thrust_figure.select_one({"name": "motor_ends_text"}).data_source is f.ends


def test_tap_on_the_rod_moves_the_rotor(scene: MotorScene) -> None:
    scene._on_tap(SimpleNamespace(x=-7.12345, y=0.0))
    assert scene.state.x0 == -7.123
    assert_x0_matches_core(scene)
    scene._on_tap(SimpleNamespace(x=25.0, y=0.0))  # off the rod: refused, explained
    assert scene.state.x0 == -7.123
    assert scene.inputs["x0"].error == ("x₀ = 25 mm is off the rod: x₀ must lie between "
                                        "-20 and 20 mm (the rod's ends excluded)")


@pytest.mark.parametrize(("part", "name"), [("rotor", "alumina"), ("rod", "pzt60")])
def test_presets(scene: MotorScene, part: str, name: str) -> None:
    select = scene.rod_select if part == "rod" else scene.rotor_select
    select.value = name
    preset = (ROD_PRESETS if part == "rod" else ROTOR_PRESETS)[name]
    for k, v in preset.values.items():
        assert getattr(scene.state, k) == v
        assert scene.inputs[k].value == v
    assert getattr(scene.state, f"{part}_preset") == name
    assert_rod_matches_core(scene)
    assert_x0_matches_core(scene)
    assert_curve_matches_core(scene)
    # an edit leaves the preset, in the state and the menu
    field = next(iter(preset.values))
    scene.inputs[field].value = preset.values[field] * 1.1
    assert getattr(scene.state, f"{part}_preset") == "" and select.value == ""
    assert_rod_matches_core(scene)


@pytest.mark.parametrize(("name", "text"), [
    ("L", "30"), ("delta", "2.5"), ("A", "4"), ("f", "55"), ("R", "2"), ("G", "120"),
    ("nu", "0.25"), ("mu", "0.45"), ("N", "1.5"), ("nu_rod", "0.2")])
def test_si_inputs(scene: MotorScene, name: str, text: str) -> None:
    scene.inputs[name]._entry.value = text
    assert getattr(scene.state, name) == float(text)
    assert scene.inputs[name].error == ""
    assert_rod_matches_core(scene)
    assert_x0_matches_core(scene)


def test_si_units_reach_core(scene: MotorScene) -> None:
    m, x0 = scene.state.motor()
    assert (m.rod.half_length, m.rod.thickness, m.rod.amplitude, m.rod.frequency) == (
        0.02, 0.004, 1e-5, 40e3)
    assert (m.R, m.G, m.preload, x0) == (0.005, 79.3e9, 0.5, -0.005)
    assert (m.rod_G, m.rod_nu, m.rod_R) == (None, None, None)  # the paper's bodies


@pytest.mark.parametrize(("name", "text", "words"), [
    ("L", "-1", "L = -1 mm is outside the allowed range [0.001, 100000] mm"),
    ("L", "abc", "L = 'abc' is not a number"),
    ("L", "4", "L = 4 mm would leave the rotor (x₀ = -5 mm) off the rod: move x₀ inside "
               "±4 mm first"),
    ("nu", "0.7", "ν = 0.7 is outside the allowed range (-1, 0.5]"),
    ("G", "0", "G = 0 GPa is outside the allowed range [1e-09, 10000] GPa"),
    ("N", "nan", "N must be a finite number, not nan"),
    ("x0", "20", "x₀ = 20 mm is off the rod: x₀ must lie between -20 and 20 mm (the rod's "
                 "ends excluded)"),
    ("x0", "abc", "x₀ = 'abc' is not a number"),
    ("A", "0.0000001", "A = 1e-07 µm is outside the allowed range [1e-06, 100000] µm"),
    ("mass", "0", "m = 0 g is outside the allowed range [1e-06, 1e+09] g"),
    ("load", "-1", "F_L = -1 N is outside the allowed range [0, 1e+06] N"),
    ("hardness", "0", "H_V = 0 GPa is outside the allowed range [1e-06, 1000] GPa"),
])
def test_bad_input_is_explained_in_the_boxs_unit_and_the_last_good_state_kept(
        scene: MotorScene, name: str, text: str, words: str) -> None:
    before = scene.state.values()
    thrust = np.asarray(scene.figures.thrust.data["stall_thrust"]).copy()
    widget = scene.inputs[name]
    widget._entry.value = text
    assert widget.error == words
    assert widget._message.visible
    assert scene.state.values() == before
    assert widget._entry.value == f"{before[name]:.6g}"  # the box shows the good value
    eq(scene.figures.thrust.data["stall_thrust"], thrust)
    widget._entry.value = "21" if name == "L" else widget._entry.value  # a good one clears
    if name == "L":
        assert widget.error == "" and scene.state.L == 21.0


def test_slider_move_core_refuses_is_reverted(scene: MotorScene) -> None:
    scene.inputs["L"].model.value = 5.0  # as a drag in the browser: x0 = -5 mm is off
    assert scene.state.L == 20.0 and scene.inputs["L"].value == 20.0
    assert scene.inputs["L"].error == ("L = 5 mm would leave the rotor (x₀ = -5 mm) off "
                                       "the rod: move x₀ inside ±5 mm first")
    assert_rod_matches_core(scene)


def test_query_round_trip(scene: MotorScene) -> None:
    assert scene.query() == {"motor_rod": "pzt40", "motor_rotor": "steel",
                             "motor_x0": "-5.0"}
    scene.rotor_select.value = "alumina"
    scene.inputs["A"]._entry.value = "7.25"
    scene.inputs["x0"]._entry.value = "-0.1234"
    scene.material_select.value = "PZT-4"
    scene.flat_box.value = True
    scene.inputs["load"]._entry.value = "0.005"
    q = scene.query()
    assert q["motor_rotor"] == "alumina" and "motor_rod" not in q and q["motor_A"] == "7.25"
    assert (q["motor_material"], q["motor_flat"], q["motor_load"]) == ("PZT-4", "1", "0.005")
    other = MotorScene()
    try:
        assert other.apply_query({**q, "psi": "3"}) == []  # others' keys are ignored
        assert other.state.values() == scene.state.values()
        assert other.query() == q
        assert other.contact == scene.contact
    finally:
        other.close()


def test_bad_query_values_keep_the_last_good_state(scene: MotorScene) -> None:
    before = scene.state.values()
    messages = scene.apply_query({"motor_L": ["abc"], "motor_x0": b"30", "motor_G": "-2",
                                  "motor_rotor": "wood", "motor_speed": "1",
                                  "motor_mu": "0.3", "motor_material": "cheese",
                                  "motor_flat": "yes"})
    assert messages[0].startswith("unknown parameter 'motor_speed' ignored (known: ")
    assert messages[1:] == [
        "motor_rotor = 'wood' is unknown (known: steel, alumina)",
        "motor_material = 'cheese' is unknown (known: PZT-4, PZT-8, alumina, steel, "
        "phosphor bronze, PEEK composite)",
        "motor_flat = 'yes' must be 0 or 1",
        "motor_L: L = 'abc' is not a number",
        "motor_G: G = -2 GPa is outside the allowed range [1e-09, 10000] GPa",
        "motor_x0: x₀ = 30 mm is off the rod: x₀ must lie between -20 and 20 mm (the rod's "
        "ends excluded)"]
    assert scene.state.values() == {**before, "mu": 0.3}  # the good value applied
    assert scene.state.rotor_preset == ""
    assert_rod_matches_core(scene)


def test_fields_have_units() -> None:
    units = {name: f.unit for name, f in FIELDS.items()}
    assert units == {"L": "mm", "delta": "mm", "nu_rod": "", "A": "µm", "f": "kHz",
                     "R": "mm", "G": "GPa", "nu": "", "mu": "", "N": "N", "x0": "mm",
                     "k": "× 10⁻⁶", "hardness": "GPa", "load": "N", "mass": "g"}


SPEED_NAMES = ["V/(omega u0)", "F/(mu N)", "eta", "P_out/(mu N omega u0)",
               "P_in/(mu N omega u0)", "P_loss/(mu N omega u0)", "V (m/s)", "F (N)",
               "P_out (W)", "P_in (W)", "P_loss (W)"]
