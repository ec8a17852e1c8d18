"""The presentation view (`/main?view=present`): one screen for a class.

At 1280 x 720 and larger, without scrolling: a row of the controls a teacher uses in
front of a class (preset, Play, Step, speed, the time), the two spheres with their
phase badge, the traction profile with the contact disc beside it, and T(tau).  The
other scenes are a click away on the full page (the link in the header keeps the
parameters).  The same scenes and controls as the full page (`app.layout.page`), sized
for the screen: this module only arranges them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import panel as pn

from app import layout

if TYPE_CHECKING:
    from app.explorer import Explorer

#: The name of the view in the URL (`view=present`).
VIEW = "present"

#: Plot sizes (px) that fit 1280 x 720 below the header and the controls.
SPHERES_SIZE = (330, 500)  # width, height: the drawing's equal scales (3.2 x 4.55 radii)
TRACTION_HEIGHT = 270
DISC_SIZE = 250
FORCE_HEIGHT = 235
BADGE_FONT = "26pt"

#: The full page: this page's link without `view=present` (the parameters kept).
FULL_PAGE_JS = """
const q = new URLSearchParams(window.location.search);
q.delete("view");
window.location.search = q.toString();
"""


def presentation(ex: Explorer) -> pn.Column:
    """The one-screen page of `ex`'s scenes and controls."""
    spheres = ex.spheres.figure
    spheres.width, spheres.height = SPHERES_SIZE
    spheres.sizing_mode = "fixed"
    ex.spheres.badge.glyph.text_font_size = BADGE_FONT
    traction, disc, force = ex.traction.figure, ex.disc.figure, ex.force.figure
    traction.height = TRACTION_HEIGHT
    disc.width = disc.height = DISC_SIZE
    force.height = FORCE_HEIGHT
    header = pn.pane.HTML(f"<h1>{layout.TITLE}</h1>", styles=layout.HEADER_STYLE,
                          sizing_mode="stretch_width", margin=0,
                          stylesheets=[layout.HEADING_CSS])
    full = pn.widgets.Button(label="All scenes and controls", width=220, align="end")
    full.js_on_click(code=FULL_PAGE_JS)  # the same link without view=present
    controls = pn.FlexBox(
        pn.Column(ex.preset_select, styles={"flex": "1 1 260px"}),
        pn.Row(ex.play_button, ex.step_button, ex.reset_button, align="end"),
        pn.Column(ex.speed_slider, styles={"flex": "0 1 200px"}),
        pn.Column(ex.tau_slider, styles={"flex": "2 1 320px"}),
        full,
        align_items="flex-end", sizing_mode="stretch_width")
    scenes = pn.FlexBox(
        pn.pane.Bokeh(spheres, margin=(0, 8)),
        pn.Column(
            pn.Row(pn.pane.Bokeh(traction, sizing_mode="stretch_width"),
                   pn.pane.Bokeh(disc), sizing_mode="stretch_width"),
            pn.pane.Bokeh(force, sizing_mode="stretch_width"),
            styles={"flex": "1 1 600px", "min-width": "0"}),
        flex_wrap="wrap", align_items="flex-start", sizing_mode="stretch_width")
    if layout.CSS not in pn.config.raw_css:  # once per process
        pn.config.raw_css.append(layout.CSS)
    return pn.Column(header, controls, ex.message, scenes, sizing_mode="stretch_width")
