"""Server-side tests of the explorer (no browser): widgets in, named sources out.

Every plotted number must be exactly what `core` computes for the current state.
"""

from __future__ import annotations

import base64
import html
import io
import json
import math
import re

import numpy as np
import pytest
from bokeh.document import Document
from bokeh.models import Range1d

import app.kit.widgets
import app.page.explorer
from app.contact import data, spheres
from app.contact.animation import CONTACT_SECONDS
from app.contact.formulas import formulas
from app.contact.notes import NOTES
from app.contact.phases import STYLES
from app.contact.player import frame_index, frame_taus
from app.contact.query import parse_query
from app.contact.radii import RadiiScene
from app.contact.state import DEFAULT_PRESET, PRESETS, SQRT2_1, ExplorerState
from app.contact.traction import PROFILE_COLUMNS, TractionScene
from app.kit.figures import CURVE_POINTS, PROFILE_POINTS, fit_range, nice_step
from app.page.explorer import Explorer
from core import PHASE_NAMES, Contact, Phase, impulse_ratio

eq = np.testing.assert_array_equal


@pytest.fixture
def ex() -> Explorer:
    return Explorer()


def contact_of(ex: Explorer) -> Contact:
    s = ex.state
    return Contact(s.psi, s.tau0, mu=s.mu, nu=s.nu)


def assert_sources_match_core(ex: Explorer) -> None:
    """Every named source holds what core computes for the explorer's state, each curve
    scene once its tab is opened (the open tab is left as it was)."""
    active = ex.contact.tabs.active
    for i in range(len(ex.contact.tabbed)):
        ex.contact.tabs.active = i
    ex.contact.tabs.active = active
    assert not any(s.stale for s in ex.contact.scenes)  # every tab was opened: all caught up
    c, tau = contact_of(ex), ex.state.tau
    grid = c.tau_grid(CURVE_POINTS)

    d = ex.contact.force.source.data
    eq(d["tau"], grid)
    eq(d["T"], c.tangential_force(grid))
    eq(d["muP"], c.normal_force(grid))
    assert "neg_muP" not in d  # (the browser draws -muP: `CurveScene.mirrors`)
    m = ex.contact.force.marker.data
    assert m["x"] == [tau] * 3
    assert m["y"][0] == float(c.tangential_force(np.array([tau]))[0])

    d = ex.contact.radii.source.data
    eq(d["tau"], grid)
    eq(d["approach"], c.approach(grid))
    eq(d["a"], c.contact_radius(grid))
    eq(d["b"], c.stick_radius(grid))

    d = ex.contact.motion.source.data
    grid = ex.contact.motion.grid(c)  # with the jumps and a margin outside the contact
    eq(d["tau"], grid)
    eq(d["v2"], c.centre_velocity(grid))
    eq(d["u2"], c.centre_displacement(grid))
    eq(d["drive_v"], c.drive_velocity(grid))
    eq(d["drive_u"], c.drive_displacement(grid))

    d = ex.contact.traction.source.data
    r = np.asarray(d["r"])
    # the grid with -a, a, -b, b inserted: a constant length, so the player can copy
    # frames in place (duplicates where b = 0 or b = a)
    assert r.size == PROFILE_POINTS + 4 and np.all(np.diff(r) >= 0)
    eq(d["traction"], c.traction(r, tau))
    eq(d["upper"], c.pressure(r, tau))
    a, b = float(c.contact_radius(tau)), float(c.stick_radius(tau))
    assert {a, -a} <= set(r.tolist())  # the contact edge is drawn exactly
    stick = (np.abs(r) <= b) & (b > 0)
    eq(d["stick_hi"], np.where(stick, c.pressure(r, tau), 0.0))
    # (-p and the stick zone's lower edge the browser draws, negated)
    assert tuple(d) == PROFILE_COLUMNS
    phase = PHASE_NAMES[int(c.phase(tau))]
    assert ex.contact.traction.phase_label.text == phase

    d = ex.contact.disc.source.data
    assert d["inner"] == [0.0, b] and d["outer"] == [b, a]

    d = ex.contact.impulse.source.data
    eq(d["ratio"], impulse_ratio(np.asarray(d["psi"]), c.tau0))
    assert ex.contact.impulse.marker.data == {"psi": [c.psi], "ratio": [c.impulse_ratio]}


def test_default_state_is_the_default_preset(ex: Explorer) -> None:
    p = PRESETS[DEFAULT_PRESET]
    assert (ex.state.psi, ex.state.tau0, ex.state.tau) == (p.psi, p.tau0, p.tau)
    assert_sources_match_core(ex)
    assert int(contact_of(ex).phase(ex.state.tau)) == 3  # Fig. 6e: partial stick
    assert not ex.message.visible


@pytest.mark.parametrize(("widget", "value"), [
    ("psi_slider", 0.6), ("psi_slider", 7.5), ("psi_slider", 2e5),
    ("tau0_slider", -0.4), ("tau0_slider", 1.2), ("mu_slider", 0.55), ("nu_slider", 0.05),
])
def test_widget_change_recomputes_every_source(ex: Explorer, widget: str, value: float) -> None:
    before = np.asarray(ex.contact.force.source.data["T"]).copy()
    getattr(ex.contact.controls, widget).value = value
    assert getattr(ex.state, widget.removesuffix("_slider")) == value
    assert_sources_match_core(ex)
    c = contact_of(ex)
    assert c.tau0 <= ex.state.tau <= c.tau_end
    assert ((ex.contact.controls.tau_slider.start, ex.contact.controls.tau_slider.end) ==
            (c.tau0, c.tau_end))
    if widget in ("psi_slider", "tau0_slider"):
        after = np.asarray(ex.contact.force.source.data["T"])
        assert after.shape != before.shape or not np.array_equal(after, before)
    assert ex.state.preset == ""  # an edit leaves the preset


def readout_rows(ex: Explorer) -> list[tuple[str, str]]:
    """The (quantity, value) rows the derived-quantities table shows (the browser sets
    them as text: tests/app/test_accessibility.py reads the table drawn)."""
    rows = json.loads(ex.contact.readout.pane.cells)
    assert all(len(r) == 2 and all(isinstance(x, str) for x in r) for r in rows)
    return [tuple(r) for r in rows]


def test_theta_readout_follows_mu_and_nu(ex: Explorer) -> None:
    ex.contact.controls.mu_slider.value = 0.5
    c = contact_of(ex)
    rows = readout_rows(ex)
    assert rows == data.readout_rows(c)
    values = [v for _, v in rows]
    assert f"{math.degrees(c.theta0):.3f}°" in values
    assert f"{math.degrees(c.theta):.3f}°" in values


def test_tau_change_updates_only_tau_dependent_data(ex: Explorer) -> None:
    force_data = ex.contact.force.source.data
    ex.contact.controls.tau_slider.value = 1.0
    assert ex.state.tau == 1.0
    assert ex.contact.force.source.data is force_data  # curves untouched by a tau change
    assert list(ex.contact.force.marker.data["x"]) == [1.0] * 3  # markers and the tau cursor
    assert_sources_match_core(ex)
    assert "Slip (while loading" in ex.contact.controls.formulas.object


def test_tau_is_clamped_into_the_new_contact(ex: Explorer) -> None:
    ex.contact.controls.tau_slider.value = 0.6
    ex.contact.controls.tau0_slider.value = 1.0
    assert ex.state.tau == 1.0
    assert_sources_match_core(ex)


def test_log_psi_axis_reaches_1e6(ex: Explorer) -> None:
    ex.contact.tabs.active = ex.contact.tabbed.index(ex.contact.impulse)
    ex.contact.controls.log_box.value = True
    psi = np.asarray(ex.contact.impulse.source.data["psi"])
    assert psi.min() <= 1e-3 and psi.max() >= 1e6 and 1.0 in psi
    assert (ex.contact.panes[ex.contact.tabbed.index(ex.contact.impulse)].object is
            ex.contact.impulse.log_figure)
    assert_sources_match_core(ex)
    ex.contact.controls.log_box.value = False
    assert np.asarray(ex.contact.impulse.source.data["psi"]).max() == pytest.approx(30.0)
    assert (ex.contact.panes[ex.contact.tabbed.index(ex.contact.impulse)].object is
            ex.contact.impulse.linear_figure)


def test_large_psi_in_linear_mode_extends_the_axis(ex: Explorer) -> None:
    ex.contact.tabs.active = ex.contact.tabbed.index(ex.contact.impulse)
    ex.contact.controls.psi_slider.value = 100.0
    psi = np.asarray(ex.contact.impulse.source.data["psi"])
    assert psi.max() >= 100.0 and 1.0 in psi
    assert (ex.contact.impulse.marker.data ==
            {"psi": [100.0], "ratio": [contact_of(ex).impulse_ratio]})


def test_moving_psi_sends_only_the_impulse_marker(ex: Explorer) -> None:
    """The impulse curve depends on tau0 only: a psi move must not recompute it."""
    ex.contact.tabs.active = ex.contact.tabbed.index(ex.contact.impulse)
    curve = ex.contact.impulse.source.data
    ex.contact.controls.psi_slider.value = 3.0
    assert ex.contact.impulse.source.data is curve
    assert ex.contact.impulse.marker.data["psi"] == [3.0]
    ex.contact.controls.tau0_slider.value = 0.3
    assert ex.contact.impulse.source.data is not curve
    assert_sources_match_core(ex)


def _same(a: object, b: object) -> bool:
    """Whether two property values are equal (data columns element by element)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.dtype.kind in "fiu" and b.dtype.kind in "fiu":
            return np.array_equal(a, b, equal_nan=True)
        return a.shape == b.shape and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, list | tuple) and isinstance(b, list | tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


def _values(doc: Document) -> dict:
    """Every property value of every model of `doc` (data columns copied)."""
    out = {}
    for m in doc.models:
        for k in m.properties_with_values(include_defaults=True):
            v = getattr(m, k)
            if isinstance(v, dict):
                v = {c: np.array(x, copy=True) if isinstance(x, np.ndarray) else
                     list(x) if isinstance(x, list) else x for c, x in v.items()}
            out[m.id, k] = list(v) if isinstance(v, list) else v
    return out


def _sent_unchanged(doc: Document, ex: Explorer, psi: float) -> list[tuple]:
    """The (model type, name, property) of what a psi move to `psi` (as a move in the
    browser arrives) sent holding the value it held before; the move must send something."""
    before = _values(doc)
    events = []
    doc.on_change(events.append)
    ex.contact.controls.psi_slider.model.value = psi
    assert events
    return [(type(e.model).__name__, e.model.name, getattr(e, "attr", "data"))
            for e in events
            if _same(before.get((e.model.id, getattr(e, "attr", "data"))),
                     getattr(e.model, getattr(e, "attr", "data")))]


@pytest.mark.parametrize("psi", [2.51, 0.8, 7.0])
def test_a_psi_move_sets_only_what_changes(ex: Explorer, psi: float) -> None:
    """Every property a psi move sends holds a new value: each costs the server its
    serialization (and the browser its work), so what did not change is not set."""
    doc = Document()
    ex.view().server_doc(doc)
    ex.contact.controls.psi_slider.value = 2.5  # (leaves the preset)
    assert _sent_unchanged(doc, ex, psi) == []


@pytest.mark.parametrize("tab", [0, 2, 3])  # T(tau), the radii with Fig. 4a, the motion
def test_a_psi_move_below_1_sends_nothing_held_already(ex: Explorer, tab: int) -> None:
    """Below psi = 1 (no tau1) a psi move moves neither tau0 nor a landmark: what depends
    on them alone (the landmarks, Fig. 4a, the period strip and the pictograms, the
    traction plot's ranges) is not sent again, nor anything else a source holds."""
    doc = Document()
    ex.view().server_doc(doc)
    ex.contact.tabs.active = tab
    ex.contact.controls.psi_slider.value = 0.8  # (leaves the preset)
    assert _sent_unchanged(doc, ex, 0.81) == []


def test_what_depends_on_tau0_alone_follows_tau0(ex: Explorer) -> None:
    """The scenes draw what depends on tau0 alone (the spheres' period strip, pictograms
    and sphere at rest, the traction plot's r grid, Fig. 4a and its disks) again only
    when tau0 changes: after any series of moves they hold what new scenes draw for the
    contact shown."""
    ex.contact.tabs.active = ex.contact.tabbed.index(ex.contact.radii)
    for psi, tau0 in [(0.8, 0.5), (3.0, 0.5), (3.0, -0.3), (0.5, -0.3), (0.5, 0.0),
                      (2.0, 0.0), (2.0, 1.2), (0.9, 1.2)]:
        ex.state.param.update(psi=psi, tau0=tau0)
        c = ex.state.current
        assert (c.psi, c.tau0) == (psi, tau0)
        new = {"spheres": spheres.SpheresScene(), "traction": TractionScene(),
               "radii": RadiiScene()}
        for scene in new.values():
            scene.update_contact(c)
        shown = ex.contact
        for name in ("rest", "still", "period", "period_contact", "period_words",
                     "pictograms"):
            held, drawn = getattr(shown.spheres, name).data, getattr(new["spheres"], name).data
            assert _same(dict(held), dict(drawn)), name
        for name in ("drive", "levels", "bracket", "disks"):
            held, drawn = getattr(shown.radii, name).data, getattr(new["radii"], name).data
            assert _same(dict(held), dict(drawn)), name
        assert shown.traction.r_grid.tobytes() == new["traction"].r_grid.tobytes()
        assert (shown.traction.figure.x_range.start, shown.traction.figure.y_range.end) == (
            new["traction"].figure.x_range.start, new["traction"].figure.y_range.end)


def test_a_psi_move_changes_only_data_and_the_canvas_caption(ex: Explorer) -> None:
    """What a slider move sends decides the browser's work: new data for the plots that
    show psi, the caption drawn on the traction canvas and the derived-quantities table's
    text; the curve scenes of closed tabs send nothing (they catch up when opened).  No
    other text pane, no range, no title (each makes the browser restyle or lay out the
    page again); the number box shows the slider's value; the page's URL query goes with
    them (`app.page.url.UrlWriter`: the browser writes it into the address bar).  (The
    slider's own value is in the set because the move is made here, server side; Panel
    does not send a browser's change back.)"""
    doc = Document()
    ex.view().server_doc(doc)
    # leaves the preset: the preset menu changes this once
    ex.contact.controls.psi_slider.value = 2.5
    events = []
    doc.on_change(events.append)
    ex.contact.controls.psi_slider.model.value = 2.51  # as a move in the browser arrives
    changed = {(type(e.model).__name__, e.model.name, getattr(e, "attr", "data"))
               for e in events}
    data = {("ColumnDataSource", n, "data") for n in (
        "traction", "disc", "force", "force_marker", "force_landmarks",
        "spheres_drive", "spheres_lower", "spheres_patch", "spheres_forces", "spheres_bound")}
    slider = doc.select_one({"tags": "psi-value"})  # the slider's values (SliderModel)
    # (the drive angle's slider follows psi: theta = arctan(psi tan theta0))
    theta = doc.select_one({"tags": "theta-value"})
    # the texts: the derived quantities' table and the four plots' descriptions for
    # screen readers (`app.kit.texts`: their text, a property of their data model, is
    # all they send)
    texts = {(type(m).__name__, m.name, attr) for m in doc.models
             for name, attr in [("derived_quantities", "cells"),
                                *((f"{k}_description", "description")
                                  for k in ("spheres", "traction", "disc", "curves"))]
             if m.name == name and attr in m.properties()}
    assert len(texts) == 5
    url = doc.get_model_by_name("url_writer")
    assert changed == data | texts | {("Label", "traction_caption", "text"),
                                      (type(url).__name__, url.name, "query"),
                                      ("Label", "spheres_rest_note", "text"),
                                      (type(slider).__name__, slider.name, "value"),
                                      (type(theta).__name__, theta.name, "value"),
                                      ("TextInput", None, "value")}
    assert ex.state.psi == ex.contact.controls.psi_slider.value == 2.51
    # the parameters hold what the page shows: the URL and the table as sent
    assert dict(json.loads(ex.url_writer.query))["psi"] == "2.51" == \
        dict(json.loads(url.query))["psi"]
    assert ex.contact.readout.pane.cells == doc.get_model_by_name("derived_quantities").cells
    events.clear()
    assert doc.get_model_by_name("radii") is None  # a closed tab's plot is not in the page
    # opening a tab brings it up to date
    ex.contact.tabs.active = ex.contact.tabbed.index(ex.contact.radii)
    changed = {(type(e.model).__name__, e.model.name) for e in events}
    assert ("ColumnDataSource", "radii_marker") in changed
    assert ("ColumnDataSource", "motion") not in changed
    radii = doc.get_model_by_name("radii")  # in the page now, with the current data
    c = contact_of(ex)
    eq(radii.data["b"], c.stick_radius(c.tau_grid(CURVE_POINTS)))


def test_legend_entries_are_static_proxies_of_the_curves(ex: Explorer) -> None:
    """A legend whose renderers' data change is repainted with them; the entries show
    empty copies instead, whose click handler names the real curves by id only."""
    items = [item for fig in ex.contact.motion.figures for item in fig.legend[0].items]
    fig = ex.contact.motion.figure
    curves = [ex.contact.motion.curves[i] for i in (0, 2, 1, 3)]  # v2, drive_v | u2, drive_u
    for item, (col, label, color, _) in zip(items, curves, strict=True):
        (proxy,) = item.renderers
        assert item.label.value == label
        assert all(len(v) == 1 and math.isnan(v[0]) for v in proxy.data_source.data.values())
        assert proxy.glyph.line_color == color
        (callback,) = proxy.js_property_callbacks["change:visible"]
        assert callback.args == {}
        curve = fig.select_one({"name": f"motion_{col}"})
        assert repr(curve.id) in callback.code
        assert proxy.data_source is not ex.contact.motion.source


@pytest.mark.parametrize(("span", "step"), [(1.0, 0.1), (0.7, 0.1), (0.25, 0.05),
                                            (0.11, 0.02), (3.0, 0.5), (1e-3, 1e-4)])
def test_nice_step(span: float, step: float) -> None:
    assert nice_step(span) == pytest.approx(step)


def test_snapped_ranges_hold_the_data_and_stay_put_for_small_moves() -> None:
    rng = Range1d(0, 1)
    fit_range(rng, [-0.313, 0.352], snap=True)
    assert rng.start <= -0.313 and rng.end >= 0.352
    assert (rng.start, rng.end) == pytest.approx((-0.4, 0.4))
    fit_range(rng, [-0.312, 0.353], snap=True)  # a small move: same range
    assert (rng.start, rng.end) == pytest.approx((-0.4, 0.4))


def test_radii_and_force_ranges_stay_put_for_a_psi_step(ex: Explorer) -> None:
    figures = (ex.contact.force.figure, ex.contact.radii.figures[0])
    before = [(f.y_range.start, f.y_range.end) for f in figures]
    ex.contact.controls.psi_slider.value = ex.contact.controls.psi_slider.value + 0.01
    after = [(f.y_range.start, f.y_range.end) for f in figures]
    assert after == before


@pytest.mark.parametrize("name", list(PRESETS))
def test_presets_reproduce_the_papers_parameters(ex: Explorer, name: str) -> None:
    ex.contact.controls.tau0_slider.value = 0.1  # leave the default first
    ex.contact.controls.preset_select.value = name
    p = PRESETS[name]
    assert (ex.state.psi, ex.state.tau0, ex.state.tau) == (p.psi, p.tau0, p.tau)
    assert (ex.state.mu, ex.state.nu) == (0.2, 0.3)
    assert ex.state.preset == name
    assert_sources_match_core(ex)
    fam = ex.contact.force.family.data
    assert [float(x.split("= ")[1]) for x in fam["label"]] == list(p.family)
    for psi, ys in zip(p.family, fam["ys"], strict=True):
        c = Contact(psi, p.tau0)
        eq(ys, c.tangential_force(c.tau_grid(CURVE_POINTS)))


def _type_tau(ex: Explorer) -> None:
    ex.contact.controls.tau_slider._entry.value = "2.3"  # what a typed value does (the box's value)


@pytest.mark.parametrize("change", [
    lambda ex: ex.state.param.update(physical=True),
    lambda ex: ex.state.param.update(mu=0.25),
    lambda ex: ex.contact.controls.psi_slider.param.update(value=7.0),
], ids=["SI inputs", "mu", "psi"])
def test_a_change_of_a_contact_input_leaves_the_preset_everywhere(ex: Explorer,
                                                                   change) -> None:
    ex.contact.controls.preset_select.value = "fig7b"
    assert ex.state.preset == "fig7b" and len(ex.contact.force.family.data["ys"]) == 3
    change(ex)
    assert ex.state.preset == "" and ex.contact.controls.preset_select.value == ""
    assert ex.contact.force.family.data["ys"] == []  # the preset's family goes with it
    assert float(ex.contact.controls.note.styles["opacity"]) < 0.6  # its note faded
    assert "preset" not in ex.state.query()
    ex.contact.controls.log_box.value = True  # a view option: no preset to leave
    ex.contact.controls.preset_select.value = "fig6e"
    ex.contact.controls.log_box.value = False
    assert ex.state.preset == "fig6e" == ex.contact.controls.preset_select.value


@pytest.mark.parametrize("change", [
    _type_tau,
    lambda ex: ex.contact.animation.step(),
    lambda ex: ex.state.param.update(tau=ex.state.tau + 0.01),  # an animation tick's tau
    lambda ex: ex.state.param.update(playing=True),
], ids=["typed tau", "step", "animation tau", "play"])
def test_a_change_of_tau_keeps_the_preset(ex: Explorer, change) -> None:
    """The preset names the contact on screen: playing, stepping or scrubbing its contact
    keeps it, its note (which names its own tau) and its comparison curves."""
    ex.contact.controls.preset_select.value = "fig7b"
    tau = ex.state.tau
    change(ex)
    ex.state.playing = False  # (a pause keeps it too)
    assert ex.state.tau != tau or ex.state.playing is False
    assert ex.state.preset == "fig7b" == ex.contact.controls.preset_select.value
    assert len(ex.contact.force.family.data["ys"]) == 3
    assert ex.contact.controls.note.visible
    q = ex.state.query()
    assert q["preset"] == "fig7b" and float(q["tau"]) == ex.state.tau
    again = Explorer(query=q)  # the link restores the preset at the tau shown
    assert (again.state.preset, again.state.tau) == ("fig7b", ex.state.tau)


@pytest.mark.parametrize(("name", "tab"), [("fig4", "radii"), ("fig8", "impulse"),
                                           ("fig9", "motion"), ("fig7b", "force")])
def test_a_preset_opens_the_tab_of_its_figure(ex: Explorer, name: str, tab: str) -> None:
    ex.contact.tabs.active = 3 if tab != "motion" else 0  # another tab open
    ex.contact.controls.preset_select.value = name
    assert ex.contact.tabbed[ex.contact.tabs.active].name == tab
    assert_sources_match_core(ex)
    linked = Explorer(query={"preset": name})  # a link too
    assert linked.contact.tabbed[linked.contact.tabs.active].name == tab


def test_a_typed_value_widens_a_slider_only_while_it_is_shown(ex: Explorer) -> None:
    """psi = 1e12 typed in the box stretched the slider to 1e12 for good."""
    slider = ex.contact.controls.psi_slider
    own = (slider.start, slider.end)
    slider._entry.value = "1e12"
    assert ex.state.psi == 1e12 and slider.end == 1e12
    slider._entry.value = "3"
    assert ex.state.psi == 3.0 and (slider.start, slider.end) == own
    assert (slider.model.start, slider.model.end) == own


def test_fig6_presets_walk_through_the_phases(ex: Explorer) -> None:
    phases = []
    for key in ("fig6a", "fig6b", "fig6c", "fig6d", "fig6e", "fig6f"):
        ex.state.apply_preset(key)
        phases.append(int(contact_of(ex).phase(ex.state.tau)))
    assert phases == [2, 2, 2, 3, 3, 4]
    # Fig. 6f sits at tau1 = 3 pi / 4: counter-slip starts, the stick disc has vanished,
    # and every part of the page says so
    assert contact_of(ex).tau1 == ex.state.tau == pytest.approx(3 * math.pi / 4, rel=1e-15)
    assert ex.contact.disc.source.data["inner"][1] == 0.0
    assert ex.contact.disc.source.data["label"][1] == "counter-slip"
    assert ex.contact.controls.formulas.object.startswith("<p><b>Counter-slip (τ₁ ≤ τ")
    assert ex.contact.traction.phase_label.text == "counter-slip"
    assert max(ex.contact.traction.source.data["stick_hi"]) == 0.0  # no stick sliver drawn


def test_reset_restores_defaults(ex: Explorer) -> None:
    ex.contact.controls.psi_slider.value = 9.0
    ex.contact.controls.speed_slider.value = 2.5
    ex.contact.controls.material_select.value = "steel"  # physical inputs on, steel's G
    ex.state.param.update(H=5e-6, omega=1e5)
    ex.state.playing = True
    ex.contact.controls.reset_button.clicks += 1
    assert ex.state.psi == SQRT2_1 and ex.state.preset == DEFAULT_PRESET
    assert not ex.state.playing and ex.state.speed == 1.0
    assert not ex.state.physical and ex.state.material == "custom"
    assert all(getattr(ex.state, k) == ExplorerState.param[k].default
               for k in ("R", "G", "H", "u0", "h", "omega"))
    assert ex.state.current.scales is None and ex.state.mu == 0.2 and ex.state.nu == 0.3
    assert_sources_match_core(ex)


# ---------------------------------------------------------------- URL query


def test_parse_query_accepts_good_values() -> None:
    values, messages = parse_query({"psi": "6.46", "tau0": "0.3", "mu": "0.25", "nu": "0.2",
                                    "tau": "2.0", "log_psi": "1"})
    assert messages == []
    assert values == {"psi": 6.46, "tau0": 0.3, "mu": 0.25, "nu": 0.2, "tau": 2.0,
                      "log_psi": True}


def test_parse_query_reads_session_args_bytes() -> None:
    values, messages = parse_query({"psi": [b"1e6"], "preset": [b"fig9"]})
    assert messages == [] and values["psi"] == 1e6 and values["tau"] == PRESETS["fig9"].tau


@pytest.mark.parametrize(("query", "fragment"), [
    ({"psi": "abc"}, "psi must be a real number in [0, 1e+12], got 'abc'"),
    ({"psi": "-1"}, "psi = -1 is outside the allowed range [0, 1e+12]"),
    ({"psi": "2e12"}, "psi = 2e+12 is outside the allowed range"),
    ({"psi": "nan"}, "psi must be a finite number"),
    ({"tau0": "1.6"}, "tau0 = 1.6 is outside the allowed range (-1.5708, 1.5708)"),
    ({"mu": "-1"}, "mu = -1 is outside the allowed range (0, 1000]"),
    ({"nu": "0.6"}, "nu = 0.6 is outside the allowed range (-1, 0.5]"),
    ({"tau": "3.1"}, "outside the contact"),
    ({"tau0": "1", "tau": "2.5"}, "tau = 2.5 is outside the contact [1, 2.142]"),
    ({"log_psi": "maybe"}, "log_psi = 'maybe' must be 0 or 1"),
    ({"preset": "fig99"}, "preset = 'fig99' is unknown"),
    ({"colour": "red"}, "unknown parameter 'colour'"),
])
def test_parse_query_rejects_bad_values(query: dict, fragment: str) -> None:
    values, messages = parse_query(query)
    assert len(messages) == 1 and fragment in messages[0], messages
    rejected = list(query)[-1]
    assert rejected not in values


@pytest.mark.parametrize(("query", "message"), [
    ({"psi": "1e400"}, "psi = 1e400 is too large: it is outside the allowed range [0, 1e+12]"),
    ({"tau": "10"}, "tau = 10 is outside the contact [0.5236, 2.618] (tau0 = 0.5236)"),
    ({"tau": "abc"}, "tau must be a real number in the contact [0.5236, 2.618]"),
])
def test_a_refusal_quotes_the_text_and_the_range_that_apply(query: dict, message: str) -> None:
    """"1e400" was refused as "got inf", and tau = 10 with the app's [-pi/2, 3 pi/2]
    rather than the contact's range."""
    values, messages = parse_query(query)
    assert len(messages) == 1 and messages[0].startswith(message), messages
    assert next(iter(query)) not in values


def test_a_link_takes_multiples_of_pi() -> None:
    values, messages = parse_query({"tau0": "pi/6", "tau": "3pi/4"})
    assert messages == [] and values["tau0"] == math.pi / 6 and values["tau"] == 3 * math.pi / 4


def test_bad_query_shows_message_and_keeps_defaults() -> None:
    ex = Explorer(query={"psi": [b"-3"], "mu": [b"0.3"]})
    assert ex.message.visible and "psi = -3 is outside the allowed range" in ex.message.object
    assert ex.state.psi == ExplorerState.param.psi.default
    assert ex.state.mu == 0.3  # the good value is still applied
    assert_sources_match_core(ex)


def test_good_query_sets_state_and_round_trips() -> None:
    ex = Explorer(query={"psi": "12.5", "tau0": "-0.2", "tau": "2.5", "log_psi": "1"})
    assert not ex.message.visible
    assert (ex.state.psi, ex.state.tau0, ex.state.tau, ex.state.log_psi) == (12.5, -0.2, 2.5,
                                                                             True)
    assert_sources_match_core(ex)
    again, messages = parse_query(ex.state.query())
    assert messages == [] and again["psi"] == 12.5 and again["tau"] == 2.5


@pytest.mark.parametrize("name", list(PRESETS))
def test_a_link_restores_the_very_state_preset_included(name: str) -> None:
    ex = Explorer(query={"preset": name})
    ex.contact.controls.psi_slider.value = ex.state.psi  # no change
    shared = Explorer(query=ex.state.query())
    assert shared.state.query() == ex.state.query()
    assert shared.state.preset == name and not shared.message.visible
    assert (shared.state.psi, shared.state.tau0, shared.state.tau) == (
        ex.state.psi, ex.state.tau0, ex.state.tau)


# --------------------------------------------------------------------- CSV


def read_csv(text: str) -> dict[str, np.ndarray]:
    """The columns of a CSV download, after its '#' lines and its line of names."""
    lines = text.splitlines()
    k = next(i for i, line in enumerate(lines) if not line.startswith("#"))
    names = lines[k].split(",")
    body = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=k + 1, ndmin=2)
    return {n: body[:, i] for i, n in enumerate(names)}


def test_csv_curves_hold_the_plotted_data(ex: Explorer) -> None:
    text = ex.contact.csv_text("curves")
    assert not re.search(r"(^|,)-0(,|$)", text, re.MULTILINE)  # no negative zeros
    table = read_csv(text)
    assert list(table) == ["tau (rad)", "T/T0", "mu P/T0", "-mu P/T0", "alpha/(H-h)", "a/a*",
                           "b/a*", "v2/(omega u0)", "u2/u0", "(du_x0/dt)/(omega u0)",
                           "u_x0/u0"]
    c = contact_of(ex)
    np.testing.assert_allclose(table["tau (rad)"], c.tau_grid(CURVE_POINTS), rtol=1e-9)
    np.testing.assert_allclose(table["T/T0"], c.tangential_force(table["tau (rad)"]),
                               atol=1e-9)
    np.testing.assert_allclose(table["b/a*"], ex.contact.radii.source.data["b"], rtol=1e-9,
                               atol=1e-12)


def test_csv_traction_and_impulse(ex: Explorer) -> None:
    tr = read_csv(ex.contact.csv_text("traction"))
    np.testing.assert_allclose(tr["tau_u/(mu p*)"], ex.contact.traction.source.data["traction"],
                               atol=1e-9)
    im = read_csv(ex.contact.csv_text("impulse"))
    np.testing.assert_allclose(im["T_imp/(mu P_imp)"], impulse_ratio(im["psi"], ex.state.tau0),
                               rtol=1e-8, atol=1e-12)
    assert (ex.contact.controls.downloads["impulse"].callback().read() ==
            ex.contact.csv_text("impulse"))
    assert (ex.contact.controls.downloads["impulse"].filename ==
            "zharii_impulse_psi2.414_tau0_0.5236_mu0.2_nu0.3.csv")
    assert (ex.contact.controls.downloads["traction"].callback().read() ==
            ex.contact.csv_text("traction"))
    assert ex.contact.controls.downloads["traction"].filename == (
        "zharii_traction_psi2.414_tau0_0.5236_mu0.2_nu0.3_tau2.225.csv")


def test_download_named_after_the_parameters_at_the_click(ex: Explorer) -> None:
    ex.state.psi = 7.5
    download = ex.contact.controls.downloads["curves"]
    download._clicks += 1  # what a click in the browser does
    assert download.filename.startswith("zharii_curves_psi7.5_")
    head, b64 = download.data.split(",", 1)
    assert head.endswith(";base64")
    assert base64.b64decode(b64).decode() == ex.contact.csv_text("curves")


# --------------------------------------------------------------- animation


def test_step_advances_tau_and_wraps(ex: Explorer) -> None:
    c = contact_of(ex)
    ex.state.tau = c.tau0
    ex.contact.controls.speed_slider.value = 2.0
    new = ex.contact.animation.step(0.1)
    assert new == pytest.approx(c.tau0 + 2.0 * (c.tau_end - c.tau0) * 0.1 / CONTACT_SECONDS)
    assert ex.state.tau == new
    assert_sources_match_core(ex)
    ex.state.tau = c.tau_end - 1e-3
    assert ex.contact.animation.step(0.5) == c.tau_end  # the last frame lands on the end of contact
    assert ex.contact.animation.step() == c.tau0  # then the contact starts again


def test_step_button_and_play_toggle(ex: Explorer, monkeypatch) -> None:
    tau = ex.state.tau
    ex.contact.controls.step_button.clicks += 1
    assert ex.state.tau > tau
    c = contact_of(ex)
    ex.state.tau = c.tau0
    ex.contact.controls.play_button.clicks += 1
    assert ex.state.playing and "Pause" in ex.contact.controls.play_button.label
    progress, started, _ = ex.contact.animation.started
    assert progress == 0.0
    now = [started]
    monkeypatch.setattr(app.contact.animation.time, "monotonic", lambda: now[0])
    # the browser's player shows the frames; the server follows its clock (the state
    # keeps the tau the play started from), and a change made while playing goes on
    # from the player's place in the contact
    now[0] += 1.53  # (off the frame boundaries: 1.53 s = 91.8 frames)
    progress = ex.state.speed * 1.53 / CONTACT_SECONDS
    expected = frame_taus(c)[frame_index(progress)]
    assert ex.contact.animation.clock_tau() == expected and ex.state.tau == c.tau0
    ex.contact.controls.speed_slider.value = 2.0  # the pace changes, the place stays
    assert ex.contact.animation.started == (pytest.approx(progress, abs=1e-9), now[0], 2.0)
    assert ex.contact.animation.clock_tau() == expected and ex.state.tau == c.tau0
    ex.contact.controls.speed_slider.value = 1.0
    now[0] += 0.23
    ex.contact.controls.play_button.clicks += 1  # pause: the plots settle on the frame being shown
    assert not ex.state.playing and "Play" in ex.contact.controls.play_button.label
    progress += 0.23 / CONTACT_SECONDS  # at speed 1 again
    assert ex.state.tau == frame_taus(c)[frame_index(progress)]
    assert ex.contact.controls.tau_slider.value == ex.state.tau
    assert len(ex.contact.player.frames.data) == 0
    assert_sources_match_core(ex)


def test_play_sends_the_frames_of_the_contact(ex: Explorer) -> None:
    """The browser's player only copies frames: each one is what core computes."""
    ex.state.playing = True
    c = contact_of(ex)
    taus = frame_taus(c)
    f, p = ex.contact.player.frames.data, ex.contact.player.profiles.data
    eq(f["tau"], taus)
    eq(f["a"], c.contact_radius(taus))
    eq(f["b"], c.stick_radius(taus))
    eq(f["phase"], c.phase(taus))
    eq(f["force:T"], c.tangential_force(taus))
    eq(f["force:muP"], c.normal_force(taus))
    eq(f["radii:b"], c.stick_radius(taus))
    eq(f["motion:u2"], c.centre_displacement(taus))
    assert f["caption"][0].startswith(f"τ = {c.tau0:.4f} rad")
    # the tau box's text
    assert f["tau_text"] == [ex.contact.controls.tau_slider.text(t) for t in taus]
    shape = (taus.size, PROFILE_POINTS + 4)
    r = np.asarray(p["r"]).reshape(shape)
    eq(np.asarray(p["traction"]).reshape(shape), c.traction(r, taus[:, None]))
    eq(np.asarray(p["upper"]).reshape(shape), c.pressure(r, taus[:, None]))
    # a parameter change while playing sends the new contact's frames
    ex.contact.controls.psi_slider.value = 6.46
    c = contact_of(ex)
    eq(ex.contact.player.frames.data["force:T"], c.tangential_force(frame_taus(c)))
    ex.state.playing = False
    assert len(ex.contact.player.frames.data) == 0 and len(ex.contact.player.profiles.data) == 0


def test_the_player_writes_the_pages_tau_box_slider_and_formulas() -> None:
    """In a page, the player's script is given the models of the tau box, the tau
    slider and the formula card (found by their tags) and each phase's formulas."""
    ex = Explorer()
    doc = Document()
    doc.add_root(ex.view().get_root(doc))
    args = ex.contact.player.script.args
    assert args["entry"] is None  # nothing looked up before Play
    ex.state.playing = True
    args = ex.contact.player.script.args
    assert args["entry"].value == ex.contact.controls.tau_slider.text(ex.state.tau)
    assert args["slider"].value == ex.state.tau and args["slider"].end == ex.state.current.tau_end
    assert args["formula"].text == formulas(int(ex.state.current.phase(ex.state.tau)))
    assert args["formulas"] == [formulas(p) for p in Phase]
    assert {args[k].document for k in ("entry", "slider", "formula")} == {doc}


def test_each_figures_renderers_share_one_filter_of_all_rows() -> None:
    """Bokeh gives each glyph's view a filter of its own, and each source a selection
    policy; the page's figures give all their renderers one of each
    (`app.kit.figures.lean`): one model per figure, not per glyph, indexed by Bokeh on
    every message."""
    from bokeh.models import AllIndices, GlyphRenderer
    from bokeh.plotting import figure

    doc = Document()
    doc.add_root(Explorer().view().get_root(doc))
    figures = [m for m in doc.models if isinstance(m, figure)]
    assert len(figures) >= 4
    for fig in figures:
        filters = {id(r.view.filter) for r in fig.renderers if isinstance(r, GlyphRenderer)
                   and isinstance(r.view.filter, AllIndices)}
        assert len(filters) <= 1, fig.title.text
        policies = {id(r.data_source.selection_policy) for r in fig.renderers
                    if isinstance(r, GlyphRenderer)}
        assert len(policies) == 1, fig.title.text  # (one selection policy per figure)
    assert sum(isinstance(m, AllIndices) for m in doc.models) <= len(figures)


def test_the_formula_card_follows_the_phase_in_its_page() -> None:
    """In a page's document, a move to another phase writes that phase's formulas, and
    nothing else, into the formula card's model (past Panel's update of the pane,
    `app.kit.texts.PaneText`: Panel's watchers of the pane are not called), with no
    model added; a move within the phase writes nothing.  The page is built as a
    server builds it, in its document (the formulas are first written before the pane
    is rendered; the request's guard is the document's first root, `app.page.guard`)."""
    from bokeh.document.events import ModelChangedEvent
    from panel.io import hold
    from panel.io.state import set_curdoc

    from app.page.pulls import PullGuard

    doc = Document()
    doc.add_root(PullGuard())
    with set_curdoc(doc):
        ex = Explorer()
        doc.add_root(ex.view().get_root(doc))
    [model] = [m for m in doc.models if "formulas" in m.tags]
    events: list = []
    doc.on_change(lambda e: events.append(e))
    panels: list = []  # (Panel's own update of the pane)
    ex.contact.controls.formulas.param.watch(panels.append, "object")
    with set_curdoc(doc):
        for psi, tau in ((0.5, 1.0), (0.6, 1.0), (3.0, 1.0), (3.0, 2.2)):
            models = set(doc.models)
            events.clear()
            with hold(doc):
                ex.state.param.update(psi=psi, tau=tau)
            phase = int(ex.state.current.phase(tau))
            assert model.text == ex.contact.controls.formulas.object == formulas(phase)
            assert set(doc.models) == models
            written = [e.attr for e in events
                       if isinstance(e, ModelChangedEvent) and e.model is model]
            assert written == (["text"] if psi != 0.6 else []), (psi, tau)
    assert panels == []


# ---------------------------------------------------------- physical units


def test_physical_inputs_give_si_scales(ex: Explorer) -> None:
    s = ex.state
    s.param.update(R=0.005, H=2e-6, u0=3e-6, h=1e-6, omega=2 * math.pi * 30e3)
    ex.contact.controls.material_select.value = "steel"
    ex.contact.controls.physical_box.value = True
    c = Contact.from_physical(R=0.005, G=s.G, nu=s.nu, mu=s.mu, H=2e-6, u0=3e-6, h=1e-6,
                              omega=2 * math.pi * 30e3)
    assert (s.psi, s.tau0) == (c.psi, c.tau0)
    assert ex.contact.controls.psi_slider.disabled and ex.contact.controls.tau0_slider.disabled
    assert_sources_match_core(ex)
    assert f"{c.scales.T0:.4g} N" in [v for _, v in readout_rows(ex)]
    table = read_csv(ex.contact.csv_text("curves"))
    np.testing.assert_allclose(table["T (N)"], table["T/T0"] * c.scales.T0, rtol=1e-9)
    assert " N\na = " in ex.contact.traction.caption.text


def test_each_change_is_shown_once_corrections_included(ex: Explorer, monkeypatch) -> None:
    """The state corrects itself (tau clamped, psi and tau0 from SI inputs) and a scene
    draws the result once: what depends on the contact once per contact change, the
    time once per change (of tau or of the contact), nothing for a value already
    shown."""
    calls = {"update_contact": 0, "update_tau": 0}
    scene = ex.contact.traction

    def counting(name: str):
        method = getattr(scene, name)

        def counted(*args) -> None:
            calls[name] += 1
            method(*args)
        return counted

    for name in calls:
        monkeypatch.setattr(scene, name, counting(name))

    def shown(update_contact: int, update_tau: int) -> None:
        assert calls == {"update_contact": update_contact, "update_tau": update_tau}
        calls.update(update_contact=0, update_tau=0)
        assert_sources_match_core(ex)
        assert ex.contact.controls.tau_slider.value == ex.state.tau

    ex.state.tau = 2.5
    shown(0, 1)
    ex.state.tau = 2.5  # already shown
    shown(0, 0)
    ex.contact.controls.tau0_slider.value = 1.0  # tau = 2.5 is past the end of contact pi - 1
    assert ex.state.tau == math.pi - 1.0
    shown(1, 1)
    ex.contact.controls.physical_box.value = True  # psi and tau0 follow from the SI inputs
    c = Contact.from_physical(**{k: getattr(ex.state, k) for k in (
        "R", "G", "nu", "mu", "H", "u0", "h", "omega")})
    assert (ex.state.psi, ex.state.tau0, ex.state.tau) == (c.psi, c.tau0, math.pi - 1.0)
    shown(1, 1)
    ex.state.R *= 2  # the same psi and tau0, other SI scales (a*, T0)
    assert ex.state.current.scales.a_star == pytest.approx(c.scales.a_star * math.sqrt(2))
    shown(1, 1)
    ex.state.H = 4e-6  # psi and tau0 change with H; tau clamps into the new contact
    assert ex.state.tau0 == pytest.approx(math.asin(0.25)) and ex.state.tau == math.pi - 1.0
    shown(1, 1)


def test_invalid_physical_inputs_show_a_message(ex: Explorer) -> None:
    ex.contact.controls.physical_box.value = True
    psi = ex.state.psi
    ex.state.h = 5 * ex.state.H  # h must be < H
    # said once, under the boxes, not above the plots
    pane = ex.contact.controls.physical_inputs.refusal
    assert pane.visible and "(-H, H)" in pane.object and not ex.message.visible
    assert ex.state.psi == psi and ex.state.current == contact_of(ex)


# ------------------------------------------------------------------- motor


def test_the_motor_card_is_built_when_opened_and_drives_the_scenes_when_asked(
        ex: Explorer) -> None:
    """The Motor card's contact reaches the plots only when its box is ticked (opening
    the card used to replace the explorer's contact); unticked, the explorer's own
    contact is back; a contact input the user changes ends the following."""
    assert ex.motor is None  # nothing built or computed until the card opens
    own = (ex.state.psi, ex.state.tau0, ex.state.mu, ex.state.nu)
    ex.motor_card.collapsed = False
    assert ex.motor is not None
    assert not ex.follow_motor.value
    assert (ex.state.psi, ex.state.tau0, ex.state.mu, ex.state.nu) == own
    assert {"motor_x0", "motor_rod", "motor_rotor"} <= set(ex.query())
    ex.follow_motor.value = True  # the plots show the rotor's contact
    psi, tau0 = ex.motor.contact
    m = ex.motor.state
    assert (ex.state.psi, ex.state.tau0, ex.state.mu, ex.state.nu) == (psi, tau0, m.mu, m.nu)
    assert_sources_match_core(ex)
    # the banner says why the contact's inputs changed, and how to get one's own back
    assert ex.message.visible and "the rotor&#x27;s contact at x₀" in ex.message.object
    assert f"ψ = {psi:.4g}" in ex.message.object
    ex.motor.state.x0 = ex.motor.state.x0 / 2  # and follow it
    assert ex.motor.contact[0] != psi and ex.state.psi == ex.motor.contact[0]
    ex.follow_motor.value = False  # the explorer's own contact again
    assert (ex.state.psi, ex.state.tau0, ex.state.mu, ex.state.nu) == own
    assert_sources_match_core(ex)
    assert not ex.message.visible
    ex.follow_motor.value = True
    ex.contact.controls.psi_slider.value = 3.0  # the user takes the contact over
    assert not ex.follow_motor.value and ex.state.psi == 3.0
    x0 = ex.motor.state.x0
    ex.motor.state.x0 = x0 / 2
    assert ex.state.psi == 3.0


def test_a_motor_link_opens_the_motor_and_restores_it() -> None:
    ex = Explorer(query={"motor_x0": "-0.2", "motor_rotor": "alumina"})
    assert not ex.motor_card.collapsed and ex.motor is not None
    assert ex.messages == [] and not ex.message.visible
    assert ex.motor.query()["motor_x0"] == "-0.2"
    assert ex.motor.query()["motor_rotor"] == "alumina"
    bad = Explorer(query={"motor_x0": "abc"})
    assert bad.message.visible and "motor" in bad.message.object


def contrast_on_white(color: str) -> float:
    """WCAG 2 contrast ratio of `color` ('#rrggbb') on white."""
    def linear(c: float) -> float:
        return c / 12.92 if c <= 0.03928 else ((c + 0.055) / 1.055) ** 2.4
    r, g, b = (linear(int(color[i:i + 2], 16) / 255) for i in (1, 3, 5))
    return 1.05 / (0.2126 * r + 0.7152 * g + 0.0722 * b + 0.05)


@pytest.mark.parametrize("phase", list(Phase))
def test_phase_colours_read_on_white(phase: Phase) -> None:
    look = STYLES[phase]
    assert contrast_on_white(look.color) >= 3.0
    assert contrast_on_white(look.ring_color) >= 3.0
    assert look.name == PHASE_NAMES[phase]  # the name says it without colour


def test_contrast_ratio_matches_wcag_examples() -> None:
    assert contrast_on_white("#000000") == pytest.approx(21.0)
    assert contrast_on_white("#ffffff") == pytest.approx(1.0)
    assert contrast_on_white("#767676") == pytest.approx(4.54, abs=0.01)  # WebAIM's value


@pytest.mark.parametrize("psi", [0.4, SQRT2_1])
def test_time_axes_mark_the_papers_landmarks(ex: Explorer, psi: float) -> None:
    ex.contact.controls.psi_slider.value = psi
    assert_sources_match_core(ex)  # opens every tab
    c = contact_of(ex)
    expected = [c.tau0, math.pi / 2, *([] if psi <= 1 else [c.tau1]), c.tau_end]
    for scene in (ex.contact.force, ex.contact.radii, ex.contact.motion):
        d = scene.landmarks.data
        assert d["x"] == expected
        assert d["label"] == ["τ₀", "π/2", *([] if psi <= 1 else ["τ₁"]), "π−τ₀"]
        assert d["align"] == ["left", "center", *([] if psi <= 1 else ["center"]), "right"]
        assert d["hi"] == [scene.figures[0].y_range.end] * len(expected)
        # tau1 a line lower than its neighbours (pi - tau0 for psi near 1, pi/2 for large
        # psi: a few px apart on a phone)
        assert d["dy"] == [2, 2, *([] if psi <= 1 else [18]), 2]


# ---------------------------------------------------------- the two spheres


@pytest.mark.parametrize(("psi", "tau0", "tau"), [(SQRT2_1, math.pi / 6, 2.3),
                                                  (0.5, -0.4, 1.0), (40.0, 1.2, 1.6)])
def test_the_spheres_are_drawn_from_core(psi: float, tau0: float, tau: float) -> None:
    """The drawing at tau: the lower sphere moved along its drive line (eq 3), both
    flattened at the midway plane, the patch of radius a and stick disc b (core's, on the
    drawn scale), arrows P / P0 and T / T0, the phase named in its colour."""
    ex = Explorer()
    ex.state.param.update(psi=psi, tau0=tau0, tau=tau)
    c, s = contact_of(ex), ex.contact.spheres.sources
    H, u0 = spheres.drawn_amplitudes(c)
    assert H == spheres.DRIVE
    assert u0 == pytest.approx(min(spheres.DRIVE * psi * math.tan(c.theta0), spheres.MAX_SIDE))
    lower, upper = s["spheres_lower"].data, s["spheres_upper"].data
    overlap = H * (math.sin(tau) - math.sin(tau0))
    mid = overlap / 2
    assert max(lower["y"]) == pytest.approx(mid) and min(upper["y"]) == pytest.approx(mid)
    centre_x = (max(lower["x"]) + min(lower["x"])) / 2
    assert centre_x == pytest.approx(u0 * math.sin(tau), abs=1e-12)
    assert min(lower["y"]) == pytest.approx(-2.0 - H * math.sin(tau0) + H * math.sin(tau))
    a_star = math.sqrt(H * (1 - math.sin(tau0)) / 2)
    a, b = float(c.contact_radius(tau)) * a_star, float(c.stick_radius(tau)) * a_star
    patch = s["spheres_patch"].data
    xc = centre_x / 2
    np.testing.assert_allclose(patch["x0"], [xc - a, xc - b, xc + b], atol=1e-12)
    np.testing.assert_allclose(patch["x1"], [xc - b, xc + b, xc + a], atol=1e-12)
    look = STYLES[Phase(int(c.phase(tau)))]
    assert list(patch["color"]) == [look.ring_color, STYLES[Phase.FULL_STICK].color,
                                    look.ring_color]
    f = s["spheres_forces"].data
    P, T = float(c.normal_force(tau)), float(c.tangential_force(tau))
    # one physical unit for both (T / P0 = mu T / T0): the largest P (mu = 0.2) ARROW long
    unit = spheres.ARROW / float(c.normal_force(math.pi / 2))
    np.testing.assert_allclose(np.subtract(f["y1"], f["y0"]), [unit * P, 0], atol=1e-12)
    np.testing.assert_allclose(np.subtract(f["x1"], f["x0"]), [0, unit * c.mu * T],
                               atol=1e-12)
    assert list(f["label"]) == [f"P = {P:.3g} P₀", f"T = {T:+.3g} T₀"]
    bound = s["spheres_bound"].data  # the Coulomb bound +-mu P, about the arrows' foot
    np.testing.assert_allclose(np.subtract(bound["x0"], f["x0"][1]),
                               [-unit * c.mu * P, unit * c.mu * P], atol=1e-12)
    assert s["spheres_badge"].data["text"] == [look.name]
    assert s["spheres_badge"].data["color"] == [look.color]


def test_the_spheres_note_states_the_scale() -> None:
    ex = Explorer()
    assert ex.contact.spheres.note.text == "not to scale: H as 0.15 R"
    ex.state.param.update(R=0.01, H=2e-6, u0=1e-6, h=1e-6, omega=1e5)
    ex.contact.controls.physical_box.value = True
    assert ex.contact.spheres.note.text == f"displacements drawn ×{0.15 * 0.01 / 2e-6:.3g}"
    ex.contact.controls.physical_box.value = False
    ex.state.psi = 1e4  # u0 beyond the drawing: shortened, and said so
    assert ex.contact.spheres.note.text == "not to scale: H as 0.15 R, u₀ ≤ 0.45 R"


def test_the_player_animates_the_spheres() -> None:
    """The frames of each spheres source are its drawing at the frame times."""
    ex = Explorer()
    ex.state.playing = True
    c = contact_of(ex)
    taus = frame_taus(c)
    for name, cols in spheres.drawing(c, taus).items():
        data = ex.contact.player.sprite_frames[name].data
        for col, v in cols.items():
            assert list(np.asarray(data[col])) == list(v.ravel()), (name, col)
    ex.state.playing = False
    assert all(len(src.data) == 0 for src in ex.contact.player.sprite_frames.values())


# ---------------------------------------------------------- the paper's figures in full


def test_fig9_has_two_panels_and_draws_the_velocity_jumps(ex: Explorer) -> None:
    """v2 jumps at tau0 (from rest), at tau1 (partial stick to counter-slip) and at
    pi - tau0 (to rest): the grid holds a time just outside each jump, so the curve
    steps from core's value on one side to core's value on the other."""
    ex.contact.tabs.active = ex.contact.tabbed.index(ex.contact.motion)
    c = contact_of(ex)
    assert [f.title.text for f in ex.contact.motion.figures] == [
        "Contact-centre velocity (Fig. 9a)", "Contact-centre displacement (Fig. 9b)"]
    assert ex.contact.motion.figure.children == ex.contact.motion.figures  # one above the other
    d = {k: np.asarray(v) for k, v in ex.contact.motion.source.data.items()}
    tau, v2 = d["tau"], d["v2"]
    eq(v2, c.centre_velocity(tau))
    eq(d["u2"], c.centre_displacement(tau))
    span = c.tau_end - c.tau0
    assert tau[0] < c.tau0 - 0.09 * span and tau[-1] > c.tau_end + 0.09 * span
    for jump in (c.tau0, c.tau1, c.tau_end):
        i = int(np.searchsorted(tau, jump))
        if jump == c.tau_end:
            i += 1  # pi - tau0 is the last time in contact
        before, after = tau[i - 1], tau[i]
        assert after - before <= 1.01e-6 * span, jump
        assert abs(v2[i] - v2[i - 1]) > 0.1, (jump, v2[i - 1], v2[i])  # drawn as a step
    assert v2[0] == 0 and v2[-1] == 0  # at rest outside the contact
    # the markers of each panel are drawn in that panel's range
    m = ex.contact.motion.marker.data
    ranges = [ex.contact.motion.figures[0].y_range, ex.contact.motion.figures[1].y_range] * 2
    assert m["lo"] == [r.start for r in ranges] and m["hi"] == [r.end for r in ranges]


def test_fig8_marks_the_psi_of_fig7(ex: Explorer) -> None:
    ex.contact.tabs.active = ex.contact.tabbed.index(ex.contact.impulse)
    d = ex.contact.impulse.points.data
    psi = [0.4, 0.8, 1.0, 2.41, 6.46, 28.35]
    eq(d["psi"], psi)
    eq(d["ratio"], impulse_ratio(np.array(psi), ex.state.tau0))
    assert d["label"] == ["1", "2", "3", "4", "5", "6"]


def test_fig4_shows_the_drive_and_the_fig6_times(ex: Explorer) -> None:
    ex.contact.tabs.active = ex.contact.tabbed.index(ex.contact.radii)
    c = contact_of(ex)
    drive = {k: np.asarray(v) for k, v in ex.contact.radii.drive.data.items()}
    eq(drive["uz"], np.sin(drive["tau"]))  # u_z0 / H (eq 3)
    inside = (drive["tau"] >= c.tau0) & (drive["tau"] <= c.tau_end)
    eq(drive["touch"][inside], drive["uz"][inside])
    assert np.isnan(drive["touch"][~inside]).all()
    assert ex.contact.radii.levels.data["y"] == [math.sin(c.tau0), 1.0]
    disks = ex.contact.radii.disks.data
    eq(disks["tau"], [math.pi / 4, math.pi / 3, math.pi / 2, 7 * math.pi / 12,
                      17 * math.pi / 24, 3 * math.pi / 4])
    eq(disks["a"], c.contact_radius(disks["tau"]))
    assert disks["label"] == list("abcdef")
    ex.contact.controls.tau0_slider.value = 1.2  # a short contact holds only some of the times
    c = contact_of(ex)
    assert all(c.tau0 <= t <= c.tau_end for t in ex.contact.radii.disks.data["tau"])
    assert ex.contact.radii.disks.data["label"] == ["c", "d"]  # pi/2, 7 pi/12 in [1.2, 1.94]


def test_fig6_small_multiples_are_the_six_profiles_of_the_paper(ex: Explorer) -> None:
    """One click (the card) shows Fig. 6a-f: each panel the traction core gives at its
    preset's time, titled with the time and the phase (core's rule: 6f at tau1 is
    counter-slip)."""
    assert ex.contact.fig6_card.objects == []  # built on first opening
    ex.contact.fig6_card.collapsed = False
    (pane,) = ex.contact.fig6_card.objects
    titles = [fig.title.text for fig, *_ in pane.object.children]
    assert titles == ["6a: τ = π/4, slip", "6b: τ = π/3, slip", "6c: τ = π/2, slip",
                      "6d: τ = 7π/12, partial stick", "6e: τ = 17π/24, partial stick",
                      "6f: τ = 3π/4, counter-slip"]
    for (fig, *_), key in zip(pane.object.children, ("fig6a", "fig6b", "fig6c", "fig6d",
                                                     "fig6e", "fig6f"), strict=True):
        p = PRESETS[key]
        c = Contact(p.psi, p.tau0)
        (source,) = {r.data_source for r in fig.renderers}
        r = np.asarray(source.data["r"])
        eq(source.data["traction"], c.traction(r, p.tau))
        eq(source.data["upper"], c.pressure(r, p.tau))
        b = float(c.stick_radius(p.tau))
        assert (np.asarray(source.data["stick_hi"]) > 0).any() == (b > 0)


def test_each_preset_says_what_to_notice(ex: Explorer) -> None:
    """Every preset has its note, shown while it is on screen and faded in its place once
    left (no layout shift); the notes' checkable claims hold."""
    assert set(NOTES) == set(PRESETS)
    note = ex.contact.controls.note
    for key in PRESETS:
        ex.contact.controls.preset_select.value = key
        assert note.visible and note.object == html.escape(NOTES[key])
        assert "opacity" not in note.styles
    ex.contact.controls.psi_slider.value = 3.0  # leaves the preset
    assert note.visible and note.object == html.escape(NOTES[key])  # the box stays...
    assert float(note.styles["opacity"]) < 0.6  # ...faded
    ex.contact.controls.preset_select.value = "fig6e"
    assert "opacity" not in note.styles
    c = Contact(SQRT2_1, math.pi / 6)
    assert c.tau1 == pytest.approx(3 * math.pi / 4)  # figs 4, 6f
    assert int(c.phase(math.pi / 4)) == Phase.SLIP == int(c.phase(math.pi / 2))  # 6a-6c
    assert int(c.phase(7 * math.pi / 12)) == Phase.PARTIAL_STICK  # 6d
    assert float(c.stick_radius(math.pi / 2 + 1e-9)) == pytest.approx(
        float(c.contact_radius(math.pi / 2)), rel=1e-6)  # b starts as large as a
    T = c.tangential_force(np.array([math.pi / 2, 7 * math.pi / 12, 17 * math.pi / 24]))
    assert T[1] > 0 > T[2] and abs(T[2]) < 0.15 * T[0]  # 6e: T changed sign, small
    assert int(c.phase(PRESETS["fig6f"].tau)) == Phase.COUNTER_SLIP  # 6f, at tau1
    for psi in (0.4, 0.8, 1.0):  # 7a: full stick, symmetric about pi/2
        c = Contact(psi, math.pi / 6)
        tau = np.linspace(c.tau0, c.tau_end, 101)
        assert set(c.phase(tau[1:-1]).tolist()) == {Phase.FULL_STICK}
        np.testing.assert_allclose(c.tangential_force(tau), c.tangential_force(tau[::-1]),
                                   atol=1e-12)
    taus = [Contact(p, math.pi / 6).tau1 for p in (2.41, 6.46, 28.35)]  # 7b
    np.testing.assert_allclose(taus, [3 * math.pi / 4, 2 * math.pi / 3, 7 * math.pi / 12],
                               atol=2e-3)
    ratios = impulse_ratio(np.array([0.5, 1.0, 2.0]), math.pi / 6)  # 8: largest at 1
    assert ratios[1] > ratios[0] and ratios[1] > ratios[2]


def test_the_view_is_chosen_by_the_url_and_kept_in_it() -> None:
    ex = Explorer(query={"view": "present", "psi": "3"})
    assert ex.view_name == "present" and ex.messages == [] and ex.state.psi == 3.0
    root = ex.view().get_root(Document())  # the one-screen page (sizes: browser test)
    assert root.select_one({"name": "spheres_badge"}) is not None
    from app.page.presentation import BADGE_FONT
    assert ex.contact.spheres.badge.glyph.text_font_size == BADGE_FONT != "20pt"
    ex = Explorer(query={"view": "<b>x</b>"})
    assert ex.view_name == "" and ex.messages == [
        "view = '<b>x</b>' is unknown (known: present, student); the full page is shown"]
    assert "&lt;b&gt;" in ex.message.object  # shown as text


def test_reset_and_the_physical_inputs_clear_a_refusal_message() -> None:
    """"theta = 95 ..." stayed under its box after Reset and after the switch to the
    physical inputs, quoting a value no longer on screen."""
    ex = Explorer()
    controls = ex.contact.controls
    controls.theta_slider._entry.value = "95"  # typed in the box
    assert "theta = 95" in controls.theta_slider.error
    controls.reset_button.clicks += 1
    assert controls.theta_slider.error == ""
    controls.psi_slider._entry.value = "-1"
    assert controls.psi_slider.error
    controls.physical_box.value = True
    assert controls.psi_slider.error == ""


def test_the_impulse_ratio_keeps_its_digits_at_large_psi() -> None:
    """The readout said T_imp / (mu P_imp) = 0.00000 at psi = 1e12 (it decays as
    psi^(-1/2), Fig. 8): five significant digits at any psi."""
    c = Contact(1e12, math.pi / 6)
    rows = dict(data.readout_rows(c))
    assert float(rows["T_imp / (μ P_imp)"]) == pytest.approx(c.impulse_ratio, rel=1e-4)
    assert c.impulse_ratio < 1e-5


def test_fig7s_family_is_painted_over_the_contacts_own_curve() -> None:
    """Fig. 7a's psi = 0.8 (7b's 6.46) is both the contact on screen and a member of the
    family: its legend entry's curve lay under the thick black curve, on the glyph layer
    below the overlay the contact's curves are painted on."""
    from bokeh.models import GlyphRenderer, MultiLine

    ex = Explorer(query={"preset": "fig7a"})
    fig = ex.contact.force.figure
    fig = fig if hasattr(fig, "renderers") else fig.children[0]
    renderers = [r for r in fig.renderers if isinstance(r, GlyphRenderer)]
    family = next(r for r in renderers if isinstance(r.glyph, MultiLine))
    curve = next(r for r in renderers if r.data_source is ex.contact.force.source
                 and getattr(r.glyph, "y", None) == "T")
    assert family.level == curve.level
    assert renderers.index(family) > renderers.index(curve)  # painted after it
    assert 0.8 in [float(lbl.split("= ")[1]) for lbl in family.data_source.data["label"]]
