"""Speed-ups for BokehJS, installed in the page when the document is ready.

BokehJS 3.10 does work on every data change and every paint that this app never needs.
Each change below was found in a Chrome trace or CPU profile of slider moves and
checked by paired A/B runs (two pages, moves alternated); each leaves what is drawn as
it was, and the browser tests check that.

1. Skip stylesheet rewrites that would not change the stylesheet's text (most of
   them).  BokehJS gives every renderer a DOM element positioned by a stylesheet of its
   own, rewritten on every paint, and reads visual properties (text colours, fonts)
   from CSS while it paints; a write that changes a stylesheet makes the next read wait
   for the page's styles to be recalculated (1.5-2.5 ms each on this page, in software
   rendering).  With a dozen renderers repainted per animation frame this ping-pong
   cost the explorer about 15 % of its frame rate.
2. Write glyph renderers' element positions late.  The element sits over the glyph's
   bounding box on screen, which moves with the data: a slider move changed seven of
   them, one plot after another, each change followed by the next plot's CSS reads:
   five recalculations per move.  The elements are empty (glyphs are drawn on the
   canvas), so their positions are written once all plots have painted (the next task)
   instead: one recalculation.  95 ms -> 82.5 ms median from a slider move to all
   plots updated.
3. Keep a glyph renderer's variant glyphs up to date only while they can be drawn.
   Each renderer has five variants of its glyph (decimated, selection, non-selection,
   hover, muted), and BokehJS gives every one the new data, visuals and screen
   coordinates on each change, although it draws them only while something is
   selected, hovered with a hover glyph, muted, or decimated (more points than the
   plot's `lod_threshold`, while panning).  Nothing of that happens on a slider move
   or an animation frame.  A variant skipped this way is marked stale; the first paint
   that needs it draws the base glyph instead and brings the variants up to date, so
   they draw themselves one frame later.
4. Compute the viewport query of markers and circles (`_mask_data`) with numbers
   instead of four throw-away `Range1d` models per call: building a Bokeh model costs
   ~0.1 ms, and it ran twice per marker per paint.

5. Paint a plot only while it is on screen (or within 200 px of it).  BokehJS paints
   every plot whose data changed, in view or not; a plot scrolled out of view now keeps
   its new data and is painted when it comes back into view (an IntersectionObserver),
   or before the page is printed.  On a projector or a laptop most plots are out of
   view at any time.

3 and 4 together: JavaScript per slider move 50 -> 35 ms (CPU profile of ten moves),
81 vs 85 ms median to all plots updated, 38 vs 30 frames/s (paired runs); 5 on top
(1600x1400 page, two plots out of view): 76 vs 80 ms, 42 vs 37 frames/s.

If a future BokehJS renames what these replace, the shim leaves that part alone, says
so in the console, and only speed is lost.
"""

from __future__ import annotations

from bokeh.document import Document
from bokeh.models import CustomJS

SHIM_JS = """
const Bokeh = window.Bokeh;
// patch(name, targets, make): targets maps a key to [module, class, method]; when every
// one exists, each is replaced by make(originals)[key], once per page, and its class's
// prototype gets the flag __zharii_<name> (and the original in __zharii_originals);
// otherwise nothing is replaced and the console says why.
const patch = (name, targets, make) => {
  const found = {};
  for (const [key, [path, cls, method]] of Object.entries(targets)) {
    let module = null;
    try { module = Bokeh.require(path); } catch (e) { module = null; }
    const proto = module && module[cls] ? module[cls].prototype : null;
    if (proto == null || typeof proto[method] !== "function") {
      console.info(`zharii: BokehJS shim ${name} not installed (${cls}.${method} changed)`);
      return;
    }
    found[key] = [proto, method];
  }
  const flag = `__zharii_${name}`;
  if (Object.values(found).some(([proto]) => Object.hasOwn(proto, flag))) { return; }
  const originals = {};
  for (const [key, [proto, method]] of Object.entries(found)) {
    originals[key] = proto[method];
  }
  const replacements = make(originals);
  for (const [key, [proto, method]] of Object.entries(found)) {
    if (!Object.hasOwn(proto, "__zharii_originals")) { proto.__zharii_originals = {}; }
    proto.__zharii_originals[method] = originals[key];
    proto[method] = replacements[key];
  }
  for (const [proto] of Object.values(found)) { proto[flag] = true; }
};

// 1. stylesheets: skip rewrites to the same text
patch("skip_same", {update: ["core/dom", "InlineStyleSheet", "_update"]}, (orig) => ({
  update(css) {
    if (this.el == null || this.el.textContent !== css) { orig.update.call(this, css); }
  },
}));

// 2. glyph renderers' element positions: written once all plots have painted
patch("late_position",
      {position: ["models/renderers/glyph_renderer", "GlyphRendererView", "update_position"]},
      (orig) => {
  const pending = new Set();
  const flush = () => {
    const views = [...pending];
    pending.clear();
    for (const view of views) {
      try { orig.position.call(view); } catch (e) { /* removed meanwhile */ }
    }
  };
  return {
    position() {
      if (pending.size === 0) { setTimeout(flush, 0); }
      pending.add(this);
    },
  };
});

// 3. variant glyphs (decimated, selection, non-selection, hover, muted): kept up to date
// only while the renderer can draw them
const renderer = "models/renderers/glyph_renderer";
patch("lazy_variants", {
  set_data: ["models/glyphs/glyph", "GlyphView", "set_data"],
  set_visuals: [renderer, "GlyphRendererView", "set_visuals"],
  map_data: [renderer, "GlyphRendererView", "map_data"],
  paint: [renderer, "GlyphRendererView", "_paint"],
}, (orig) => {
  const variants = (r) => [r.decimated_glyph, r.selection_glyph, r.nonselection_glyph,
                           r.hover_glyph, r.muted_glyph];
  const glyphs = (r) => [r.glyph, ...variants(r)].filter((g) => g != null);
  // what GlyphRendererView._paint draws a variant for (decimation: any large glyph)
  const drawn = (r) => {
    const source = r.model.data_source;
    const {lod_threshold} = r.plot_model;
    return r.model.muted || !source.selected.is_empty()
      || (r.hover_glyph != null && !source.inspected.is_empty())
      || (lod_threshold != null && r.model.view.indices.count > lod_threshold);
  };
  const stale = (r) => variants(r).some((g) => g != null && g.__zharii_stale);
  return {
    set_data(source, indices, changed) {
      if (this.base != null && !drawn(this.parent)) {
        this.__zharii_stale = true;
        return Promise.resolve();
      }
      this.__zharii_stale = false;
      return orig.set_data.call(this, source, indices, changed);
    },
    async set_visuals() {
      const source = this.model.data_source;
      for (const g of glyphs(this)) {
        if (g.__zharii_stale) { continue; }
        g.set_visuals(source, this.all_indices);
        g.after_visuals();
        await g.after_lazy_visuals();
      }
    },
    map_data() {
      for (const g of glyphs(this)) {
        if (!g.__zharii_stale) { g.map_data(); }
      }
    },
    paint(ctx) {
      if (!(stale(this) && drawn(this))) { return orig.paint.call(this, ctx); }
      // this frame: the base glyph in every role; next frame: the variants, updated
      const keep = variants(this);
      this.decimated_glyph = this.selection_glyph = this.nonselection_glyph = this.glyph;
      this.muted_glyph = this.glyph;
      if (this.hover_glyph != null) { this.hover_glyph = this.glyph; }
      try {
        orig.paint.call(this, ctx);
      } finally {
        [this.decimated_glyph, this.selection_glyph, this.nonselection_glyph,
         this.hover_glyph, this.muted_glyph] = keep;
      }
      this.update_data();
    },
  };
});

// 4. the viewport query of markers and circles, without building Range1d models
// (same numbers as Range1d.widen and Range1d.map: a reversed range widens inwards)
const widen = (start, end, by) => (start > end ? [start + by, end - by]
                                               : [start - by, end + by]);
patch("plain_mask", {
  marker: ["models/glyphs/marker", "MarkerView", "_mask_data"],
  radial: ["models/glyphs/radial_glyph", "RadialGlyphView", "_mask_data"],
}, () => ({
  marker() {
    const {x_target: xt, y_target: yt} = this.renderer.plot_view.frame;
    const {xscale, yscale} = this.renderer;
    const [x0, x1] = widen(xt.start, xt.end, this.max_size);
    const [y0, y1] = widen(yt.start, yt.end, this.max_size);
    return this.index.indices({x0: xscale.invert(x0), x1: xscale.invert(x1),
                               y0: yscale.invert(y0), y1: yscale.invert(y1)});
  },
  radial() {
    const {x_target: xt, y_target: yt} = this.renderer.plot_view.frame;
    const {xscale, yscale} = this.renderer;
    const r = this.max_radius;
    let x, y;
    if (this.model.properties.radius.units == "data") {
      x = widen(xscale.invert(xt.start), xscale.invert(xt.end), r);
      y = widen(yscale.invert(yt.start), yscale.invert(yt.end), r);
    } else {
      x = widen(xt.start, xt.end, r).map((v) => xscale.invert(v));
      y = widen(yt.start, yt.end, r).map((v) => yscale.invert(v));
    }
    return this.index.indices({x0: x[0], x1: x[1], y0: y[0], y1: y[1]});
  },
}));

// 5. plots out of view keep their data and are painted when they come into view
patch("paint_in_view", {repaint: ["models/plots/plot", "PlotView", "repaint"]}, (orig) => {
  const views = new Map();  // element -> plot view
  const observer = new IntersectionObserver((entries) => {
    for (const entry of entries) {
      const view = views.get(entry.target);
      if (view == null) { continue; }
      if (!entry.target.isConnected) {
        observer.unobserve(entry.target);
        views.delete(entry.target);
        continue;
      }
      view.__zharii_in_view = entry.isIntersecting;
      if (entry.isIntersecting && view.__zharii_deferred) {
        view.__zharii_deferred = false;
        view.request_paint();
      }
    }
  }, {rootMargin: "200px"});
  window.addEventListener("beforeprint", () => {
    for (const view of views.values()) {
      if (!view.__zharii_deferred) { continue; }
      view.__zharii_deferred = false;
      try { orig.repaint.call(view); } catch (e) { /* removed meanwhile */ }
    }
  });
  return {
    repaint() {
      if (!views.has(this.el)) {  // in view until the observer says otherwise
        views.set(this.el, this);
        this.__zharii_in_view = true;
        observer.observe(this.el);
      }
      if (this.__zharii_in_view) { return orig.repaint.call(this); }
      this.__zharii_deferred = true;
      if (this._needs_notify === true) {  // what paint() would have done after painting
        this._needs_notify = false;
        this.notify_finished();
      }
    },
  };
});
"""


def install(doc: Document) -> None:
    """Install the shim in the browser showing `doc`, once its document is ready."""
    doc.js_on_event("document_ready", CustomJS(code=SHIM_JS))
