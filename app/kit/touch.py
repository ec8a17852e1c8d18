"""Plots that leave a touch screen's swipes to the page.

BokehJS gives a plot whose pan (or wheel zoom) tool is active the CSS `touch-action`
`pinch-zoom` (or `none`): a finger swiping over it pans the plot instead of scrolling the
page, and a phone's plots are as wide as the screen.  `PlotGestures`, in the browser of
a touch screen (its primary pointer coarse: `matchMedia("(pointer: coarse)")`), leaves
every plot of the page without an active drag or scroll tool, so that BokehJS gives the
plots `touch-action: auto` and a swipe scrolls the page; its "Pan and zoom the plots"
button (shown on a touch screen only) gives the plots their tools back, and a second
press takes them away again.  With a mouse nothing changes.  Plots added later (a tab or
a card opened) are handled when they arrive.  Everything happens in the browser (the
server is told nothing).
"""

from __future__ import annotations

from typing import ClassVar

import panel as pn

#: JavaScript of `PlotGestures`: on a touch screen, every toolbar of the document (and
#: every one that arrives later) without an active drag and scroll tool, unless the
#: button is pressed; the toolbars' own choices are kept to be given back.
_GESTURES_START = """
const coarse = window.matchMedia("(pointer: coarse)").matches;
toggle.hidden = !coarse;
if (!coarse || state.apply != null) { return; }
const doc = model.document;
const own = new WeakMap();
const off = {active_drag: null, active_scroll: null};
state.exploring = false;
state.apply = () => {
  for (const m of doc.all_models) {
    if (m.type !== "Toolbar") { continue; }
    if (!own.has(m)) { own.set(m, {active_drag: m.active_drag, active_scroll: m.active_scroll}); }
    const want = state.exploring ? own.get(m) : off;
    if (m.active_drag !== want.active_drag || m.active_scroll !== want.active_scroll) {
      m.setv(want, {sync: false});
    }
  }
};
const holds_models = (v) => v != null && typeof v === "object" && !(v instanceof Map)
  && (Array.isArray(v) ? v.length < 1000 && v.some(holds_models) : v.id != null);
let pending = false;
doc.on_change((event) => {
  if (pending || !holds_models(event.value)) { return; }
  pending = true;
  setTimeout(() => { pending = false; state.apply(); });
});
state.apply();
"""

#: JavaScript of `PlotGestures`: the button gives the plots their tools, or takes them.
_GESTURES_PRESS = """
if (state.apply == null) { return; }
state.exploring = !state.exploring;
toggle.setAttribute("aria-pressed", String(state.exploring));
state.apply();
"""


class PlotGestures(pn.reactive.ReactiveHTML):
    """On a touch screen, the page's plots without active drag and scroll tools (a swipe
    over a plot scrolls the page) until the "Pan and zoom the plots" button, a toggle
    (`aria-pressed`), gives them back; shown on a touch screen only."""

    _template = ('<button id="toggle" type="button" aria-pressed="false" hidden '
                 'onclick="${script(\'press\')}">Pan and zoom the plots</button>')
    _scripts: ClassVar[dict[str, str]] = {"render": _GESTURES_START, "press": _GESTURES_PRESS}

    #: A plain button, dark while pressed; at least 44 px high (a finger's target).
    CSS = """
button { font: inherit; min-height: 44px; padding: 0.3em 0.9em; margin: 4px 6px;
         color: #0b3d66; background: white; border: 2px solid #0072B2; border-radius: 6px; }
button[aria-pressed=true] { color: white; background: #0072B2; }
button[hidden] { display: none; }
"""

    def __init__(self, **params) -> None:
        params["stylesheets"] = [self.CSS, *params.get("stylesheets", [])]
        params.setdefault("margin", 0)
        super().__init__(**params)
