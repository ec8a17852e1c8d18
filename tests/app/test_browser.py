"""The explorer in a real browser: Debian's Chromium driven by Playwright (sync API).

Runs against EXPLORER_URL when set (e.g. a container), else against a
`python -m app.serve` started here (fixtures in conftest.py).
`pytest -m smoke` selects the short subset.
"""

from __future__ import annotations

import math
from pathlib import Path
from urllib.parse import urlencode

import numpy as np
import pytest
from explorer_browser import (
    ROOT,
    column,
    open_explorer,
    steady,
    wait_until,
)

from app.contact import spheres
from app.contact.phases import style
from app.contact.query import parse_query
from app.contact.state import PRESETS, ExplorerState
from app.kit.figures import CURVE_POINTS
from core import Contact

pytestmark = pytest.mark.browser

ARTIFACTS = ROOT / "artifacts"
IGNORED_CONSOLE = ("could not set initial ranges",)  # Bokeh's note on hidden figures


def errors(console: list[str]) -> list[str]:
    return [m for m in console if m.startswith(("error", "pageerror"))
            and not any(s in m for s in IGNORED_CONSOLE)]


def typeset(page, formulas: int = 4) -> None:
    """Wait until KaTeX has typeset at least `formulas` displayed formulas."""
    wait_until(lambda: page.locator(".katex-display").count() >= formulas,
               what=f"{formulas} typeset formulas")


@pytest.mark.smoke
def test_page_loads_without_console_errors_and_screenshot(browser, url) -> None:
    page, console = open_explorer(browser, url)
    page.wait_for_load_state("networkidle")  # every resource loaded or failed
    typeset(page)  # KaTeX's errors, if any, are in the console now
    assert errors(console) == []
    T = column(page, "force", "T")
    assert len(T) > 300 and max(T) > 0 > min(T)
    assert page.get_by_text("Partial stick (π/2 < τ < τ₁").is_visible()
    assert page.locator(".katex-display").count() >= 4  # the formulas are typeset
    ARTIFACTS.mkdir(exist_ok=True)
    shot = ARTIFACTS / "explorer.png"
    page.screenshot(path=str(shot), full_page=True)
    assert shot.stat().st_size > 50_000
    page.close()


def settled(page, name: str, col: str, timeout_ms: int = 20_000) -> list[float]:
    """The column once it has stopped changing for 0.5 s (the browser caught up)."""
    return steady(lambda: column(page, name, col), quiet=0.5, timeout=timeout_ms / 1000)


@pytest.mark.smoke
def test_keyboard_slider_changes_plot_data(browser, url) -> None:
    page, console = open_explorer(browser, url)
    psi0 = psi_of(page)
    handle = page.locator(".slider-psi input[type=range]")  # the psi slider
    handle.focus()
    for _ in range(3):
        page.keyboard.press("ArrowRight")
    page.wait_for_function("(v) => __psi() > v + 0.02", arg=psi0, timeout=20_000)
    settled(page, "force", "T")  # the server's data for the last move arrived
    psi = psi_of(page)
    assert psi == pytest.approx(psi0 + 0.03, abs=0.011)  # three steps of 0.01
    # the plotted curve is exactly what core computes for the new psi
    tau, T = column(page, "force", "tau"), column(page, "force", "T")
    c = Contact(psi, math.pi / 6)
    np.testing.assert_allclose(tau, c.tau_grid(CURVE_POINTS), rtol=1e-15)
    np.testing.assert_allclose(T, c.tangential_force(np.asarray(tau)), rtol=1e-12,
                               atol=1e-15)
    # the URL follows (once, after the moves)
    page.wait_for_function("(p) => location.search.includes('psi=' + p)", arg=repr(psi),
                           timeout=5000)
    assert errors(console) == []
    page.close()


def test_a_burst_of_moves_leaves_one_history_entry(browser, url) -> None:
    """The address bar follows a burst of slider moves once, at its end, as one new
    history entry (`app.page.url.UrlWriter`: the query comes with each move's data, the
    browser writes it URL_DELAY_S after the last); Back returns to the link before."""
    page, console = open_explorer(browser, url)
    page.wait_for_timeout(1500)  # the page's own link written (in place), if it must be
    before = page.evaluate("() => [history.length, location.search]")
    handle = page.locator(".slider-psi input[type=range]")
    handle.focus()
    for _ in range(5):  # (the pauses are the test's subject: a burst, moves 100 ms apart)
        page.keyboard.press("ArrowRight")
        page.wait_for_timeout(100)
    settled(page, "force", "T")
    psi = psi_of(page)
    page.wait_for_function("(p) => location.search.includes('psi=' + p)", arg=repr(psi),
                           timeout=5000)
    page.wait_for_timeout(1500)  # (time let pass on purpose: no further entry may come)
    assert page.evaluate("() => history.length") == before[0] + 1
    page.go_back()
    page.wait_for_function("(s) => location.search === s", arg=before[1], timeout=5000)
    assert errors(console) == []
    page.close()


def psi_of(page) -> float:
    """psi as the page's psi slider holds it (exact)."""
    return page.evaluate("() => __psi()")


def wait_for_new(page, name: str, col: str, before: list[float] | None) -> list[float]:
    """Wait until the column differs from `before` (the server's data arrived); the column."""
    page.wait_for_function("([n, c, b]) => JSON.stringify(__col(n, c)) !== JSON.stringify(b)",
                           arg=[name, col, before], timeout=20_000)
    return column(page, name, col)


def step_psi(page) -> float:
    """Press ArrowRight on the psi slider and wait until the plots' data follow; the new psi."""
    T = column(page, "force", "T")
    page.locator(".slider-psi input[type=range]").focus()
    page.keyboard.press("ArrowRight")
    wait_for_new(page, "force", "T", T)
    return psi_of(page)


def test_number_box_follows_the_slider_and_takes_exact_values(browser, url) -> None:
    """The box shows each slider move; a value typed in it, even beyond the slider's
    range, reaches the plots and the slider."""
    page, console = open_explorer(browser, url)
    box = page.locator("input.bk-input").first  # the psi box, above the psi slider
    psi = step_psi(page)
    assert float(box.input_value()) == pytest.approx(psi, rel=1e-5)  # shown to 6 digits
    T = column(page, "force", "T")
    box.fill("250.5")
    box.press("Enter")
    T = wait_for_new(page, "force", "T", T)
    assert psi_of(page) == 250.5
    c = Contact(250.5, math.pi / 6)
    np.testing.assert_allclose(T, c.tangential_force(c.tau_grid(CURVE_POINTS)),
                               rtol=1e-12, atol=1e-15)
    slider_end = page.evaluate("() => __slider('psi').end")
    assert slider_end == 250.5  # the slider widened to show it
    drawn = page.locator(".slider-psi input[type=range]")
    assert (drawn.get_attribute("max"), drawn.input_value()) == ("250.5", "250.5")
    # a value the server sets reaches the box too, also the value the server last
    # heard from the box itself (the box never reports the slider's moves)
    page.locator(".slider-psi input[type=range]").focus()
    page.keyboard.press("ArrowLeft")
    page.wait_for_function("() => __psi() < 250.5", timeout=20_000)
    T = wait_for_new(page, "force", "T", T)
    page.get_by_role("button", name="Reset").click()
    default = ExplorerState().psi
    page.wait_for_function("(v) => __psi() === v", arg=default, timeout=20_000)
    T = wait_for_new(page, "force", "T", T)
    wait_until(lambda: float(box.input_value()) == pytest.approx(default, abs=5e-4), 5,
               what="the box to follow the slider")  # in the browser
    assert float(box.input_value()) == pytest.approx(default, abs=5e-4)
    box.fill("250.5")  # the value the server last heard from the box
    box.press("Enter")
    wait_for_new(page, "force", "T", T)
    assert psi_of(page) == 250.5
    assert errors(console) == []
    page.close()


@pytest.mark.parametrize(("box", "typed"), [(0, "-1"), (0, "abc"), (0, "1e13"), (2, "0"),
                                            (3, "0.7"), (4, "3.0")])
def test_a_refused_entry_says_why_under_its_box_and_keeps_the_value(
        browser, url, box: int, typed: str) -> None:
    """Boxes 0-4: psi, tau0, mu, nu, tau.  The message is the URL's for the same value."""
    name = ("psi", "tau0", "mu", "nu", "tau")[box]
    page, console = open_explorer(browser, url)
    entry = page.locator(f".entry-{name} input")
    before = entry.input_value()
    T = column(page, "force", "T")
    entry.fill(typed)
    entry.press("Enter")
    message = parse_query({name: typed})[1][0]
    page.get_by_text(message).wait_for(timeout=20_000)
    assert page.get_by_text(message).is_visible()
    page.wait_for_function("([b, v]) => b.value === v", arg=[entry.element_handle(), before],
                           timeout=20_000)
    assert column(page, "force", "T") == T  # nothing changed
    entry.fill(("3", "0.4", "0.3", "0.25", "2")[box])  # a good value clears the message
    entry.press("Enter")
    page.get_by_text(message).wait_for(state="hidden", timeout=20_000)
    assert errors(console) == []
    page.close()


@pytest.mark.parametrize(("name", "typed", "value"), [("tau0", "pi/4", math.pi / 4),
                                                     ("tau", "3pi/4", 3 * math.pi / 4)])
def test_a_box_takes_a_multiple_of_pi_as_typed(browser, url, name: str, typed: str,
                                               value: float) -> None:
    """"pi/2" was refused ("must be a real number"): a teacher types the paper's times
    as the paper writes them."""
    page, console = open_explorer(browser, url)
    entry = page.locator(f".entry-{name} input")
    entry.fill(typed)
    entry.press("Enter")
    page.wait_for_function("([n, v]) => __slider(n).value === v", arg=[name, value],
                           timeout=20_000)
    assert entry.input_value() == f"{value:.6g}"
    assert errors(console) == []
    page.close()


@pytest.mark.smoke
def test_bad_query_shows_message_and_falls_back(browser, url) -> None:
    query = {"psi": "banana", "tau0": "9"}
    page, console = open_explorer(browser, f"{url}?{urlencode(query)}")
    for message in parse_query(query)[1]:
        assert page.get_by_text(message).is_visible(), message
    assert psi_of(page) == math.sqrt(2) + 1
    assert errors(console) == []
    page.close()


def test_good_query_sets_the_parameters(browser, url) -> None:
    page, _ = open_explorer(browser, f"{url}?psi=6.46&tau0=0.2&tau=2.0")
    assert psi_of(page) == 6.46
    assert column(page, "force_marker", "x")[0] == 2.0
    assert column(page, "force", "tau")[0] == pytest.approx(0.2)
    page.close()


def play(page) -> None:
    """Press Play; wait for the player's frames to arrive."""
    page.get_by_role("button", name="▶ Play").click()
    page.wait_for_function("() => (__col('frames', 'tau') || []).length > 0", timeout=10_000)


def pause(page) -> None:
    """Press Pause; wait for the player to stop (its frames emptied)."""
    page.get_by_role("button", name="‖ Pause").click()
    page.wait_for_function("() => (__col('frames', 'tau') || []).length === 0",
                           timeout=10_000)


def play_until_the_marker_moves(page) -> None:
    """Play until the T(tau) marker has moved, then pause."""
    play(page)
    x0 = column(page, "force_marker", "x")[0]
    page.wait_for_function("(v) => __col('force_marker', 'x')[0] !== v", arg=x0,
                           timeout=10_000)
    pause(page)


def test_animation_advances(browser, url) -> None:
    page, console = open_explorer(browser, url)
    page.get_by_role("button", name="▶ Play").click()
    seen = set()
    for _ in range(30):  # samples 50 ms apart: the marker's positions over ~1.5 s
        seen.add(column(page, "force_marker", "x")[0])
        page.wait_for_timeout(50)  # (a sampling interval, not a wait)
    page.get_by_role("button", name="‖ Pause").click()
    assert len(seen) >= 5, seen
    stopped = settled(page, "force_marker", "x")
    page.wait_for_timeout(500)  # time let pass on purpose: nothing may move in it
    assert column(page, "force_marker", "x") == stopped
    assert errors(console) == []
    page.close()


def test_play_starts_right_after_slider_moves(browser, url) -> None:
    """Play pressed while the server is still writing a slider move's update (and the
    delayed URL) must start the player every time: the frame store arrives and the
    marker moves.  Before the player's updates went through hold(), about 1 Play in 8
    did nothing (this test failed 1 run in 3 against that code)."""
    page, console = open_explorer(browser, url)
    handle = page.locator(".slider-psi input[type=range]")
    # press Play at several delays around URL_DELAY_S after the last move, when the
    # server writes the new URL
    # (the pauses are the test's subject, not waits: moves 120 ms apart, then Play
    # `delay_ms` after the last)
    for round_, delay_ms in enumerate((300, 360, 400, 440, 500, 560)):
        handle.focus()
        for i in range(4):
            page.keyboard.press("ArrowRight" if (i + round_) % 2 == 0 else "ArrowLeft")
            page.wait_for_timeout(120)
        page.wait_for_timeout(delay_ms)
        play_until_the_marker_moves(page)
    assert errors(console) == []
    page.close()


#: What the page shows now of tau, read from what is drawn (the DOM of the tau box, the
#: tau slider's range input, whose value places the thumb the browser draws, and the
#: formula card's title) and the T(tau) marker's position.
JS_SHOWN_TAU = """() => {
  const view = (tag) => __views((v) => v.model != null && v.model.tags != null
      && v.model.tags.includes(tag))[0];
  const root = (v) => v.el.shadowRoot || v.el;
  const slider = root(view("tau-slider")).querySelector("input[type=range]");
  return {
    marker: __col("force_marker", "x")[0],
    box: root(view("tau-entry")).querySelector("input").value,
    handle: parseFloat(slider.value),
    pixel: (slider.max - slider.min) / slider.getBoundingClientRect().width,
    formula: root(view("formulas")).querySelector("b").textContent,
    badge: __col("spheres_badge", "text")[0],
    patch: __col("spheres_patch", "x1")[2] - __col("spheres_patch", "x0")[0],
  };
}"""


def assert_one_tau_shown(shown: dict, psi: float, tau0: float) -> None:
    """The tau box, the slider and the formula card show the marker's tau and phase."""
    tau = shown["marker"]
    assert float(shown["box"]) == pytest.approx(tau, rel=1e-5, abs=1e-6), shown
    assert shown["handle"] == pytest.approx(tau, abs=2 * shown["pixel"]), shown
    name = phase_of(psi, tau0, tau)
    assert shown["formula"].lower().startswith(name.lower()), (shown, name)
    assert shown["badge"] == name, (shown, name)  # the spheres scene's phase badge
    c = Contact(psi, tau0)
    a_star = math.sqrt(spheres.DRIVE * (1 - math.sin(tau0)) / 2)  # the patch's diameter
    assert shown["patch"] == pytest.approx(2 * float(c.contact_radius(tau)) * a_star,
                                           abs=1e-9), shown


def test_play_moves_the_tau_box_slider_and_formulas_with_the_plots(browser, url) -> None:
    """During Play every view of tau shows the frame being drawn (read in one go from
    the page, many times over more than one contact: the tau box, the slider, the
    formulas, and the spheres scene's phase badge and contact patch), and after each pause the page
    shows what the server holds: the paused frame, also when its phase is the one the
    play started in (the server then sends no new formulas)."""
    page, console = open_explorer(browser, url)
    psi, tau0 = psi_of(page), math.pi / 6
    page.wait_for_function(f"() => {{ try {{ return ({JS_SHOWN_TAU})().formula !== ''; }}"
                           " catch (e) { return false; } }", timeout=30_000)  # typeset
    assert_one_tau_shown(page.evaluate(JS_SHOWN_TAU), psi, tau0)
    for play_ms in (4600, 900, 2300):
        play(page)
        seen = set()
        for _ in range(play_ms // 100):  # samples 100 ms apart over play_ms
            shown = page.evaluate(JS_SHOWN_TAU)
            assert_one_tau_shown(shown, psi, tau0)
            seen.add(shown["formula"].split(" (")[0])
            page.wait_for_timeout(100)  # (a sampling interval, not a wait)
        pause(page)
        settled(page, "force_marker", "x")
        assert_one_tau_shown(page.evaluate(JS_SHOWN_TAU), psi, tau0)
        if play_ms > 4000:  # a whole contact: every phase of psi > 1 went by
            assert {"Slip", "Partial stick", "Counter-slip"} <= seen, seen
    assert errors(console) == []
    page.close()


def test_step_button_moves_tau(browser, url) -> None:
    page, _ = open_explorer(browser, url)
    tau = column(page, "force_marker", "x")[0]
    page.get_by_role("button", name="Step").click()
    page.wait_for_function("(v) => __col('force_marker', 'x')[0] > v", arg=tau)
    page.close()


def test_preset_loads(browser, url) -> None:
    page, console = open_explorer(browser, url)
    page.locator("select").first.select_option(label=PRESETS["fig7b"].label)
    page.wait_for_function("() => __psi() === 6.46", timeout=20_000)
    page.wait_for_function("() => (__col('force_family', 'label') || []).length === 3")
    assert column(page, "force_marker", "x")[0] == pytest.approx(math.pi / 2)
    page.wait_for_function("() => location.search.includes('preset=fig7b')",
                           timeout=5000)  # written once the changes settle
    assert errors(console) == []
    page.close()


def test_phone_width_stacks_the_plots(browser, url) -> None:
    page, console = open_explorer(browser, url, width=390, height=844)
    boxes = [page.locator(".bk-Canvas").nth(i).bounding_box() for i in range(4)]
    assert all(b is not None and b["x"] + b["width"] <= 390 for b in boxes), boxes
    # nothing wider than the phone: no sideways scrolling
    assert page.evaluate("() => document.scrollingElement.scrollWidth") <= 390
    page.screenshot(path=str(Path(ARTIFACTS, "explorer-phone.png")), full_page=True)
    assert errors(console) == []
    page.close()


def test_legend_click_hides_the_curve(browser, url) -> None:
    """Legend entries are empty proxies (app.kit.figures.add_legend); a click on one must
    still hide the real curve, and a second click show it again."""
    page, console = open_explorer(browser, url)
    assert column(page, "motion", "u2") is None  # its tab is closed: not in the page
    page.get_by_role("tab", name="Centre motion (Fig. 9)").click()
    page.wait_for_function("() => (__col('motion', 'u2') || []).length > 0", timeout=20_000)
    visible = "() => Bokeh.documents[0].get_model_by_name('motion_u2').visible"
    assert page.evaluate(visible) is True
    entry = page.get_by_text("u₂ / u₀", exact=True)
    entry.click()
    page.wait_for_function(f"() => !({visible})()", timeout=5000)
    entry.click()
    page.wait_for_function(visible, timeout=5000)
    assert errors(console) == []
    page.close()


def test_one_legend_entry_hides_both_coulomb_bounds(browser, url) -> None:
    """T(tau)'s "±μP / T₀" entry stands for the two bounds: a click hides both, a second
    shows both."""
    page, console = open_explorer(browser, url)
    page.wait_for_function("() => (__col('force', 'muP') || []).length > 0", timeout=20_000)
    shown = ("() => ['force_muP', 'force_neg_muP'].map("
             "(n) => Bokeh.documents[0].get_model_by_name(n).visible)")
    assert page.evaluate(shown) == [True, True]
    entry = page.get_by_text("±μP / T₀", exact=True)
    entry.click()
    page.wait_for_function(f"() => ({shown})().every((v) => !v)", timeout=5000)
    entry.click()
    page.wait_for_function(f"() => ({shown})().every((v) => v)", timeout=5000)
    assert errors(console) == []
    page.close()


#: JavaScript: the lower Coulomb bound's line as painted (its y after the browser's
#: transform) and the muP column it is drawn from.
JS_LOWER_BOUND = """() => {
  const v = __views((v) => v.model != null && v.model.name === "force_neg_muP")[0];
  return {painted: Array.from(v.glyph.y), muP: __col("force", "muP")};
}"""


def test_the_lower_coulomb_bound_is_painted_as_minus_mu_p(browser, url) -> None:
    """-muP / T0 is not sent: the browser draws it from the muP column, negated
    (`CurveScene.mirrors`), before and after a move changes the curves' grid."""
    page, console = open_explorer(browser, url)
    page.wait_for_function("() => (__col('force', 'muP') || []).length > 0", timeout=20_000)
    for _ in range(2):
        bound = page.evaluate(JS_LOWER_BOUND)
        assert len(bound["muP"]) > 300
        assert bound["painted"] == [-x for x in bound["muP"]]
        muP = bound["muP"]
        step_psi(page)  # (psi moves tau1, so the grid and the muP column change)
        page.wait_for_function(
            "(b) => JSON.stringify(__col('force', 'muP')) !== JSON.stringify(b)", arg=muP,
            timeout=20_000)
    assert errors(console) == []
    page.close()


#: JavaScript: the traction plot's lines and stick zone as painted (y after the browser's
#: transforms), and the columns they are drawn from.
JS_TRACTION_PAINTED = """() => {
  const rs = __renderers().filter((v) => v.model.data_source.name === "traction");
  const area = rs.find((v) => v.model.glyph.type === "VArea");
  return {lines: rs.filter((v) => v.model.glyph.type === "Line").map((v) => Array.from(v.glyph.y)),
          y1: Array.from(area.glyph.y1), y2: Array.from(area.glyph.y2),
          upper: __col("traction", "upper"), stick_hi: __col("traction", "stick_hi"),
          traction: __col("traction", "traction")};
}"""


def test_the_traction_plots_lower_halves_are_painted_negated(browser, url) -> None:
    """The traction source carries p and the stick zone's upper edge only
    (`traction.PROFILE_COLUMNS`); the browser paints -p and the zone's lower edge from
    them, negated."""
    page, console = open_explorer(browser, url)
    page.wait_for_function("() => (__col('traction', 'upper') || []).length > 0",
                           timeout=20_000)
    p = page.evaluate(JS_TRACTION_PAINTED)
    assert max(p["upper"]) > 0 and max(p["stick_hi"]) > 0  # (partial stick at 17 pi / 24)
    assert sorted(p["lines"]) == sorted([p["upper"], [-x for x in p["upper"]], p["traction"]])
    assert p["y2"] == p["stick_hi"] and p["y1"] == [-x for x in p["stick_hi"]]
    assert errors(console) == []
    page.close()


#: The page box of the traction plot and the phase its label names.
JS_TRACTION_BOX = """() => {
  const v = __views((v) => v.model != null && v.model.type === "Figure"
      && v.model.title != null && v.model.title.text === "Traction profile")[0];
  const r = v.el.getBoundingClientRect();
  const label = Bokeh.documents[0].get_model_by_name("traction_phase");
  return {x: r.x, y: r.y, width: r.width, height: r.height, phase: label.text};
}"""


def painted_phase(page) -> bytes:
    """The pixels of the traction plot's top-left corner, where its phase label is."""
    box = page.evaluate(JS_TRACTION_BOX)
    clip = {"x": box["x"], "y": box["y"], "width": box["width"] / 2, "height": 110}
    return page.screenshot(clip=clip)


def assert_phase_painted(page, expected: str) -> None:
    """The traction plot's phase label is `expected` and the canvas shows it: the corner
    looks the same after the browser repaints every plot from scratch (a resize)."""
    page.wait_for_function(f"() => ({JS_TRACTION_BOX})().phase === {expected!r}",
                           timeout=20_000)
    # whatever the browser paints on its own is painted once the pixels stay the same
    shown = steady(lambda: painted_phase(page))
    box = page.evaluate(JS_TRACTION_BOX)
    size = page.viewport_size
    page.set_viewport_size({"width": size["width"] - 40, "height": size["height"]})
    steady(lambda: painted_phase(page))
    page.set_viewport_size(size)
    wait_until(lambda: page.evaluate(JS_TRACTION_BOX) == box, what="the plot's own box")
    fresh = steady(lambda: painted_phase(page))
    if shown != fresh:
        ARTIFACTS.mkdir(exist_ok=True)
        (ARTIFACTS / "phase_shown.png").write_bytes(shown)
        (ARTIFACTS / "phase_after_resize.png").write_bytes(fresh)
    assert shown == fresh, f"the canvas did not show the phase {expected!r} until a resize"


def phase_of(psi: float, tau0: float, tau: float) -> str:
    return style(Contact(psi, tau0).phase(tau)).name


def test_the_traction_phase_is_painted_after_psi_moves_into_counter_slip(browser, url) -> None:
    page, console = open_explorer(browser, url)
    box = page.locator(".entry-tau input")
    box.fill("2.30")
    box.press("Enter")
    assert_phase_painted(page, phase_of(math.sqrt(2) + 1, math.pi / 6, 2.30))
    page.locator(".slider-psi input[type=range]").focus()  # psi
    T = column(page, "force", "T")
    for _ in range(11):
        page.keyboard.press("PageUp")
        T = wait_for_new(page, "force", "T", T)  # the server has shown this move
    settled(page, "force", "T")
    psi = psi_of(page)
    expected = phase_of(psi, math.pi / 6, 2.30)
    assert expected == "counter-slip", psi
    assert_phase_painted(page, expected)
    assert errors(console) == []
    page.close()


@pytest.mark.parametrize("preset", ["fig6a", "fig6b", "fig6c"])
def test_the_traction_phase_is_painted_after_a_preset(browser, url, preset: str) -> None:
    page, console = open_explorer(browser, url)
    page.locator("select").first.select_option(label=PRESETS[preset].label)
    p = PRESETS[preset]
    assert_phase_painted(page, phase_of(p.psi, p.tau0, p.tau))
    assert errors(console) == []
    page.close()


def test_the_traction_phase_is_painted_after_a_typed_tau(browser, url) -> None:
    page, console = open_explorer(browser, url)
    box = page.locator(".entry-tau input")
    box.fill("2.5")
    box.press("Enter")
    assert_phase_painted(page, phase_of(math.sqrt(2) + 1, math.pi / 6, 2.5))
    assert errors(console) == []
    page.close()


#: JavaScript: the page box of the figure titled `title`.
JS_FIGURE_BOX = """(title) => {
  const v = __views((v) => v.model != null && v.model.type === "Figure"
      && v.model.title != null && v.model.title.text === title)[0];
  const r = v.el.getBoundingClientRect();
  return {x: r.x, y: r.y, width: r.width, height: r.height};
}"""


def test_the_drive_line_is_painted_over_the_lower_sphere(browser, url) -> None:
    """The line the lower sphere's centre moves along lies inside that sphere: it is
    painted over it (hiding the line changes the plot's pixels)."""
    page, console = open_explorer(browser, url)
    clip = page.evaluate(JS_FIGURE_BOX, "Two spheres in section")

    def shot(visible: bool) -> bytes:
        page.evaluate("(v) => { Bokeh.documents[0].get_model_by_name("
                      "'spheres_drive_line').visible = v; }", visible)
        return steady(lambda: page.screenshot(clip=clip))  # repainted

    shown, hidden, again = shot(True), shot(False), shot(True)
    assert shown == again  # (the scene is still: only the line changed)
    assert shown != hidden, "the drive line is not painted"
    assert errors(console) == []
    page.close()


def test_the_papers_figures_in_full_are_drawn(browser, url) -> None:
    """Fig. 9's two panels (the v2 step at tau1 in the drawn data), Fig. 4a above 4b, and
    Fig. 6's six profiles one click away, each painted on its own canvas."""
    page, console = open_explorer(browser, url)
    figure_views = """(titles) => __views((v) => v.model != null && v.model.type === "Figure"
        && titles.includes(v.model.title.text)).map((v) => {
          const r = v.el.getBoundingClientRect(); return [r.width, r.height]; })"""
    page.get_by_role("tab", name="Centre motion (Fig. 9)").click()
    page.wait_for_function("() => (__col('motion', 'v2') || []).length > 0", timeout=20_000)
    panels = ["Contact-centre velocity (Fig. 9a)", "Contact-centre displacement (Fig. 9b)"]
    page.wait_for_function(f"() => ({figure_views})({panels!r}).length === 2", timeout=10_000)
    assert all(w > 300 and h > 200 for w, h in page.evaluate(f"({figure_views})", panels))
    tau, v2 = column(page, "motion", "tau"), column(page, "motion", "v2")
    c = Contact(math.sqrt(2) + 1, math.pi / 6)
    i = int(np.searchsorted(tau, c.tau1))
    assert tau[i] - tau[i - 1] < 1e-5 and v2[i - 1] < -0.3 < 0.1 < v2[i]  # the jump
    page.get_by_role("tab", name="Radii (Fig. 4b)").click()
    page.wait_for_function("() => (__col('radii_drive', 'uz') || []).length > 0",
                           timeout=20_000)
    assert column(page, "radii_disks", "label") == list("abcdef")
    page.get_by_text("Fig. 6 in full", exact=False).click()
    titles = ["6a: τ = π/4, slip", "6b: τ = π/3, slip", "6c: τ = π/2, slip",
              "6d: τ = 7π/12, partial stick", "6e: τ = 17π/24, partial stick",
              "6f: τ = 3π/4, counter-slip"]
    page.wait_for_function(f"() => ({figure_views})({titles!r}).length === 6", timeout=20_000)
    assert all(w > 150 and h > 150 for w, h in page.evaluate(f"({figure_views})", titles))
    assert errors(console) == []
    page.close()


#: The plots of the presentation view (their titles).
PRESENTED = ["Two spheres in section", "Traction profile", "Contact disc (top view)",
             "Tangential force T / T₀"]

#: The page boxes of the plots with these titles, their frames (the drawing's area:
#: the figure's inner_width and inner_height), the width / height of their ranges, and
#: the page's scroll extent.
JS_PLOT_BOXES = """(titles) => {
  const boxes = {}, frames = {}, ranges = {};
  for (const v of __views((v) => v.model != null && v.model.type === "Figure"
      && v.model.title != null && titles.includes(v.model.title.text))) {
    const r = v.el.getBoundingClientRect(), m = v.model, t = m.title.text;
    boxes[t] = [r.left, r.top, r.right, r.bottom];
    frames[t] = [m.inner_width, m.inner_height];
    ranges[t] = (m.x_range.end - m.x_range.start) / (m.y_range.end - m.y_range.start);
  }
  const s = document.scrollingElement;
  return {boxes, frames, ranges, scroll: [s.scrollWidth, s.scrollHeight],
          view: [innerWidth, innerHeight]};
}"""


def presented(page, width: int, height: int) -> dict:
    """The presentation's plots as drawn in a `width` x `height` window (JS_PLOT_BOXES),
    once the layout has settled, checked to fit it: nothing to scroll, every plot inside
    the window, none over another, the spheres and the disc at equal scales on both axes
    (their frames have the aspect of their ranges)."""
    page.wait_for_function(f"() => Object.keys(({JS_PLOT_BOXES})({PRESENTED!r}).boxes)"
                           ".length === 4", timeout=20_000)
    # settled: the frames follow the boxes a paint later
    shown = steady(lambda: page.evaluate(f"({JS_PLOT_BOXES})", PRESENTED))
    assert shown["view"] == [width, height]
    assert shown["scroll"][0] <= width and shown["scroll"][1] <= height, shown
    boxes = shown["boxes"]
    for title, (left, top, right, bottom) in boxes.items():
        assert -0.5 <= left < right <= width + 0.5, (title, shown)
        assert -0.5 <= top < bottom <= height + 0.5, (title, shown)
        assert right - left > 200 and bottom - top > 200, (title, shown)
    for i, a in enumerate(PRESENTED):
        for b in PRESENTED[i + 1:]:
            (l1, t1, r1, b1), (l2, t2, r2, b2) = boxes[a], boxes[b]
            overlap = min(r1, r2) - max(l1, l2), min(b1, b2) - max(t1, t2)
            assert min(overlap) <= 0.5, (a, b, shown)
    for title in ("Two spheres in section", "Contact disc (top view)"):
        w, h = shown["frames"][title]
        assert w / h == pytest.approx(shown["ranges"][title], rel=0.015), (title, shown)
    return shown


def areas(shown: dict) -> dict[str, tuple[float, float]]:
    """Each plot's area (px²) and its frame's area."""
    return {t: ((r - left) * (b - top), shown["frames"][t][0] * shown["frames"][t][1])
            for t, (left, top, r, b) in shown["boxes"].items()}


@pytest.mark.parametrize(("width", "height"), [(1280, 720), (1920, 1080), (2560, 1440)])
def test_the_presentation_view_fits_one_screen(browser, url, width: int, height: int) -> None:
    """view=present: the spheres with their phase badge, the traction profile, the disc
    and T(tau) are all on the screen, nothing to scroll, nothing overflowing its box; on a
    larger screen they are larger (the same page, the window resized to 1280 x 720, shows
    them smaller and still fits); Play animates them; the button leads to the full page
    with the same parameters."""
    page, console = open_explorer(browser, url + "?view=present&psi=3.5", width=width,
                                  height=height)
    shown = presented(page, width, height)
    assert laid_out(page) == []  # the controls' text laid out: nothing overflows
    assert page.evaluate(JS_CLIPPED_OPTIONS) == []
    assert column(page, "spheres_badge", "text") == [phase_of(3.5, math.pi / 6, 17 * math.pi / 24)]
    if width in (1280, 1920):
        ARTIFACTS.mkdir(exist_ok=True)
        page.screenshot(path=str(ARTIFACTS / f"presentation-{width}x{height}.png"))
    if width > 1280:
        page.set_viewport_size({"width": 1280, "height": 720})
        small = presented(page, 1280, 720)
        assert page.evaluate(JS_OVERFLOWS) == []
        large = areas(shown)
        for title, (box, frame) in areas(small).items():
            assert large[title][0] >= 1.3 * box and large[title][1] >= 1.3 * frame, (
                title, shown, small)
    play_until_the_marker_moves(page)
    page.wait_for_function("() => location.search.includes('view=present')", timeout=5000)
    page.get_by_role("button", name="All scenes and controls").click()
    page.wait_for_function("() => !location.search.includes('view=')", timeout=10_000)
    page.get_by_text("Curves over the contact").wait_for(timeout=30_000)  # the full page
    assert "psi=3.5" in page.evaluate("() => location.search")
    assert errors(console) == []
    page.close()


#: The options of every select whose text is wider than the select shows it (its width
#: less its padding, which holds the arrow), measured in the select's own font:
#: (option, by how many px). A select's scrollWidth does not tell.
JS_CLIPPED_OPTIONS = """() => {
  const found = [];
  const ctx = document.createElement("canvas").getContext("2d");
  const walk = (root) => {
    for (const el of root.querySelectorAll("*")) {
      if (el.shadowRoot) walk(el.shadowRoot);
      if (el.tagName !== "SELECT" || el.clientWidth === 0) continue;
      const cs = getComputedStyle(el);
      ctx.font = cs.font;
      const room = el.clientWidth - parseFloat(cs.paddingLeft) - parseFloat(cs.paddingRight);
      for (const o of el.options) {
        const over = ctx.measureText(o.text).width - room;
        if (over > 0) found.push([o.text, Math.round(over)]);
      }
    }
  };
  walk(document);
  return found;
}"""


#: Elements that overflow their box or stick out of their card: (what, by how many px).
#: Bokeh's plot frames clip their drawing on purpose, and a caption for screen readers
#: only is clipped to nothing: neither counts.
JS_OVERFLOWS = """() => {
  const found = [];
  const name = (el) => el.tagName.toLowerCase() + (el.className && el.className.baseVal
      === undefined ? "." + String(el.className).split(" ")[0] : "");
  const walk = (root, card) => {
    for (const el of root.querySelectorAll("*")) {
      const inCard = el.classList.contains("card") ? el : card;
      if (el.shadowRoot) walk(el.shadowRoot, inCard);
      if (el.classList.contains("bk-CartesianFrame")) continue;
      const cs = getComputedStyle(el);
      if (cs.clip === "rect(0px, 0px, 0px, 0px)" || cs.clipPath === "inset(50%)") continue;
      const over = el.scrollWidth - el.clientWidth;
      if (el.clientWidth > 0 && over > 1 && cs.overflowX !== "visible") {
        found.push([name(el), over]);
      }
      if (inCard && inCard !== el && el.textContent.trim() && el.children.length === 0) {
        const r = el.getBoundingClientRect(), c = inCard.getBoundingClientRect();
        const out = Math.max(r.right - c.right, c.left - r.left);
        if (r.width > 0 && out > 1) found.push([name(el) + " out of its card", out]);
      }
    }
  };
  walk(document, null);
  return found;
}"""


def laid_out(page) -> list:
    """JS_OVERFLOWS once the page's fonts are loaded and its layout has settled (the
    list stays the same for 0.5 s)."""
    page.evaluate("() => document.fonts.ready.then(() => true)")
    return steady(lambda: page.evaluate(JS_OVERFLOWS))


@pytest.mark.parametrize(("width", "height"), [(390, 844), (768, 1024), (1024, 768),
                                               (1280, 720), (1920, 1080), (2560, 1440)])
def test_nothing_is_clipped_from_a_phone_to_2560_wide(browser, url, width: int,
                                                      height: int) -> None:
    """The formulas (partial stick's, the longest), the tables, every card's text and
    every option of the menus fit their boxes at every screen size, a phone's and a
    tablet's included: nothing overflows or is scrolled out of view."""
    page, console = open_explorer(browser, url, width=width, height=height)
    typeset(page)
    assert laid_out(page) == []
    assert page.evaluate(JS_CLIPPED_OPTIONS) == []  # every preset's name shows whole
    assert errors(console) == []
    page.close()


def test_a_key_press_moves_tau_one_degree(browser, url) -> None:
    """The tau slider stepped 0.002 rad a key press: about a thousand presses for one
    contact, none of them visible."""
    from app.contact.controls import TAU_STEP

    page, console = open_explorer(browser, url)
    before = page.evaluate("() => __slider('tau').value")
    thumb = page.locator(".slider-tau input[type=range]")
    thumb.focus()
    thumb.press("ArrowRight")
    page.wait_for_function("(v) => __slider('tau').value > v", arg=before, timeout=20_000)
    start = page.evaluate("() => __slider('tau').start")
    after = page.evaluate("() => __slider('tau').value")
    # one step, from the value snapped to start + k step (the browser's range input)
    assert 0.5 * TAU_STEP - 1e-9 <= after - before <= 1.5 * TAU_STEP + 1e-9
    k = (after - start) / TAU_STEP
    assert k == pytest.approx(round(k), abs=1e-6)
    assert TAU_STEP == pytest.approx(math.radians(1))
    assert errors(console) == []
    page.close()
