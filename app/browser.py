"""Two small speed-ups for BokehJS, installed in the page when the document is ready.

Both are about style recalculation.  BokehJS 3.10 gives every renderer a DOM element
positioned by a stylesheet of its own, rewritten on every paint, and it reads visual
properties (text colours, fonts) from CSS (`getComputedStyle`) while it paints.  A
write that changes a stylesheet makes the next read wait for the page's styles to be
recalculated (1.5-2.5 ms each on this page, in software rendering).

1. Skip rewrites that would not change a stylesheet's text (most of them).  With a
   dozen renderers repainted per animation frame this ping-pong cost the explorer
   about 15 % of its frame rate.
2. A glyph renderer's element is placed over the glyph's bounding box on screen, which
   moves with the data: a slider move changed seven of them, one plot after another,
   each change followed by the next plot's CSS reads: five recalculations per move.
   Their elements are empty (glyphs are drawn on the canvas), so their positions are
   written once all plots have painted (the next task) instead: one recalculation.
   Paired A/B runs (moves alternated in one page, 60 per arm): 95 ms -> 82.5 ms
   median from a slider move to all plots updated.

If a future BokehJS renames what these wrap, the shim leaves it alone, says so in the
console, and only speed is lost.
"""

from __future__ import annotations

from bokeh.document import Document
from bokeh.models import CustomJS

SHIM_JS = """
const Bokeh = window.Bokeh;
// wrap(path, cls, method, flag, make): replace cls.prototype[method] by make(original),
// once per page; if BokehJS no longer has it, leave it alone and say so
const wrap = (path, cls, method, flag, make) => {
  let module = null;
  try { module = Bokeh.require(path); } catch (e) { module = null; }
  const proto = module && module[cls] ? module[cls].prototype : null;
  if (proto == null || typeof proto[method] !== "function") {
    console.info(`zharii: BokehJS shim for ${cls}.${method} not installed (API changed)`);
  } else if (!proto[flag]) {
    proto[method] = make(proto[method]);
    proto[flag] = true;
  }
};
wrap("core/dom", "InlineStyleSheet", "_update", "__zharii_skip_same", (update) =>
  function (css) {
    if (this.el == null || this.el.textContent !== css) { update.call(this, css); }
  });
wrap("models/renderers/glyph_renderer", "GlyphRendererView", "update_position",
     "__zharii_late_position", (update_position) => {
  const pending = new Set();
  const flush = () => {
    const views = [...pending];
    pending.clear();
    for (const view of views) {
      try { update_position.call(view); } catch (e) { /* removed meanwhile */ }
    }
  };
  return function () {
    if (pending.size === 0) { setTimeout(flush, 0); }
    pending.add(this);
  };
});
"""


def install(doc: Document) -> None:
    """Install the shim in the browser showing `doc`, once its document is ready."""
    doc.js_on_event("document_ready", CustomJS(code=SHIM_JS))
