"""The speed-against-accuracy chart of the numerical methods (speed_accuracy.csv).

Built here once for both places it is shown: the explorer's Methods card (a selector
whose callback runs on the server, only the chosen view sent) and the stand-alone HTML
page (`app.methods.publish`: the same selector run in the browser, every view in the
page).

Time per contact (one call each from Python, the call included; docs/numerics.md has the
times many contacts a call) against error, per view (all cases, one regime, or one case;
relative or absolute error): every run of a method as a faint marker, its Pareto front as
a line (no faster run of it is more accurate), the closed form as a labelled star at its
measured error, a grey band for the float64 floor (the closed form's own worst error
against 50-digit mpmath: below it errors are not resolved); quadrature of core's T, a
check of eq 41 that needs the closed form, in a second plot. Okabe-Ito colours and one
marker shape per method.  Presentation only: every number is the benchmarks'.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from bokeh.models import (
    BoxAnnotation,
    ColumnDataSource,
    HoverTool,
    Label,
    Legend,
    LegendItem,
)
from bokeh.plotting import figure

from app.methods.results import FLOOR

# ------------------------------------------------------------- speed against accuracy

#: Okabe-Ito colours and one marker per method (the peers; then the two quadratures,
#: which are drawn in a plot of their own).
STYLE: dict[str, tuple[str, str]] = {
    "mdr": ("#0072B2", "circle"),
    "annulus": ("#D55E00", "square"),
    "lammps_mindlin": ("#E69F00", "triangle"),
    "lammps_mindlin_force": ("#56B4E9", "inverted_triangle"),
    "lammps_mindlin_rescale": ("#009E73", "diamond"),
    "lammps_mindlin_rescale_force": ("#CC79A7", "hex"),
    "lammps_linear_history": ("#F0E442", "square_pin"),
    "liggghts_history": ("#999999", "triangle_pin"),
    "direnzo": ("#000000", "circle_x"),
    "quad": ("#0072B2", "circle"),
    "gauss_legendre": ("#D55E00", "square"),
}
CHECKS = ("quad", "gauss_legendre")
PEERS = tuple(m for m in STYLE if m not in CHECKS)
CLOSED_FORM = "closed_form"
REGIMES = ("psi <= 1", "psi > 1", "grazing", "preload")
#: Error columns: (column, name in the view's title).
KINDS = (("err_rel", "relative"), ("err", "absolute"))
SPEED_HOVER = [("run", "@run"), ("time", "@x{0.00e} s"), ("error", "@y{0.0e}")]


def label(r: dict) -> str:
    """A run's name: method and resolution (and MDR's time steps)."""
    if r["method"] == "mdr":
        return f"mdr N={r['resolution']} M={r['steps']}"
    return f"{r['method']} {r['resolution']}"


def pareto(points: list[tuple[float, float, str]]) -> list[tuple[float, float, str]]:
    """The points (time, error, label) no other point beats in both time and error."""
    front, best = [], np.inf
    for t, e, lab in sorted(points):
        if e < best:
            front.append((t, e, lab))
            best = e
    return front


def selections(rows: list[dict]) -> dict[str, list[dict]]:
    """The rows of each view: all cases, each regime, each case."""
    cases = sorted({(r["psi"], r["tau0"]) for r in rows}, key=lambda c: (c[1], c[0]))
    out = {"all cases": rows}
    for reg in REGIMES:
        out[f"regime: {reg}"] = [r for r in rows if r["regime"] == reg]
    for p, t in cases:
        sel = [r for r in rows if (r["psi"], r["tau0"]) == (p, t)]
        out[f"case: psi = {p:g}, tau0 = {t:.4g} ({sel[0]['regime']})"] = sel
    return out


@dataclass(frozen=True)
class SpeedAccuracyData:
    """What the chart shows, per view key ('<selection> | <kind> error'): per method,
    every run (`all`) and the Pareto front (`front`), each as columns x (time per
    contact, s: median over the view's cases), y (error: worst over them) and run;
    the closed form's point (`closed_form`); and the float64 floor (the closed form's
    worst error over every case)."""

    views: dict[str, dict[str, dict[str, dict[str, list]]]]
    closed_form: dict[str, dict[str, list]]
    floor: float

    @property
    def keys(self) -> list[str]:
        return list(self.views)


def speed_accuracy_data(rows: list[dict]) -> SpeedAccuracyData:
    """The views of speed_accuracy.csv's `rows`."""
    views: dict = {}
    marks: dict = {}
    for title, sel in selections(rows).items():
        cf = [r for r in sel if r["method"] == CLOSED_FORM]
        for key, kind in KINDS:
            groups: dict[tuple, list[dict]] = {}
            for r in sel:
                if r["method"] != CLOSED_FORM:
                    groups.setdefault((r["method"], r["resolution"], r["steps"]), []).append(r)
            points: dict[str, list] = {}
            for (name, _, _), rs in groups.items():
                points.setdefault(name, []).append((
                    float(np.median([r["wall_time"] for r in rs])),
                    max(max(r[key] for r in rs), FLOOR), label(rs[0])))
            view_key = f"{title} | {kind} error"
            views[view_key] = {name: {"all": _columns(pts), "front": _columns(pareto(pts))}
                               for name, pts in points.items()}
            marks[view_key] = {
                "x": [float(np.median([r["wall_time"] for r in cf]))] if cf else [],
                "y": [max(max(r[key] for r in cf), FLOOR)] if cf else [],
                "run": ["closed form"] if cf else []}
    cf_rows = [r for r in rows if r["method"] == CLOSED_FORM]
    floor = max((max(r["err_rel"], r["err"]) for r in cf_rows), default=FLOOR)
    return SpeedAccuracyData(views, marks, floor)


def _columns(points: list[tuple[float, float, str]]) -> dict[str, list]:
    return {"x": [p[0] for p in points], "y": [p[1] for p in points],
            "run": [p[2] for p in points]}


EMPTY = {"x": [], "y": [], "run": []}


@dataclass
class SpeedAccuracyChart:
    """The two plots (peers with the closed form; the quadrature check) and their
    sources: per method (every run, Pareto front), and the closed form's star."""

    data: SpeedAccuracyData
    peers: figure
    checks: figure
    sources: dict[str, tuple[ColumnDataSource, ColumnDataSource]]
    closed_form: ColumnDataSource

    def show(self, key: str) -> None:
        """Draw view `key` of `data`."""
        view = self.data.views[key]
        for name, (every, front) in self.sources.items():
            d = view.get(name)
            every.data = dict(d["all"]) if d else dict(EMPTY)
            front.data = dict(d["front"]) if d else dict(EMPTY)
        self.closed_form.data = dict(self.data.closed_form[key])


def _speed_figure(title: str, methods: tuple[str, ...], floor: float, **kwargs
                  ) -> tuple[figure, dict, list[LegendItem]]:
    fig = figure(title=title, x_axis_type="log", y_axis_type="log",
                 x_axis_label="time per contact, one call each from Python (s)",
                 y_axis_label="error (worst over the cases shown)",
                 x_range=(1e-7, 10), y_range=(FLOOR / 2, 10), **kwargs)
    fig.add_layout(BoxAnnotation(bottom=FLOOR / 2, top=floor, fill_color="#bbbbbb",
                                 fill_alpha=0.35, line_color=None))
    fig.add_layout(Label(x=1.5e-7, y=FLOOR / 2, y_offset=4, text_font_size="9pt",
                         text=f"float64 floor: below {floor:.1e} (the worst closed-form "
                         "error against 50-digit mpmath) errors are not resolved"))
    sources, items = {}, []
    for name in methods:
        colour, marker = STYLE[name]
        every, front = ColumnDataSource(dict(EMPTY)), ColumnDataSource(dict(EMPTY))
        r1 = fig.scatter("x", "y", source=every, marker=marker, color=colour, size=6,
                         alpha=0.25)
        r2 = fig.step("x", "y", source=front, color=colour, line_width=2, mode="after")
        r3 = fig.scatter("x", "y", source=front, marker=marker, color=colour, size=9,
                         line_color="black", line_width=0.5)
        items.append(LegendItem(label=name, renderers=[r1, r2, r3]))
        sources[name] = (every, front)
    fig.add_tools(HoverTool(tooltips=SPEED_HOVER))
    return fig, sources, items


def speed_accuracy_chart(data: SpeedAccuracyData, key: str | None = None,
                         peers_height: int = 620, checks_height: int = 360,
                         **kwargs) -> SpeedAccuracyChart:
    """The chart of `data`, showing view `key` (the first by default); `kwargs` go to
    both figures (width, sizing_mode, ...)."""
    peers, sources, items = _speed_figure("Compiled peers against the closed form", PEERS,
                                          data.floor, height=peers_height, **kwargs)
    star = ColumnDataSource(dict(EMPTY))
    cf = peers.scatter("x", "y", source=star, marker="star", size=24, color="black",
                       fill_color="white", line_width=2)
    peers.text("x", "y", text="run", source=star, x_offset=14, y_offset=-4,
               text_font_size="10pt", text_font_style="bold")
    items.insert(0, LegendItem(label="closed form (core.curve)", renderers=[cf]))
    peers.add_layout(Legend(items=items, click_policy="hide", label_text_font_size="9pt"),
                     "right")
    checks, check_sources, check_items = _speed_figure(
        "Check of eq 41: quadrature of core's T (needs the closed form; not a peer)",
        CHECKS, data.floor, height=checks_height, **kwargs)
    checks.add_layout(Legend(items=check_items, click_policy="hide",
                             label_text_font_size="9pt"), "right")
    chart = SpeedAccuracyChart(data, peers, checks, {**sources, **check_sources}, star)
    chart.show(key or data.keys[0])
    return chart
