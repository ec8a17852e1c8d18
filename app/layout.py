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


def page(ex: Explorer) -> pn.template.BootstrapTemplate:
    """The explorer's page."""
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
    template = pn.template.BootstrapTemplate(
        title="Zharii (1996): two elastic spheres in intermittent frictional contact",
        # one root each: Bokeh rescans the whole document for every root it adds
        sidebar=[pn.Column(*sidebar, sizing_mode="stretch_width")],
        main=[pn.Column(*main, sizing_mode="stretch_width")],
        sidebar_width=380, header_background="#0072B2",
        meta_viewport="width=device-width, initial-scale=1",
        busy_indicator=None)  # its per-message restyling slows every frame
    template.config.raw_css.append(CSS)
    return template

