"""The presentation view's CSS (`app.page.presentation`): three arrangements chosen by
the window's size in CSS px (which browser zoom divides), so that the page reflows under
zoom and on a resize without the server.

* wide (at least `WIDE`: neither `SHORT_QUERY` nor `NARROW_QUERY`): the controls in a
  row, then the spheres (the scenes' height), the traction profile and the disc, the
  curve under them;
* short (`SHORT_QUERY`): the controls in a column at the left, then the spheres, the
  traction profile over the curve, and the disc below (scrolled to);
* narrow (`NARROW_QUERY`): one column, scrolled.

The scenes' box (`.pp-main`) is the size container: `100cqh` is its height, `100cqw` its
width.  Sizes are CSS px.  The spheres' and the disc's boxes are sized so that their
frames (the box less a fixed rim) have the aspect of their ranges (equal scales).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: The least width and height of a plot (CSS px): its ticks and labels stay readable.
MIN_PLOT = (240, 180)
#: Space between the plots and between the controls and the plots (px).
GAP = 8
#: Below this window width (CSS px) everything stacks in one column.
NARROW_WIDTH = 800
#: The wide arrangement needs this window (CSS px): the controls in one row and the
#: spheres at least `MIN_PLOT` wide under them.
WIDE = (1200, 600)
#: The width of the controls' column in the short arrangement (CSS px): at 150 % of a
#: 1280 x 720 screen it leaves the traction profile the width of its stamp's line.
CONTROLS_WIDTH = 236
#: The share of the scenes' height of the traction profile (and the disc) in the wide
#: arrangement (the curve takes the rest).
TOP_SHARE = 0.53
#: The largest shares of the scenes' width the spheres and the disc take in the wide
#: arrangement (less but on a narrow screen: their height sets their width).
SPHERES_MAX_WIDTH = 0.34
DISC_MAX_WIDTH = 0.3
#: The widest spheres and disc in the narrow arrangement (CSS px).
NARROW_SPHERES, NARROW_DISC = 340, 380
#: The height of the traction profile and of each curve in the narrow arrangement (px).
NARROW_PLOT_HEIGHT = 280

#: A box sized by the page alone (BokehJS bounds a plot by its parent: 100 %).
UNBOUNDED = ("min-width: 0 !important; min-height: 0 !important; max-width: none !important; "
             "max-height: none !important;")

NARROW_QUERY = f"(max-width: {NARROW_WIDTH - 0.02}px)"
SHORT_QUERY = (f"(min-width: {NARROW_WIDTH}px) and (max-width: {WIDE[0] - 0.02}px), "
               f"(min-width: {NARROW_WIDTH}px) and (max-height: {WIDE[1] - 0.02}px)")


@dataclass(frozen=True)
class Rims:
    """The aspects (width / height of their ranges) of the spheres' and the disc's plots
    and their rims (px across, px down: the box less the frame)."""

    spheres: float
    spheres_rim: tuple[int, int]
    disc: float
    disc_rim: tuple[int, int]


def box_for_height(aspect: float, rim: tuple[int, int], height: str) -> str:
    """CSS of a plot `height` high (a CSS length) whose frame has width / height
    `aspect`: its width follows."""
    across, down = rim
    return (f"height: {height} !important; "
            f"width: calc(({height} - {down}px) * {aspect!r} + {across}px) !important; "
            f"{UNBOUNDED}")


def box_for_width(aspect: float, rim: tuple[int, int], width: str) -> str:
    """CSS of a plot `width` wide (a CSS length) whose frame has width / height `aspect`:
    its height follows."""
    across, down = rim
    return (f"width: {width} !important; "
            f"height: calc(({width} - {across}px) / {aspect!r} + {down}px) !important; "
            f"{UNBOUNDED}")


def height_for_width(aspect: float, rim: tuple[int, int], width: float) -> int:
    """The height (px, rounded up) of a plot `width` px wide whose frame has width /
    height `aspect`."""
    across, down = rim
    return math.ceil((width - across) / aspect + down)


def capped_height(aspect: float, rim: tuple[int, int], height: str, max_width: str) -> str:
    """`height` (a CSS length), or less: the height at which the plot is `max_width`
    wide."""
    across, down = rim
    return f"min({height}, calc(({max_width} - {across}px) / {aspect!r} + {down}px))"


def scenes_css(r: Rims) -> str:
    """The scenes' grid (spheres, traction profile, disc, curve) in each arrangement."""
    top = f"{100 * TOP_SHARE:g}cqh"
    wide_spheres = capped_height(r.spheres, r.spheres_rim, "100cqh",
                                 f"{100 * SPHERES_MAX_WIDTH:g}cqw")
    wide_disc = capped_height(r.disc, r.disc_rim, top, f"{100 * DISC_MAX_WIDTH:g}cqw")
    # short: two rows, each at least half the spheres' least height
    spheres_least = height_for_width(r.spheres, r.spheres_rim, MIN_PLOT[0])
    row = f"max({math.ceil((spheres_least - GAP) / 2)}px, calc(50cqh - {GAP / 2:g}px))"
    disc_least = height_for_width(r.disc, r.disc_rim, MIN_PLOT[0])
    return f"""
:host {{ display: grid !important; gap: {GAP}px; width: 100cqw !important;
         height: 100cqh !important; min-height: 0; align-items: start;
         grid-template-columns: auto minmax(0, 1fr) auto;
         grid-template-rows: {top} minmax(0, 1fr);
         grid-template-areas: "spheres traction disc" "spheres bottom bottom"; }}
.pp-spheres {{ grid-area: spheres; {box_for_height(r.spheres, r.spheres_rim, wide_spheres)} }}
.pp-disc {{ grid-area: disc; {box_for_height(r.disc, r.disc_rim, wide_disc)} }}
.pp-traction {{ grid-area: traction; width: 100% !important; height: 100% !important;
                min-width: 0; }}
.pp-bottom {{ grid-area: bottom; width: 100% !important; height: 100% !important;
              min-width: 0; min-height: 0; }}
@media {SHORT_QUERY} {{
  :host {{ grid-template-columns: auto minmax(0, 1fr); height: auto !important;
           grid-template-rows: {row} minmax({row}, auto) auto;
           grid-template-areas: "spheres traction" "spheres bottom" "disc disc"; }}
  .pp-spheres {{ {box_for_height(r.spheres, r.spheres_rim, f"calc(2 * {row} + {GAP}px)")} }}
  .pp-disc {{ {box_for_height(r.disc, r.disc_rim, f"max({disc_least}px, 50cqh)")} }}
  .pp-bottom {{ height: auto !important; min-height: 100%; }}
}}
@media {NARROW_QUERY} {{
  :host {{ grid-template-columns: minmax(0, 1fr); grid-template-rows: none;
           grid-template-areas: "spheres" "traction" "bottom" "disc"; height: auto !important;
           justify-items: center; }}
  .pp-spheres {{ {box_for_width(r.spheres, r.spheres_rim, f"min(100cqw, {NARROW_SPHERES}px)")} }}
  .pp-disc {{ {box_for_width(r.disc, r.disc_rim, f"min(100cqw, {NARROW_DISC}px)")} }}
  .pp-traction {{ height: {NARROW_PLOT_HEIGHT}px !important; }}
  .pp-bottom {{ height: auto !important; }}
}}
"""


def bottom_css() -> str:
    """The curve's place: its panels side by side, wrapping onto more rows when the place
    is narrower than their least widths."""
    w, h = MIN_PLOT
    return f"""
:host {{ display: flex !important; flex-direction: row !important; flex-wrap: wrap;
         gap: {GAP}px; }}
.pp-curve {{ flex: 1 1 {w}px !important; min-width: {w}px; min-height: {h}px;
             height: auto !important; align-self: stretch; }}
@media {NARROW_QUERY} {{ .pp-curve {{ height: {NARROW_PLOT_HEIGHT}px !important; }} }}
"""


#: The page: the header, the message, the controls and the scenes (the size container)
#: one above the other, one screen high (wide); the scenes at the right of the rest, one
#: screen high (short); one column as high as its content (narrow).
PAGE_CSS = f"""
:host {{ display: grid !important; height: 100vh; width: 100% !important;
         grid-template-columns: minmax(0, 1fr);
         grid-template-rows: auto auto auto minmax(0, 1fr);
         grid-template-areas: "header" "message" "controls" "main"; column-gap: {GAP}px; }}
.pp-header {{ grid-area: header; width: 100% !important; }}
.pp-message {{ grid-area: message; }}
.pp-controls {{ grid-area: controls; width: 100% !important; min-width: 0; }}
.pp-main {{ grid-area: main; width: 100% !important; height: 100% !important; min-width: 0;
            min-height: 0; container-type: size; }}
@media {SHORT_QUERY} {{
  :host {{ grid-template-columns: {CONTROLS_WIDTH}px minmax(0, 1fr);
           grid-template-rows: auto auto minmax(0, 1fr);
           grid-template-areas: "header main" "message main" "controls main"; }}
  .pp-main {{ grid-row: 1 / span 3; }}
}}
@media {NARROW_QUERY} {{
  :host {{ height: auto; grid-template-rows: none; }}
  .pp-main {{ height: auto !important; container-type: inline-size; }}
}}
"""

#: The header: the title, then the projector box and the link to the full page, which
#: wrap under it on a narrow window; the title's type smaller on a short one.
HEADER_CSS = f"""
.pp-title {{ flex: 1 1 auto !important; width: auto !important; min-width: 0; }}
@media {SHORT_QUERY}, {NARROW_QUERY} {{ .pp-title {{ font-size: 1em !important; }} }}
"""

#: The controls: one row when wide; one column in the short arrangement (and a phone's).
CONTROLS_CSS = f"""
.pp-preset {{ flex: 1 1 340px; min-width: 0; }}
.pp-buttons {{ flex: 0 0 auto; width: auto !important; min-width: 0; }}
.pp-speed {{ flex: 0 1 200px; min-width: 0; }}
.pp-tau {{ flex: 2 1 320px; min-width: 0; }}
@media {SHORT_QUERY}, {NARROW_QUERY} {{
  .pp-preset, .pp-buttons, .pp-speed, .pp-tau {{ flex: 1 1 100%; }}
}}
"""
