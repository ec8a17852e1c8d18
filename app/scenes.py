"""The explorer's scenes: one Bokeh figure each, fed by one named ColumnDataSource.

A scene never computes physics: it asks a `core.Contact` for the curve it shows and
writes the numbers into its source (`source.data = ...`), so the figure itself is
built once and only its data changes.  Two entry points:

* `update_contact(c)` when a parameter changes: the curves over the whole contact;
* `update_tau(c, tau)` on every animation frame: only what depends on tau
  (the traction profile, the contact disc, the markers at the current tau).

Sources are named after the scene (`traction`, `disc`, `force`, `impulse`, `radii`,
`motion`) so that tests and the browser can find them with `get_model_by_name`; the
current-tau markers live in `<name>_marker`.
"""

from __future__ import annotations

import math
from functools import cached_property

import numpy as np
from bokeh.models import (
    ColumnDataSource,
    CustomJS,
    GlyphRenderer,
    Label,
    Legend,
    LegendItem,
    Range1d,
)
from bokeh.plotting import figure

from app.phases import STICK_COLOR, style
from app.wire import inline
from core import Contact, impulse_ratio

TOOLS = "pan,wheel_zoom,box_zoom,reset,save"
CURVE_POINTS = 400  # points per curve over the contact: finer than any screen needs
PROFILE_POINTS = 151  # points across the contact diameter for the traction profile

LINE_COLORS = ("#000000", "#D55E00", "#0072B2", "#CC79A7", "#009E73")
#: Bokeh level of everything that changes on an animation frame or a slider move: the
#: browser then repaints only the plot's overlay layer, not its axes, grid and legend
#: (repainting a legend restyles the page, which is what costs most in the browser).
FRAME_LEVEL = "overlay"


def _style(fig) -> None:
    """Large type, readable on a projector."""
    fig.title.text_font_size = "15pt"
    for axis in (*fig.xaxis, *fig.yaxis):
        axis.axis_label_text_font_size = "14pt"
        axis.major_label_text_font_size = "12pt"
    fig.toolbar.logo = None
    fig.toolbar.autohide = True
    if fig.legend:
        fig.legend.label_text_font_size = "12pt"
        fig.legend.background_fill_alpha = 0.7
        fig.legend.click_policy = "hide"


def add_legend(fig, entries: list[tuple[str, list[GlyphRenderer]]], place: str = "right",
               location: str = "top_left") -> Legend:
    """A legend that the browser never repaints when the data change.

    BokehJS repaints a legend whenever anything its entries refer to changes, data
    included, and a legend repaint restyles the page (the costliest part of a slider
    move).  So each entry shows a copy of its first renderer holding one NaN point (drawn
    nowhere; BokehJS draws no legend swatch for an empty renderer), and clicking it
    hides or shows the real renderers: the copy's callback finds them by id, since a
    reference to them would tie the legend to their data again.
    """
    items = []
    for label, renderers in entries:
        first = renderers[0]
        proxy = fig.add_glyph(ColumnDataSource({k: [math.nan] for k in first.data_source.data}),
                              first.glyph.clone())
        ids = [r.id for r in renderers]
        proxy.js_on_change("visible", CustomJS(code=(
            f"for (const id of {ids!r}) {{\n"
            "  const r = cb_obj.document.get_model_by_id(id);\n"
            "  if (r != null) r.visible = cb_obj.visible;\n}")))
        items.append(LegendItem(label=label, renderers=[proxy]))
    legend = Legend(items=items, location=location, click_policy="hide")
    fig.add_layout(legend, place)
    return legend


def nice_step(span: float, parts: int = 10) -> float:
    """The 1-2-5 x 10^k step nearest above span / parts (span > 0)."""
    raw = span / parts
    k = math.floor(math.log10(raw))
    f = raw / 10.0**k
    return next(m for m in (1.0, 2.0, 5.0, 10.0) if f <= m * (1 + 1e-12)) * 10.0**k


def fit_range(rng: Range1d, *columns, pad: float = 0.06, snap: bool = False) -> None:
    """Set a fixed range around the finite values of `columns`.

    Ranges are explicit (not auto-ranged) so that moving a marker never makes the
    browser lay the plot out again: only the data of a frame changes.  With `snap` the
    ends are rounded outwards to a multiple of a 1-2-5 step of about a tenth of the
    span, so that a small parameter move usually leaves the range (and the axes, which
    the browser would otherwise redraw) as they were.
    """
    values = np.concatenate([np.ravel(np.asarray(c, float)) for c in columns])
    values = values[np.isfinite(values)]
    lo, hi = (float(values.min()), float(values.max())) if values.size else (0.0, 1.0)
    margin = pad * (hi - lo) if hi > lo else 0.5
    lo, hi = lo - margin, hi + margin
    if snap:
        step = nice_step(hi - lo)
        lo, hi = math.floor(lo / step) * step, math.ceil(hi / step) * step
    if (rng.start, rng.end) != (lo, hi):
        rng.start, rng.end = lo, hi


def _figure(title: str, x_label: str, y_label: str, **kwargs):
    kwargs.setdefault("x_range", Range1d(0, 1))
    kwargs.setdefault("y_range", Range1d(0, 1))
    kwargs.setdefault("tools", TOOLS)
    kwargs.setdefault("sizing_mode", "stretch_width")
    kwargs.setdefault("height", 340)
    kwargs.setdefault("min_width", 300)
    return figure(title=title, x_axis_label=x_label, y_axis_label=y_label, **kwargs)


class Scene:
    """Base: a figure, its named source, and the two update hooks."""

    name: str = ""

    def __init__(self, data: dict) -> None:
        self.source = ColumnDataSource(data=data, name=self.name)

    def update_contact(self, c: Contact) -> None:
        """Recompute what depends on the parameters (default: nothing)."""

    def update_tau(self, c: Contact, tau: float) -> None:
        """Recompute what depends on the current tau (default: nothing)."""

    def table(self) -> dict[str, np.ndarray]:
        """The data shown, for the CSV download."""
        return {k: np.asarray(v) for k, v in self.source.data.items()}


class TractionScene(Scene):
    """Fig. 6: tau_u(r) / (mu p*) across the diameter at the current tau."""

    name = "traction"

    def __init__(self) -> None:
        super().__init__({k: [] for k in ("r", "traction", "upper", "lower", "stick_lo",
                                          "stick_hi")})
        fig = _figure("Traction profile", "r / a*", "traction  τᵤ / (μ p*)")
        stick = fig.varea("r", "stick_lo", "stick_hi", source=self.source,
                          fill_color=STICK_COLOR, fill_alpha=0.25, level=FRAME_LEVEL)
        envelope = [fig.line("r", col, source=self.source, line_dash="dashed", color="grey",
                             line_width=2, level=FRAME_LEVEL) for col in ("upper", "lower")]
        self.line = fig.line("r", "traction", source=self.source, color="black", line_width=3,
                             level=FRAME_LEVEL)
        add_legend(fig, [("stick zone", [stick]), ("±μ p", envelope), ("τᵤ", [self.line])],
                   place="center")
        # values at the current tau, drawn on the canvas: a text pane beside the plot
        # would make the browser lay out the whole page again on every frame
        self.caption = Label(x=0, y=0, text="", text_align="right", text_baseline="top",
                             text_font_size="13pt", background_fill_color="white",
                             background_fill_alpha=0.8, name="traction_caption",
                             level=FRAME_LEVEL)
        fig.add_layout(self.caption)
        # the phase, in its colour, drawn with the data: BokehJS does not always repaint a
        # changed Title (its new text showed only after a resize), a Label on the overlay
        # level is painted with every frame
        self.phase_label = Label(x=0, y=0, text="", text_baseline="bottom",
                                 text_align="center", text_font_size="17pt",
                                 text_font_style="bold",
                                 background_fill_color="white", background_fill_alpha=0.8,
                                 name="traction_phase", level=FRAME_LEVEL)
        fig.add_layout(self.phase_label)
        _style(fig)
        self.figure = fig

    def update_contact(self, c: Contact) -> None:
        a_max = float(c.contact_radius(math.pi / 2))
        p_max = float(c.pressure(0.0, math.pi / 2))
        self.r_grid = np.linspace(-1.05 * a_max, 1.05 * a_max, PROFILE_POINTS)
        self.figure.x_range.start, self.figure.x_range.end = -1.1 * a_max, 1.1 * a_max
        self.figure.y_range.start, self.figure.y_range.end = -1.6 * p_max, 1.6 * p_max
        self.caption.x, self.caption.y = 1.08 * a_max, 1.55 * p_max
        self.phase_label.x, self.phase_label.y = 0.0, -1.55 * p_max  # bottom centre

    def profiles(self, c: Contact, taus: np.ndarray) -> dict[str, np.ndarray]:
        """The profile at each of the K times `taus`: columns of shape (K, L).

        Each row is the r grid with -a, a, -b, b inserted (sharp corners at the contact
        and stick edges), so every frame has the same length L and the browser's player
        can copy frames into the plotted arrays in place.
        """
        taus = np.atleast_1d(np.asarray(taus, float))
        line = c.at(taus)
        a, b = line.contact_radius, line.stick_radius
        grid = np.broadcast_to(self.r_grid, (taus.size, self.r_grid.size))
        r = np.sort(np.concatenate([grid, np.stack([-a, a, -b, b], axis=1)], axis=1), axis=1)
        t = taus[:, None]
        p = c.pressure(r, t)
        stick = (np.abs(r) <= b[:, None]) & (b[:, None] > 0)
        return {"r": r, "traction": c.traction(r, t), "upper": p, "lower": -p,
                "stick_lo": np.where(stick, -p, 0.0), "stick_hi": np.where(stick, p, 0.0)}

    def update_tau(self, c: Contact, tau: float) -> None:
        self.source.data = inline({k: v[0] for k, v in self.profiles(c, np.array([tau])).items()})
        look = style(c.phase(tau))
        self.phase_label.text_color = look.color
        self.phase_label.text = look.name


class DiscScene(Scene):
    """Top view of the contact disc: stick disc and slip annulus coloured by phase."""

    name = "disc"

    def __init__(self) -> None:
        super().__init__({"x": [0.0, 0.0], "y": [0.0, 0.0], "inner": [0.0, 0.0],
                          "outer": [0.0, 0.0], "color": [STICK_COLOR, STICK_COLOR],
                          "label": ["stick", "slip"]})
        # no legend: a legend built from the data would repaint the whole plot per frame
        fig = _figure("Contact disc (top view)", "x / a*", "y / a*", match_aspect=True,
                      sizing_mode="fixed", width=350, height=350)
        self.envelope = fig.circle(0, 0, radius=1.0, fill_alpha=0, line_dash="dotted",
                                   line_color="grey", line_width=2)
        fig.annulus("x", "y", inner_radius="inner", outer_radius="outer", source=self.source,
                    fill_color="color", line_color="black", line_width=1, level=FRAME_LEVEL)
        fig.x_range.start, fig.x_range.end = -1.15, 1.15
        fig.y_range.start, fig.y_range.end = -1.15, 1.15
        _style(fig)
        self.figure = fig

    def update_contact(self, c: Contact) -> None:
        a_max = float(c.contact_radius(math.pi / 2))
        self.envelope.glyph.radius = a_max
        self.figure.x_range.start, self.figure.x_range.end = -1.15 * a_max, 1.15 * a_max
        self.figure.y_range.start, self.figure.y_range.end = -1.15 * a_max, 1.15 * a_max

    def update_tau(self, c: Contact, tau: float) -> None:
        line = c.at(tau)
        a, b, look = float(line.contact_radius), float(line.stick_radius), style(line.phase)
        self.source.data = {
            "x": [0.0, 0.0], "y": [0.0, 0.0], "inner": [0.0, b], "outer": [b, a],
            "color": [STICK_COLOR, look.ring_color], "label": ["stick", look.ring],
        }


class CurveScene(Scene):
    """A scene of curves over tau with markers (and a vertical line) at the current tau.

    Subclasses list their curves as (column, legend, colour, dash) in `curves` and
    implement `columns(c, tau)` returning each column's values.
    """

    curves: tuple[tuple[str, str, str, str], ...] = ()
    title = ""
    y_label = ""

    def __init__(self) -> None:
        super().__init__({"tau": [], **{col: [] for col, *_ in self.curves}})
        self.marker = ColumnDataSource({"x": [], "y": [], "color": [], "lo": [], "hi": []},
                                       name=f"{self.name}_marker")
        #: the paper's landmarks on the time axis: tau0, pi/2, tau1 (psi > 1), pi - tau0
        self.landmarks = ColumnDataSource({"x": [], "label": [], "lo": [], "hi": []},
                                          name=f"{self.name}_landmarks")

    @cached_property
    def figure(self):
        """The plot, built on first use (a scene in a closed tab may never need it)."""
        return self._make_figure()

    def _make_figure(self):
        fig = _figure(self.title, "τ = ωt (rad)", self.y_label)
        fig.segment(x0="x", y0="lo", x1="x", y1="hi", source=self.landmarks,
                    line_color="#bbbbbb", line_width=1, line_dash="dashed")
        fig.text("x", "hi", text="label", source=self.landmarks, text_align="center",
                 text_baseline="top", text_font_size="12pt", text_color="#555555",
                 y_offset=2)
        lines = [fig.line("tau", col, source=self.source, color=color, line_width=3,
                          line_dash=dash, level=FRAME_LEVEL, name=f"{self.name}_{col}")
                 for col, _, color, dash in self.curves]
        # the curves are drawn above the legend's level, so the legend goes beside them
        add_legend(fig, [(label, [line]) for (_, label, *_), line
                         in zip(self.curves, lines, strict=True)])
        fig.scatter("x", "y", source=self.marker, size=13, color="color", line_color="black",
                    level=FRAME_LEVEL)
        # the cursor at the current tau is drawn from the marker's own source, so that a
        # frame changes one data source per plot (moving a Span model costs the browser
        # a full repaint of the plot)
        fig.segment(x0="x", y0="lo", x1="x", y1="hi", source=self.marker, line_color="#666666",
                    line_width=2, line_dash="dotted", level=FRAME_LEVEL)
        _style(fig)
        return fig

    def columns(self, c: Contact, tau: np.ndarray) -> dict[str, np.ndarray]:
        """Values of every curve at the times tau (an array)."""
        raise NotImplementedError

    def update_contact(self, c: Contact) -> None:
        tau = c.tau_grid(CURVE_POINTS)
        columns = self.columns(c, tau)
        self.source.data = inline({"tau": tau, **columns})
        fit_range(self.figure.x_range, tau, pad=0.02)
        fit_range(self.figure.y_range, *columns.values(), pad=0.03, snap=True)
        marks = [(c.tau0, "τ₀"), (math.pi / 2, "π/2"), (c.tau1, "τ₁"), (c.tau_end, "π−τ₀")]
        marks = [(x, label) for x, label in marks if not math.isnan(x)]
        y = self.figure.y_range
        self.landmarks.data = {"x": [x for x, _ in marks], "label": [lb for _, lb in marks],
                               "lo": [y.start] * len(marks), "hi": [y.end] * len(marks)}

    def update_tau(self, c: Contact, tau: float) -> None:
        values = self.columns(c, np.array([tau]))
        n = len(self.curves)
        y_range = self.figure.y_range
        self.marker.data = {
            "x": [tau] * n,
            "y": [float(values[col][0]) for col, *_ in self.curves],
            "color": [color for _, _, color, _ in self.curves],
            "lo": [y_range.start] * n,
            "hi": [y_range.end] * n,
        }


class ForceScene(CurveScene):
    """Fig. 7: T / T0 over the contact with the Coulomb bounds +-mu P / T0."""

    name = "force"
    title = "Tangential force T / T₀"
    y_label = "T / T₀"
    curves = (
        ("T", "T / T₀", "#000000", "solid"),
        ("muP", "+μP / T₀", "#999999", "dashed"),
        ("neg_muP", "−μP / T₀", "#999999", "dashed"),
    )

    def __init__(self) -> None:
        super().__init__()
        self.family = ColumnDataSource({"xs": [], "ys": [], "label": [], "color": []},
                                       name="force_family")
        self._family: list[tuple] = []

    def _make_figure(self):
        fig = super()._make_figure()
        fig.multi_line("xs", "ys", source=self.family, color="color", line_width=2,
                       line_alpha=0.7, legend_field="label")
        return fig

    def columns(self, c: Contact, tau: np.ndarray) -> dict[str, np.ndarray]:
        line = c.at(tau)
        n = line.normal_force  # P / P0 = mu P / T0
        return {"T": line.tangential_force, "muP": n, "neg_muP": -n}

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

    def columns(self, c: Contact, tau: np.ndarray) -> dict[str, np.ndarray]:
        line = c.at(tau)
        return {"approach": line.approach, "a": line.contact_radius, "b": line.stick_radius}


class MotionScene(CurveScene):
    """Fig. 9: velocity v2 and displacement u2 of the contact centre, with the drive."""

    name = "motion"
    title = "Contact-centre motion (Fig. 9)"
    y_label = "v/(ωu₀),  u/u₀"
    curves = (
        ("v2", "v₂ / (ω u₀)", "#D55E00", "solid"),
        ("u2", "u₂ / u₀", "#0072B2", "solid"),
        ("drive_v", "du₀ₓ/dt / (ω u₀)", "#D55E00", "dotted"),
        ("drive_u", "u₀ₓ / u₀", "#0072B2", "dotted"),
    )

    def columns(self, c: Contact, tau: np.ndarray) -> dict[str, np.ndarray]:
        line = c.at(tau)
        return {"v2": line.centre_velocity, "u2": line.centre_displacement,
                "drive_v": c.drive_velocity(tau), "drive_u": c.drive_displacement(tau)}


class ImpulseScene(Scene):
    """Fig. 8: T_imp / (mu P_imp) against psi at the current tau0, current psi marked.

    Two figures share the source: a linear psi axis (0 to 30, the paper's range) and a
    logarithmic one reaching psi = 1e6; `set_log` picks the one in `figure`, which the
    page shows (the other is not in the page at all: a hidden plot whose data changes
    still makes the browser lay out the page again).
    """

    name = "impulse"
    LINEAR_MAX = 30.0
    LOG_RANGE = (1e-3, 1e6)

    def __init__(self) -> None:
        super().__init__({"psi": [], "ratio": []})
        self.marker = ColumnDataSource({"psi": [], "ratio": []}, name="impulse_marker")
        self.log = False
        self._shown: tuple = ()  # (tau0, log, first psi, last psi) of the curve shown

    @cached_property
    def linear_figure(self):
        """The plot with a linear psi axis, built on first use."""
        return self._make("linear")

    @cached_property
    def log_figure(self):
        """The plot with a logarithmic psi axis, built on first use."""
        return self._make("log")

    @property
    def figure(self):
        """The plot shown: `log_figure` or `linear_figure`."""
        return self.log_figure if self.log else self.linear_figure

    def _make(self, axis: str):
        x_range = Range1d(*self.LOG_RANGE) if axis == "log" else Range1d(0.0, self.LINEAR_MAX)
        fig = _figure("Tangential impulse T_imp / (μ P_imp)", "ψ", "T_imp / (μ P_imp)",
                      x_axis_type=axis, x_range=x_range)
        fig.line("psi", "ratio", source=self.source, color="black", line_width=3)
        fig.scatter("psi", "ratio", source=self.marker, size=14, color="#D55E00",
                    line_color="black", level=FRAME_LEVEL)
        _style(fig)
        return fig

    def set_log(self, log: bool) -> None:
        """Pick the log-psi figure (True) or the linear one (False) as `figure`."""
        self.log = log

    def psi_grid(self, psi: float) -> np.ndarray:
        """The psi values plotted: screen-fine, through psi = 1 (the peak), reaching psi.

        It depends on psi only when psi lies beyond the default range, so that moving psi
        sends only the marker, not the curve (computed exactly by core either way)."""
        if self.log:
            lo, hi = self.LOG_RANGE
            grid = np.geomspace(min(lo, psi), max(hi, psi), CURVE_POINTS)
        else:
            grid = np.linspace(0.0, max(self.LINEAR_MAX, 1.1 * psi), CURVE_POINTS)
        return np.unique(np.concatenate([grid, [1.0]]))

    def update_contact(self, c: Contact) -> None:
        self.marker.data = {"psi": [c.psi], "ratio": [c.impulse_ratio]}
        psi = self.psi_grid(c.psi)
        key = (c.tau0, self.log, psi[0], psi[-1])
        if key == self._shown:
            return
        self._shown = key
        ratio = np.asarray(impulse_ratio(psi, c.tau0), float)
        self.source.data = inline({"psi": psi, "ratio": ratio})
        fig = self.figure
        if self.log:
            fig.x_range.start, fig.x_range.end = psi[0], psi[-1]
        else:
            fig.x_range.start, fig.x_range.end = 0.0, psi[-1]
        fig.y_range.start, fig.y_range.end = 0.0, 1.05 * max(float(ratio.max()), 1e-9)


class ReadoutScene(Scene):
    """The derived quantities as a two-column table drawn on a canvas.

    A table of text in the page (an HTML pane, a Bokeh Div) makes the browser lay out
    the whole page again whenever its text changes, ~50 ms per slider move; drawn as
    text glyphs, new values only repaint this canvas.
    """

    name = "readout"
    ROW_PX = 30  # height of a row (px)

    def __init__(self) -> None:
        super().__init__({"y": [], "quantity": [], "value": []})
        self.rows = 0
        fig = figure(height=self.ROW_PX, sizing_mode="stretch_width", min_width=300,
                     x_range=Range1d(0, 1), y_range=Range1d(0, 1), toolbar_location=None,
                     tools="", min_border=0, outline_line_color=None)
        fig.axis.visible = False
        fig.grid.visible = False
        fig.hspan("y", source=self.source, line_color="#dddddd", line_width=1,
                  level=FRAME_LEVEL)
        for col, x, weight in (("quantity", 0.02, "normal"), ("value", 0.58, "bold")):
            fig.text(x, "y", text=col, source=self.source, text_baseline="top",
                     text_font_size="13pt", text_font_style=weight, y_offset=6,
                     level=FRAME_LEVEL)
        self.figure = fig

    def show(self, rows: list[tuple[str, str]]) -> None:
        """Show (quantity, value) rows, top to bottom."""
        n = len(rows)
        if n != self.rows:  # the table grows or shrinks only with the physical inputs
            self.rows = n
            self.figure.height = self.ROW_PX * max(n, 1)
            self.figure.y_range.start, self.figure.y_range.end = 0, max(n, 1)
        self.source.data = {"y": [float(n - i) for i in range(n)],
                            "quantity": [k for k, _ in rows], "value": [v for _, v in rows]}
