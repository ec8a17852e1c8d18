"""The "Physical inputs" card (app/physical_inputs.py): units people think in, typed text
checked at the boxes, advisory warnings, core's refusals under the boxes, materials and
the SI state in the URL.

Document tests change the boxes as the browser does (their `value`, the text typed in the
box's unit) and compare with `core`; the browser test types in Chromium and reads what is
shown.
"""

from __future__ import annotations

import html
import json
import math
from concurrent.futures import ThreadPoolExecutor
from urllib.parse import parse_qs, urlencode, urlsplit

import pytest
from explorer_browser import open_explorer

import core
from app.contact.physical_inputs import FIELDS, REFUSED, box_text, display, to_si, to_user, warning
from app.contact.query import parse_query
from app.contact.state import SI_KEYS
from app.page.explorer import Explorer
from core import DOMAIN, DRY_MU, MATERIALS, Contact

#: The SI value of one box unit: mm, GPa, µm, and kHz of f in rad/s.
UNIT_IN_SI = {"R": 1e-3, "G": 1e9, "H": 1e-6, "u0": 1e-6, "h": 1e-6, "omega": 2e3 * math.pi}


@pytest.fixture
def ex() -> Explorer:
    return Explorer()


def box_values(ex: Explorer) -> dict[str, float]:
    """The numbers the boxes show (their text)."""
    return {k: float(b.value) for k, b in ex.contact.controls.physical_inputs.boxes.items()}


def note(ex: Explorer, name: str) -> str:
    """The text under the box of `name` ('' when hidden), unescaped."""
    pane = ex.contact.controls.physical_inputs.notes[name]
    return html.unescape(pane.object) if pane.visible else ""


def physical_contact(ex: Explorer) -> Contact:
    s = ex.state
    return Contact.from_physical(**{k: getattr(s, k) for k in (*SI_KEYS, "mu", "nu")})


# ----------------------------------------------------------------------- units


def test_the_boxes_show_mm_gpa_micrometres_and_khz(ex: Explorer) -> None:
    titles = [b.label.split(":")[0] for b in ex.contact.controls.physical_inputs.boxes.values()]
    assert titles == ["R (mm)", "G (GPa)", "H (µm)", "u₀ (µm)", "h (µm)", "f (kHz)"]
    s = ex.state
    shown = box_values(ex)
    assert shown == pytest.approx({k: getattr(s, k) / UNIT_IN_SI[k] for k in SI_KEYS},
                                  rel=1e-15)
    assert shown["omega"] == pytest.approx(s.omega / (2 * math.pi) / 1e3, rel=1e-15)
    # each number as its shortest text ("2", "79"), to 15 digits
    assert {k: b.value for k, b in ex.contact.controls.physical_inputs.boxes.items()} == {
        "R": "10", "G": "79", "H": "2", "u0": "1", "h": "1", "omega": "40"}
    assert all(v == float(f"{v:.15g}") for v in shown.values())


@pytest.mark.parametrize("name", SI_KEYS)
def test_the_conversion_is_exact_both_ways(name: str) -> None:
    f = FIELDS[name]
    lo, hi = f.sensible
    for typed in (lo, hi, 0.1, 1.0, 2.1, 79.3, 0.37, 12345.678, 0.0003):
        si = to_si(f, typed)
        if name == "omega":  # one multiplication by 2 pi each way
            assert si == pytest.approx(typed * 1e3 * 2 * math.pi, rel=2.3e-16)
            assert to_user(f, si) == pytest.approx(typed, rel=4.5e-16)
            assert display(f, si) == typed
        else:  # the decimal point moved: the float of the same decimal digits
            assert si == float(f"{typed!r}e{f.decade}")
            assert to_user(f, si) == typed
    assert to_si(FIELDS["H"], 2.1) == 2.1e-6 and to_si(FIELDS["G"], 79.3) == 79.3e9
    assert to_si(FIELDS["omega"], 40.0) == 2 * math.pi * 40e3


def test_typed_values_reach_the_contact_in_si(ex: Explorer) -> None:
    boxes = ex.contact.controls.physical_inputs.boxes
    ex.contact.controls.physical_box.value = True
    for name, typed in (("R", "5"), ("G", "26"), ("H", "2.5"), ("u0", " 1.2 "), ("h", "-0.5"),
                        ("omega", "3e1")):
        boxes[name].value = typed
    expected = Contact.from_physical(R=0.005, G=26e9, nu=ex.state.nu, mu=ex.state.mu,
                                     H=2.5e-6, u0=1.2e-6, h=-0.5e-6,
                                     omega=2 * math.pi * 30e3)
    assert ex.state.current.scales == expected.scales
    assert (ex.state.psi, ex.state.tau0) == (expected.psi, expected.tau0)
    assert {k: b.value for k, b in boxes.items()} == {
        "R": "5", "G": "26", "H": "2.5", "u0": "1.2", "h": "-0.5", "omega": "30"}


def test_a_typed_decimal_is_kept_as_typed(ex: Explorer) -> None:
    """2.3 µm is the float of 2.3e-6 m, and the box shows "2.3" (not the float noise of
    2.3e-6 / 1e-6 = 2.3000000000000003); another text of the same value changes nothing
    and the box shows the value's own text."""
    box = ex.contact.controls.physical_inputs.boxes["H"]
    ex.contact.controls.physical_box.value = True
    psi = ex.state.psi
    for typed, H in (("2.1", 2.1e-6), ("2.2", 2.2e-6), ("2.3", 2.3e-6)):
        box.value = typed
        assert ex.state.H == H and box.value == typed
    assert 2.3e-6 / 1e-6 != 2.3 and box_text(FIELDS["H"], 2.3e-6) == "2.3"
    assert ex.state.psi == pytest.approx(psi * 2.0 / 2.3, rel=1e-14)  # psi ~ u0 / H
    assert ex.state.current.psi == physical_contact(ex).psi
    box.value = "2.30"  # the same value: nothing changes, the box shows its text
    assert ex.state.H == 2.3e-6 and note(ex, "H") == ""
    assert box.value in ("2.30", "2.3")  # (set back once the browser's entry is handled)


# -------------------------------------------------------------------- warnings


def test_the_sensible_ranges_are_those_of_the_issue() -> None:
    si = {k: tuple(to_si(FIELDS[k], v) for v in FIELDS[k].sensible) for k in SI_KEYS}
    assert si["R"] == (1e-4, 1.0) and si["G"] == (1e8, 1e12)
    assert si["H"][1] == si["u0"][1] == 1e-3 and si["h"] == (-1e-3, 1e-3)
    assert si["omega"] == pytest.approx((2 * math.pi, 2 * math.pi * 1e7), rel=1e-15)
    for k in SI_KEYS:  # advisory ranges inside what core accepts
        assert DOMAIN[k].contains(si[k][0]) and DOMAIN[k].contains(si[k][1])


@pytest.mark.parametrize(("name", "typed", "side"), [
    ("H", 1500.0, "above"), ("u0", 2000.0, "above"), ("h", -1500.0, "below"),
    ("R", 0.05, "below"), ("R", 2000.0, "above"), ("G", 0.05, "below"),
    ("G", 2000.0, "above"), ("omega", 0.0005, "below"), ("omega", 20000.0, "above")])
def test_a_value_outside_its_sensible_range_is_used_with_a_warning(
        ex: Explorer, name: str, typed: float, side: str) -> None:
    f = FIELDS[name]
    assert note(ex, name) == ""
    ex.contact.controls.physical_inputs.boxes[name].value = repr(typed)
    assert getattr(ex.state, name) == to_si(f, typed)  # used
    lo, hi = f.sensible
    assert note(ex, name) == (f"{f.symbol} = {typed:g} {f.unit} is {side} the sensible "
                              f"range {lo:g} … {hi:g} {f.unit}: is the unit right? "
                              "(a warning only: the value is used)")
    boxes = ex.contact.controls.physical_inputs.boxes
    boxes[name].value = box_text(f, ex.state.param[name].default)
    assert note(ex, name) == ""


def test_a_value_core_refuses_is_explained_under_its_box_and_kept_out(ex: Explorer) -> None:
    box = ex.contact.controls.physical_inputs.boxes["H"]
    H = ex.state.H
    box.value = "0"
    lo, hi = (DOMAIN["H"].lo * 1e6, DOMAIN["H"].hi * 1e6)
    assert note(ex, "H") == f"H (µm) = 0 is outside the allowed range [{lo:g}, {hi:g}]"
    assert ex.state.H == H and box.value == "2"  # the last good value again
    for text, shown in (("", "''"), ("2,5", "'2,5'"), ("<b>3</b>", "'<b>3</b>'")):
        box.value = text
        assert note(ex, "H") == (f"H (µm) must be a real number in [{lo:g}, {hi:g}], "
                                 f"got {shown}")
        assert ex.state.H == H and box.value == "2"
    assert "&lt;b&gt;" in ex.contact.controls.physical_inputs.notes["H"].object  # shown as text
    box.value = "nan"
    assert note(ex, "H").startswith("H (µm) must be a finite number")
    box.value = "3"
    assert note(ex, "H") == "" and ex.state.H == 3e-6


def test_inputs_core_refuses_together_show_core_words_under_the_boxes(ex: Explorer) -> None:
    ex.contact.controls.physical_box.value = True
    psi, pane = ex.state.psi, ex.contact.controls.physical_inputs.refusal
    assert not pane.visible
    ex.contact.controls.physical_inputs.boxes["h"].value = "3"  # h >= H = 2 µm
    with pytest.raises(ValueError) as err:
        core.PhysicalInputs(R=0.01, G=ex.state.G, nu=ex.state.nu, mu=ex.state.mu, H=2e-6,
                            u0=1e-6, h=3e-6, omega=ex.state.omega)
    assert "(-H, H)" in str(err.value)
    assert pane.visible and pane.object == html.escape(REFUSED + str(err.value))
    assert "&lt;" in pane.object and "<" not in pane.object  # shown as text
    assert ex.state.psi == psi and not ex.message.visible  # said once, here
    assert warning(FIELDS["h"], ex.state.h) == note(ex, "h") == ""  # 3 µm is sensible
    ex.contact.controls.physical_inputs.boxes["H"].value = "4"
    assert not pane.visible and ex.state.current.scales == physical_contact(ex).scales


# -------------------------------------------------------------------- material


def test_a_material_switches_the_physical_inputs_on(ex: Explorer) -> None:
    s = ex.state
    assert not s.physical and (s.mu, s.nu) == (0.2, 0.3)
    ex.contact.controls.material_select.value = "glass"
    m = MATERIALS["glass"]
    # never mu and nu of a dimensionless contact
    assert s.physical and ex.contact.controls.physical_box.value
    assert (s.G, s.nu, s.mu) == (m.G, m.nu, DRY_MU["glass"]) == (28.7e9, 0.22, 0.3)
    assert float(ex.contact.controls.physical_inputs.boxes["G"].value) == m.G / 1e9
    assert ex.state.current.scales == physical_contact(ex).scales
    assert ex.contact.controls.psi_slider.disabled and ex.state.query()["material"] == "glass"
    ex.contact.controls.mu_slider.value = 0.25  # another mu: no longer glass
    assert s.material == "custom" == ex.contact.controls.material_select.value
    assert "material" not in ex.state.query()
    ex.contact.controls.material_select.value = "steel"
    ex.contact.controls.preset_select.value = "fig6c"  # a preset: dimensionless, mu 0.2, nu 0.3
    assert not s.physical and s.material == "custom" == ex.contact.controls.material_select.value


# ------------------------------------------------------------------------- URL


def test_a_link_restores_the_physical_inputs(ex: Explorer) -> None:
    ex.contact.controls.material_select.value = "steel"
    for name, typed in (("R", "5"), ("H", "2.5"), ("u0", "1.2"), ("h", "-0.5"), ("omega", "30")):
        ex.contact.controls.physical_inputs.boxes[name].value = typed
    q = ex.state.query()
    assert q["physical"] == "1" and q["material"] == "steel"
    assert "psi" not in q and "tau0" not in q  # they follow from the inputs
    assert {k: float(q[k]) for k in SI_KEYS} == {
        "R": 0.005, "G": 79.3e9, "H": 2.5e-6, "u0": 1.2e-6, "h": -0.5e-6,
        "omega": 2 * math.pi * 30e3}
    shared = Explorer(query={k: [v.encode()] for k, v in q.items()})  # as session_args
    assert not shared.message.visible and shared.state.query() == q
    expected = Contact.from_physical(R=0.005, G=79.3e9, nu=0.29, mu=0.2, H=2.5e-6,
                                     u0=1.2e-6, h=-0.5e-6, omega=2 * math.pi * 30e3)
    assert shared.state.current.scales == ex.state.current.scales == expected.scales
    assert (shared.state.psi, shared.state.tau0) == (expected.psi, expected.tau0)
    assert box_values(shared) == box_values(ex)
    ui = shared.contact.controls
    assert ui.material_select.value == "steel" and not ui.physical_card.collapsed
    assert ui.physical_box.value and ui.psi_slider.disabled


@pytest.mark.parametrize(("query", "fragment"), [
    ({"physical": "maybe"}, "physical = 'maybe' must be 0 or 1"),
    ({"physical": "1", "H": "-1"}, "H = -1 is outside the allowed range [1e-15, 1000]"),
    ({"physical": "1", "R": "abc"}, "R must be a real number in [1e-09, 1000], got 'abc'"),
    ({"physical": "1", "omega": "0"}, "omega = 0 is outside the allowed range"),
    ({"material": "unobtainium"}, "material = 'unobtainium' is unknown"),
    ({"physical": "1", "psi": "3"}, "psi = '3' ignored: with physical = 1 it follows"),
])
def test_refused_url_values_say_why(query: dict, fragment: str) -> None:
    values, messages = parse_query(query)
    assert len(messages) == 1 and fragment in messages[0], messages
    rejected = list(query)[-1]  # not applied (psi: the physical inputs' psi instead)
    assert rejected not in values or values[rejected] != float(query[rejected])
    ex = Explorer(query=query)
    assert fragment in html.unescape(ex.message.object)


def test_physical_inputs_core_refuses_in_a_link_are_left_off() -> None:
    query = {"physical": "1", "H": "2e-06", "h": "5e-06"}
    values, messages = parse_query(query)
    with pytest.raises(ValueError) as err:
        Contact.from_physical(R=0.01, G=79e9, nu=0.3, mu=0.2, H=2e-6, u0=1e-6, h=5e-6,
                              omega=2 * math.pi * 40e3)
    assert messages == [f"the physical inputs are not applied: {err.value}"]
    assert values["physical"] is False and values["h"] == 5e-6
    ex = Explorer(query=query)
    assert not ex.state.physical and ex.state.h == 5e-6  # kept, for the boxes to show
    assert (ex.contact.controls.physical_inputs.refusal.visible and
            ex.contact.controls.physical_inputs.boxes["h"].value == "5")


# --------------------------------------------------------------------- browser


@pytest.mark.browser
def test_typed_values_show_in_the_units_and_warn_in_chromium(browser, url) -> None:
    q = {"physical": "1", "material": "steel", "R": "0.005", "H": "2.5e-06",
         "u0": "1.2e-06", "h": "-5e-07", "omega": repr(2 * math.pi * 30e3)}
    page, console = open_explorer(browser, f"{url}?{urlencode(q)}")
    boxes = {k: page.locator(f".si-{k} input") for k in SI_KEYS}
    boxes["H"].wait_for(timeout=20_000)  # the card is open: the link has physical inputs
    assert {k: b.input_value() for k, b in boxes.items()} == {
        "R": "5", "G": "79.3", "H": "2.5", "u0": "1.2", "h": "-0.5", "omega": "30"}

    f = FIELDS["H"]
    boxes["H"].fill("1500")
    boxes["H"].press("Enter")
    text = warning(f, to_si(f, 1500.0))
    page.get_by_text(text).wait_for(timeout=20_000)
    assert boxes["H"].input_value() == "1500"
    page.wait_for_function("() => window.location.search.includes('H=0.0015')",
                           timeout=20_000)

    boxes["H"].fill("0")  # refused by core: explained, the box back to 1500
    boxes["H"].press("Enter")
    page.get_by_text("H (µm) = 0 is outside the allowed range").wait_for(timeout=20_000)
    page.wait_for_function("(b) => b.value === '1500'", arg=boxes["H"].element_handle(),
                           timeout=20_000)

    boxes["H"].fill("2")
    boxes["H"].press("Enter")
    page.get_by_text(text).wait_for(state="hidden", timeout=20_000)
    boxes["H"].fill("2.1 µm")  # not a number: explained, the box back to 2
    boxes["H"].press("Enter")
    page.get_by_text("H (µm) must be a real number in [1e-09, 1e+09], got '2.1 µm'").wait_for(
        timeout=20_000)
    page.wait_for_function("(b) => b.value === '2'", arg=boxes["H"].element_handle(),
                           timeout=20_000)
    boxes["H"].fill("2.1")
    boxes["H"].press("Enter")
    page.wait_for_function("() => window.location.search.includes('H=2.1e-06')",
                           timeout=20_000)
    assert boxes["H"].input_value() == "2.1"
    assert page.locator(".si-H button").count() == 0  # a text box: no spin buttons
    shared = parse_qs(urlsplit(page.url).query)
    assert shared["physical"] == ["1"] and shared["R"] == ["0.005"]
    assert [m for m in console if m.startswith(("error", "pageerror"))] == []
    page.close()


# ------------------------------------------------------- served, without a browser


def test_a_typed_value_submitted_with_enter_is_drawn_without_an_error(url) -> None:
    """Text typed in a box goes to the server as it is typed (`value_input`, a change
    Panel handles a moment later) and Enter as Panel's `enter-pressed` event, which sets
    the box's value: Panel handles the two together, without Bokeh's document lock, and
    every plot the new contact redraws must still be written (inside Panel's hold:
    `app.kit.scene.Scene.follow`).  Here over the websocket, as BokehJS sends them: the
    warning under the box and the traction profile of the new contact (H = 1500 µm)
    come back."""
    import asyncio

    from bokeh_client import Tab, models, named
    from tornado.httpclient import AsyncHTTPClient

    q = {"physical": "1", "material": "steel", "R": "0.005", "H": "2.5e-06",
         "u0": "1.2e-06", "h": "-5e-07", "omega": repr(2 * math.pi * 30e3)}
    text = warning(FIELDS["H"], to_si(FIELDS["H"], 1500.0))

    async def enter() -> tuple[list[str], str]:
        tab = Tab(f"{url}?{urlencode(q)}", AsyncHTTPClient())
        await tab.open()
        try:
            await tab.quiet(0.5)
            (box,) = [i for i, m in models(tab.doc).items()
                      if "si-H" in (m.get("attributes", {}).get("css_classes") or [])]
            # (typed: the text into `value_input`; then Enter: Panel's event)
            await tab.send("PATCH-DOC", {"events": [{
                "kind": "ModelChanged", "model": {"id": box}, "attr": "value_input",
                "new": "1500"}]})
            await tab.send("PATCH-DOC", {"events": [{
                "kind": "MessageSent", "msg_type": "bokeh_event",
                "msg_data": {"type": "event", "name": "enter-pressed", "values": {
                    "type": "map",
                    "entries": [["model", {"id": box}], ["value_input", "1500"]]}}}]})
            (traction,) = named(tab.doc, "traction")
            return [content for header, content in await tab.quiet(1.5)
                    if header["msgtype"] == "PATCH-DOC"], traction
        finally:
            tab.close()

    # (on a thread of its own: a browser test of this module leaves Playwright's loop
    # running on this one)
    with ThreadPoolExecutor(1) as pool:
        patches, traction = pool.submit(asyncio.run, enter()).result()
    events = [e for p in patches for e in json.loads(p)["events"]]
    assert any(text in html.unescape(str(e.get("new"))) for e in events), "no warning"
    changed = {e["model"]["id"] for e in events if e.get("kind") == "ColumnDataChanged"}
    assert traction in changed  # (the contact's psi follows H: its profile is new)
