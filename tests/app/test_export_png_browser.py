"""Plots as a user pans and saves them, in headless Chromium: a panned curve stays
inside its frame (never over the title), and a saved PNG names the contact and the
time it shows (psi, tau0, tau).

Runs against EXPLORER_URL when set, else against a `python -m app.serve` started here
(fixtures in conftest.py).
"""

from __future__ import annotations

import io

import numpy as np
import pytest
from explorer_browser import column, open_explorer, wait_until
from PIL import Image
from test_export_browser import JS_PLOT, save_plot

from app.kit.figures import BELOW_SEP

pytestmark = pytest.mark.browser

#: JavaScript: the page rectangles of plot `title`'s canvas and frame, and its title band
#: (the title's box), in CSS px.
JS_GEOMETRY = """(title) => {
  const plot = __views((v) => v.model != null && v.model.type === "Figure"
                       && v.model.title != null && v.model.title.text === title)[0];
  plot.el.scrollIntoView({block: "center"});
  const r = plot.canvas_view.el.getBoundingClientRect();
  const f = plot.frame.bbox;
  const t = plot.model.title;
  const title_view = plot.renderer_views.get(t);
  const tb = title_view.bbox;
  // (the title inset by 4 px: a dragged plot has the keyboard, its outline dotted)
  return {canvas: [r.x, r.y, r.width, r.height], frame: [r.x + f.x, r.y + f.y, f.width,
          f.height], title: [r.x + tb.x, r.y + tb.y + 4, tb.width - 4, tb.height - 4]};
}"""


#: JavaScript: the Bokeh levels of the glyphs drawing source `source` (and its marker's).
JS_LEVELS = """(source) => [...new Set(__renderers().filter(
  (v) => [source, source + "_marker"].includes(v.model.data_source.name))
  .map((v) => v.model.level))]"""


#: JavaScript: resolves once the browser has painted twice (what changed is on screen).
PAINTED = "() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))"


def band(page, rect) -> np.ndarray:
    """The pixels (RGB) of the page rectangle `rect` = [x, y, w, h] (CSS px)."""
    x, y, w, h = rect
    png = page.screenshot(clip={"x": x, "y": y, "width": w, "height": h})
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(int)


def pan(page, frame, dx: float, dy: float) -> None:
    """Drag inside `frame` by (dx, dy) CSS px with the mouse (the pan tool is active)."""
    x, y, w, h = frame
    x0, y0 = x + w / 2, y + h * 0.6
    page.mouse.move(x0, y0)
    page.mouse.down()
    for k in range(1, 11):
        page.mouse.move(x0 + dx * k / 10, y0 + dy * k / 10)
    page.mouse.up()


@pytest.mark.parametrize(("title", "source"), [("Traction profile", "traction"),
                                               ("Tangential force T / T₀", "force")])
def test_a_panned_curve_never_covers_the_title(browser, url, title, source) -> None:
    """The scenes drew their data at Bokeh's overlay level, which BokehJS does not clip
    to the frame: dragged upwards, the curves were painted over the plot's title.  They
    are there until the user moves the view (a played frame then repaints the overlay
    layer only), and at the glyph level (clipped) from the pan's start on."""
    page, _ = open_explorer(browser, url)
    assert page.evaluate(JS_LEVELS, source) == ["overlay"]
    geometry = page.evaluate(JS_GEOMETRY, title)
    page.mouse.move(2, 2)  # (the toolbar hides)
    before = band(page, geometry["title"])
    y0 = page.evaluate(f"() => __views((v) => v.model != null && v.model.type === 'Figure'"
                       f" && v.model.title.text === {title!r})[0].model.y_range.start")
    pan(page, geometry["frame"], 0, -0.9 * geometry["frame"][3])
    # the view moved: the y range follows the drag
    wait_until(lambda: page.evaluate(
        f"() => __views((v) => v.model != null && v.model.type === 'Figure'"
        f" && v.model.title.text === {title!r})[0].model.y_range.start") < y0,
        what="the pan to move the y range")
    page.mouse.move(2, 2)
    page.evaluate(PAINTED)
    after = band(page, geometry["title"])
    # data were painted above the frame before the fix: compare the title's band
    changed = np.any(np.abs(after - before) > 40, axis=2)
    assert changed.mean() < 0.002, f"{changed.sum()} pixels of the title changed"
    assert page.evaluate(JS_LEVELS, source) == ["glyph"]
    page.close()



#: JavaScript: show (true) or hide plot `title`'s stamp, in the browser only.
JS_SHOW_STAMP = """([title, visible]) => {
  const plot = __views((v) => v.model != null && v.model.type === "Figure"
                       && v.model.title != null && v.model.title.text === title)[0];
  [...plot.model.center, ...plot.model.below, ...plot.model.right]
    .find((m) => m.tags.includes("png-stamp"))
    .setv({visible: visible}, {sync: false});
}"""


def save_pixels(page, title: str) -> np.ndarray:
    """The PNG saved from the toolbar of the plot titled `title`: its pixels (RGB)."""
    download, _ = save_plot(page, title)
    return np.asarray(Image.open(download.path()).convert("RGB")).astype(int)


def move_psi(page, presses: int) -> float:
    """Move psi's slider `presses` steps up by keyboard; psi once the server's answer
    (the traction profile) arrived."""
    before = column(page, "traction", "traction")
    page.locator(".slider-psi input[type=range]").focus()
    for _ in range(presses):
        page.keyboard.press("ArrowRight")
    wait_until(lambda: column(page, "traction", "traction") != before,
               what="the traction profile to follow psi")
    return page.evaluate("() => __psi()")


def stamp_of(psi: float, tau0: float, tau: float, sep: str = "   ") -> str:
    """A stamp's text (as app.kit.figures.STAMPS_JS writes it)."""
    return sep.join([f"ψ = {float(f'{psi:.6g}'):g}", f"τ₀ = {tau0:.4f} rad",
                     f"τ = {tau:.4f} rad"])


STAMPED = [("Traction profile", "   "), ("Tangential force T / T₀", BELOW_SEP),
           ("Two spheres in section", "\n"), ("Contact disc (top view)", "\n")]


def test_a_saved_png_names_psi_tau0_and_tau(browser, url) -> None:
    """A PNG from a plot's save tool carried neither the parameters nor the time: after
    a psi move each plot's stamp names the psi, tau0 and tau the page shows, and the PNG
    has it (the same PNG without the stamp differs inside the frame)."""
    page, console = open_explorer(browser, url)
    psi = move_psi(page, 3)
    assert psi != pytest.approx(2.414, abs=1e-3)  # moved away from the default page
    tau0 = page.evaluate("() => __slider('tau0').value")
    tau = page.evaluate("() => __slider('tau').value")
    for title, sep in STAMPED:
        wait_until(lambda t=title, s=sep: page.evaluate(JS_PLOT, t)["stamp"]
                   == stamp_of(psi, tau0, tau, s), what=f"{title}'s stamp")
    title = "Traction profile"
    stamped = save_pixels(page, title)
    # the same plot without its stamp, saved in another tab of the same link (Chromium
    # lets a tab's second download through only while the click's activation lasts:
    # on a loaded machine the save's PNG can come later)
    # (waited for in the page: Playwright's `page.url` follows the address bar only when
    # another of its calls runs, so polling it alone may never see the write)
    page.wait_for_function("(p) => location.search.includes('psi=' + p)", arg=repr(psi),
                           timeout=20_000)
    other, _ = open_explorer(browser, page.evaluate("() => location.href"))
    wait_until(lambda: page.evaluate(JS_PLOT, title)["stamp"]
               == other.evaluate(JS_PLOT, title)["stamp"], what="the same stamp")
    other.evaluate(JS_SHOW_STAMP, [title, False])
    other.evaluate(PAINTED)
    bare = save_pixels(other, title)
    other.close()
    rows, cols = np.nonzero(np.any(np.abs(stamped - bare) > 60, axis=2))
    assert rows.size > 200, "the PNG shows no stamp"
    fx, fy, fw, fh = page.evaluate(JS_PLOT, title)["frame"]
    assert fx <= cols.min() and cols.max() <= fx + fw  # in the frame
    assert fy <= rows.min() and rows.max() <= fy + fh
    assert [m for m in console if "error" in m.lower()] == []
    page.close()


def test_the_stamps_follow_the_played_frames(browser, url) -> None:
    """While playing, the browser's player shows another tau every frame and no message
    reaches the server: each stamp names the tau of the frame shown."""
    page, _ = open_explorer(browser, url)
    start = page.evaluate("() => __slider('tau').value")
    page.get_by_role("button", name="Play").first.click()
    read = ("() => [__col('spheres_forces', 'tau')[0], __slider('tau0').value, "
            "__psi(), ...__views((v) => v.model != null && v.model.type === 'Figure' && "
            "['Traction profile', 'Tangential force T / T₀'].includes(v.model.title.text))"
            ".map((v) => [...v.model.center, ...v.model.below]"
            ".find((m) => m.tags.includes('png-stamp')).text)]")
    seen = set()
    for _ in range(3):
        tau, tau0, psi, *stamps = wait_until(
            lambda: (r := page.evaluate(read)) and r[0] != start and r[0] not in seen and r,
            what="a new frame")
        seen.add(tau)
        assert sorted(stamps) == sorted([stamp_of(psi, tau0, tau),  # (traction: a line)
                                         stamp_of(psi, tau0, tau, BELOW_SEP)])  # (T: under)
    page.close()
