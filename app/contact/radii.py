"""The approach and the radii over one contact (Fig. 4b, `RadiiScene`, source `radii`),
with the lower sphere's height above them (Fig. 4a) and the times of the Fig. 6
profiles marked on a(tau)."""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np
from bokeh.layouts import column
from bokeh.models import ColumnDataSource, Range1d

from app.contact.curves import CurveScene
from app.kit.figures import lean, new_figure, stamp, style_figure
from core import Contact


class RadiiScene(CurveScene):
    """Fig. 4b: approach, contact radius a and stick radius b against tau."""

    name = "radii"
    title = "Approach α/(H−h), contact radius a/a*, stick radius b/a*"
    y_label = "dimensionless"
    curves = (
        ("approach", "α / (H−h)", "#000000", "dashed"),
        ("a", "a / a*", "#D55E00", "solid"),
        ("b", "b / a*", "#009E73", "solid"),
    )

    #: the times of the Fig. 6 profiles, marked a to f on the a(tau) curve (Fig. 4b)
    FIG6_TAUS = (("a", math.pi / 4), ("b", math.pi / 3), ("c", math.pi / 2),
                 ("d", 7 * math.pi / 12), ("e", 17 * math.pi / 24), ("f", 3 * math.pi / 4))

    def __init__(self) -> None:
        super().__init__()
        #: Fig. 4a: the lower sphere's height u_z0 / H = sin tau over half a period
        self.drive = ColumnDataSource({"tau": [], "uz": [], "touch": []}, name="radii_drive")
        self.levels = ColumnDataSource({"y": [], "label": []}, name="radii_levels")
        self.bracket = ColumnDataSource({"x": [], "lo": [], "hi": [], "mid": [], "label": []},
                                        name="radii_bracket")
        #: Fig. 4b's disks: the Fig. 6 times that lie in the contact
        self.disks = ColumnDataSource({"tau": [], "a": [], "label": []}, name="radii_disks")

    @cached_property
    def drive_figure(self):
        """Fig. 4a, built on first use: u_z0 / H against tau, the level h / H above which
        the spheres touch, and the approach scale H - h."""
        fig = new_figure("Height of the lower sphere u_z0 / H (Fig. 4a)", "τ = ωt (rad)",
                         "u_z0 / H", height=220, x_range=Range1d(0.0, math.pi))
        fig.line("tau", "uz", source=self.drive, color="black", line_width=2)
        fig.line("tau", "touch", source=self.drive, color="#D55E00", line_width=4,
                 legend_label="in contact")
        fig.hspan(y="y", source=self.levels, line_color="#888888", line_dash="dashed")
        fig.text(0.05, "y", text="label", source=self.levels, text_baseline="bottom",
                 text_font_size="12pt")
        # the approach's amplitude H - h: from the level h up to H (eq 8)
        fig.segment(x0="x", y0="lo", x1="x", y1="hi", source=self.bracket, color="#0072B2",
                    line_width=2)
        fig.scatter("x", "lo", source=self.bracket, marker="dash", angle=math.pi / 2,
                    size=10, color="#0072B2")
        fig.text("x", "mid", text="label", source=self.bracket, x_offset=6,
                 text_baseline="middle", text_font_size="12pt", text_color="#0072B2")
        stamp(fig, x=0.0, y=1.0, x_units="data", y_units="data", text_baseline="top",
              x_offset=4, y_offset=-4)
        style_figure(fig)
        fig.legend.location = "bottom_center"
        return fig

    @property
    def figure(self):
        """Fig. 4a above Fig. 4b."""
        return self._with_drive

    @cached_property
    def _with_drive(self):
        main = self.figures[0]
        main.scatter("tau", "a", source=self.disks, size=12, color="#D55E00",
                     line_color="black")
        main.text("tau", "a", text="label", source=self.disks, text_font_size="13pt",
                  x_offset=6, y_offset=-4, text_font_style="bold")
        lean(main)
        return column(self.drive_figure, main, sizing_mode="stretch_width")

    def update_contact(self, c: Contact) -> None:
        """The curves, and Fig. 4a with the Fig. 6 disks (tau0 alone: drawn again only
        when tau0 changes)."""
        super().update_contact(c)
        if not self.note_tau0(c):
            return
        tau = np.unique(np.concatenate([np.linspace(0.0, math.pi, 241), [c.tau0, c.tau_end]]))
        uz = c.drive_displacement(tau)  # u_z0 / H = u_x0 / u0 = sin tau (eq 3)
        s0 = math.sin(c.tau0)
        self.drive.data = {"tau": tau, "uz": uz, "touch": np.where(
            (tau >= c.tau0) & (tau <= c.tau_end), uz, np.nan)}
        self.levels.data = {"y": [s0, 1.0], "label": [f"h / H = sin τ₀ = {s0:.3g}", ""]}
        x = math.pi / 2 + 0.35
        self.bracket.data = {"x": [x], "lo": [s0], "hi": [1.0], "mid": [(1.0 + s0) / 2],
                             "label": ["(H − h) / H: the largest approach"]}
        marks = [(label, t) for label, t in self.FIG6_TAUS if c.tau0 <= t <= c.tau_end]
        taus = np.array([t for _, t in marks])
        self.disks.data = {"tau": taus, "a": c.contact_radius(taus) if marks else taus,
                           "label": [label for label, _ in marks]}

    def columns(self, c: Contact, tau: np.ndarray) -> dict[str, np.ndarray]:
        line = c.at(tau)
        return {"approach": line.approach, "a": line.contact_radius, "b": line.stick_radius}

    def table(self) -> dict[str, np.ndarray]:
        """The plotted curves for the CSV download: tau (rad), the approach alpha/(H-h)
        (eq 8), the contact radius a/a* (eqs 7, 8) and the stick radius b/a* (eq 30)."""
        d = {k: np.asarray(v) for k, v in self.source.data.items()}
        return {"tau (rad)": d["tau"], "alpha/(H-h)": d["approach"], "a/a*": d["a"],
                "b/a*": d["b"]}
