"""The curves over one contact: `CurveScene`, their base, with a marker at the current
tau (source `<name>_marker`); T(tau) (Fig. 7, `ForceScene`) and the motion of the
contact centre (Fig. 9, `MotionScene`); the approach and the radii are
`app.contact.radii`'s (Fig. 4)."""

from __future__ import annotations

import math
from functools import cached_property
from typing import ClassVar

import numpy as np
from bokeh.layouts import column
from bokeh.models import (
    CDSView,
    ColumnDataSource,
    GlyphRenderer,
    IndexFilter,
    Label,
    Line,
    Range1d,
    Scatter,
    Segment,
    Text,
)

from app.kit.changes import show
from app.kit.figures import (
    CURVE_POINTS,
    DATA_LEVEL,
    LINE_COLORS,
    add_legend,
    draw,
    fit_range,
    lean,
    negated,
    new_figure,
    stamp,
    stamp_outside,
    style_figure,
)
from app.kit.scene import Scene
from core import Contact

#: The landmark labels' offset below the frame's top (px), and tau1's, a line lower: it
#: comes close to pi - tau0 for psi near 1 and to pi/2 for large psi.
LANDMARK_DY, TAU1_DY = 2, 18


#: Where a curve plot's stamp stands: the corner of its ranges (x, y), and the stamp's
#: separator (a newline stacks its three values), alignment and offsets (px).
STAMP_CORNERS = {
    # under the landmarks' labels, tau1's (a line lower) included
    "top_left": ("start", "end", {"sep": "   ", "text_align": "left", "text_baseline": "top",
                                  "x_offset": 4, "y_offset": -(TAU1_DY + 20)}),
}


def place_stamp(label: Label, fig, corner: str = "top_left") -> None:
    """Put `label` at the `corner` (`STAMP_CORNERS`) of `fig`'s ranges (unless it is
    there)."""
    x, y, _ = STAMP_CORNERS[corner]
    at = (getattr(fig.x_range, x), getattr(fig.y_range, y))
    if (label.x, label.y) != at:
        label.x, label.y = at


class CurveScene(Scene):
    """A scene of curves over tau with markers (and a vertical line) at the current tau.

    Subclasses list their curves as (column, legend, colour, dash) in `curves` and
    implement `columns(c, tau)` returning each column's values.  A curve named in
    `mirrors` is the negative of another column: it is not sent, the browser draws it
    negated (its marker, its range and the CSV use its values from `columns`).
    """

    curves: tuple[tuple[str, str, str, str], ...] = ()
    #: the corner of the stamp (`STAMP_CORNERS`): one the curves leave empty; None: under
    #: the x axis (`app.kit.figures.stamp_outside`), for curves that leave none empty at
    #: every width of the plot
    stamp_corner: str | None = "top_left"
    #: the curves drawn as the negative of another column: {curve: column}
    mirrors: ClassVar[dict[str, str]] = {}
    title = ""
    y_label = ""
    #: the plot's panels, one above the other on a shared time axis: (title, y label,
    #: the columns drawn); empty: one panel of every curve
    panels: tuple[tuple[str, str, tuple[str, ...]], ...] = ()

    def __init__(self) -> None:
        super().__init__({"tau": [], **{col: [] for col, *_ in self.curves
                                        if col not in self.mirrors}})
        self.marker = ColumnDataSource({"x": [], "y": [], "color": [], "lo": [], "hi": []},
                                       name=f"{self.name}_marker")
        #: the paper's landmarks on the time axis: tau0, pi/2, tau1 (psi > 1), pi - tau0
        #: (one source per panel)
        empty = {"x": [], "label": [], "align": [], "dy": [], "lo": [], "hi": []}
        self._landmarks = [
            ColumnDataSource(empty, name=f"{self.name}_landmarks" + (f"_{i}" if i else ""))
            for i in range(len(self._panels()))]
        self.landmarks = self._landmarks[0]

    def _panels(self) -> tuple[tuple[str, str, tuple[str, ...]], ...]:
        return self.panels or ((self.title, self.y_label,
                                tuple(col for col, *_ in self.curves)),)

    @cached_property
    def figures(self) -> list:
        """The panels' plots, built on first use (a scene in a closed tab may never need
        them)."""
        return self._make_figures()

    @property
    def figure(self):
        """What the page shows: the plot, or its panels in a column."""
        figs = self.figures
        return figs[0] if len(figs) == 1 else self._column

    @cached_property
    def _column(self):
        return column(*self.figures, sizing_mode="stretch_width")

    def _make_figures(self) -> list:
        figs = []
        self._stamps: list[Label] = []
        rows = {col: i for i, (col, *_) in enumerate(self.curves)}
        for k, ((title, y_label, cols), landmarks) in enumerate(
                zip(self._panels(), self._landmarks, strict=True)):
            extra = {"x_range": figs[0].x_range} if figs else {}
            fig = new_figure(title, "τ = ωt (rad)", y_label, **extra)
            draw(fig, Segment, landmarks, x0="x", y0="lo", x1="x", y1="hi",
                 line_color="#bbbbbb", line_width=1, line_dash="dashed")
            draw(fig, Text, landmarks, x="x", y="hi", text="label", text_align="align",
                 text_baseline="top", text_font_size="12pt", text_color="#555555",
                 y_offset="dy")
            drawn = [(c, lb, color, dash) for c, lb, color, dash in self.curves if c in cols]
            lines = [draw(fig, Line, self.source, x="tau", y=self._y_spec(col), color=color,
                          line_width=3, line_dash=dash, level=DATA_LEVEL,
                          name=f"{self.name}_{col}")
                     for col, _, color, dash in drawn]
            # the curves are drawn above the legend's level, so the legend goes outside
            # the frame: in one row above it (beside it, it left a phone a narrow frame)
            # (curves of one label share an entry: +-mu P)
            entries: dict[str, list[GlyphRenderer]] = {}
            for (_, label, *_), line in zip(drawn, lines, strict=True):
                entries.setdefault(label, []).append(line)
            add_legend(fig, list(entries.items()), place="above")
            view = {} if len(self._panels()) == 1 else {"view": CDSView(
                filter=IndexFilter([rows[col] for col in cols]))}
            draw(fig, Scatter, self.marker, x="x", y="y", size=13, color="color",
                 line_color="black", level=DATA_LEVEL, **view)
            # the cursor at the current tau is drawn from the marker's own source, so that
            # a frame changes one data source per plot (moving a Span model costs the
            # browser a full repaint of the plot)
            draw(fig, Segment, self.marker, x0="x", y0="lo", x1="x", y1="hi",
                 line_color="#666666", line_width=2, line_dash="dotted", level=DATA_LEVEL,
                 **view)
            # psi, tau0 and tau in the plot's empty corner (placed with the ranges), or
            # under its x axis
            if self.stamp_corner is None:
                stamp(fig)
                stamp_outside(fig)
            else:
                self._stamps.append(stamp(fig, x_units="data", y_units="data",
                                          **STAMP_CORNERS[self.stamp_corner][2]))
            style_figure(fig)
            if k:
                fig.title.text_font_size = "13pt"
            figs.append(fig)
        return figs

    def _y_spec(self, col: str):
        """What a curve's line draws: its column, or the column it mirrors negated."""
        if col in self.mirrors:
            return negated(self.mirrors[col])
        return col

    def _y_range(self, col: str) -> Range1d:
        """The y range of the panel drawing column `col`."""
        for (_, _, cols), fig in zip(self._panels(), self.figures, strict=True):
            if col in cols:
                return fig.y_range
        raise KeyError(col)

    def grid(self, c: Contact) -> np.ndarray:
        """The times the curves are drawn at (rad)."""
        return c.tau_grid(CURVE_POINTS)

    def columns(self, c: Contact, tau: np.ndarray) -> dict[str, np.ndarray]:
        """Values of every curve at the times tau (an array)."""
        raise NotImplementedError

    def update_contact(self, c: Contact) -> None:
        tau = self.grid(c)
        columns = self.columns(c, tau)
        show(self.source, {"tau": tau, **{k: v for k, v in columns.items()
                                          if k not in self.mirrors}})
        fit_range(self.figures[0].x_range, tau, pad=0.02)
        marks = [(c.tau0, "τ₀"), (math.pi / 2, "π/2"), (c.tau1, "τ₁"), (c.tau_end, "π−τ₀")]
        marks = [(x, label) for x, label in marks if not math.isnan(x)]
        for (_, _, cols), fig, landmarks in zip(self._panels(), self.figures,
                                                self._landmarks, strict=True):
            y = fig.y_range
            fit_range(y, *(columns[col] for col in cols), pad=0.03, snap=True)
            if self.stamp_corner is not None:
                place_stamp(self._stamps[self.figures.index(fig)], fig, self.stamp_corner)
            # the first and last labels inside the frame (at its edges, centred, they
            # would be cut)
            align = ["left", *["center"] * (len(marks) - 2), "right"]
            show(landmarks, {"x": [x for x, _ in marks], "label": [lb for _, lb in marks],
                             "align": align,
                             "dy": [TAU1_DY if lb == "τ₁" else LANDMARK_DY for _, lb in marks],
                             "lo": [y.start] * len(marks), "hi": [y.end] * len(marks)})

    def update_tau(self, c: Contact, tau: float) -> None:
        values = self.columns(c, np.array([tau]))
        ranges = [self._y_range(col) for col, *_ in self.curves]
        show(self.marker, {
            "x": [tau] * len(self.curves),
            "y": [float(values[col][0]) for col, *_ in self.curves],
            "color": [color for _, _, color, _ in self.curves],
            "lo": [y.start for y in ranges],
            "hi": [y.end for y in ranges],
        })


class ForceScene(CurveScene):
    """Fig. 7: T / T0 over the contact with the Coulomb bounds +-mu P / T0."""

    name = "force"
    title = "Tangential force T / T₀"
    y_label = "T / T₀"
    # (the bound -mu P fills the bottom right corner of a plot as narrow as a phone's)
    stamp_corner = None
    curves = (
        ("T", "T / T₀", "#000000", "solid"),
        ("muP", "±μP / T₀", "#999999", "dashed"),
        ("neg_muP", "±μP / T₀", "#999999", "dashed"),
    )
    mirrors: ClassVar[dict[str, str]] = {"neg_muP": "muP"}

    def __init__(self) -> None:
        super().__init__()
        self.family = ColumnDataSource({"xs": [], "ys": [], "label": [], "color": []},
                                       name="force_family")
        self._family: list[tuple] = []

    def _make_figures(self) -> list:
        figs = super()._make_figures()
        # (over the contact's own thick curve, on its layer: the family's member of the
        # psi on screen, Fig. 7a's 0.8 or 7b's 6.46, was hidden under it)
        figs[0].multi_line("xs", "ys", source=self.family, color="color", line_width=2,
                           line_alpha=0.7, legend_field="label", level=DATA_LEVEL)
        lean(figs[0])
        return figs

    def columns(self, c: Contact, tau: np.ndarray) -> dict[str, np.ndarray]:
        line = c.at(tau)
        n = line.normal_force  # P / P0 = mu P / T0
        return {"T": line.tangential_force, "muP": n, "neg_muP": -n}

    def table(self) -> dict[str, np.ndarray]:
        """The plotted curves for the CSV download: tau (rad), T/T0 (eqs 38, 39) and the
        Coulomb bounds +-mu P/T0 = +-P/P0 (eq 9)."""
        d = {k: np.asarray(v) for k, v in self.source.data.items()}
        return {"tau (rad)": d["tau"], "T/T0": d["T"], "mu P/T0": d["muP"],
                "-mu P/T0": -d["muP"]}

    def set_family(self, contacts: list[Contact]) -> None:
        """Overlay T / T0 of further contacts (the paper's Fig. 7 families).

        An unchanged family is not sent again."""
        key = [(c.psi, c.tau0, c.mu, c.nu) for c in contacts]
        if key == self._family:
            return
        self._family = key
        grids = [c.tau_grid(CURVE_POINTS) for c in contacts]
        self.family.data = {
            "xs": grids,
            "ys": [c.tangential_force(t) for c, t in zip(contacts, grids, strict=True)],
            "label": [f"ψ = {c.psi:g}" for c in contacts],
            "color": [LINE_COLORS[1 + i % 4] for i in range(len(contacts))],
        }


class MotionScene(CurveScene):
    """Fig. 9: velocity v2 and displacement u2 of the contact centre, with the drive, in
    two panels; drawn a little before and after the contact, so that the jumps of v2 at
    tau0, tau1 and pi - tau0 show as (nearly) vertical steps."""

    name = "motion"
    title = "Contact-centre motion (Fig. 9)"
    y_label = "v/(ωu₀),  u/u₀"
    curves = (
        ("v2", "v₂ / (ω u₀)", "#D55E00", "solid"),
        ("u2", "u₂ / u₀", "#0072B2", "solid"),
        ("drive_v", "du₀ₓ/dt / (ω u₀)", "#D55E00", "dotted"),
        ("drive_u", "u₀ₓ / u₀", "#0072B2", "dotted"),
    )
    panels = (
        ("Contact-centre velocity (Fig. 9a)", "v / (ω u₀)", ("v2", "drive_v")),
        ("Contact-centre displacement (Fig. 9b)", "u / u₀", ("u2", "drive_u")),
    )
    MARGIN = 0.1  # drawn before and after the contact, as a fraction of its duration
    STEP = 1e-6  # a jump is drawn over this fraction of the contact's duration

    def grid(self, c: Contact) -> np.ndarray:
        """The contact's grid, a margin outside it (no contact) and, at tau0, tau1 and
        pi - tau0, a time just on the other side of each jump (rad)."""
        span = c.tau_end - c.tau0
        margin, step = self.MARGIN * span, self.STEP * span
        inside = super().grid(c)
        before = np.linspace(c.tau0 - margin, c.tau0 - step, 12)
        after = np.linspace(c.tau_end + step, c.tau_end + margin, 12)
        jumps = [] if math.isnan(c.tau1) else [c.tau1 - step]
        return np.unique(np.concatenate([before, inside, jumps, after]))

    def columns(self, c: Contact, tau: np.ndarray) -> dict[str, np.ndarray]:
        line = c.at(tau)
        return {"v2": line.centre_velocity, "u2": line.centre_displacement,
                "drive_v": c.drive_velocity(tau), "drive_u": c.drive_displacement(tau)}

    def table(self) -> dict[str, np.ndarray]:
        """The plotted curves for the CSV download: tau (rad), the contact centre's
        velocity v2/(omega u0) (eq 42) and displacement u2/u0 (eq 43), and the drive's,
        (du_x0/dt)/(omega u0) = cos tau and u_x0/u0 = sin tau (eq 3)."""
        d = {k: np.asarray(v) for k, v in self.source.data.items()}
        return {"tau (rad)": d["tau"], "v2/(omega u0)": d["v2"], "u2/u0": d["u2"],
                "(du_x0/dt)/(omega u0)": d["drive_v"], "u_x0/u0": d["drive_u"]}
