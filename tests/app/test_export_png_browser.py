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
from explorer_browser import open_explorer, wait_until
from PIL import Image

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
    to the frame: dragged upwards, the curves were painted over the plot's title."""
    page, _ = open_explorer(browser, url)
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
    page.close()
