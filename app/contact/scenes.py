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
import re
import unicodedata
from functools import cached_property

import numpy as np
from bokeh.layouts import column
from bokeh.models import (
    Annulus,
    CDSView,
    Circle,
    ColumnDataSource,
    CustomJS,
    Glyph,
    GlyphRenderer,
    IndexFilter,
    Label,
    Legend,
    LegendItem,
    Line,
    Range1d,
    SaveTool,
    Scatter,
    Segment,
    Text,
    VArea,
)
from bokeh.plotting import figure

from app.contact.phases import STICK_COLOR, style
from app.kit.wire import inline
from core import Contact, impulse_ratio

TOOLS = "pan,wheel_zoom,box_zoom,reset,save"
#: Greek letters of the plots' titles, spelled out in the PNG file names
GREEK = str.maketrans({"α": "alpha", "μ": "mu", "ν": "nu", "τ": "tau", "ψ": "psi",
                       "ω": "omega", "θ": "theta"})
CURVE_POINTS = 400  # points per curve over the contact: finer than any screen needs
PROFILE_POINTS = 151  # points across the contact diameter for the traction profile

LINE_COLORS = ("#000000", "#D55E00", "#0072B2", "#CC79A7", "#009E73")
#: Bokeh level of everything that changes on an animation frame or a slider move: the
#: browser then repaints only the plot's overlay layer, not its axes, grid and legend
#: (repainting a legend restyles the page, which is what costs most in the browser).
FRAME_LEVEL = "overlay"


def style_figure(fig) -> None:
    """Large type, readable on a projector; the glyphs drawn so far lean (`lean`)."""
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
    lean(fig)


def lean(fig) -> None:
    """Drop the copies of every glyph that Bokeh's glyph methods make for unselected and
    for muted points: no plot has a selection tool and every legend hides (never mutes)
    its curves, so those copies are never drawn; with 'auto' BokehJS makes one if ever
    needed.  Two models fewer per glyph in every page (each model costs the server
    per page load)."""
    for r in fig.renderers:
        if isinstance(r, GlyphRenderer):
            r.nonselection_glyph = r.muted_glyph = "auto"


#: What `draw` gives the renderer (the rest goes to the glyph), as Bokeh's glyph methods.
RENDERER_PROPS = ("level", "name", "view", "visible")


def draw(fig, glyph: type[Glyph], source: ColumnDataSource | None = None,
         **props) -> GlyphRenderer:
    """Draw a `glyph` (a Bokeh glyph type: `Line`, `Segment`, ...) of `props` from
    `source` on `fig`, as its glyph method (`fig.line`, `fig.segment`, ...) would, as one
    glyph model where the method makes three (with the copies `lean` drops).  As in the
    methods, `color` and `alpha` stand for each colour and alpha of the glyph not given
    (line, fill, hatch, text), strings name the source's columns, and `RENDERER_PROPS`
    go to the renderer."""
    renderer = {k: props.pop(k) for k in RENDERER_PROPS if k in props}
    for trait in ("color", "alpha"):
        if trait in props:
            value = props.pop(trait)
            for prop in glyph.properties():
                feature, _, rest = prop.partition("_")
                if rest == trait and feature in VISUALS:
                    props.setdefault(prop, value)
    return fig.add_glyph(source or ColumnDataSource(), glyph(**props), **renderer)


#: The visual features of a glyph's properties (line_color, fill_alpha, ...).
VISUALS = ("line", "fill", "hatch", "text", "global")


def add_legend(fig, entries: list[tuple[str, list[GlyphRenderer]]], place: str = "right",
               location: str = "top_left") -> Legend:
    """A legend that the browser never repaints when the data change.

    BokehJS repaints a legend whenever anything its entries refer to changes, data
    included, and a legend repaint restyles the page (the costliest part of a slider
    move).  So each entry shows a copy of its first renderer drawing one NaN point
    (nowhere; BokehJS draws no legend swatch for an empty renderer), and clicking it
    hides or shows the real renderers: the copies' callback finds them by id, since a
    reference to them would tie the legend to their data again.  The copies share one
    source and one callback.
    """
    columns = dict.fromkeys(k for _, renderers in entries for k in renderers[0].data_source.data)
    nowhere = ColumnDataSource({k: [math.nan] for k in columns})
    proxies = [fig.add_glyph(nowhere, renderers[0].glyph.clone()) for _, renderers in entries]
    targets = {proxy.id: [r.id for r in renderers]
               for proxy, (_, renderers) in zip(proxies, entries, strict=True)}
    toggle = CustomJS(code=(
        f"for (const id of {targets!r}[cb_obj.id]) {{\n"
        "  const r = cb_obj.document.get_model_by_id(id);\n"
        "  if (r != null) r.visible = cb_obj.visible;\n}"))
    for proxy in proxies:
        proxy.js_on_change("visible", toggle)
    items = [LegendItem(label=label, renderers=[proxy])
             for (label, _), proxy in zip(entries, proxies, strict=True)]
    legend = Legend(items=items, location=location, click_policy="hide")
    place_legend(fig, legend, place)
    return legend


def place_legend(fig, legend: Legend, place: str) -> None:
    """Put `legend` in `fig`'s side panel `place` ('above', 'right', ...), out of any
    other: a row above or below (tighter around, wider between entries), a column
    beside."""
    for side in ("above", "below", "left", "right", "center"):
        setattr(fig, side, [m for m in getattr(fig, side) if m is not legend])
    row = place in ("above", "below")
    legend.update(orientation="horizontal" if row else "vertical", spacing=16 if row else 3,
                  padding=5 if row else 10, margin=4 if row else 10)
    fig.add_layout(legend, place)


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


def new_figure(title: str, x_label: str, y_label: str, **kwargs):
    """A Bokeh figure as every scene has it: unit ranges to be fitted, the scenes'
    tools, stretching to its column, and a save tool that downloads a PNG named after
    the title (`png_name`); `kwargs` override these and go to `bokeh.plotting.figure`."""
    kwargs.setdefault("x_range", Range1d(0, 1))
    kwargs.setdefault("y_range", Range1d(0, 1))
    kwargs.setdefault("tools", TOOLS)
    kwargs.setdefault("sizing_mode", "stretch_width")
    kwargs.setdefault("height", 340)
    kwargs.setdefault("min_width", 300)
    fig = figure(title=title, x_axis_label=x_label, y_axis_label=y_label, **kwargs)
    for tool in fig.select(type=SaveTool):  # downloads the PNG without asking for a name
        tool.filename = png_name(title)
    return fig


def png_name(title: str) -> str:
    """The name (without .png) under which the save tool downloads the plot titled
    `title`: 'zharii_' and the title's words in lower-case ASCII (Greek letters spelled
    out, subscripts as digits).  Fixed per plot: a name following the parameters would
    re-render the tool's button in the browser on every parameter change."""
    text = unicodedata.normalize("NFKD", title.translate(GREEK)).lower()
    return "_".join(["zharii", *re.findall(r"[a-z0-9]+", text)])


#: The landmark labels' offset below the frame's top (px), and tau1's, a line lower: it
#: comes close to pi - tau0 for psi near 1 and to pi/2 for large psi.
LANDMARK_DY, TAU1_DY = 2, 18


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
        fig = new_figure("Traction profile", "r / a*", "traction  τᵤ / (μ p*)", height=390)
        stick = draw(fig, VArea, self.source, x="r", y1="stick_lo", y2="stick_hi",
                     fill_color=STICK_COLOR, fill_alpha=0.25, level=FRAME_LEVEL)
        envelope = [draw(fig, Line, self.source, x="r", y=col, line_dash="dashed",
                         color="grey", line_width=2, level=FRAME_LEVEL)
                    for col in ("upper", "lower")]
        self.line = draw(fig, Line, self.source, x="r", y="traction", color="black",
                         line_width=3, level=FRAME_LEVEL)
        # in one row above the frame (inside it, it covered the stick zone and the rim;
        # beside it, it left a phone too narrow a frame)
        add_legend(fig, [("stick zone", [stick]), ("±μ p", envelope), ("τᵤ", [self.line])],
                   place="above")
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
        style_figure(fig)
        self.figure = fig

    def update_contact(self, c: Contact) -> None:
        a_max = float(c.contact_radius(math.pi / 2))
        p_max = float(c.pressure(0.0, math.pi / 2))
        self.r_grid = np.linspace(-1.05 * a_max, 1.05 * a_max, PROFILE_POINTS)
        self.figure.x_range.start, self.figure.x_range.end = -1.1 * a_max, 1.1 * a_max
        # room above the largest pressure for the caption's two lines, below it for the phase
        self.figure.y_range.start, self.figure.y_range.end = -1.6 * p_max, 2.4 * p_max
        self.caption.x, self.caption.y = 1.08 * a_max, 2.35 * p_max
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

    def table(self, c: Contact, tau: float) -> dict[str, np.ndarray]:
        """The profile of contact `c` at time tau (rad), on the points `update_tau` plots,
        for the CSV download: r/a* (signed position along x through the centre), the
        traction tau_u/(mu p*) (eqs 18, 24, 33, 36), the pressure p/p* (eq 6; also the
        Coulomb bound mu p in units of mu p*) and stick (1 in the stick disc |r| <= b,
        0 in slip and outside contact)."""
        profile = {k: v[0] for k, v in self.profiles(c, np.array([tau])).items()}
        r, b = profile["r"], float(c.stick_radius(tau))
        return {"r/a*": r, "tau_u/(mu p*)": profile["traction"], "p/p*": profile["upper"],
                "stick": ((np.abs(r) <= b) & (b > 0)).astype(float)}

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
        fig = new_figure("Contact disc (top view)", "x / a*", "y / a*", match_aspect=True,
                         sizing_mode="fixed", width=350, height=350)
        self.envelope = draw(fig, Circle, x=0, y=0, radius=1.0, fill_alpha=0,
                             line_dash="dotted", line_color="grey", line_width=2)
        draw(fig, Annulus, self.source, x="x", y="y", inner_radius="inner",
             outer_radius="outer", fill_color="color", line_color="black", line_width=1,
             level=FRAME_LEVEL)
        fig.x_range.start, fig.x_range.end = -1.15, 1.15
        fig.y_range.start, fig.y_range.end = -1.15, 1.15
        style_figure(fig)
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
    #: the plot's panels, one above the other on a shared time axis: (title, y label,
    #: the columns drawn); empty: one panel of every curve
    panels: tuple[tuple[str, str, tuple[str, ...]], ...] = ()

    def __init__(self) -> None:
        super().__init__({"tau": [], **{col: [] for col, *_ in self.curves}})
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
            lines = [draw(fig, Line, self.source, x="tau", y=col, color=color, line_width=3,
                          line_dash=dash, level=FRAME_LEVEL, name=f"{self.name}_{col}")
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
                 line_color="black", level=FRAME_LEVEL, **view)
            # the cursor at the current tau is drawn from the marker's own source, so that
            # a frame changes one data source per plot (moving a Span model costs the
            # browser a full repaint of the plot)
            draw(fig, Segment, self.marker, x0="x", y0="lo", x1="x", y1="hi",
                 line_color="#666666", line_width=2, line_dash="dotted", level=FRAME_LEVEL,
                 **view)
            style_figure(fig)
            if k:
                fig.title.text_font_size = "13pt"
            figs.append(fig)
        return figs

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
        self.source.data = inline({"tau": tau, **columns})
        fit_range(self.figures[0].x_range, tau, pad=0.02)
        marks = [(c.tau0, "τ₀"), (math.pi / 2, "π/2"), (c.tau1, "τ₁"), (c.tau_end, "π−τ₀")]
        marks = [(x, label) for x, label in marks if not math.isnan(x)]
        for (_, _, cols), fig, landmarks in zip(self._panels(), self.figures,
                                                self._landmarks, strict=True):
            y = fig.y_range
            fit_range(y, *(columns[col] for col in cols), pad=0.03, snap=True)
            # the first and last labels inside the frame (at its edges, centred, they
            # would be cut)
            align = ["left", *["center"] * (len(marks) - 2), "right"]
            landmarks.data = {"x": [x for x, _ in marks], "label": [lb for _, lb in marks],
                              "align": align,
                              "dy": [TAU1_DY if lb == "τ₁" else LANDMARK_DY for _, lb in marks],
                              "lo": [y.start] * len(marks), "hi": [y.end] * len(marks)}

    def update_tau(self, c: Contact, tau: float) -> None:
        values = self.columns(c, np.array([tau]))
        ranges = [self._y_range(col) for col, *_ in self.curves]
        self.marker.data = {
            "x": [tau] * len(self.curves),
            "y": [float(values[col][0]) for col, *_ in self.curves],
            "color": [color for _, _, color, _ in self.curves],
            "lo": [y.start for y in ranges],
            "hi": [y.end for y in ranges],
        }


class ForceScene(CurveScene):
    """Fig. 7: T / T0 over the contact with the Coulomb bounds +-mu P / T0."""

    name = "force"
    title = "Tangential force T / T₀"
    y_label = "T / T₀"
    curves = (
        ("T", "T / T₀", "#000000", "solid"),
        ("muP", "±μP / T₀", "#999999", "dashed"),
        ("neg_muP", "±μP / T₀", "#999999", "dashed"),
    )

    def __init__(self) -> None:
        super().__init__()
        self.family = ColumnDataSource({"xs": [], "ys": [], "label": [], "color": []},
                                       name="force_family")
        self._family: list[tuple] = []

    def _make_figures(self) -> list:
        figs = super()._make_figures()
        figs[0].multi_line("xs", "ys", source=self.family, color="color", line_width=2,
                           line_alpha=0.7, legend_field="label")
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
                "-mu P/T0": d["neg_muP"]}

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
        super().update_contact(c)
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

    #: the psi of the curves of Fig. 7 (a: 0.4, 0.8, 1; b: 2.41, 6.46, 28.35), marked 1
    #: to 6 on the impulse curve as in Fig. 8
    FIG7_PSI = (0.4, 0.8, 1.0, 2.41, 6.46, 28.35)

    def __init__(self) -> None:
        super().__init__({"psi": [], "ratio": []})
        self.marker = ColumnDataSource({"psi": [], "ratio": []}, name="impulse_marker")
        self.points = ColumnDataSource({"psi": [], "ratio": [], "label": []},
                                       name="impulse_points")
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
        fig = new_figure("Tangential impulse T_imp / (μ P_imp)", "ψ", "T_imp / (μ P_imp)",
                         x_axis_type=axis, x_range=x_range)
        fig.line("psi", "ratio", source=self.source, color="black", line_width=3)
        fig.scatter("psi", "ratio", source=self.points, size=11, color="white",
                    line_color="black", line_width=2)
        fig.text("psi", "ratio", text="label", source=self.points, text_font_size="13pt",
                 text_font_style="bold", x_offset=6, y_offset=-6)
        fig.scatter("psi", "ratio", source=self.marker, size=14, color="#D55E00",
                    line_color="black", level=FRAME_LEVEL)
        style_figure(fig)
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
        marked = np.array(self.FIG7_PSI)
        self.points.data = {"psi": marked, "ratio": np.asarray(impulse_ratio(marked, c.tau0)),
                            "label": [str(i) for i in range(1, marked.size + 1)]}
        fig = self.figure
        if self.log:
            fig.x_range.start, fig.x_range.end = psi[0], psi[-1]
        else:
            fig.x_range.start, fig.x_range.end = 0.0, psi[-1]
        fig.y_range.start, fig.y_range.end = 0.0, 1.05 * max(float(ratio.max()), 1e-9)

    def table(self) -> dict[str, np.ndarray]:
        """The plotted curve for the CSV download: psi and the impulse ratio
        T_imp/(mu P_imp) (eq 41) at the contact's tau0."""
        d = {k: np.asarray(v) for k, v in self.source.data.items()}
        return {"psi": d["psi"], "T_imp/(mu P_imp)": d["ratio"]}

