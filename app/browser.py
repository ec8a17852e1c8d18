"""A small speed-up for BokehJS, installed in the page when the document is ready.

BokehJS 3.10 rewrites the text of every renderer's position stylesheet on every paint,
even when the text is the same; each rewrite invalidates the page's styles, and the
next paint's reads of CSS values (colours, font sizes through `getComputedStyle`) then
wait for a style recalculation.  With a dozen renderers repainted per animation frame
this ping-pong costs the explorer about 15 % of its frame rate in software rendering.
The shim skips writes that would not change the text; if a future BokehJS renames the
method, the shim does nothing (and says so in the console), and only speed is lost.
"""

from __future__ import annotations

from bokeh.document import Document
from bokeh.models import CustomJS

SHIM_JS = """
const Bokeh = window.Bokeh;
let dom = null;
try { dom = Bokeh.require("core/dom"); } catch (e) { dom = null; }
const proto = dom && dom.InlineStyleSheet ? dom.InlineStyleSheet.prototype : null;
if (proto == null || typeof proto._update !== "function") {
  console.info("zharii: BokehJS stylesheet shim not installed (API changed)");
} else if (!proto.__zharii_skip_same) {
  const update = proto._update;
  proto._update = function (css) {
    if (this.el == null || this.el.textContent !== css) { update.call(this, css); }
  };
  proto.__zharii_skip_same = true;
}
"""


def install(doc: Document) -> None:
    """Install the shim in the browser showing `doc`, once its document is ready."""
    doc.js_on_event("document_ready", CustomJS(code=SHIM_JS))
