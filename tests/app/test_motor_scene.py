"""Server-side tests of the Motor scene (no browser): inputs in, named sources out.

Every plotted number must be exactly what `core.motor` computes for the scene's state.
"""

from __future__ import annotations

import io
import math
import threading
from importlib.metadata import version
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from test_export import Csv, written

from app.methods import SharedWorker
from app.motor import (
    FIELDS,
    ROD_PRESETS,
    ROTOR_PRESETS,
    SPEED_POINTS,
    MotorScene,
    contact_key,
    rod_grid,
)
from core.motor import Motor, Rod, best_efficiency, no_load_speed, thrust_speed_curve

eq = np.testing.assert_array_equal


@pytest.fixture
def scene() -> MotorScene:
    s = MotorScene()
    wait(s)
    yield s
    s.close()


def wait(s: MotorScene) -> None:
    """Wait for the background thrust-speed curve (shown when its future is done)."""
    if s.pending is not None:
        s.pending.result(timeout=30)


def motor_of(s: MotorScene) -> tuple[Motor, float]:
    """The core motor of the state, built here from the display units (mm, µm, kHz,
    GPa, N), independently of the scene's own conversion."""
    v = s.state
    rod = Rod(half_length=v.L / 1e3, thickness=v.delta / 1e3, nu_rod=v.nu_rod,
              amplitude=v.A / 1e6, frequency=v.f * 1e3)
    return Motor(rod, R=v.R / 1e3, G=v.G * 1e9, nu=v.nu, mu=v.mu, preload=v.N), v.x0 / 1e3


def assert_rod_matches_core(s: MotorScene) -> None:
    m, _ = motor_of(s)
    x = np.asarray(s.thrust_source.data["x"])
    eq(x, rod_grid(m.rod.half_length))
    assert np.all(np.abs(x) < m.rod.half_length)
    d = s.rod_source.data
    eq(d["x"], x)
    eq(d["u0_um"], m.rod.u0(x) * 1e6)
    eq(d["H_um"], m.rod.H(x) * 1e6)
    d = s.thrust_source.data
    eq(d["stall_thrust"], m.stall_thrust(x))
    eq(d["thrust_mN"], m.stall_thrust(x) * 1e3)
    eq(d["psi"], m.psi(x))
    eq(d["tau0"], m.tau0(x))
    # the never-opening region: nan from core, and shaded exactly there
    closed = ~m.opens(x)
    eq(np.isnan(np.asarray(d["stall_thrust"])), closed)
    left = np.asarray(s.invalid_source.data["left"])
    right = np.asarray(s.invalid_source.data["right"])
    x_mm = x * 1e3
    shaded = ((x_mm[:, None] >= left) & (x_mm[:, None] <= right)).any(axis=1)
    eq(shaded, closed)
    # the optimum: the largest |stall thrust| of the plotted points, both signs
    thrust = m.stall_thrust(x) * 1e3
    assert sorted(s.optimum_source.data["thrust_mN"]) == [np.nanmin(thrust), np.nanmax(thrust)]


def assert_x0_matches_core(s: MotorScene) -> None:
    m, x0 = motor_of(s)
    assert s.x0 == x0
    F = float(m.stall_thrust(x0))
    d = s.x0_source.data
    assert d["x_mm"] == [x0 * 1e3]
    eq(d["thrust_mN"], [F * 1e3])
    if m.opens(x0):
        assert s.contact == (float(m.psi(x0)), float(m.tau0(x0)))
    else:
        assert s.contact is None
    assert s.rotor_source.data["x"] == [x0 * 1e3]
    assert s.rotor_source.data["radius"] == [m.R * 1e3]


def assert_curve_matches_core(s: MotorScene) -> None:
    """The background curve, once arrived, is core's thrust_speed_curve at the contact."""
    wait(s)
    m, x0 = motor_of(s)
    key = contact_key(float(m.psi(x0)), float(m.tau0(x0)), m.mu, m.nu)
    assert s.shown_key == key
    psi, tau0, mu, nu = key
    c = thrust_speed_curve(psi, tau0, SPEED_POINTS, mu=mu, nu=nu)
    d = s.speed_source.data
    eq(d["v"], c.v)
    eq(d["thrust_ratio"], c.thrust_ratio)
    eq(d["efficiency"], c.efficiency)
    speed = m.rod.omega * abs(float(m.rod.u0(x0)))
    eq(d["V_mm_s"], c.v * speed * 1e3)
    eq(d["thrust_mN"], c.thrust_ratio * m.mu * m.preload * 1e3)
    v0 = no_load_speed(psi, tau0, mu=mu, nu=nu)
    best = best_efficiency(psi, tau0, mu=mu, nu=nu)
    marks = s.marks_source.data
    assert marks["V_mm_s"] == [v0 * speed * 1e3, best.v * speed * 1e3]
    assert marks["efficiency_pct"][1] == best.efficiency * 100.0
    assert marks["thrust_mN"][1] == best.thrust_ratio * m.mu * m.preload * 1e3


def test_default_scene_is_core(scene: MotorScene) -> None:
    assert (scene.state.rod_preset, scene.state.rotor_preset) == ("pzt40", "steel")
    assert_rod_matches_core(scene)
    assert_x0_matches_core(scene)
    assert_curve_matches_core(scene)
    assert len(scene.invalid_source.data["left"]) == 2  # both ends never open
    assert not scene.progress.visible


def test_x0_move_updates_the_contact_and_the_curve(scene: MotorScene) -> None:
    seen = []
    scene.on_contact(seen.append)
    rod_before = dict(scene.thrust_source.data)
    scene.inputs["x0"].value = 3.0
    assert scene.state.x0 == 3.0
    assert scene.progress.visible or scene.pending.done()
    assert_x0_matches_core(scene)
    assert seen == [scene.contact]
    assert scene.rotor_source.data["label"] == ["↻"]  # clockwise for x0 > 0
    assert scene.thrust_source.data is rod_before or all(
        np.array_equal(scene.thrust_source.data[k], v, equal_nan=True)
        for k, v in rod_before.items())
    assert_curve_matches_core(scene)
    # typed in the box, as the browser sends it
    scene.inputs["x0"]._entry.value = "-0.2"
    assert scene.state.x0 == -0.2
    assert_x0_matches_core(scene)
    assert_curve_matches_core(scene)


def test_never_opening_x0_has_no_curve(scene: MotorScene) -> None:
    seen = []
    scene.on_contact(seen.append)
    scene.inputs["x0"].value = 19.0
    assert_x0_matches_core(scene)
    assert seen == [None] and scene.contact is None
    assert math.isnan(scene.x0_source.data["thrust_mN"][0])
    assert scene.rotor_source.data["label"] == ["never opens"]
    wait(scene)
    assert scene.shown_key is None and list(scene.speed_source.data["v"]) == []
    assert "never opens" in scene.status.object
    text = scene.csv_text("speed")  # the header block and the column names, no rows
    assert "# no curve: the contact never opens at x0\n" in text
    table = pd.read_csv(io.StringIO(text), comment="#")
    assert list(table.columns) == SPEED_NAMES and len(table) == 0


def test_no_curve_at_the_centre_and_its_csv_says_why(scene: MotorScene) -> None:
    scene.inputs["x0"].value = 0.0  # no tangential drive: core refuses psi = 0
    wait(scene)
    assert scene.shown is None and list(scene.speed_source.data["v"]) == []
    text = scene.csv_text("speed")
    assert "# no curve: no tangential drive at x0\n" in text
    assert "# x0 (m) = 0.0\n" in text
    assert list(pd.read_csv(io.StringIO(text), comment="#").columns) == SPEED_NAMES
    assert scene.csv_filename("speed").endswith("_N0.5N_x0_0mm.csv")


def test_tap_on_the_rod_moves_the_rotor(scene: MotorScene) -> None:
    scene._on_tap(SimpleNamespace(x=-7.12345, y=0.0))
    assert scene.state.x0 == -7.123
    assert_x0_matches_core(scene)
    scene._on_tap(SimpleNamespace(x=25.0, y=0.0))  # off the rod: refused, explained
    assert scene.state.x0 == -7.123
    assert "outside the allowed range" in scene.inputs["x0"].error


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


@pytest.mark.parametrize(("name", "text", "words"), [
    ("L", "-1", "half_length = -0.001 is outside the allowed range (0, inf)"),
    ("L", "abc", "half_length must be a real number in (0, inf), got 'abc'"),
    ("L", "4", "x0 = -0.005 is outside the allowed range (-0.004, 0.004)"),
    ("nu", "0.7", "nu = 0.7 is outside the allowed range (-1, 0.5]"),
    ("G", "0", "G = 0 is outside the allowed range [1, 1e+13]"),
    ("N", "nan", "preload must be a finite number in (0, inf), got nan"),
    ("x0", "20", "x0 = 0.02 is outside the allowed range (-0.02, 0.02)"),
])
def test_bad_input_is_explained_and_the_last_good_state_kept(
        scene: MotorScene, name: str, text: str, words: str) -> None:
    before = scene.state.values()
    thrust = np.asarray(scene.thrust_source.data["stall_thrust"]).copy()
    widget = scene.inputs[name]
    widget._entry.value = text
    assert words in widget.error
    assert widget._message.visible
    assert scene.state.values() == before
    assert widget._entry.value == f"{before[name]:.6g}"  # the box shows the good value
    eq(scene.thrust_source.data["stall_thrust"], thrust)
    widget._entry.value = "21" if name == "L" else widget._entry.value  # a good one clears
    if name == "L":
        assert widget.error == "" and scene.state.L == 21.0


def test_slider_move_core_refuses_is_reverted(scene: MotorScene) -> None:
    scene.inputs["L"]._slider.value = 5.0  # as a drag in the browser: x0 = -5 mm is off
    assert scene.state.L == 20.0 and scene.inputs["L"].value == 20.0
    assert "x0 = -0.005" in scene.inputs["L"].error
    assert_rod_matches_core(scene)


def test_query_round_trip(scene: MotorScene) -> None:
    assert scene.query() == {"motor_rod": "pzt40", "motor_rotor": "steel",
                             "motor_x0": "-5.0"}
    scene.rotor_select.value = "alumina"
    scene.inputs["A"]._entry.value = "7.25"
    scene.inputs["x0"]._entry.value = "-0.1234"
    q = scene.query()
    assert q["motor_rotor"] == "alumina" and "motor_rod" not in q and q["motor_A"] == "7.25"
    other = MotorScene()
    try:
        assert other.apply_query({**q, "psi": "3"}) == []  # others' keys are ignored
        assert other.state.values() == scene.state.values()
        assert other.query() == q
        assert other.contact == scene.contact
        assert_rod_matches_core(other)
        assert_x0_matches_core(other)
    finally:
        other.close()


def test_bad_query_values_keep_the_last_good_state(scene: MotorScene) -> None:
    before = scene.state.values()
    messages = scene.apply_query({"motor_L": ["abc"], "motor_x0": b"30", "motor_G": "-2",
                                  "motor_rotor": "wood", "motor_speed": "1",
                                  "motor_mu": "0.3"})
    text = "\n".join(messages)
    assert "unknown parameter 'motor_speed'" in text
    assert "motor_rotor = 'wood' is unknown" in text
    assert "half_length must be a real number" in text
    assert "x0 = 0.03 is outside the allowed range" in text
    assert "G = -2e+09 is outside the allowed range" in text
    assert len(messages) == 5
    assert scene.state.values() == {**before, "mu": 0.3}  # the good value applied
    assert scene.state.rotor_preset == ""
    assert_rod_matches_core(scene)


THRUST_NAMES = ["x0 (m)", "u0 (m)", "H (m)", "psi", "Phi", "opens", "tau0 (rad)",
                "F_x/(mu N)", "F_x (N)"]
SPEED_NAMES = ["V/(omega u0)", "F/(mu N)", "eta", "P_out/(mu N omega u0)",
               "P_in/(mu N omega u0)", "P_loss/(mu N omega u0)", "V (m/s)", "F (N)",
               "P_out (W)", "P_in (W)", "P_loss (W)"]
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
    wait(s)


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
    wait(scene)
    got = Csv(scene.csv_text("speed"))
    assert got.names == SPEED_NAMES
    assert list(got.descriptions) == SPEED_NAMES
    assert_header(got, scene, "speed")
    m, x0 = motor_of(scene)
    psi, tau0, mu, nu = contact_key(float(m.psi(x0)), float(m.tau0(x0)), m.mu, m.nu)
    assert got.parameters["psi"] == ("", psi) and got.parameters["tau0"] == ("rad", tau0)
    c = thrust_speed_curve(psi, tau0, SPEED_POINTS, mu=mu, nu=nu)
    speed = m.rod.omega * abs(float(m.rod.u0(x0)))  # omega |u0|
    force = m.mu * m.preload
    col = got.columns
    assert len(col["V (m/s)"]) == SPEED_POINTS
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


def test_close_cancels_the_waiting_request() -> None:
    worker = SharedWorker()
    s = MotorScene(worker=worker)
    wait(s)
    gate = threading.Event()
    blocker = worker.submit(gate.wait)  # the worker is busy with another session
    try:
        s.inputs["x0"].value = -2.0
        waiting = s.pending
        assert waiting is not None and not waiting.done()
        assert s.progress.visible
        s.close()
        assert waiting.cancelled()
        s.inputs["x0"].value = -3.0  # a closed scene asks for nothing more
        assert s.pending is waiting
    finally:
        gate.set()
        blocker.result(timeout=10)


def test_a_stale_result_is_dropped() -> None:
    worker = SharedWorker()
    s = MotorScene(worker=worker)
    wait(s)
    gate = threading.Event()
    blocker = worker.submit(gate.wait)
    try:
        s.inputs["x0"].value = -2.0
        first = s.pending
        s.inputs["x0"].value = -4.0  # replaces the waiting request
        assert first.cancelled()
    finally:
        gate.set()
        blocker.result(timeout=10)
    assert_curve_matches_core(s)
    s.close()


def test_fields_have_units() -> None:
    units = {name: f.unit for name, f in FIELDS.items()}
    assert units == {"L": "mm", "delta": "mm", "nu_rod": "", "A": "µm", "f": "kHz",
                     "R": "mm", "G": "GPa", "nu": "", "mu": "", "N": "N", "x0": "mm"}
