"""The full page's first screen, measured in Debian's Chromium at a laptop's and a
projector's window (issue 39): Play on the first screen beside the other scenes, a
preset's figure brought into view when it is chosen, and nothing that moves while the
animation changes phase (the formula card as tall in every phase)."""

from __future__ import annotations

import pytest
from explorer_browser import open_explorer, steady, wait_until

from app.contact.state import PRESETS

pytestmark = pytest.mark.browser

#: JavaScript: the boxes [left, top, right, bottom] (CSS px, in the window) of the plots
#: with these titles, drawn and laid out.
JS_PLOTS = """(titles) => {
  const out = {};
  for (const v of __views((v) => v.model != null && v.model.type === "Figure"
      && v.model.title != null && titles.includes(v.model.title.text))) {
    const r = v.el.getBoundingClientRect();
    if (r.width > 0) out[v.model.title.text] = [r.left, r.top, r.right, r.bottom];
  }
  return out;
}"""

#: The plots of each preset's figure on the full page (their titles).
FIGURES = {
    "fig4": ["Height of the lower sphere u_z0 / H (Fig. 4a)",
             "Approach α/(H−h), contact radius a/a*, stick radius b/a*"],
    "fig7b": ["Tangential force T / T₀"],
    "fig8": ["Tangential impulse T_imp / (μ P_imp)"],
    "fig9": ["Contact-centre velocity (Fig. 9a)", "Contact-centre displacement (Fig. 9b)"],
    "fig6c": ["Traction profile"],
}


def plots(page, titles: list[str]) -> dict[str, list[float]]:
    return page.evaluate(JS_PLOTS, titles)


def in_view(box: list[float], view: tuple[int, int]) -> bool:
    left, top, right, bottom = box
    return -0.5 <= left and right <= view[0] + 0.5 and -0.5 <= top and bottom <= view[1] + 0.5


def test_the_first_screen_holds_play_and_the_scenes_at_1280x720(browser, url) -> None:
    """At 1280 x 720 Play was below the fold and the 40 % of the width at the right of
    the spheres blank (the scenes wrapped under the controls): Play is on the first
    screen, and the traction profile beside the spheres, reaching the window's right."""
    page, console = open_explorer(browser, url, width=1280, height=720)
    page.evaluate("() => document.fonts.ready.then(() => true)")
    play = steady(lambda: page.get_by_role("button", name="▶ Play").bounding_box())
    assert play["y"] + play["height"] <= 720, play
    shown = steady(lambda: plots(page, ["Two spheres in section", "Traction profile"]))
    spheres, traction = shown["Two spheres in section"], shown["Traction profile"]
    assert in_view(spheres, (1280, 720)), shown
    assert traction[0] >= spheres[2] and traction[1] < 200, shown  # beside, at the top
    assert traction[2] >= 0.9 * 1280, shown  # the width used
    assert [m for m in console if m.startswith(("error", "pageerror"))] == []
    page.close()


@pytest.mark.parametrize("screen", [(1280, 720), (1920, 1080)], ids=lambda s: f"{s[0]}x{s[1]}")
def test_choosing_a_preset_brings_its_figure_into_view(browser, url, screen) -> None:
    """A preset's figure sat 2000-2900 px down at 1280 x 720 (Figs. 4 and 9 below the
    fold at 1920 x 1080 too), and nothing brought it into view: once chosen in the menu,
    its plots are on the screen, whole (the first of two panels at 1280 x 720, where the
    two do not fit one screen)."""
    width, height = screen
    page, console = open_explorer(browser, url, width=width, height=height)
    menu = page.get_by_role("combobox", name="Preset: the paper's figures")
    for preset, titles in FIGURES.items():
        menu.select_option(label=PRESETS[preset].label)
        needed = titles if height >= 1000 else titles[:1]
        wait_until(lambda t=titles, n=needed: len(shown := plots(page, t)) == len(t) and all(
            in_view(shown[title], screen) for title in n),
            what=f"{preset}'s figure in view: {titles}")
        page.evaluate("() => window.scrollTo(0, 0)")  # the next one from the top
    assert [m for m in console if m.startswith(("error", "pageerror"))] == []
    page.close()


def card_box(page, title: str) -> list[float]:
    """[top, height] of the card titled `title` on the page (CSS px, from the page's
    top)."""
    box = page.locator(".card").filter(
        has=page.locator(".card-header", has_text=title)).first.bounding_box()
    return [round(box["y"] + page.evaluate("() => scrollY"), 1), round(box["height"], 1)]


def test_nothing_moves_when_the_phase_changes(browser, url) -> None:
    """The formula card changed its height with the phase, so that at 1920 x 1080 the
    cards below it moved between y = 858 and 1079 while playing: in slip, partial stick
    and counter-slip (Figs. 6c, 6e, 6f) the formula card and the cards around it are
    where they are, and as high."""
    page, _ = open_explorer(browser, url, width=1920, height=1080)
    boxes = []
    menu = page.get_by_role("combobox", name="Preset: the paper's figures")
    for preset, phase in (("fig6c", "Slip"), ("fig6e", "Partial stick"),
                          ("fig6f", "Counter-slip")):
        menu.select_option(label=PRESETS[preset].label)
        page.locator(".card").filter(has_text="Formulas of the current phase").locator(
            "b", has_text=phase).first.wait_for()
        page.evaluate("() => document.fonts.ready.then(() => true)")
        boxes.append(steady(lambda: [card_box(page, t) for t in (
            "Formulas of the current phase", "Derived quantities", "Curves over the contact")]))
    assert boxes[0] == boxes[1] == boxes[2], boxes
    page.close()

