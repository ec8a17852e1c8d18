"""The charts of the numerical methods' benchmarks (speed_accuracy.csv, stability_map.csv).

The explorer reads the files from its package data, `app/results/` (`RESULTS`).
`benchmarks/core/methods.py` and `benchmarks/core/stability_map.py` write them to
`benchmarks/results/`; `python -m app.benchmark_charts benchmarks/results --publish`
(`make bench-charts`) renders their stand-alone HTML pages there and copies the two
files to `app/results/`.

Two charts, each built here once for both places it is shown: the explorer's Methods
card (selectors whose callbacks run on the server, only the chosen view sent) and the
stand-alone HTML pages (the same selectors run in the browser, every view in the page).

- **Speed against accuracy** (speed_accuracy.csv): time per contact (one call each from
  Python, the call included; docs/numerics.md has the times many contacts a call)
  against error, per view (all cases, one regime, or one case; relative or absolute
  error): every run of a method as a faint marker, its Pareto front as a line (no
  faster run of it is more accurate), the closed form as a labelled star at its
  measured error, a grey band for the float64 floor (the closed form's own worst error
  against 50-digit mpmath: below it errors are not resolved); quadrature of core's T, a
  check of eq 41 that needs the closed form, in a second plot. Okabe-Ito colours and
  one marker shape per method.
- **Stability map** (stability_map.csv): the error of one method at a fixed resolution
  over (psi, tau0), on a log colour scale over the whole range of the data (from 1e-16
  to the worst error, the printed closed form's included); psi on a log axis, tau0 in
  radians on an axis spaced by log(pi/2 - tau0 + `Y_SHIFT`), so that grazing contact
  (tau0 -> pi/2) stays visible beside preload (tau0 < 0).

Presentation only: every number is the benchmarks'.
"""

from __future__ import annotations

import argparse
import shutil
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np
from bokeh.models import (
    BoxAnnotation,
    ColorBar,
    ColumnDataSource,
    CustomJS,
    CustomJSTickFormatter,
    Div,
    FixedTicker,
    HoverTool,
    Label,
    Legend,
    LegendItem,
    LogColorMapper,
    LogTicker,
    Select,
)
from bokeh.palettes import Viridis256
from bokeh.plotting import figure

# ------------------------------------------------------------------ the result files

#: The results the explorer shows (speed_accuracy.csv, stability_map.csv): package
#: data of `app`.
RESULTS = resources.files("app") / "results"


def read_rows(path) -> list[dict]:
    """The rows of a results CSV file (a path or a `RESULTS` entry), each column as
    numpy reads it: whole numbers as int, other numbers as float, text as str."""
    with path.open(newline="") as fh:
        table = np.atleast_1d(np.genfromtxt(fh, delimiter=",", names=True, dtype=None,
                                            encoding="utf-8"))
    return [dict(zip(table.dtype.names, row, strict=True)) for row in table.tolist()]


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
#: Errors are drawn at FLOOR at least (a log axis has no 0).
FLOOR = 1e-17
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


# ------------------------------------------------------------------ stability map

#: The tau0 axis is logarithmic in pi/2 - tau0 + Y_SHIFT (rad).
Y_SHIFT = 0.02
Y_TICKS = [-1.4, -0.84, 0.0, 0.84, 1.12, 1.4, 1.5, 1.55, 1.565, 1.569]
#: The quantities a map shows: title -> column.
STABILITY_FIELDS = {"combined error: max(|T error| / T0, |impulse-ratio error|)": "err",
                    "relative impulse-ratio error": "rel_err_impulse"}


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges around increasing values: midpoints inside, half a step outside."""
    mids = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[values[0] - (mids[0] - values[0])], mids,
                           [values[-1] + (values[-1] - mids[-1])]])


@dataclass(frozen=True)
class StabilityData:
    """Per method, its resolution and its cells (left, right, top, bottom edges in
    plot coordinates, psi, tau0, and each quantity of `STABILITY_FIELDS`, at FLOOR at
    least); the plot's ranges; the colour scale's top (a power of ten at or above the
    worst error of any method, 1 at least)."""

    cells: dict[str, dict[str, list]]
    resolution: dict[str, int]
    x_range: tuple[float, float]
    y_range: tuple[float, float]
    high: float

    @property
    def methods(self) -> list[str]:
        return list(self.cells)


def stability_data(rows: list[dict]) -> StabilityData:
    """The cells of stability_map.csv's `rows` (methods in the file's order)."""
    psis = np.array(sorted({r["psi"] for r in rows}))
    tau0s = np.array(sorted({r["tau0"] for r in rows}))
    lx = _edges(np.log10(psis))
    gaps = np.pi / 2 + Y_SHIFT - tau0s  # decreasing as tau0 increases
    ly = _edges(np.log10(gaps[::-1]))[::-1]
    x_index = {float(p): i for i, p in enumerate(psis)}
    y_index = {float(t): i for i, t in enumerate(tau0s)}
    cells, resolution = {}, {}
    for name in dict.fromkeys(r["method"] for r in rows):
        sel = [r for r in rows if r["method"] == name]
        i = np.array([x_index[r["psi"]] for r in sel], dtype=int)
        j = np.array([y_index[r["tau0"]] for r in sel], dtype=int)
        cells[name] = {
            "left": (10.0 ** lx[i]).tolist(), "right": (10.0 ** lx[i + 1]).tolist(),
            "top": (10.0 ** ly[j]).tolist(), "bottom": (10.0 ** ly[j + 1]).tolist(),
            "psi": [r["psi"] for r in sel], "tau0": [r["tau0"] for r in sel],
            **{col: np.maximum([r[col] for r in sel], FLOOR).tolist()
               for col in STABILITY_FIELDS.values()}}
        resolution[name] = sel[0]["resolution"]
    worst = max(max(r[col] for col in STABILITY_FIELDS.values()) for r in rows)
    return StabilityData(cells, resolution, (10.0 ** lx[0], 10.0 ** lx[-1]),
                         (10.0 ** ly[0], 10.0 ** ly[-1]),
                         float(10.0 ** np.ceil(np.log10(max(worst, 1.0)))))


def error_mapper(data: StabilityData) -> LogColorMapper:
    """Viridis on a log scale from 1e-16 to the data's worst error."""
    return LogColorMapper(palette=Viridis256, low=1e-16, high=data.high,
                          low_color="#000004", nan_color="red")


def map_cells(data: StabilityData, method: str, field: str) -> dict[str, list]:
    """The columns of `method`'s map, the quantity `field` (a column) as `shown`."""
    cells = data.cells[method]
    return {**cells, "shown": cells[field]}


def map_title(data: StabilityData, method: str) -> str:
    return f"{method} (resolution {data.resolution[method]})"


def stability_figure(data: StabilityData, method: str, mapper: LogColorMapper,
                     field: str = "err", **kwargs) -> tuple[figure, ColumnDataSource]:
    """The map of one method (its quantity `field`) and its source; `kwargs` go to the
    figure."""
    source = ColumnDataSource(map_cells(data, method, field))
    fig = figure(title=map_title(data, method), x_axis_type="log", y_axis_type="log",
                 x_axis_label="ψ", y_axis_label="τ₀ (rad)", x_range=data.x_range,
                 y_range=data.y_range, **kwargs)
    fig.quad(left="left", right="right", top="top", bottom="bottom", source=source,
             line_color=None, fill_color={"field": "shown", "transform": mapper})
    fig.yaxis.ticker = FixedTicker(ticks=[float(np.pi / 2 + Y_SHIFT - t) for t in Y_TICKS])
    fig.yaxis.formatter = CustomJSTickFormatter(
        args=dict(shift=Y_SHIFT),
        code="const t = Math.PI / 2 + shift - tick; "
             "return t.toFixed(Math.abs(t) > 1.52 ? 3 : 2);")
    fig.add_tools(HoverTool(tooltips=[("ψ", "@psi{0.000}"), ("τ₀", "@tau0{0.0000} rad"),
                                      ("error", "@shown{0.0e}")]))
    return fig, source


def colour_bar(mapper: LogColorMapper) -> ColorBar:
    return ColorBar(color_mapper=mapper, ticker=LogTicker(desired_num_ticks=12), width=16,
                    title="error (log)")


STABILITY_NOTE = (
    "Error of each method against the closed form of <code>core</code> over (ψ, τ₀), "
    "each method at a fixed resolution. Colour: error on a log scale from 1e-16 (dark) "
    "to {high:.0e} (yellow), the whole range of the data. Rows are spaced by "
    f"log(π/2 − τ₀ + {Y_SHIFT:g}) so that grazing contact (τ₀ near π/2) stays visible "
    "next to preload (τ₀ &lt; 0); the axis reads τ₀ in radians. <b>textbook</b> is the "
    "closed form as printed (eq 11 with ellipk/ellipe, τ₁ = π − arcsin(...)).")


# ------------------------------------------------------------------ stand-alone pages


def speed_accuracy_page(rows: list[dict], path: Path) -> None:
    """The speed chart as a stand-alone page: every view in the page, its selector run
    in the browser."""
    from bokeh.io import save
    from bokeh.layouts import column
    from bokeh.resources import INLINE

    data = speed_accuracy_data(rows)
    shown = speed_accuracy_chart(data, width=1100)
    select = Select(title="View (time: median over the cases shown; error: worst)",
                    value=data.keys[0], options=data.keys, width=700)
    select.js_on_change("value", CustomJS(
        args=dict(views=data.views, stars=data.closed_form, star=shown.closed_form,
                  sources={k: list(v) for k, v in shown.sources.items()},
                  empty=EMPTY),
        code="""
const v = views[this.value];
for (const [name, [every, front]] of Object.entries(sources)) {
  every.data = v[name] ? v[name].all : empty;
  front.data = v[name] ? v[name].front : empty;
}
star.data = stars[this.value];
"""))
    intro = Div(width=1100, text=(
        "<p>One contact from (psi, tau0): T on the method's own times and the impulse ratio. "
        "Peers are numba kernels called from Python (compile time excluded); the closed "
        "form is <code>core.curve</code> (one compiled call: T and b on 200 points, impulse "
        "ratio). Same timing for all: the best of several windows of a few ms each "
        "(<code>benchmarks/core/methods.py</code>). "
        "Lines: each method's Pareto front (no faster run of it is more accurate); faint "
        "markers: every run. Errors against core (the closed form's own error against "
        "mpmath is the star). Click a legend entry to hide a method.</p>"))
    save(column(intro, select, shown.peers, shown.checks), filename=str(path),
         resources=INLINE, title="Speed against accuracy, like for like")


def stability_page(rows: list[dict], path: Path) -> None:
    """The maps, one per method, as a stand-alone page; the quantity's selector runs in
    the browser."""
    from bokeh.io import save
    from bokeh.layouts import column, gridplot
    from bokeh.resources import INLINE

    data = stability_data(rows)
    mapper = error_mapper(data)
    figs, sources = [], []
    for name in data.methods:
        fig, src = stability_figure(data, name, mapper, width=470, height=400,
                                    toolbar_location=None)
        figs.append(fig)
        sources.append(src)
    bar = figure(width=470, height=340, toolbar_location=None, min_border=0,
                 outline_line_color=None, title="colour scale")
    bar.add_layout(colour_bar(mapper), "left")
    bar.axis.visible = False
    bar.grid.visible = False
    figs.append(bar)
    select = Select(title="Quantity", value=next(iter(STABILITY_FIELDS)),
                    options=list(STABILITY_FIELDS), width=500)
    select.js_on_change("value", CustomJS(
        args=dict(sources=sources, fields=STABILITY_FIELDS), code="""
const col = fields[this.value];
for (const src of sources) {
  src.data = Object.assign({}, src.data, {shown: src.data[col]});
}
"""))
    intro = Div(text=f"<p>{STABILITY_NOTE.format(high=data.high)}</p>", width=1300)
    save(column(intro, select, gridplot(figs, ncols=3)), filename=str(path),
         resources=INLINE, title="Stability map of the numerical methods")


PAGES = {"speed_accuracy.csv": speed_accuracy_page, "stability_map.csv": stability_page}


def main(argv: list[str] | None = None) -> None:
    """`python -m app.benchmark_charts DIR [--publish]`: the HTML page of each results
    file in DIR, written beside it; with --publish the files are copied to `RESULTS`."""
    parser = argparse.ArgumentParser(description=main.__doc__)
    parser.add_argument("folder", type=Path, help="where the benchmarks wrote their CSV "
                        "files (benchmarks/results)")
    parser.add_argument("--publish", action="store_true",
                        help="copy the files to the app's package data (app/results/)")
    args = parser.parse_args(argv)
    for name, page in PAGES.items():
        path = args.folder / name
        page(read_rows(path), path.with_suffix(".html"))
        print(f"wrote {path.with_suffix('.html')}")
        if args.publish:
            with resources.as_file(RESULTS / name) as target:
                shutil.copyfile(path, target)
            print(f"copied {path} to {target}")


if __name__ == "__main__":
    main()
