"""PNG export in a real browser: each plot's save tool downloads a PNG of the plot.

Runs against EXPLORER_URL when set, else against a `python -m app.serve` started here
(fixtures in conftest.py).
"""

from __future__ import annotations

import io

import numpy as np
import pytest
from explorer_browser import JS_HELPERS, JS_READY
from PIL import Image

pytestmark = pytest.mark.browser

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

#: JavaScript: the page rectangle of plot `title`, its canvas's size (CSS px), the
#: device pixel ratio, whether its toolbar is shown, the rectangle of its save button,
#: its frame's box (CSS px, within the canvas) and the text of its stamp (null if none).
JS_PLOT = """(title) => {
  const plot = __views((v) => v.model != null && v.model.type === "Figure"
                       && v.model.title != null && v.model.title.text === title)[0];
  const bar = __views((v) => v.model != null && v.model.type === "Toolbar"
                      && v.parent != null && v.parent.parent === plot)[0];
  const save = [...bar.children()].find((b) => b.model.tool.type === "SaveTool");
  const rect = (el) => { const r = el.getBoundingClientRect();
                         return [r.x, r.y, r.width, r.height]; };
  const stamp = [...plot.model.center, ...plot.model.below, ...plot.model.right]
    .find((m) => m.tags.includes("png-stamp"));
  const f = plot.frame.bbox;
  return {plot: rect(plot.el), canvas: [plot.canvas_view.bbox.width,
                                        plot.canvas_view.bbox.height],
          ratio: window.devicePixelRatio, shown: !bar.el.classList.contains("bk-hidden"),
          save: rect(save.el), frame: [f.x, f.y, f.width, f.height],
          stamp: stamp == null ? null : stamp.text};
}"""


def save_plot(page, title: str):
    """Hover the plot titled `title` (its toolbar hides otherwise), click its save tool;
    the download and the plot's geometry."""
    page.evaluate("(t) => __views((v) => v.model != null && v.model.type === 'Figure'"
                  " && v.model.title != null && v.model.title.text === t)[0]"
                  ".el.scrollIntoView({block: 'center'})", title)
    x, y, w, h = page.evaluate(JS_PLOT, title)["plot"]
    page.mouse.move(x + w / 2, y + h / 2)
    page.wait_for_function(f"() => ({JS_PLOT})({title!r}).shown", timeout=10_000)
    geometry = page.evaluate(JS_PLOT, title)
    bx, by, bw, bh = geometry["save"]
    assert bw > 0 and bh > 0  # the button is laid out
    with page.expect_download(timeout=20_000) as info:
        page.mouse.click(bx + bw / 2, by + bh / 2)
    return info.value, geometry


def open_page(browser, url: str, scale: float):
    """The explorer at `url` on a screen of `scale` device pixels per CSS pixel."""
    page = browser.new_page(viewport={"width": 1600, "height": 1400},
                            device_scale_factor=scale)
    page.goto(url)
    page.wait_for_function(JS_READY, timeout=60_000)
    page.evaluate(JS_HELPERS)
    return page


@pytest.mark.parametrize(("title", "file", "scale"), [
    ("Traction profile", "zharii_traction_profile.png", 1),
    ("Tangential force T / T₀", "zharii_tangential_force_t_t0.png", 2),
    ("Two spheres in section", "zharii_two_spheres_in_section.png", 1),
])
def test_the_save_tool_downloads_a_png_of_the_plot(browser, url, tmp_path, title, file,
                                                   scale) -> None:
    """A PNG named after the plot, of the plot's canvas size in device pixels, drawn."""
    page = open_page(browser, url, scale)
    download, geometry = save_plot(page, title)
    assert download.failure() is None
    assert download.suggested_filename == file
    path = tmp_path / "plot.png"
    download.save_as(path)
    data = path.read_bytes()
    assert data[:8] == PNG_MAGIC
    width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
    ratio = geometry["ratio"]
    assert ratio == scale
    canvas_w, canvas_h = geometry["canvas"]
    assert (width, height) == (round(canvas_w * ratio), round(canvas_h * ratio))
    pixels = np.asarray(Image.open(io.BytesIO(data)).convert("RGB")).reshape(-1, 3)
    assert pixels.shape[0] == width * height
    colours = np.unique(pixels, axis=0)
    assert len(colours) > 10  # lines, text, legend: not a blank canvas
    dark = np.all(pixels < 80, axis=1).mean()  # the black curve, axes and labels
    assert 0.001 < dark < 0.5
    page.close()
