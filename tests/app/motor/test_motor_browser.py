"""The Motor card in a real browser (Debian's Chromium through Playwright): it opens,
computes on the runner, drives the scenes above, and paints the rotor on the rod, the
explanation of the never-opening ends and an efficiency curve resolved to its best."""

from __future__ import annotations

import time

import numpy as np
import pytest
from explorer_browser import column, open_explorer
from test_browser import errors, psi_of, wait_for_new

from app.kit.figures import CURVE_POINTS
from core import Contact
from core.motor import Motor, Rod

pytestmark = pytest.mark.browser

CARD = "Motor: the rod, its thrust and speed (Fig. 1)"


def opened(browser, url):
    page, console = open_explorer(browser, url)
    assert column(page, "motor_thrust", "x_mm") is None  # not built until opened
    T = column(page, "force", "T")
    page.get_by_text(CARD).click()
    page.wait_for_function("() => (__col('motor_thrust', 'x_mm') || []).length > 100",
                           timeout=30_000)
    # the thrust-speed curve arrives from the background runner
    page.wait_for_function("() => (__col('motor_speed', 'v') || []).length > 10",
                           timeout=60_000)
    return page, console, T


def test_the_motor_card_opens_computes_its_curve_and_drives_the_scenes_when_asked(
        browser, url) -> None:
    page, console, T = opened(browser, url)
    assert column(page, "force", "T") == T  # opening the card leaves the contact alone
    page.get_by_label("Show the rotor's contact (at x₀) in the plots above").check()
    T = wait_for_new(page, "force", "T", T)  # the scenes above show the rotor's contact

    def shown() -> tuple[list[float], np.ndarray]:  # T drawn, and T of the sliders shown
        c = Contact(psi_of(page), page.evaluate("() => __slider('tau0').value"),
                    mu=page.evaluate("() => __slider('mu').value"),
                    nu=page.evaluate("() => __slider('nu').value"))
        return column(page, "force", "T"), c.tangential_force(c.tau_grid(CURVE_POINTS))

    # (the sliders and the plot are read one after the other: read until one reading
    # finds them at rest together, the rotor's contact having fully arrived)
    deadline = time.monotonic() + 20
    T, expected = shown()
    while not np.allclose(T, expected, rtol=1e-12, atol=1e-15) and time.monotonic() < deadline:
        page.wait_for_timeout(100)
        T, expected = shown()
    np.testing.assert_allclose(T, expected, rtol=1e-12, atol=1e-15)
    page.wait_for_function("() => location.search.includes('motor_x0=')", timeout=10_000)
    assert errors(console) == []
    page.close()


def default_motor() -> tuple[Motor, float]:
    """The card's default state (PZT rod 2L = 40 mm, steel rotor, x0 = -5 mm) in SI."""
    rod = Rod(half_length=0.02, thickness=0.004, nu_rod=0.31, amplitude=1e-5,
              frequency=40e3)
    return Motor(rod, R=0.005, G=79.3e9, nu=0.29, mu=0.2, preload=0.5), -0.005


def test_the_rotor_is_painted_on_the_rod_and_the_ends_are_explained(browser, url) -> None:
    page, console, _ = opened(browser, url)
    m, x0 = default_motor()
    k_H = 0.3 * m.rod.thickness / abs(m.rod.vertical_amplitude)
    top = (0.5 * m.rod.thickness + k_H * float(m.rod.H(x0))) * 1e3
    y, r = column(page, "motor_rotor", "y"), column(page, "motor_rotor", "radius")
    assert y[0] - r[0] == pytest.approx(top, rel=1e-12)  # touching the drawn face
    text = column(page, "motor_ends", "text")
    assert text == ["contact never opens:\nnormal motion H too small\nfor the preload "
                    "(Φ ≥ 8)"] * 2
    painted = page.evaluate("""() => __views((v) => v.model != null
        && v.model.name === 'motor_ends_text').map((v) => v.model.visible)""")
    assert painted == [True]
    eta = np.array(column(page, "motor_speed", "efficiency_pct"), float)
    best = column(page, "motor_speed_marks", "efficiency_pct")[1]
    assert np.sum(eta > 0) >= 40 and np.nanmax(eta) == best
    assert errors(console) == []
    page.close()


#: The sliders a drag test moves: the card's (Panel's title of the card holding it, None
#: for x0 at the top) and the URL key its value is written under.
DRAGGED = {"x0": None, "N": "Rotor", "load": "Load and start-up"}
#: JavaScript: true once no text of the page says that the card's job is running.
COMPUTED = """() => ![...Bokeh.documents[0].all_models].some((m) =>
    typeof m.text === 'string' && m.text.startsWith('computing the thrust-speed'))"""


@pytest.mark.parametrize("name", list(DRAGGED))
def test_a_motor_slider_follows_a_whole_drag_of_the_real_mouse(browser, url,
                                                               name: str) -> None:
    """x0, the preload and the load followed the first 15 px of a drag and then stopped
    (x0 -5 -> -3.89 of an expected +11.7): the server's answer to the first step showed
    the progress bar (Panel's `visible`), BokehJS laid the card's column out again, and
    the slider lost the pointer; x0's range was also rewritten (+-19.98 -> +-20)."""
    page, console, _ = opened(browser, url)
    if DRAGGED[name]:
        page.get_by_role("button", name=DRAGGED[name], exact=True).click()  # (its title)
    track = page.locator(f".slider-motor_{name} input[type=range]")
    track.scroll_into_view_if_needed()
    page.wait_for_function("(n) => __slider(n) != null", arg=f"motor_{name}")
    js = f"() => {{ const d = __slider('motor_{name}'); return [d.value, d.start, d.end]; }}"
    value, start, end = page.evaluate(js)
    box = track.bounding_box()
    y = box["y"] + box["height"] / 2
    # (Chromium's thumb is 16 px wide: the track is the input less the thumb)
    x = box["x"] + 8 + (value - start) / (end - start) * (box["width"] - 16)
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x + 15, y)
    first = page.evaluate(js)[0]
    assert first > value
    # the server's whole answer to the first step: the URL, then the job's outcome
    page.wait_for_function("(k) => location.search.includes(k)",
                           arg=f"motor_{name}={first!r}", timeout=60_000)
    page.wait_for_function(COMPUTED, timeout=60_000)
    for k in range(2, 9):  # the rest of a 120 px drag, 15 px a move
        page.mouse.move(x + 15 * k, y)
    page.mouse.up()
    last = page.evaluate(js)
    assert last[1:] == [start, end]  # the range stayed the rod's (x0) or the field's
    page.wait_for_function("(k) => location.search.includes(k)",
                           arg=f"motor_{name}={last[0]!r}", timeout=60_000)
    # the last 105 px moved the value as far as 105 px of the track are worth
    assert last[0] - first == pytest.approx(105 * (end - start) / (box["width"] - 16),
                                            rel=0.1)
    # and the job's bar, which kept its place, is not painted once the job has ended
    page.wait_for_function(COMPUTED, timeout=60_000)
    assert page.locator("progress").evaluate_all(
        "(els) => els.map((e) => getComputedStyle(e).visibility)") == ["hidden"]
    assert errors(console) == []
    page.close()
