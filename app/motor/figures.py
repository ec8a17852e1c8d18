"""The Motor card's figures and their named sources (updated in place by the card).

1. the rod to scale with the amplitudes of its standing wave magnified, the rotor resting
   on its drawn top face at x0, a readout; taps on it move the rotor;
2. the stall thrust along the rod, its extremes marked, the regions where the contact
   never opens shaded and labelled, upright inside the shading (so that the label is
   neither cut at the frame's edge nor over the curve), with why the thrust stops short
   of the ends;
3. thrust and 4. efficiency against the rotor's speed at x0, the no-load speed, the best
   efficiency and the operating point under the load marked;
5. Archard wear rate along the rod (depth per hour of operation);
6. the rotor's start-up from rest (speed against time).

The legends of 2-5 stand above their frames (`LEGEND_PLACE`), so that they cover no
curve.
"""

from __future__ import annotations

import math

from bokeh.models import ColumnDataSource, DataRange1d, Label, Range1d

from app.kit.figures import FRAME_LEVEL, new_figure, place_legend, style_figure

#: Colours (Okabe-Ito) and the shading of the never-opening region.
THRUST_COLOR, EFFICIENCY_COLOR, ROTOR_COLOR = "#0072B2", "#009E73", "#D55E00"
INVALID_COLOR = "#999999"
NO_LOAD_COLOR, BEST_COLOR, OPERATING_COLOR = "#CC79A7", "#F0E442", "#000000"
#: Where the curve plots' legends stand: in a row above the frame, out of the curves.
LEGEND_PLACE = "above"


def legend_above(fig) -> None:
    """`fig`'s legend in rows of at most two entries above its frame (`LEGEND_PLACE`):
    it covers no curve, and two entries fit a phone's width."""
    legend = fig.legend[0]
    place_legend(fig, legend, LEGEND_PLACE)
    legend.ncols = min(2, len(legend.items))


def source(name: str, *columns: str) -> ColumnDataSource:
    """An empty source named `name` (so that a test or the browser can find it)."""
    return ColumnDataSource({c: [] for c in columns}, name=name)


class MotorFigures:
    """The card's six figures and their sources (see the module's docstring)."""

    def __init__(self) -> None:
        self.rod = source("motor_rod", "x", "x_mm", "u0_um", "H_um", "top", "bottom", "wave")
        self.rotor = source("motor_rotor", "x", "y", "radius", "label")
        self.frame = source("motor_frame", "x", "y")
        self.thrust = source("motor_thrust", "x", "x_mm", "psi", "tau0", "stall_thrust",
                             "thrust_mN")
        self.invalid = source("motor_invalid", "left", "right")
        self.ends = source("motor_ends", "x_mm", "y", "text")
        self.optimum = source("motor_optimum", "x_mm", "thrust_mN")
        self.x0 = source("motor_x0", "x_mm", "thrust_mN")
        self.speed = source("motor_speed", "v", "thrust_ratio", "efficiency", "V_mm_s",
                            "thrust_mN", "efficiency_pct")
        self.marks = source("motor_speed_marks", "V_mm_s", "thrust_mN", "efficiency_pct",
                            "label")
        self.operating = source("motor_operating", "V_mm_s", "thrust_mN", "efficiency_pct")
        self.wear = source("motor_wear", "x_mm", "peak_um_h", "centre_um_h")
        self.start = source("motor_startup", "t_ms", "V_mm_s")
        self._rod_figure()
        self._thrust_figure()
        self._speed_figures()
        self._wear_figure()
        self._start_figure()

    def _rod_figure(self) -> None:
        # to scale (x and y in mm); the range follows an invisible frame only, so that
        # moving the rotor leaves it as it is
        fig = new_figure("Rod and rotor", "x (mm)", "y (mm)", match_aspect=True,
                         x_range=DataRange1d(), y_range=DataRange1d(), width=900, height=300,
                         sizing_mode="scale_width")
        frame = fig.scatter("x", "y", source=self.frame, alpha=0.0, size=1)
        fig.x_range.renderers = fig.y_range.renderers = [frame]
        fig.vstrip("left", "right", source=self.invalid, fill_color=INVALID_COLOR,
                   fill_alpha=0.3, line_color=None)
        fig.varea("x_mm", "bottom", "top", source=self.rod, fill_color="#E69F00",
                  fill_alpha=0.5, legend_label="rod, top face at its peak (H magnified)")
        fig.line("x_mm", "wave", source=self.rod, color="black", line_width=2,
                 line_dash="dashed", legend_label="u₀(x) magnified (+: along +x)")
        fig.circle("x", "y", radius="radius", source=self.rotor, fill_color=ROTOR_COLOR,
                   fill_alpha=0.35, line_color="black", level=FRAME_LEVEL)
        fig.text("x", "y", text="label", source=self.rotor, text_align="center",
                 text_baseline="middle", text_font_size="12pt", level=FRAME_LEVEL)
        fig.legend.location = "top_right"
        # at the top left of the frame (its y is set with the frame, in mm)
        self.readout = Label(x=8, y=0, x_units="screen", text="", text_baseline="top",
                             text_font_size="12pt", background_fill_color="white",
                             background_fill_alpha=0.8, level=FRAME_LEVEL,
                             name="motor_readout")
        fig.add_layout(self.readout)
        style_figure(fig)
        self.rod_figure = fig

    def _thrust_figure(self) -> None:
        # (taller: its legend's two rows above the frame)
        fig = new_figure("Stall thrust along the rod (rotor held)", "x₀ (mm)",
                         "stall thrust (mN, + along +x)", height=380)
        fig.vstrip("left", "right", source=self.invalid, fill_color=INVALID_COLOR,
                   fill_alpha=0.3, line_color=None, legend_label="contact never opens")
        # upright in the shading (bottom to top), which holds no curve: the strip at an
        # end is narrower than the label's lines are long
        fig.text("x_mm", "y", text="text", source=self.ends, text_align="center",
                 text_baseline="middle", text_font_size="10pt", text_color="#333333",
                 angle=math.pi / 2, name="motor_ends_text")
        fig.line("x_mm", "thrust_mN", source=self.thrust, color=THRUST_COLOR,
                 line_width=3, legend_label="stall thrust")
        fig.scatter("x_mm", "thrust_mN", source=self.optimum, marker="star", size=18,
                    color=BEST_COLOR, line_color="black", legend_label="optimum")
        fig.vspan("x_mm", source=self.x0, line_color=ROTOR_COLOR, line_width=2,
                  line_dash="dotted", level=FRAME_LEVEL)
        fig.scatter("x_mm", "thrust_mN", source=self.x0, size=12, color=ROTOR_COLOR,
                    line_color="black", level=FRAME_LEVEL)
        style_figure(fig)
        legend_above(fig)
        self.thrust_figure = fig

    def _speed_figures(self) -> None:
        speed_range = Range1d(0, 1)
        figs = []
        for title, y_label, column, colour in (
                ("Thrust against rotor speed at x₀", "thrust (mN, along the drive)",
                 "thrust_mN", THRUST_COLOR),
                ("Efficiency against rotor speed at x₀", "efficiency (%)",
                 "efficiency_pct", EFFICIENCY_COLOR)):
            fig = new_figure(title, "rotor speed V (mm/s)", y_label, x_range=speed_range)
            fig.line("V_mm_s", column, source=self.speed, color=colour, line_width=3)
            fig.scatter("V_mm_s", column, source=self.marks, size=12, marker="diamond",
                        color="label", line_color="black")
            fig.scatter("V_mm_s", column, source=self.operating, size=14, marker="square",
                        fill_color="white", line_color=OPERATING_COLOR, line_width=3,
                        legend_label="operating point under the load")
            style_figure(fig)
            legend_above(fig)
            figs.append(fig)
        self.speed_figure, self.efficiency_figure = figs

    def _wear_figure(self) -> None:
        fig = new_figure("Archard wear rate along the rod (rotor held)", "x₀ (mm)",
                         "worn depth per hour (µm/h)", x_range=Range1d(-1, 1),
                         y_range=DataRange1d(start=0.0))
        fig.vstrip("left", "right", source=self.invalid, fill_color=INVALID_COLOR,
                   fill_alpha=0.3, line_color=None)
        fig.line("x_mm", "peak_um_h", source=self.wear, color=ROTOR_COLOR, line_width=3,
                 legend_label="deepest point of the contact patch")
        fig.line("x_mm", "centre_um_h", source=self.wear, color=THRUST_COLOR, line_width=2,
                 line_dash="dashed", legend_label="centre of the patch")
        fig.vspan("x_mm", source=self.x0, line_color=ROTOR_COLOR, line_width=2,
                  line_dash="dotted", level=FRAME_LEVEL)
        style_figure(fig)
        legend_above(fig)
        self.wear_figure = fig

    def _start_figure(self) -> None:
        fig = new_figure("Start-up from rest at x₀ under the load", "time (ms)",
                         "rotor speed V (mm/s)", x_range=DataRange1d(start=0.0),
                         y_range=DataRange1d(start=0.0))
        fig.line("t_ms", "V_mm_s", source=self.start, color=THRUST_COLOR, line_width=3)
        style_figure(fig)
        self.startup_figure = fig

    @property
    def figures(self) -> list:
        """The figures in the card's order."""
        return [self.rod_figure, self.thrust_figure, self.speed_figure,
                self.efficiency_figure, self.wear_figure, self.startup_figure]
