"""The Motor card's design map in a real browser (Debian's Chromium through Playwright):
opened inside the Motor card, a small map computed on the runner, its image and hover
columns held in the browser equal to the server's kernel, the hover naming every merit
of the design under the pointer, and a click of the real mouse on the image loading
that design's x0 and preload into the card; a map of several blocks advancing its
progress bar block by block."""

from __future__ import annotations

import numpy as np
import pytest
from test_browser import errors
from test_motor_browser import opened

import app.motor.map_data as md
from app.motor.map_view import MapCard
from app.motor.state import MotorState

pytestmark = pytest.mark.browser

SIZE = 5
#: JavaScript: the named source's column `col` as [shape, flat values] of its one image.
IMAGE = """([name, col]) => {
  const m = Bokeh.documents[0].get_model_by_name(name);
  const v = m.data instanceof Map ? m.data.get(col) : m.data[col];
  if (v == null || v.length !== 1) return null;
  return [Array.from(v[0].shape), Array.from(v[0])];
}"""
#: JavaScript: the map's progress bar as [value, max, shown] (null: not on the page).
BAR = """() => {
  const m = Bokeh.documents[0].all_models;
  const bar = [...m].find((x) => x.css_classes != null
    && x.css_classes.includes('motor-map-progress'));
  if (bar == null) return null;
  const st = bar.styles;
  const shown = (st instanceof Map ? st.get('visibility') : st.visibility) === 'visible';
  return [bar.value, bar.max, shown];
}"""
#: JavaScript: the page position of the map's data point (x, y), the map scrolled into
#: the middle of the window.
WHERE = """([x, y]) => {
  const v = __views((v) => v.model != null && v.model.title != null
    && v.model.title.text != null && v.model.title.text.startsWith('Design map'))[0];
  v.canvas_view.el.scrollIntoView({block: 'center'});
  const r = v.canvas_view.el.getBoundingClientRect();
  return [r.left + v.frame.x_scale.compute(x), r.top + v.frame.y_scale.compute(y)];
}"""


def test_the_design_map_computes_shows_every_merit_and_a_click_loads_a_design(
        browser, url) -> None:
    page, console, _ = opened(browser, url)
    page.get_by_role("button", name=MapCard.TITLE, exact=True).click()  # (its title)
    box = page.locator(".motor-map-size input")
    box.wait_for(timeout=30_000)
    box.fill(str(SIZE))
    box.press("Enter")
    page.wait_for_function(f"(a) => {{ const got = ({IMAGE})(a); return got != null"
                           f" && got[0][0] === {SIZE}; }}", arg=["motor_map", "image"],
                           timeout=60_000)
    expected = md.compute(md.MapRequest.of(MotorState().values(), "x0", "N", SIZE))
    for col in ("image", *md.SHOWN):
        shape, flat = page.evaluate(IMAGE, ["motor_map", col])
        assert shape == [SIZE, SIZE]
        merit = "stall_thrust" if col == "image" else col
        np.testing.assert_array_equal(np.array(flat, float),
                                      expected.image(merit).ravel())  # nan where refused
    _, ax = page.evaluate(IMAGE, ["motor_map", "ax"])
    np.testing.assert_array_equal(np.reshape(ax, (SIZE, SIZE))[0], expected.x)
    # a design in the model's range: its hover names every merit, a click loads it
    j, i = next(zip(*np.nonzero(np.isfinite(expected.merits["best_efficiency"])),
                    strict=True))
    x, y = float(expected.x[i]), float(expected.y[j])
    sx, sy = page.evaluate(WHERE, [x, y])
    page.mouse.move(sx, sy)
    tooltip = page.locator(".bk-tooltip-content").first
    tooltip.wait_for(timeout=10_000)
    text = tooltip.inner_text()
    for label, unit, _ in md.SHOWN.values():
        assert f"{label} ({unit})" in text
    assert f"{expected.image('stall_thrust')[j, i]:.4g}" in text  # this design's
    page.mouse.click(sx + 3, sy - 3)  # (within the design's cell)
    page.wait_for_function("(x) => __slider('motor_x0').value === x", arg=x, timeout=20_000)
    page.wait_for_function("(n) => __slider('motor_N').value === n", arg=y, timeout=20_000)
    page.wait_for_function("(k) => location.search.includes(k)", arg=f"motor_x0={x!r}",
                           timeout=20_000)
    mark = page.evaluate("() => [__col('motor_map_mark', 'x'), __col('motor_map_mark', 'y')]")
    assert mark == [[x], [y]]
    # a map of several row blocks: the bar shows the designs done advance block by block
    big = 40  # 1600 designs: 7 blocks of 240 (6 rows), the last of 4 rows
    box.fill(str(big))
    box.press("Enter")
    page.wait_for_function(f"() => {{ const b = ({BAR})(); return b != null && b[0] > 0"
                           f" && b[0] < b[1] && b[1] === {big * big} && b[2]; }}",
                           timeout=60_000)
    page.wait_for_function(f"(a) => {{ const got = ({IMAGE})(a); return got != null"
                           f" && got[0][0] === {big}; }}", arg=["motor_map", "image"],
                           timeout=120_000)
    page.wait_for_function(f"() => {{ const b = ({BAR})(); return b != null && !b[2]; }}",
                           timeout=20_000)  # hidden with the map shown
    assert errors(console) == []
    page.close()

