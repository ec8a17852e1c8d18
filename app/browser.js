// BokehJS speed-ups for the explorer: see app/browser.py for what each does and why.
// Runs as the body of a CustomJS callback on the document's "document_ready" event.
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

// 6. axis sizes: measured again only when something that sizes them changed.  On every
// paint BokehJS checks whether an axis needs more or less room than it has, measuring
// its tick labels and title (canvas text metrics and CSS reads); here the size from the
// last measurement is reused while the axis, its ticker and formatter models (watched
// through their change signals), its ranges' ends, its side and the plot's base font
// size are the same.  Only for that check: a forced layout (resize) measures afresh.
// Axes with TeX titles or label overrides (sizes that change when MathJax is done) are
// always measured.
patch("axis_sizes", {
  get_size: ["models/axes/axis", "AxisView", "get_size"],
  check: ["models/plots/plot", "PlotView", "_invalidate_layout_if_needed"],
}, (orig) => {
  const generation = (view) => {  // bumped on any change of the models that size the axis
    const watch = view.__zharii_watch ??= {generation: 0, models: new Set()};
    for (const model of [view.model, view.model.ticker, view.model.formatter]) {
      if (!watch.models.has(model)) {  // first seen (a new ticker or formatter: a change)
        watch.models.add(model);
        watch.generation += 1;
        view.connect(model.change, () => { watch.generation += 1; });
      }
    }
    return watch.generation;
  };
  const key = (view) => {  // null: not memoised
    const label = view._axis_label_view;
    if ((label != null && label.model.type !== "PlainText") || view._major_label_views.size > 0) {
      return null;
    }
    const parts = [generation(view), view.plot_view.base_font_size, view.panel.side];
    for (const range of view.ranges) {
      if (range.factors !== undefined) { return null; }
      parts.push(range.start, range.end);
    }
    return parts.join(",");
  };
  return {
    get_size() {
      const now = key(this);
      if (this.plot_view.__zharii_checking && now !== null && now === this.__zharii_size_key) {
        return {...this.__zharii_size};
      }
      const size = orig.get_size.call(this);
      this.__zharii_size_key = now;
      this.__zharii_size = {...size};
      return size;
    },
    check() {
      this.__zharii_checking = !this._needs_layout;
      try {
        return orig.check.call(this);
      } finally {
        this.__zharii_checking = false;
      }
    },
  };
});
