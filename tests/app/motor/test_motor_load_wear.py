"""The Motor card's parts beyond the held rotor: the rod's own contact layer and face
(Dundurs' beta and core's warning), Archard wear along the rod, the operating point under
a load (refused in plain words above the stall thrust) and the start-up from rest; each
is core's very numbers."""

from __future__ import annotations

import math

import numpy as np
import panel as pn
from bokeh.document import Document
from test_motor_scene import wait

from app.motor import MotorScene
from app.motor.data import WEAR_POINTS, contact_key, rod_grid
from core.materials import MATERIALS
from core.motor import Motor, operating_point, start_up, wear_along_rod
from core.physical import BETA_WARN

eq = np.testing.assert_array_equal


def test_the_card_holds_every_plot(scene: MotorScene) -> None:
    root = pn.panel(scene).get_root(Document())
    for name in ("motor_rod", "motor_thrust", "motor_speed", "motor_operating",
                 "motor_wear", "motor_startup", "motor_ends"):
        assert root.select_one({"name": name}) is not None, name


def test_the_rods_material_and_face_reach_core(scene: MotorScene) -> None:
    assert scene.beta.object == ("Dundurs&#x27; β = 0 (0 for the paper&#x27;s identical "
                                 "bodies)")
    scene.material_select.value = "PZT-4"
    scene.flat_box.value = True
    wait()
    s = scene.state
    pzt = MATERIALS["PZT-4"]
    m, x0 = s.motor()
    assert (m.rod_G, m.rod_nu, m.rod_R) == (pzt.G, pzt.nu, math.inf)
    assert s.hardness == pzt.hardness / 1e9  # the softer body's (PZT, not steel)
    x = rod_grid(m.rod.half_length)
    eq(scene.figures.thrust.data["stall_thrust"], m.stall_thrust(x))
    assert scene.contact == (float(m.psi(x0)), float(m.tau0(x0)))
    # the curve at the equivalent pair's nu
    assert scene.results.at_x0.key == contact_key(*scene.contact, m.mu, m.equivalent[2])
    assert scene.beta.object == (f"Dundurs&#x27; β = {m.beta:.3g} (0 for the paper&#x27;s "
                                 "identical bodies)")
    assert m.beta_warning is None


def test_dissimilar_bodies_beyond_the_threshold_are_warned_of(scene: MotorScene) -> None:
    scene.inputs["G"]._entry.value = "1"  # a soft rotor, nu = 0, on PZT-4: beta 0.48
    scene.inputs["nu"]._entry.value = "0"
    scene.material_select.value = "PZT-4"
    m, _ = scene.state.motor()
    assert abs(m.beta) > BETA_WARN and m.beta_warning
    assert scene.beta.object.endswith(
        "⚠ " + m.beta_warning.replace("'", "&#x27;").replace(">", "&gt;") + ".")


def test_wear_along_the_rod_is_cores(scene: MotorScene) -> None:
    scene.inputs["k"]._entry.value = "3"
    scene.inputs["hardness"]._entry.value = "2"
    wait()
    m, _ = scene.state.motor()
    w = wear_along_rod(m, rod_grid(m.rod.half_length, WEAR_POINTS), 3e-6, 2e9)
    d = scene.figures.wear.data
    eq(d["x_mm"], w.x0 * 1e3)
    eq(d["peak_um_h"], w.peak_depth_rate * 1e6)
    eq(d["centre_um_h"], w.centre_depth_rate * 1e6)
    i = int(np.nanargmax(w.peak_depth_rate))
    assert scene.wear_text.object == (
        f"The rod wears most at x₀ = {w.x0[i] * 1e3:.3g} mm: "
        f"{w.peak_depth_rate[i] * 1e6:.3g} µm per hour of operation.")


def test_the_operating_point_and_the_start_up_are_cores(scene: MotorScene) -> None:
    scene.inputs["load"]._entry.value = "0.01"
    scene.inputs["mass"]._entry.value = "25"
    wait()
    m, x0 = scene.state.motor()
    p = operating_point(m, x0, 0.01)
    assert scene.figures.operating.data == {"V_mm_s": [p.speed * 1e3],
                                            "thrust_mN": [p.load * 1e3],
                                            "efficiency_pct": [p.efficiency * 100.0]}
    s = start_up(m, x0, 0.025, 0.01)
    eq(scene.figures.start.data["t_ms"], s.t * 1e3)
    eq(scene.figures.start.data["V_mm_s"], s.speed * 1e3)
    text = scene.operating_text.object
    assert text.startswith(f"Under F_L = 0.01 N: speed <b>{p.speed * 1e3:.4g} mm/s</b>, "
                           f"output power <b>{p.output_power * 1e3:.4g} mW</b>, efficiency "
                           f"<b>{p.efficiency * 100:.3g} %</b>")
    assert f"90 % of that speed in {s.t90 * 1e3:.3g} ms" in text


def test_a_load_above_the_stall_thrust_is_refused_in_plain_words(scene: MotorScene) -> None:
    scene.inputs["load"]._entry.value = "0.05"
    wait()
    m, x0 = scene.state.motor()
    stall = abs(float(m.stall_thrust(x0)))
    assert stall < 0.05
    assert scene.operating_text.object == (
        f"F_L = 0.05 N is more than the stall thrust at x₀ = -5 mm ({stall:.4g} N): the "
        "rotor cannot move; lower the load or move the rotor.")
    assert scene.figures.operating.data["V_mm_s"] == []
    assert scene.figures.start.data["t_ms"] == []
    assert scene.state.load == 0.05 and not scene.progress.busy
    assert len(scene.figures.speed.data["v"]) > 60  # the curve stays
    scene.inputs["load"]._entry.value = "0.01"  # a load it can carry: shown again
    wait()
    assert scene.figures.operating.data["V_mm_s"] == [
        operating_point(m, x0, 0.01).speed * 1e3]


def test_a_preset_rotor_sets_the_softer_hardness(scene: MotorScene) -> None:
    scene.rotor_select.value = "alumina"
    assert scene.state.hardness == MATERIALS["alumina"].hardness / 1e9
    scene.material_select.value = "phosphor bronze"
    assert scene.state.hardness == MATERIALS["phosphor bronze"].hardness / 1e9
    m, _ = scene.state.motor()
    assert isinstance(m, Motor) and m.rod_G == MATERIALS["phosphor bronze"].G
