"""Helpers of the browser tests of text drawn on the plots' canvases (issue 39): the
boxes of every title, label, text glyph and y tick label BokehJS draws, and the data
points and circles beside them, read from the plots' views in the page."""

from __future__ import annotations

#: JavaScript: for each plot drawn (a Figure view of some size): its title, canvas and
#: frame boxes [left, top, right, bottom] (CSS px, in the window); `texts`, the box of
#: every text drawn on it (a turned one's box around it): the titles', each `Label`'s
#: (`stamp` true for the psi/tau0/tau stamp; `clipped`: BokehJS clips it to the frame)
#: and each point of each `Text` glyph (`clipped` below the overlay level); `ticks`, per
#: y axis, the least distance between two major ticks and the tick labels' height (px);
#: `points`, the screen points of the other glyphs (lines, markers, segments' ends), and
#: `circles` [x, y, r] of the circles and annuli drawn.
JS_CANVAS_TEXTS = r"""() => {
  const views = [];
  const walk = (v) => {
    if (v.model != null && v.model.type === "Figure") views.push(v);
    for (const c of v.children()) walk(c);
  };
  Object.values(window.Bokeh.index).forEach(walk);
  const px = (size) => {
    const m = /^([\d.]+)(pt|px)$/.exec(typeof size === "object" ? size.value : size);
    return m == null ? 16 : parseFloat(m[1]) * (m[2] === "pt" ? 4 / 3 : 1);
  };
  const out = [];
  for (const v of views) {
    const c = v.canvas_view.el.getBoundingClientRect();
    if (c.width === 0 || c.height === 0) continue;
    const f = v.frame.bbox;
    const at = (x0, y0, x1, y1) => [c.left + x0, c.top + y0, c.left + x1, c.top + y1];
    const texts = [], points = [], circles = [], ticks = [];
    for (const [m, rv] of v.renderer_views) {
      if (!m.visible) continue;
      if (rv._rect != null && typeof m.text === "string" && m.text.trim() !== "") {
        // (a title on a side is drawn turned by `angle` about its anchor point)
        const {sx, sy, width, height, anchor} = rv._rect, angle = rv._rect.angle ?? 0;
        const x0 = -anchor.x * width, y0 = -anchor.y * height;
        const corners = [[x0, y0], [x0 + width, y0], [x0, y0 + height],
                         [x0 + width, y0 + height]].map(([dx, dy]) => [
          sx + dx * Math.cos(angle) - dy * Math.sin(angle),
          sy + dx * Math.sin(angle) + dy * Math.cos(angle)]);
        const xs = corners.map((q) => q[0]), ys = corners.map((q) => q[1]);
        texts.push({text: m.text.slice(0, 40),
                    box: at(Math.min(...xs), Math.min(...ys), Math.max(...xs), Math.max(...ys)),
                    clipped: m.type === "Label", title: m.type === "Title",
                    stamp: m.tags.includes("png-stamp")});
      } else if (m.type === "GlyphRenderer") {
        const g = rv.glyph;
        if (m.glyph.type === "Text") {
          for (let i = 0; i < g.sx.length; i++) {
            const label = g.labels == null ? null : g.labels[i];
            const r = g.rect_i(i);
            const xs = [r.p0.x, r.p1.x, r.p2.x, r.p3.x], ys = [r.p0.y, r.p1.y, r.p2.y, r.p3.y];
            if (label == null || !xs.concat(ys).every(isFinite)) continue;
            texts.push({text: String(label.text ?? "").slice(0, 40),
                        box: at(Math.min(...xs), Math.min(...ys), Math.max(...xs),
                                Math.max(...ys)),
                        clipped: m.level !== "overlay", title: false, stamp: false});
          }
        } else if (g.sradius != null || g.souter_radius != null) {
          const r = g.souter_radius ?? g.sradius;
          for (let i = 0; i < g.sx.length; i++) {
            if (isFinite(g.sx[i] + g.sy[i] + r[i]) && r[i] > 0) {
              circles.push([c.left + g.sx[i], c.top + g.sy[i], r[i]]);
            }
          }
        } else {
          const pairs = [[g.sx, g.sy], [g.sx0, g.sy0], [g.sx1, g.sy1], [g.sx, g.sy1],
                         [g.sx, g.sy2]].filter(([xs, ys]) => xs != null && ys != null);
          for (const [xs, ys] of pairs) {
            for (let i = 0; i < xs.length; i++) {
              if (isFinite(xs[i] + ys[i])) points.push([c.left + xs[i], c.top + ys[i]]);
            }
          }
        }
      } else if (m.type === "LinearAxis" && rv.dimension === 1 && rv.ranges != null) {
        const ys = rv.tick_coords.major[1].map((y) => rv.coordinates.y_scale.compute(y))
          .sort((a, b) => a - b);
        let least = Infinity;
        for (let i = 1; i < ys.length; i++) least = Math.min(least, ys[i] - ys[i - 1]);
        ticks.push({least: least, height: px(m.major_label_text_font_size)});
      }
    }
    out.push({title: v.model.title == null ? "" : v.model.title.text,
              canvas: [c.left, c.top, c.right, c.bottom],
              frame: at(f.left, f.top, f.right, f.bottom), texts, points, circles, ticks});
  }
  return out;
}"""


def overlap(a: list[float], b: list[float]) -> float:
    """How far two boxes [left, top, right, bottom] overlap (px; <= 0: apart)."""
    return min(min(a[2], b[2]) - max(a[0], b[0]), min(a[3], b[3]) - max(a[1], b[1]))


def outside(box: list[float], frame: list[float]) -> float:
    """How far `box` reaches out of `frame` (px; <= 0: inside)."""
    return max(frame[0] - box[0], frame[1] - box[1], box[2] - frame[2], box[3] - frame[3])


def text_defects(plots: list[dict], slack: float = 1.0) -> list[tuple]:
    """What is wrong with the text drawn on `plots` (`JS_CANVAS_TEXTS`): two texts of a
    plot over each other, a text cut by its frame (a label, a clipped text glyph) or by
    the canvas (a title, a text on the overlay level), y tick labels closer than their
    height (stacked); each (plot, what, by how many px)."""
    found = []
    for p in plots:
        texts = p["texts"]
        for i, a in enumerate(texts):
            edge = p["frame"] if a["clipped"] else p["canvas"]
            if (out := outside(a["box"], edge)) > slack:
                found.append((p["title"], f"cut: {a['text']!r}", round(out, 1)))
            for b in texts[i + 1:]:
                if (o := overlap(a["box"], b["box"])) > slack:
                    found.append((p["title"], f"{a['text']!r} over {b['text']!r}", round(o, 1)))
        for t in p["ticks"]:
            if t["least"] < t["height"]:
                found.append((p["title"], "y tick labels stacked",
                              round(t["height"] - t["least"], 1)))
    return found


def stamp_over_data(plots: list[dict], margin: float = 2.0) -> list[tuple]:
    """The stamps of `plots` (`JS_CANVAS_TEXTS`) with a data point or a circle's line
    under them (within `margin` px): (plot, what, how many)."""
    found = []
    for p in plots:
        for s in (t for t in p["texts"] if t["stamp"]):
            left, top, right, bottom = s["box"]
            n = sum(left - margin <= x <= right + margin and top - margin <= y <= bottom + margin
                    for x, y in p["points"])
            # a circle's line crosses the box: its nearest point is inside the circle and
            # its farthest outside it
            for x, y, r in p["circles"]:
                nx, ny = min(max(x, left), right), min(max(y, top), bottom)
                near = ((nx - x) ** 2 + (ny - y) ** 2) ** 0.5
                far = max(((cx - x) ** 2 + (cy - y) ** 2) ** 0.5
                          for cx in (left, right) for cy in (top, bottom))
                n += near <= r + margin and far >= r - margin
            if n:
                found.append((p["title"], "stamp over data", n))
    return found
