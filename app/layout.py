"""The page: the explorer's controls in the sidebar, its scenes in cards in the main area.

Sizes and type are for a projector (17 px base); on a phone the cards stack.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import panel as pn

from app.phases import STYLES
from core import Phase

if TYPE_CHECKING:
    from app.explorer import Explorer

#: Colour key of the contact disc (the figure has no legend, see DiscScene).
DISC_KEY = " ".join(
    f'<span style="color:{STYLES[p].color}; font-size: 1.3em">●</span> {name}'
    for p, name in ((Phase.FULL_STICK, "stick"), (Phase.SLIP, "slip"),
                    (Phase.COUNTER_SLIP, "counter-slip")))

#: The warning box above the plots (rejected URL values).
MESSAGE_STYLE = {"background": "#fff3cd", "color": "#664d03", "border": "1px solid #ffe69c",
                 "border-radius": "6px", "padding": "0.6em 1em"}

#: Large type for a projector; a little smaller on a phone.
CSS = """
:root { --bokeh-font-size: 17px; }
html { font-size: 17px; }
@media (max-width: 700px) { :root { --bokeh-font-size: 15px; } html { font-size: 15px; } }
"""


def card(*objs, title: str, flex: str = "1 1 520px") -> pn.Card:
    """A fixed card of the main area, growing by `flex` (CSS) in its row."""
    return pn.Card(*objs, title=title, collapsible=False, margin=6,
                   styles={"flex": flex, "min-width": "0"})


#: The page's title (browser tab and header).
TITLE = "Zharii (1996): two elastic spheres in intermittent frictional contact"

#: The header bar.
HEADER_STYLE = {"background": "#0072B2", "color": "white", "padding": "0.4em 1em",
                "font-size": "1.3em", "font-weight": "bold"}

#: <meta> tags of the page (Bokeh's page template reads them from the document).
META = {"viewport": "width=device-width, initial-scale=1",
        "description": "Interactive exact solution of two elastic spheres in intermittent "
                       "oblique frictional contact (O. Yu. Zharii, 1996)"}


def page(ex: Explorer) -> pn.Column:
    """The explorer's page: a header, the controls in a sidebar, the scenes beside it (a
    plain Panel layout: a template's header, modal and theming tripled the server's work
    per page load); on a narrow screen the sidebar stacks above the scenes."""
    sidebar = [
        ex.preset_select,
        pn.Row(ex.reset_button, ex.downloads["curves"]),
        ex.psi_slider, ex.tau0_slider, ex.mu_slider, ex.nu_slider,
        pn.pane.Markdown("### Time"),
        ex.tau_slider,
        pn.Row(ex.play_button, ex.step_button),
        ex.speed_slider,
        ex.log_box,
        ex.physical_card,
        pn.Row(ex.downloads["traction"], ex.downloads["impulse"]),
    ]
    main = [
        ex.message,
        pn.FlexBox(
            card(pn.pane.Bokeh(ex.spheres.figure), title="The two spheres (Fig. 2)",
                 flex="0 0 440px"),
            card(pn.pane.Bokeh(ex.traction.figure, sizing_mode="stretch_width"),
                 title="Traction profile (Fig. 6)", flex="3 1 560px"),
            card(pn.pane.Bokeh(ex.disc.figure), pn.pane.HTML(DISC_KEY),
                 title="Contact disc", flex="0 0 380px"),
            card(ex.formulas, title="Formulas of the current phase", flex="2 1 480px"),
            card(pn.pane.Bokeh(ex.readout.figure, sizing_mode="stretch_width"),
                 title="Derived quantities", flex="1 1 380px"),
            card(ex.tabs, title="Curves over the contact", flex="1 1 100%"),
            sizing_mode="stretch_width", align_content="flex-start"),
        ex.methods.view(),
        ex.motor_card,
    ]
    if CSS not in pn.config.raw_css:  # once per process
        pn.config.raw_css.append(CSS)
    return pn.Column(
        pn.pane.HTML(TITLE, styles=HEADER_STYLE, sizing_mode="stretch_width", margin=0),
        pn.FlexBox(
            pn.Column(*sidebar, styles={"flex": "0 1 370px", "min-width": "0"}),
            pn.Column(*main, styles={"flex": "1 1 600px", "min-width": "0"}),
            flex_wrap="wrap", align_items="flex-start", sizing_mode="stretch_width"),
        sizing_mode="stretch_width")
