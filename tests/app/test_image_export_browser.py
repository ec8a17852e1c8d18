"""Images for slides, in headless Chromium: each plot's toolbar saves a PNG at 2x and at
3x the plot's CSS size and an SVG, each with the plot's stamp (psi, tau0, tau), named
as the save tool's PNG (app.kit.image_export).

Runs against EXPLORER_URL when set, else against a `python -m app.serve` started here
(fixtures in conftest.py).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from explorer_browser import open_explorer
from PIL import Image
from test_export_browser import JS_PLOT, save_plot
from test_export_png_browser import JS_SHOW_STAMP, PAINTED

pytestmark = pytest.mark.browser

#: JavaScript: the page rectangles of the toolbar button of plot `title` whose tooltip
#: is `tip` (null when the toolbar has no such button) and of the toolbar's overflow
#: button ("⋯", which opens the menu of the buttons that did not fit; null if none).
JS_ACTION = """([title, tip]) => {
  const plot = __views((v) => v.model != null && v.model.type === "Figure"
                       && v.model.title != null && v.model.title.text === title)[0];
  const bar = __views((v) => v.model != null && v.model.type === "Toolbar"
                      && v.parent != null && v.parent.parent === plot)[0];
  const button = [...bar.children()].find((b) => b.el.title === tip);
  const rect = (el) => { if (el == null || !el.isConnected) return null;
                         const r = el.getBoundingClientRect();
                         return r.width > 0 ? [r.x, r.y, r.width, r.height] : null; };
  return button == null ? null : {button: rect(button.el), overflow: rect(bar.overflow_el)};
}"""


def click(page, rect) -> None:
    """Click the middle of page rectangle `rect` = [x, y, w, h] (CSS px)."""
    x, y, w, h = rect
    page.mouse.click(x + w / 2, y + h / 2)


def export(page, title: str, tip: str):
    """Hover plot `title` (its toolbar hides otherwise) and click its toolbar button
    `tip` (first opening the toolbar's overflow menu if the button is in it, as on a
    short plot): the download."""
    page.evaluate("(t) => __views((v) => v.model != null && v.model.type === 'Figure'"
                  " && v.model.title != null && v.model.title.text === t)[0]"
                  ".el.scrollIntoView({block: 'center'})", title)
    x, y, w, h = page.evaluate(JS_PLOT, title)["plot"]
    page.mouse.move(x + w / 2, y + h / 2)
    page.wait_for_function(f"() => ({JS_PLOT})({title!r}).shown", timeout=10_000)
    where = page.evaluate(JS_ACTION, [title, tip])
    assert where is not None, f"{title!r} has no {tip!r} in its toolbar"
    if where["button"] is None:
        assert where["overflow"] is not None, f"{tip!r} is neither shown nor in a menu"
        click(page, where["overflow"])
        page.wait_for_function(f"() => ({JS_ACTION})({[title, tip]!r}).button != null",
                               timeout=10_000)
        where = page.evaluate(JS_ACTION, [title, tip])
    with page.expect_download(timeout=20_000) as info:
        click(page, where["button"])
    download = info.value
    assert download.failure() is None
    return download


def pixels(download) -> np.ndarray:
    """A downloaded PNG's pixels (RGB, int)."""
    return np.asarray(Image.open(download.path()).convert("RGB")).astype(int)


def test_png_at_2x_and_3x_with_the_stamp(browser, url) -> None:
    """Only the screen's resolution could be saved: at one device pixel per CSS pixel,
    "Save PNG 2x" and "3x" give 2 and 3 times the plot's pixels, the same picture as the
    save tool's PNG (averaged back to 1x), and the stamp drawn inside the frame."""
    page, console = open_explorer(browser, url)
    title = "Traction profile"
    geometry = page.evaluate(JS_PLOT, title)
    assert geometry["ratio"] == 1
    width, height = (round(v) for v in geometry["canvas"])
    screen = pixels(save_plot(page, title)[0])
    assert screen.shape[:2] == (height, width)
    for scale in (2, 3):
        download = export(page, title, f"Save PNG {scale}x")
        assert download.suggested_filename == f"zharii_traction_profile_{scale}x.png"
        image = pixels(download)
        assert image.shape[:2] == (scale * height, scale * width)
        # averaged over scale x scale blocks, the picture the save tool draws at 1x
        back = image.reshape(height, scale, width, scale, 3).mean(axis=(1, 3))
        assert np.abs(back - screen).mean() < 6, "not the plot's picture"
    # the stamp: the same 2x PNG without it differs in the frame, in a text-sized box
    stamped = pixels(export(page, title, "Save PNG 2x"))
    page.evaluate(JS_SHOW_STAMP, [title, False])
    page.evaluate(PAINTED)
    bare = pixels(export(page, title, "Save PNG 2x"))
    rows, cols = np.nonzero(np.any(np.abs(stamped - bare) > 60, axis=2))
    assert rows.size > 400, "the 2x PNG shows no stamp"
    fx, fy, fw, fh = (2 * v for v in geometry["frame"])
    assert fx <= cols.min() and cols.max() <= fx + fw
    assert fy <= rows.min() and rows.max() <= fy + fh
    # one line of 9 pt text at 2x: about 24 px high, a few hundred wide
    assert 10 < rows.max() - rows.min() < 60 and cols.max() - cols.min() > 200
    assert [m for m in console if "error" in m.lower()] == []
    page.close()


@pytest.mark.parametrize(("title", "file"), [
    ("Traction profile", "zharii_traction_profile.svg"),
    ("Tangential force T / T₀", "zharii_tangential_force_t_t0.svg"),
])
def test_svg_of_the_plot_with_its_stamp(browser, url, title, file) -> None:
    """No vector image could be saved: "Save SVG" gives an SVG document of the plot's
    CSS size holding its title, its axis labels and the stamp's text."""
    page, console = open_explorer(browser, url)
    geometry = page.evaluate(JS_PLOT, title)
    download = export(page, title, "Save SVG")
    assert download.suggested_filename == file
    root = ET.parse(download.path()).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    width, height = geometry["canvas"]
    assert float(root.get("width")) == pytest.approx(width, abs=1)
    assert float(root.get("height")) == pytest.approx(height, abs=1)
    texts = ["".join(t.itertext()) for t in root.iter("{http://www.w3.org/2000/svg}text")]
    assert title in texts
    assert geometry["stamp"]  # (a stacked stamp is a text per line)
    assert all(line in texts for line in geometry["stamp"].split("\n"))
    assert [m for m in console if "error" in m.lower()] == []
    page.close()
