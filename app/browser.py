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
6. Measure axes only when something that sizes them changed.  On every paint BokehJS
   checks whether an axis needs more or less room, measuring its tick labels and title
   (canvas text metrics, CSS reads): ~5 ms a slider move, ~3.5 ms an animation frame.
   The last size is reused while the axis, ticker and formatter models (their change
   signals), the ranges' ends, the side and the plot's font size are unchanged; a
   forced layout (a resize) measures afresh, and axes with TeX titles or label
   overrides are always measured.

3 and 4 together: JavaScript per slider move 50 -> 35 ms (CPU profile of ten moves),
81 vs 85 ms median to all plots updated, 38 vs 30 frames/s (paired runs); 5 on top
(1600x1400 page, two plots out of view): 76 vs 80 ms, 42 vs 37 frames/s; 6 on top
(two servers, 30 moves per arm): 60.6 vs 67.7 ms, 45.6 vs 39.8 frames/s.

If a future BokehJS renames what these replace, the shim leaves that part alone, says
so in the console, and only speed is lost.
"""

from __future__ import annotations

from pathlib import Path

from bokeh.document import Document
from bokeh.models import CustomJS

#: The shim (the body of a CustomJS callback), kept in browser.js beside this file.
SHIM_JS = (Path(__file__).parent / "browser.js").read_text(encoding="utf-8")


def install(doc: Document) -> None:
    """Install the shim in the browser showing `doc`, once its document is ready."""
    doc.js_on_event("document_ready", CustomJS(code=SHIM_JS))
