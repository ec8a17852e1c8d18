"""The animation player's Play / Pause in headless Chromium (issue 23): a pause lands on
the frame the browser shows at the click, and the keyboard stays on Play / Pause."""

from __future__ import annotations

import random
from urllib.parse import parse_qs

import pytest
from explorer_browser import open_explorer, wait_until

pytestmark = pytest.mark.browser

#: JavaScript: from now on, each click records the tau the page shows at that moment
#: (the tau slider, which the player moves with every frame) in `window.__at_click`,
#: before the clicked control handles it (a listener of the capture phase).
JS_RECORD_AT_CLICK = """() => window.addEventListener(
  "click", () => { window.__at_click = __slider("tau").value; }, true)"""

#: JavaScript: the element the keyboard is on, inside shadow roots: [tag, text].
JS_DEEP_FOCUS = """() => {
  let el = document.activeElement;
  while (el != null && el.shadowRoot != null && el.shadowRoot.activeElement != null) {
    el = el.shadowRoot.activeElement;
  }
  return el == null ? null : [el.tagName, (el.textContent || "").trim()];
}"""

PLAY, PAUSE = "▶ Play", "‖ Pause"


def url_tau(page) -> float | None:
    """The tau in the page's URL (the server's state, written after each change)."""
    values = parse_qs(page.evaluate("() => location.search").lstrip("?")).get("tau")
    return float(values[0]) if values else None


def frames_sent(page) -> bool:
    return page.evaluate("() => (__col('frames', 'tau') || []).length > 0")


def pause_at(page, target: float) -> float:
    """Play, wait until the page shows tau >= `target`, click Pause; the tau shown at the
    click."""
    page.get_by_role("button", name=PLAY).click()
    wait_until(lambda: frames_sent(page), what="the player's frames")
    page.wait_for_function("(t) => __slider('tau').value >= t", arg=target, timeout=20_000)
    page.get_by_role("button", name=PAUSE).click()
    wait_until(lambda: not frames_sent(page), what="the player to stop")
    return page.evaluate("() => window.__at_click")


def test_pause_lands_on_the_frame_shown_at_the_click(browser, url) -> None:
    """The server took the tau a pause lands on from its own clock, ahead of the browser
    by the frames' journey and the click's: the plots jumped forward at the pause."""
    seed = random.randrange(1 << 30)
    rng = random.Random(seed)
    # the default contact (psi = 2.414, tau0 = pi/6: tau in [0.524, 2.618]), from 0.6
    page, console = open_explorer(browser, f"{url}?tau=0.6")
    page.evaluate(JS_RECORD_AT_CLICK)
    step = (2.618 - 0.524) / 239  # one frame
    before = 0.6
    for low, high in ((0.8, 1.4), (1.6, 2.3)):  # two pauses at random moments
        shown = pause_at(page, rng.uniform(low, high))
        paused = wait_until(lambda b=before: url_tau(page) not in (None, b) and url_tau(page),
                            what="the paused tau in the URL")
        assert abs(paused - shown) < 1e-9, (
            f"seed {seed}: shown {shown}, paused {paused} ({(paused - shown) / step:.1f} "
            "frames apart)")
        # the page shows the server's tau once stopped
        assert page.evaluate("() => __slider('tau').value") == paused
        before = paused
    assert [line for line in console if "error" in line.lower()] == []
    page.close()


def test_the_keyboard_stays_on_play_pause(browser, url) -> None:
    """Enter on Play started the animation and dropped the keyboard to the page's body
    (BokehJS draws a new button for the new label), so that Space then scrolled the page
    instead of pausing."""
    page, _ = open_explorer(browser, url, width=1280, height=600)  # a page that scrolls
    page.get_by_role("button", name=PLAY).focus()
    y = page.evaluate("() => window.scrollY")
    page.keyboard.press("Enter")
    wait_until(lambda: frames_sent(page), what="the player's frames")
    page.get_by_role("button", name=PAUSE).wait_for()
    assert page.evaluate(JS_DEEP_FOCUS) == ["BUTTON", PAUSE]
    page.keyboard.press("Space")
    wait_until(lambda: not frames_sent(page), what="the player to stop")
    page.get_by_role("button", name=PLAY).wait_for()
    assert page.evaluate(JS_DEEP_FOCUS) == ["BUTTON", PLAY]
    assert page.evaluate("() => window.scrollY") == y
    # a click keeps the keyboard there too, and Alt + K plays and pauses with it there
    page.get_by_role("button", name=PLAY).click()
    page.get_by_role("button", name=PAUSE).wait_for()
    assert page.evaluate(JS_DEEP_FOCUS) == ["BUTTON", PAUSE]
    page.keyboard.press("Alt+K")
    page.get_by_role("button", name=PLAY).wait_for()
    wait_until(lambda: not frames_sent(page), what="the player to stop")
    assert page.evaluate(JS_DEEP_FOCUS) == ["BUTTON", PLAY]
    page.keyboard.press("Space")
    page.get_by_role("button", name=PAUSE).wait_for()
    assert page.evaluate(JS_DEEP_FOCUS) == ["BUTTON", PAUSE]
    assert page.evaluate("() => window.scrollY") == y
    page.close()



#: JavaScript: {title: [hold_render, in the viewport]} of the page's plots laid out (in
#: an open tab).
JS_HELD = """() => Object.fromEntries(__views((v) => v.model != null
    && v.model.type === "Figure" && v.el.getBoundingClientRect().width > 0)
  .map((v) => { const r = v.el.getBoundingClientRect();
                return [v.model.title.text,
                        [v.model.hold_render, r.bottom > 0 && r.top < innerHeight]]; }))"""

#: JavaScript: scroll plot `title` into the middle of the viewport.
JS_SCROLL_TO = """(title) => __views((v) => v.model != null && v.model.type === "Figure"
  && v.model.title.text === title)[0].el.scrollIntoView({block: "center"})"""

FORCE = "Tangential force T / T₀"


def held_out_of_view(page) -> bool:
    """Whether exactly the plots out of the viewport are held."""
    return all(h == (not shown) for h, shown in page.evaluate(JS_HELD).values())


def test_plots_out_of_view_wait_while_playing(browser, url) -> None:
    """While playing, every frame was painted in every plot, those below the viewport
    too: they are held (BokehJS's hold_render) until they come into view, and every plot
    is painted again at the pause; their sources follow the frames all along."""
    page, console = open_explorer(browser, url, height=900)
    held = page.evaluate(JS_HELD)
    assert held[FORCE] == [False, False]  # below the viewport, not held
    assert not any(h for h, _ in held.values())
    page.get_by_role("button", name=PLAY).click()
    wait_until(lambda: frames_sent(page), what="the player's frames")
    wait_until(lambda: held_out_of_view(page) and page.evaluate(JS_HELD)[FORCE][0],
               what="the plots out of view to be held")
    marker = page.evaluate("() => __col('force_marker', 'x')")
    wait_until(lambda: page.evaluate("() => __col('force_marker', 'x')") != marker,
               what="the held plot's marker to follow the frames")
    page.evaluate(JS_SCROLL_TO, FORCE)
    wait_until(lambda: held_out_of_view(page) and page.evaluate(JS_HELD)[FORCE] == [False, True],
               what="the plot come into view to be painted, those gone out held")
    assert any(h for h, _ in page.evaluate(JS_HELD).values())
    page.get_by_role("button", name=PAUSE).click()
    wait_until(lambda: not frames_sent(page), what="the player to stop")
    wait_until(lambda: not any(h for h, _ in page.evaluate(JS_HELD).values()),
               what="every plot painted again")
    assert [m for m in console if "error" in m.lower()] == []
    page.close()
