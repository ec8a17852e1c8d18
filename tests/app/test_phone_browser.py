"""The explorer on a 390 x 844 touch phone (Chromium emulating one: touch events, a
coarse pointer, 3 device pixels per CSS pixel): a swipe over a plot scrolls the page,
the first screen shows the two spheres and Play, nothing is wider than the phone."""

from __future__ import annotations

import time

import pytest
from explorer_browser import load, wait_until
from test_browser import ARTIFACTS, errors, typeset

from app.page.layout import ANIMATION_LABEL

pytestmark = pytest.mark.browser

WIDTH, HEIGHT = 390, 844
PHONE = {"viewport": {"width": WIDTH, "height": HEIGHT}, "has_touch": True,
         "is_mobile": True, "device_scale_factor": 3}
EXPLORE = "Pan and zoom the plots"

#: JavaScript: [x start, x end, y start, y end] of the figure titled `title`.
JS_RANGES = """(title) => {
  const f = [...Bokeh.documents[0].all_models].find(
    (m) => m.type === "Figure" && m.title != null && m.title.text === title);
  return [f.x_range.start, f.x_range.end, f.y_range.start, f.y_range.end];
}"""

#: JavaScript: [active drag tool or null, active scroll tool or null] of every toolbar
#: (the tool's type, 'auto' as it is).
JS_ACTIVE = """() => [...Bokeh.documents[0].all_models].filter((m) => m.type === "Toolbar")
  .map((t) => [t.active_drag, t.active_scroll]
    .map((a) => a == null || a === "auto" ? a : a.type))"""

#: JavaScript: the CSS touch-action of every plot's event layer (BokehJS sets it from the
#: plot's active tools).
JS_TOUCH_ACTIONS = """() => {
  const out = [];
  const walk = (root) => {
    for (const el of root.querySelectorAll("*")) {
      if (el.classList.contains("bk-events")) out.push(getComputedStyle(el).touchAction);
      if (el.shadowRoot) walk(el.shadowRoot);
    }
  };
  walk(document);
  return out;
}"""


def open_phone(browser, url: str, touch: bool = True):
    """A page of the explorer on the phone (`touch`) or, as wide, with a mouse, once its
    data arrived; and its console log."""
    context = browser.new_context(**(PHONE if touch else {"viewport": PHONE["viewport"]}))
    return load(context.new_page(), url)


def swipe_up(page, x: float, y: float, distance: float = 150, steps: int = 10) -> None:
    """A finger put down at (x, y) (CSS px in the viewport), moved up by `distance` px
    in `steps` moves 16 ms apart, held still for 100 ms and lifted: touch events as a
    touch screen sends them (CDP, with their times).  Held still, the swipe leaves no
    fling behind, which would take the next tap to stop it (as a finger's tap stops a
    fling) instead of clicking."""
    cdp = page.context.new_cdp_session(page)
    t0, end = time.time(), y - distance

    def touch(kind: str, at: float, points: list) -> None:
        cdp.send("Input.dispatchTouchEvent",
                 {"type": kind, "touchPoints": points, "timestamp": t0 + at})

    touch("touchStart", 0.0, [{"x": x, "y": y}])
    for k in range(1, steps + 1):
        touch("touchMove", 0.016 * k, [{"x": x, "y": y - distance * k / steps}])
    touch("touchMove", 0.016 * steps + 0.1, [{"x": x, "y": end}])
    touch("touchEnd", 0.016 * steps + 0.11, [])
    cdp.detach()


def traction_in_view(page) -> dict:
    """Scroll the traction profile's plot to the middle of the screen; its box there."""
    canvas = page.locator(".card").filter(has_text="Traction profile (Fig. 6)").locator(
        ".bk-Canvas")
    canvas.evaluate("(el) => el.scrollIntoView({block: 'center'})")
    wait_until(lambda: 0 < canvas.bounding_box()["y"] < HEIGHT / 2,
               what="the traction plot in view")
    return canvas.bounding_box()


def test_a_swipe_over_a_plot_scrolls_the_page_and_leaves_the_plot(browser, url) -> None:
    """A vertical swipe over the full-width traction plot panned the plot (its y range
    moved by 2.3, the curve dragged over its title) and the page stayed (scrollY the
    same): the pan tool was active and BokehJS gave the plot `touch-action: pinch-zoom`."""
    page, console = open_phone(browser, url)
    box = traction_in_view(page)
    ranges = page.evaluate(JS_RANGES, "Traction profile")
    top = page.evaluate("() => window.scrollY")
    swipe_up(page, box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    scrolled = wait_until(lambda: page.evaluate("() => window.scrollY") - top >= 100,
                          timeout=5, what="the page scrolled by the swipe")
    assert scrolled
    assert page.evaluate(JS_RANGES, "Traction profile") == ranges
    touch_actions = page.evaluate(JS_TOUCH_ACTIONS)
    assert len(touch_actions) >= 4 and set(touch_actions) == {"auto"}
    assert errors(console) == []
    page.close()


def test_pan_and_zoom_on_request_and_off_again(browser, url) -> None:
    """'Pan and zoom the plots' gives the plots their pan tools (a swipe pans the plot,
    the page stays); pressed again, a swipe scrolls the page again."""
    page, console = open_phone(browser, url)
    assert {tuple(a) for a in page.evaluate(JS_ACTIVE)} == {(None, None)}
    button = page.get_by_role("button", name=EXPLORE)
    button.tap()
    wait_until(lambda: button.get_attribute("aria-pressed") == "true", what="pressed")
    assert {tuple(a) for a in page.evaluate(JS_ACTIVE)} == {("auto", "auto")}
    box = traction_in_view(page)
    ranges = page.evaluate(JS_RANGES, "Traction profile")
    top = page.evaluate("() => window.scrollY")
    swipe_up(page, box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    moved = wait_until(lambda: (r := page.evaluate(JS_RANGES, "Traction profile")) != ranges
                       and r, timeout=5, what="the plot panned")
    assert moved[2] < ranges[2]  # dragged up: the range moves down, by 150 px worth
    assert page.evaluate("() => window.scrollY") == top
    button.tap()
    wait_until(lambda: button.get_attribute("aria-pressed") == "false", what="released")
    assert {tuple(a) for a in page.evaluate(JS_ACTIVE)} == {(None, None)}
    swipe_up(page, box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    wait_until(lambda: page.evaluate("() => window.scrollY") - top >= 100, timeout=5,
               what="the page scrolled by the swipe")
    assert errors(console) == []
    page.close()


def test_a_plot_shown_later_leaves_the_swipe_to_the_page_too(browser, url) -> None:
    """A figure sent after the page loaded (a curve tab's, built when opened) arrives
    without an active drag tool as well."""
    page, console = open_phone(browser, url)
    toolbars = len(page.evaluate(JS_ACTIVE))
    page.get_by_role("tab", name="Impulse (Fig. 8)").tap()
    page.wait_for_function("() => (__col('impulse', 'psi') || []).length > 0",
                           timeout=20_000)
    active = wait_until(lambda: (a := page.evaluate(JS_ACTIVE)) and len(a) > toolbars
                        and {tuple(t) for t in a} == {(None, None)} and a,
                        what="the new plot's toolbar without active tools")
    assert len(active) == toolbars + 1
    wait_until(lambda: set(page.evaluate(JS_TOUCH_ACTIONS)) == {"auto"},
               what="every plot leaving touches to the page")
    assert errors(console) == []
    page.close()


def test_with_a_mouse_the_plots_pan_as_before(browser, url) -> None:
    """As wide as a phone but with a mouse (a fine pointer): no button, the plots' pan
    tools active as the server made them."""
    page, console = open_phone(browser, url, touch=False)
    assert page.evaluate("() => matchMedia('(pointer: coarse)').matches") is False
    assert page.get_by_role("button", name=EXPLORE).count() == 0
    assert {tuple(a) for a in page.evaluate(JS_ACTIVE)} == {("auto", "auto")}
    assert "pinch-zoom" in page.evaluate(JS_TOUCH_ACTIONS)  # the pan tool's
    assert errors(console) == []
    page.close()


def test_first_screen_shows_the_spheres_and_play(browser, url) -> None:
    """The first 844 px showed the header and ~1100 px of controls (Play at y = 1103,
    the spheres from y = 1419): now the spheres' plot and Play are on it, whole."""
    page, console = open_phone(browser, url)
    page.evaluate("() => document.fonts.ready.then(() => true)")
    spheres = page.locator(".bk-Canvas").first.bounding_box()  # the page's first plot
    play = page.get_by_role("button", name="▶ Play").bounding_box()
    assert spheres["y"] >= 0 and spheres["y"] + spheres["height"] <= HEIGHT, spheres
    assert spheres["height"] > 500  # the plot itself, not shrunk to fit
    assert play["y"] >= spheres["y"] + spheres["height"], (play, spheres)
    assert play["y"] + play["height"] <= HEIGHT, play
    assert page.evaluate("() => window.scrollY") == 0
    region = page.get_by_role("region", name=ANIMATION_LABEL).locator(".bk-Canvas")
    assert region.bounding_box() == spheres  # the spheres' plot, in the animation region
    ARTIFACTS.mkdir(exist_ok=True)
    page.screenshot(path=str(ARTIFACTS / "explorer-phone-first-screen.png"))
    assert errors(console) == []
    page.close()


def test_nothing_is_wider_than_the_phone(browser, url) -> None:
    """The whole page fits 390 px, no sideways scrolling, also with the sidebar's cards
    (physical inputs, keyboard) and Fig. 6 in full open: its three columns of plots
    (660 px) made the page 666 px wide; they scroll sideways in their card now."""
    page, console = open_phone(browser, url)
    typeset(page)
    for title in ("Physical inputs", "Keyboard"):
        page.get_by_role("button", name=title).tap()
    wait_until(lambda: page.get_by_text("Use physical inputs").is_visible(),
               what="the physical inputs shown")
    plots = page.locator(".bk-Canvas").count()
    page.get_by_text("Fig. 6 in full").first.dispatch_event("click")  # (a tap's place moves)
    wait_until(lambda: page.locator(".bk-Canvas").count() >= plots + 6,
               what="the six plots of Fig. 6 in full")
    page.evaluate("() => document.fonts.ready.then(() => true)")
    assert page.evaluate("() => document.documentElement.scrollWidth") <= WIDTH
    assert errors(console) == []
    page.close()
