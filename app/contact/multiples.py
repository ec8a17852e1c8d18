"""Fig. 6 in full: the six traction profiles of the paper as small multiples.

The paper's Fig. 6 shows tau_u(r) for psi = sqrt 2 + 1, tau0 = pi / 6 at six times, three
while loading (slip) and three while unloading (partial stick, then counter-slip at
tau1 = 3 pi / 4).  Each small plot is `TractionScene.profiles` of the contact of its
preset (`app.contact.state.PRESETS`, fig6a to fig6f): the same numbers as the big traction plot
shows for that preset.  The figures are built on first use (the card opening them).
"""

from __future__ import annotations

from functools import cached_property

import numpy as np
from bokeh.layouts import gridplot
from bokeh.models import ColumnDataSource

from app.contact.phases import STICK_COLOR, style
from app.contact.state import PRESETS
from app.contact.traction import TractionScene
from app.kit.figures import negated, new_figure, style_figure
from core import Contact

#: The presets of Fig. 6, in the paper's order.
KEYS = ("fig6a", "fig6b", "fig6c", "fig6d", "fig6e", "fig6f")


def panel_title(key: str) -> str:
    """'6a: τ = π/4, slip': the panel, its time and the phase at that time."""
    p = PRESETS[key]
    when = p.label.split("τ = ")[-1]
    phase = style(Contact(p.psi, p.tau0).phase(p.tau)).name
    return f"6{key[-1]}: τ = {when}, {phase}"


class SmallMultiples:
    """Six small traction plots (Fig. 6a-f), one source each, named `fig6a` ... `fig6f`."""

    def __init__(self) -> None:
        self.traction = TractionScene()  # its `profiles` draws each panel
        self.sources = {key: ColumnDataSource(data={}, name=key) for key in KEYS}

    @cached_property
    def figure(self):
        """The 2 x 3 grid of plots, with their data (computed once: fixed parameters)."""
        figs = []
        for key in KEYS:
            p = PRESETS[key]
            c = Contact(p.psi, p.tau0)
            self.traction.update_contact(c)
            self.sources[key].data = {k: v[0] for k, v in
                                      self.traction.profiles(c, np.array([p.tau])).items()}
            fig = new_figure(panel_title(key), "r / a*", "τᵤ / (μ p*)", height=230,
                             min_width=220, x_range=self.traction.figure.x_range.clone(),
                             y_range=self.traction.figure.y_range.clone())
            source = self.sources[key]
            fig.varea(x="r", y1=negated("stick_hi"), y2="stick_hi", source=source,
                      fill_color=STICK_COLOR, fill_alpha=0.25)
            for y in ("upper", negated("upper")):
                fig.line(x="r", y=y, source=source, line_dash="dashed", color="grey",
                         line_width=1.5)
            fig.line("r", "traction", source=source, color="black", line_width=2.5)
            style_figure(fig)
            fig.title.text_font_size = "12pt"
            fig.title.text_color = style(c.phase(p.tau)).color
            figs.append(fig)
        return gridplot(figs, ncols=3, sizing_mode="stretch_width", toolbar_location=None)
