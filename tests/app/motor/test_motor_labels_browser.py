"""The Motor card's plots in Chromium: the "contact never opens" labels painted whole,
inside the frame and inside their shading (over no curve), and the legends of the curve
plots out of their frames (over no curve)."""

from __future__ import annotations

import pytest
from test_browser import errors
from test_motor_browser import opened

pytestmark = pytest.mark.browser

THRUST = "Stall thrust along the rod (rotor held)"
LEGENDED = [THRUST, "Archard wear rate along the rod (rotor held)",
            "Thrust against rotor speed at x₀", "Efficiency against rotor speed at x₀"]

#: JavaScript: the view of the plot titled `title`.
JS_PLOT = """(title) => __views((v) => v.model != null && v.model.type === "Figure"
  && v.model.title != null && v.model.title.text === title)[0]"""

#: JavaScript: plot `title`'s frame [left, top, right, bottom] (canvas px), each "never
#: opens" label's painted box there (its lines measured in the label's font, turned by
#: its angle about its centre) and each shaded strip's [left, right].
JS_LABELS = f"""(title) => {{
  const plot = ({JS_PLOT})(title);
  const f = plot.frame.bbox;
  const r = __views((v) => v.model != null && v.model.name === "motor_ends_text")[0];
  const g = r.model.glyph;
  const val = (p) => (p != null && typeof p === "object" && "value" in p) ? p.value : p;
  const col = (s, c) => Array.from(s.data instanceof Map ? s.data.get(c) : s.data[c]);
  const sx = (x) => plot.frame.x_scale.compute(x);
  const sy = (y) => plot.frame.y_scale.compute(y);
  const ctx = document.createElement("canvas").getContext("2d");
  const size = val(g.text_font_size);
  ctx.font = `${{val(g.text_font_style)}} ${{size}} ${{val(g.text_font)}}`;
  const px = parseFloat(size) * (size.endsWith("pt") ? 4 / 3 : 1);
  const angle = val(g.angle);
  const [c, s] = [Math.abs(Math.cos(angle)), Math.abs(Math.sin(angle))];
  const xs = col(r.model.data_source, "x_mm"), ys = col(r.model.data_source, "y");
  const boxes = col(r.model.data_source, "text").map((text, i) => {{
    const lines = text.split("\\n");
    const w = Math.max(...lines.map((l) => ctx.measureText(l).width));
    const h = lines.length * px * val(g.text_line_height);
    const [bw, bh] = [w * c + h * s, w * s + h * c];
    const [x, y] = [sx(xs[i]), sy(ys[i])];
    return [x - bw / 2, y - bh / 2, x + bw / 2, y + bh / 2];
  }});
  const invalid = [...Bokeh.documents[0].all_models].find((m) => m.name === "motor_invalid");
  const strips = col(invalid, "left").map((a, i) => [sx(a), sx(col(invalid, "right")[i])]);
  return {{frame: [f.left, f.top, f.right, f.bottom], boxes, strips}};
}}"""

#: JavaScript: plot `title`'s frame and its legends' boxes [left, top, right, bottom].
JS_LEGENDS = f"""(title) => {{
  const plot = ({JS_PLOT})(title);
  const f = plot.frame.bbox;
  const legends = [...plot.renderer_views.values()].filter((v) => v.model.type === "Legend")
    .map((v) => [v.bbox.left, v.bbox.top, v.bbox.right, v.bbox.bottom]);
  return {{frame: [f.left, f.top, f.right, f.bottom], legends}};
}}"""


def overlap(a, b) -> bool:
    """Whether boxes a and b ([left, top, right, bottom]) share an area."""
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def test_labels_whole_in_their_shading_and_legends_out_of_the_frames(browser, url) -> None:
    """The labels, centred on the narrow strips at the rod's ends, ran past the frame's
    edge (cut) and over the thrust curve; the wear legend stood over its curves."""
    page, console, _ = opened(browser, url)
    page.evaluate(f"(t) => ({JS_PLOT})(t).el.scrollIntoView({{block: 'center'}})", THRUST)
    page.wait_for_function(f"(t) => ({JS_LABELS})(t).boxes.length == 2", arg=THRUST,
                           timeout=20_000)
    shown = page.evaluate(JS_LABELS, THRUST)
    left, top, right, bottom = shown["frame"]
    for box, (a, b) in zip(shown["boxes"], shown["strips"], strict=True):
        assert left - 1 <= box[0] and box[2] <= right + 1, f"cut across: {box} {shown}"
        assert top - 1 <= box[1] and box[3] <= bottom + 1, f"cut up or down: {box} {shown}"
        assert max(a, left) - 1 <= box[0] and box[2] <= min(b, right) + 1, \
            f"outside its shading: {box}, strip {a, b}"
    for title in LEGENDED:
        page.evaluate(f"(t) => ({JS_PLOT})(t).el.scrollIntoView({{block: 'center'}})", title)
        legends = page.evaluate(JS_LEGENDS, title)
        assert legends["legends"], f"{title} has no legend"
        for box in legends["legends"]:
            assert not overlap(box, legends["frame"]), f"{title}'s legend over its frame"
    assert errors(console) == []
    page.close()
