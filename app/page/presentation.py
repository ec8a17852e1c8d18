"""The presentation view (`/main?view=present`): one screen for a class.

In the header, the link to the full page (it keeps the parameters); below it a row of
the controls a teacher uses in front of a class (preset, Play, Step, Reset, speed, the
time); then, without scrolling, the two spheres with their phase badge, the traction
profile with the contact disc beside it, and T(tau).  The same scenes and controls as
the full page (`app.page.layout.page`): this module only arranges and sizes them.

The page is one screen high (`100vh`) and the scenes take the height the header and
the controls leave: the plots grow with the screen (at 1280 x 720 the spheres are about
390 x 580 px, at 1920 x 1080 650 x 940 px).  The sizes are CSS, worked out by the
browser from the scenes' box (container query units: `100cqh` is its height, `100cqw`
its width), so the plots have them at the first paint and follow a resized window
without the server.  The spheres and the disc are drawn at equal scales on both axes:
their boxes are sized so that their frames (the box less the title, toolbar and axes)
have the aspect of their ranges.
"""

from __future__ import annotations

from collections.abc import Mapping

import panel as pn

from app.contact.view import ContactView
from app.kit.figures import place_legend
from app.page import layout

#: The name of the view in the URL (`view=present`).
VIEW = "present"

#: The spheres' plot outside its frame (px, with the type of `app.kit.figures.style_figure`):
#: (across, down): its borders across; its title, toolbar and borders down.
SPHERES_RIM = (10, 37)
#: The disc's plot outside its frame (px): (across, down): the y axis with its label and
#: the borders across; the title, the x axis with its label and the borders down.
DISC_RIM = (105, 87)
#: The largest shares of the scenes' width the spheres and the disc take (they take less
#: but on a narrow screen: their height sets their width).
SPHERES_MAX_WIDTH = 0.34
DISC_MAX_WIDTH = 0.3
#: The share of the scenes' height of the traction profile and the disc (T(tau) takes
#: the rest).
TOP_SHARE = 0.53
#: Space between the plots (px).
GAP = 8
BADGE_FONT = "26pt"

#: The full page: this page's link without `view=present` (the parameters kept).
FULL_PAGE_JS = """
const q = new URLSearchParams(window.location.search);
q.delete("view");
window.location.search = q.toString();
"""


def equal_scales_box(aspect: float, rim: tuple[int, int], height: str,
                     max_width: str) -> dict[str, str]:
    """CSS width and height of a plot whose frame (the box less its `rim` in px, across
    and down) has width / height = `aspect`: as high as `height` allows, narrower than
    `max_width` (CSS lengths)."""
    across, down = rim
    h = f"min({height}, calc(({max_width} - {across}px) / {aspect!r} + {down}px))"
    return {"height": h, "width": f"calc(({h} - {down}px) * {aspect!r} + {across}px)",
            "flex": "0 0 auto", "min-width": "0", "max-width": "none", "max-height": "none"}


def aspect(fig) -> float:
    """Width over height of `fig`'s ranges (its data at equal scales)."""
    return (fig.x_range.end - fig.x_range.start) / (fig.y_range.end - fig.y_range.start)


def presentation(contact: ContactView, message: pn.viewable.Viewable,
                 descriptions: Mapping[str, pn.viewable.Viewable] | None = None,
                 announcer: pn.viewable.Viewable | None = None) -> pn.Column:
    """The one-screen page of `contact`'s scenes and controls, with the page's banner
    `message`; `descriptions` and `announcer` as for `app.page.layout.page` (out of
    sight: they take no room), and the same play / pause key."""
    ui = contact.controls
    spheres = contact.spheres.figure
    contact.spheres.badge.glyph.text_font_size = BADGE_FONT
    traction, disc, force = contact.traction.figure, contact.disc.figure, contact.force.figure
    for fig in (spheres, traction, disc, force):
        fig.sizing_mode, fig.margin = "stretch_both", 0
        fig.min_width = fig.max_width = None
    # equal scales: their frames are their boxes less a fixed rim, so not aligned with
    # their neighbours' frames (BokehJS aligns them by default: the traction plot's
    # legend row above its frame would push the disc's frame down, out of its aspect)
    spheres.frame_align = disc.frame_align = False
    # T(tau) spans the screen's width but little of its height: its legend beside it
    for legend in force.legend:
        place_legend(force, legend, "right")
    # the scenes' box is the size container: 100cqh is its height, 100cqw its width
    spheres.styles = equal_scales_box(aspect(spheres), SPHERES_RIM, "100cqh",
                                      f"{100 * SPHERES_MAX_WIDTH}cqw")
    disc.styles = equal_scales_box(aspect(disc), DISC_RIM, f"{100 * TOP_SHARE}cqh",
                                   f"{100 * DISC_MAX_WIDTH}cqw")
    traction.styles = {"flex": "1 1 0", "min-width": "0", "height": "100%"}
    force.styles = {"flex": "1 1 0", "min-height": "0", "width": "100%"}
    force.margin = (GAP, 0, 0, 0)
    full = pn.widgets.Button(label="All scenes and controls", width=220, align="center")
    full.js_on_click(code=FULL_PAGE_JS)  # the same link without view=present
    header = pn.Row(
        layout.heading(),
        full, styles={"background": layout.HEADER_STYLE["background"]},
        sizing_mode="stretch_width")
    for widget in (ui.preset_select, ui.speed_slider):  # as wide as their columns
        widget.param.update(width=None, sizing_mode="stretch_width")
    controls = pn.FlexBox(
        pn.Column(ui.preset_select, styles={"flex": "1 1 340px"}),  # (the longest name)
        pn.Row(ui.play_button, ui.step_button, ui.reset_button, align="end"),
        pn.Column(ui.speed_slider, styles={"flex": "0 1 200px"}),
        pn.Column(ui.tau_slider, styles={"flex": "2 1 320px"}),
        align_items="flex-end", sizing_mode="stretch_width")
    scenes = pn.Row(
        pn.pane.Bokeh(spheres),
        pn.Column(
            pn.Row(pn.pane.Bokeh(traction), pn.pane.Bokeh(disc), sizing_mode="stretch_both",
                   styles={"height": f"{100 * TOP_SHARE}cqh", "flex": "0 0 auto",
                           "gap": f"{GAP}px"}),
            pn.pane.Bokeh(force),
            sizing_mode="stretch_both", styles={"min-width": "0"}),
        sizing_mode="stretch_both",
        styles={"flex": "1 1 0", "min-height": "0", "container-type": "size",
                "gap": f"{GAP}px"})
    unseen = [layout.play_key(contact), *(descriptions or {}).values(),
              *([announcer] if announcer is not None else [])]
    layout.use_css()
    # one screen high: the scenes take what the header and the controls leave
    return pn.Column(header, controls, message, scenes, *unseen, sizing_mode="stretch_both",
                     styles={"height": "100vh"})
