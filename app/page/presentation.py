"""The presentation view (`/main?view=present`): one screen for a class.

In the header, the link to the full page (it keeps the parameters) and the projector
box (larger type, thicker lines); the controls a teacher uses in front of a class
(preset, Play, Step, Reset, speed, the time); the two spheres with their phase badge,
the traction profile, the contact disc, and below the traction profile the curve of the
preset's figure: T(tau), or Fig. 4's radii, Fig. 8's impulse, Fig. 9's centre motion
when such a preset is on.  The same scenes and controls as the full page
(`app.page.layout.page`): this module only arranges and sizes them.

The arrangement is CSS (`app.page.present_css`), worked out by the browser from the
window's size in CSS px, which browser zoom divides: so it follows zoom and a resized
window without the server.  Three arrangements:

* wide (at least `app.page.present_css.WIDE` CSS px): the controls in a row under the
  header, then the spheres (the screen's height), the traction profile and the disc,
  and the curve below them, all on one screen;
* short (a zoomed laptop screen): the controls in a column at the left, the spheres,
  the traction profile over the curve, on one screen; the disc below them;
* narrow (a phone; a laptop screen zoomed to 175 % and more): everything in one
  column, scrolled.

No plot is narrower than `MIN_PLOT` (CSS px); the spheres and the disc are drawn at
equal scales on both axes (their boxes are sized so that their frames have the aspect of
their ranges).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import panel as pn
from bokeh.models import Button as BokehButton
from bokeh.models import Column as BokehColumn
from bokeh.models import CustomJS

from app.contact.view import ContactView
from app.kit.a11y import Landmark
from app.kit.figures import stamp_outside
from app.page import keyboard, layout
from app.page.present_css import (
    CONTROLS_CSS,
    HEADER_CSS,
    PAGE_CSS,
    Rims,
    bottom_css,
    scenes_css,
)
from app.page.projector import Projector

#: The name of the view in the URL (`view=present`).
VIEW = "present"

#: The spheres' plot outside its frame (px, with the type of `app.kit.figures.style_figure`):
#: (across, down): its borders and its stamp (up the frame's right edge) across; its
#: title and toolbar down (no borders there).
SPHERES_RIM = (19, 30)
#: The disc's plot outside its frame (px): (across, down): the y axis with its label and
#: the borders across; the title, the x axis with its label, the stamp and the borders
#: down.
DISC_RIM = (105, 96)
BADGE_FONT = "15pt"
#: The spheres' and the disc's titles' type (their plots are the narrowest: 240 px on a
#: zoomed laptop screen).  The disc's title ends at its frame's right edge: its y axis,
#: wider or narrower with its tick labels, is left of it.
NARROW_TITLE_FONT = "12pt"
#: How many ticks the plots' y axes ask for (fewer than BokehJS's 6: a plot 180 px high
#: keeps its tick labels apart), and the curves' under the traction profile (fewer
#: still: their ranges follow the curves, whatever they span).
Y_TICKS, CURVE_Y_TICKS = 5, 4
#: The type of the notes under the spheres and of the traction profile's caption (pt):
#: smaller than the full page's, for the plots of a zoomed laptop screen (240 px wide).
NOTE_PT, CAPTION_FONT = 9, "11pt"
#: The widths of Play, Step and Reset (px): side by side (Reset under them in the short
#: arrangement's column of controls).
BUTTONS = (96, 72, 72)

#: The full page: this page's link without `view=present` (the parameters kept).
FULL_PAGE_JS = """
const q = new URLSearchParams(window.location.search);
q.delete("view");
window.location.search = q.toString();
"""


def aspect(fig) -> float:
    """Width over height of `fig`'s ranges (its data at equal scales)."""
    return (fig.x_range.end - fig.x_range.start) / (fig.y_range.end - fig.y_range.start)


def panels(figure) -> list:
    """The plots of a curve scene's `figure`: itself, or the panels of its column."""
    return list(figure.children) if isinstance(figure, BokehColumn) else [figure]


def stretched(fig, css_class: str, ticks: int = Y_TICKS) -> None:
    """`fig` sized by the page's CSS: stretched to its box, no margin, class `css_class`;
    its y axes with `ticks` ticks."""
    fig.sizing_mode, fig.margin = "stretch_both", 0
    fig.min_width = fig.max_width = None
    for axis in fig.yaxis:
        if "desired_num_ticks" in axis.ticker.properties():
            axis.ticker.desired_num_ticks = ticks
    if css_class not in fig.css_classes:
        fig.css_classes = [*fig.css_classes, css_class]


class CurveSlot:
    """The place under the traction profile: the curve scene of the open curve tab
    (`ContactView.tabs`, which a preset of Figs. 4, 8 or 9 opens), T(tau) once the preset
    is left."""

    def __init__(self, contact: ContactView, projector: Projector) -> None:
        self.contact, self.projector = contact, projector
        self.pane = pn.Row(css_classes=["pp-bottom"], stylesheets=[bottom_css()], margin=0)
        self.show()
        contact.tabs.param.watch(lambda *_: self.show(), "active")
        contact.state.param.watch(lambda *_: self.show(), "log_psi")
        contact.state.param.watch(self._on_preset, "preset")

    def _on_preset(self, event) -> None:
        if not event.new:  # the preset left: T(tau) again
            self.contact.tabs.active = 0

    def figures(self) -> list:
        """The plots of the open tab's scene."""
        contact = self.contact
        return panels(contact.tabbed[contact.tabs.active].figure)

    def show(self) -> None:
        """Put the open tab's plots in the slot (when they are not there yet)."""
        figs = self.figures()
        if [p.object for p in self.pane.objects] == figs:
            return
        for fig in figs:
            stretched(fig, "pp-curve", CURVE_Y_TICKS)
            stamp_outside(fig)
            self.projector.style(fig)
        self.pane.objects = [pn.pane.Bokeh(fig) for fig in figs]


def header(projector: Projector) -> Landmark:
    """The banner: the page's title, the projector box and the way to the full page."""
    # (a Bokeh button: its click's script is its own model's, which Panel's links, not
    # followed into a landmark, would not give it)
    full = BokehButton(label="All scenes and controls", width=220)
    full.js_on_event("button_click", CustomJS(code=FULL_PAGE_JS))
    title = layout.heading()
    title.css_classes = ["pp-title"]
    return Landmark(
        object=pn.FlexBox(title, projector.box, pn.pane.Bokeh(full), stylesheets=[HEADER_CSS],
                          align_items="center", sizing_mode="stretch_width",
                          styles={"background": layout.HEADER_STYLE["background"]}),
        role="banner", css_classes=["pp-header"], margin=0)


def controls(contact: ContactView) -> Landmark:
    """The teacher's controls: preset, Play, Step, Reset, speed, time."""
    ui = contact.controls
    for widget in (ui.preset_select, ui.speed_slider):  # as wide as their columns
        widget.param.update(width=None, sizing_mode="stretch_width")
    for button, width in zip((ui.play_button, ui.step_button, ui.reset_button), BUTTONS,
                             strict=True):
        button.width = width
    box = pn.FlexBox(
        pn.Column(ui.preset_select, css_classes=["pp-preset"]),
        pn.FlexBox(ui.play_button, ui.step_button, ui.reset_button, flex_wrap="wrap",
                   css_classes=["pp-buttons"]),
        pn.Column(ui.speed_slider, css_classes=["pp-speed"]),
        pn.Column(ui.tau_slider, css_classes=["pp-tau"]),
        keyboard.play_key(contact),
        align_items="flex-end", sizing_mode="stretch_width", stylesheets=[CONTROLS_CSS])
    return Landmark(object=box, role="complementary", label="Controls",
                    css_classes=["pp-controls"], margin=0)


def presentation(contact: ContactView, message: pn.viewable.Viewable,
                 descriptions: Mapping[str, pn.viewable.Viewable] | None = None,
                 announcer: pn.viewable.Viewable | None = None,
                 unseen: Sequence[pn.viewable.Viewable] = ()) -> pn.Column:
    """The one-screen page of `contact`'s scenes and controls, with the page's banner
    `message`; `descriptions`, `announcer` and `unseen` as for `app.page.layout.page`
    (out of sight: they take no room), and the same play / pause key."""
    spheres = contact.spheres.figure
    contact.spheres.badge.glyph.text_font_size = BADGE_FONT
    contact.spheres.set_note_size(NOTE_PT)
    contact.traction.caption.text_font_size = CAPTION_FONT
    traction, disc = contact.traction.figure, contact.disc.figure
    # (the disc's title's type is in `DISC_RIM`: its frame's aspect follows from it)
    for fig in (spheres, disc):
        fig.title.text_font_size = NARROW_TITLE_FONT
    disc.title.align = "right"
    for fig, name in ((spheres, "pp-spheres"), (traction, "pp-traction"), (disc, "pp-disc")):
        stretched(fig, name)
    for fig in (traction, disc):
        stamp_outside(fig)
    stamp_outside(spheres, "right")  # (the spheres' height is the screen's)
    # equal scales: their frames are their boxes less a fixed rim, so not aligned with
    # their neighbours' frames (BokehJS aligns them by default: the traction plot's
    # legend row above its frame would push the disc's frame down, out of its aspect)
    spheres.frame_align = disc.frame_align = False
    # no border above and below the spheres' frame (no axes there): the height it leaves
    # keeps them `MIN_PLOT` wide on a zoomed laptop screen
    spheres.min_border_top = spheres.min_border_bottom = 0
    projector = Projector([spheres, traction, disc])
    slot = CurveSlot(contact, projector)
    rims = Rims(aspect(spheres), SPHERES_RIM, aspect(disc), DISC_RIM)
    # (out of sight, out of the grid: `app.kit.style.VISUALLY_HIDDEN_CSS`)
    hidden = [*(descriptions or {}).values(), *([announcer] if announcer is not None else []),
              *unseen]
    scenes = pn.Column(
        pn.pane.Bokeh(spheres), pn.pane.Bokeh(traction), pn.pane.Bokeh(disc), slot.pane,
        *hidden, css_classes=["pp-scenes"], stylesheets=[scenes_css(rims)], margin=0)
    main = Landmark(object=scenes, role="main", css_classes=["pp-main"], margin=0,
                    stylesheets=["#region { height: 100%; }"])
    message.css_classes = [*message.css_classes, "pp-message"]
    layout.use_css()
    return pn.Column(header(projector), message, controls(contact), main,
                     stylesheets=[PAGE_CSS], margin=0, sizing_mode="stretch_width")
