"""Stability map: error of every method over a (psi, tau0) grid at a fixed budget.

Shows where each method breaks down: psi near 1 (the switch between full stick and
partial stick), huge psi (partial stick lasting ~psi^-1/2), grazing contact
(tau0 -> pi/2) and preload (tau0 < 0). The printed closed form (``textbook``: eq 11 with
ellipk/ellipe, tau1 = pi - arcsin(...), sin tau - s0 formed directly) is included as a
method, to show where the formulas as written lose their digits. Reference: core.

Error per cell: max(max |T - T_closed| / T0, |impulse-ratio error|), and the relative
impulse-ratio error separately (the absolute one hides grazing contact, where T ~ 0).

Outputs (benchmarks/results/, or results/quick/ with --quick):
  stability_map.csv    one row per method and cell
  stability_map.html   Bokeh heat maps of the error, one per method, with a selector

Usage: .venv/bin/python benchmarks/stability_map.py [--quick]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "benchmarks"))

import numpy as np  # noqa: E402
from results_csv import read_csv, write_csv  # noqa: E402
from tqdm import tqdm  # noqa: E402

from core import Contact  # noqa: E402
from core.numerics import METHODS, solve  # noqa: E402
from core.numerics.metrics import errors  # noqa: E402

BUDGET: dict[str, int] = {
    "textbook": 200,
    "mdr": 200,  # springs; default time steps (100)
    "annulus": 16,
    **{name: 2000 for name in METHODS
       if name.startswith(("lammps", "liggghts", "direnzo"))},
    "quad": 50,
    "gauss_legendre": 64,
}
PSIS = np.logspace(-1.0, 4.0, 21)
TAU0S = np.concatenate([np.linspace(-1.4, 1.4, 11), [1.5, 1.55, 1.565, 1.569]])
FIELDS = ["method", "resolution", "psi", "tau0", "err", "err_T", "err_impulse",
          "rel_err_impulse", "wall_time"]
FLOOR = 1e-17
Y_SHIFT = 0.02
"""The tau0 axis is logarithmic in pi/2 - tau0 + Y_SHIFT (rad)."""
Y_TICKS = [-1.4, -0.84, 0.0, 0.84, 1.12, 1.4, 1.5, 1.55, 1.565, 1.569]


def run(psis: np.ndarray, tau0s: np.ndarray) -> list[dict]:
    rows = []
    cells = [(p, t) for t in tau0s for p in psis]
    for psi, tau0 in tqdm(cells, desc="(psi, tau0) cells", unit="cell"):
        c = Contact(float(psi), float(tau0))
        for name, resolution in BUDGET.items():
            res = solve(name, c, resolution)
            e = errors(res, c)
            rows.append(dict(method=name, resolution=resolution, psi=float(psi),
                             tau0=float(tau0), err=e.combined, err_T=e.T,
                             err_impulse=e.impulse,
                             rel_err_impulse=e.impulse / abs(c.impulse_ratio),
                             wall_time=res.wall_time))
    return rows


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges around increasing values: midpoints inside, half a step outside."""
    mids = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[values[0] - (mids[0] - values[0])], mids,
                           [values[-1] + (values[-1] - mids[-1])]])


def heat_maps(rows: list[dict], psis, tau0s, path: Path) -> None:
    from bokeh.io import save
    from bokeh.layouts import column, gridplot
    from bokeh.models import (
        ColorBar,
        ColumnDataSource,
        CustomJS,
        CustomJSTickFormatter,
        Div,
        FixedTicker,
        HoverTool,
        LogColorMapper,
        LogTicker,
        Select,
    )
    from bokeh.palettes import Viridis256
    from bokeh.plotting import figure
    from bokeh.resources import INLINE

    psis = np.asarray(sorted(psis), dtype=float)
    tau0s = np.asarray(sorted(tau0s), dtype=float)
    # psi on a log axis; tau0 on an axis spaced by log(pi/2 - tau0 + Y_SHIFT) (so that
    # grazing contact, tau0 -> pi/2, stays visible next to preload), labelled in tau0
    lx = _edges(np.log10(psis))
    gaps = np.pi / 2 + Y_SHIFT - tau0s  # decreasing as tau0 increases
    ly = _edges(np.log10(gaps[::-1]))[::-1]
    x_index = {float(p): i for i, p in enumerate(psis)}
    y_index = {float(t): i for i, t in enumerate(tau0s)}
    worst = max(max(r["err"], r["rel_err_impulse"]) for r in rows)
    high = 10.0 ** np.ceil(np.log10(max(worst, 1.0)))
    mapper = LogColorMapper(palette=Viridis256, low=1e-16, high=high, low_color="#000004",
                            nan_color="red")
    fields = {"combined error: max(|T error| / T0, |impulse-ratio error|)": "err",
              "relative impulse-ratio error": "rel_err_impulse"}
    first = next(iter(fields.values()))
    figs, sources = [], []
    for name in BUDGET:
        sel = [r for r in rows if r["method"] == name]
        i = np.array([x_index[r["psi"]] for r in sel], dtype=int)
        j = np.array([y_index[r["tau0"]] for r in sel], dtype=int)
        data = dict(
            left=10.0 ** lx[i], right=10.0 ** lx[i + 1],
            top=10.0 ** ly[j], bottom=10.0 ** ly[j + 1],
            psi=[r["psi"] for r in sel], tau0=[r["tau0"] for r in sel],
            **{col: np.maximum([r[col] for r in sel], FLOOR) for col in fields.values()})
        data["shown"] = data[first]
        src = ColumnDataSource(data)
        sources.append(src)
        fig = figure(title=f"{name} (resolution {BUDGET[name]})", x_axis_type="log",
                     y_axis_type="log", width=470, height=400, x_axis_label="psi",
                     y_axis_label="tau0 (rad)", toolbar_location=None,
                     x_range=(10.0 ** lx[0], 10.0 ** lx[-1]),
                     y_range=(10.0 ** ly[0], 10.0 ** ly[-1]))
        fig.quad(left="left", right="right", top="top", bottom="bottom", source=src,
                 line_color=None, fill_color={"field": "shown", "transform": mapper})
        fig.yaxis.ticker = FixedTicker(ticks=[float(np.pi / 2 + Y_SHIFT - t)
                                              for t in Y_TICKS])
        fig.yaxis.formatter = CustomJSTickFormatter(
            args=dict(shift=Y_SHIFT),
            code="const t = Math.PI / 2 + shift - tick; "
                 "return t.toFixed(Math.abs(t) > 1.52 ? 3 : 2);")
        fig.add_tools(HoverTool(tooltips=[("psi", "@psi{0.000}"), ("tau0", "@tau0{0.0000} rad"),
                                          ("error", "@shown{0.0e}")]))
        figs.append(fig)
    bar = figure(width=470, height=340, toolbar_location=None, min_border=0,
                 outline_line_color=None, title="colour scale")
    bar.add_layout(ColorBar(color_mapper=mapper, ticker=LogTicker(desired_num_ticks=12),
                            width=20, title="error (log)"), "left")
    bar.axis.visible = False
    bar.grid.visible = False
    figs.append(bar)
    select = Select(title="Quantity", value=next(iter(fields)), options=list(fields),
                    width=500)
    select.js_on_change("value", CustomJS(args=dict(sources=sources, fields=fields), code="""
const col = fields[this.value];
for (const src of sources) {
  src.data = Object.assign({}, src.data, {shown: src.data[col]});
}
"""))
    intro = Div(text=(
        "<p>Error of each method against the closed form of <code>core</code> over "
        "(psi, tau0), each method at a fixed resolution. Colour: error on a log scale "
        f"from 1e-16 (dark) to {high:.0e} (yellow), the whole range of the data. Rows "
        f"are spaced by log(pi/2 - tau0 + {Y_SHIFT:g}) so that grazing contact (tau0 near "
        "pi/2) stays visible next to preload (tau0 < 0); the axis reads tau0 in radians. "
        "<b>textbook</b> is the closed form as "
        "printed (eq 11 with ellipk/ellipe, tau1 = pi - arcsin(...)).</p>"), width=1300)
    save(column(intro, select, gridplot(figs, ncols=3)), filename=str(path),
         resources=INLINE, title="Stability map of the numerical methods")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="6 x 5 grid, output in results/quick/")
    parser.add_argument("--replot", action="store_true",
                        help="rebuild the heat maps from the existing CSV")
    args = parser.parse_args(argv)
    out = ROOT / "benchmarks" / "results"
    psis, tau0s = PSIS, TAU0S
    if args.quick:
        out = out / "quick"
        psis = np.array([0.3, 1.0, 1.01, 30.0, 1e3, 1e4])
        tau0s = np.array([-1.4, 0.0, 1.5, 1.565, 1.569])
    out.mkdir(parents=True, exist_ok=True)
    if args.replot:
        rows = read_csv(out / "stability_map.csv")
        psis = np.array(sorted({r["psi"] for r in rows}))
        tau0s = np.array(sorted({r["tau0"] for r in rows}))
    else:
        rows = run(psis, tau0s)
        write_csv(rows, out / "stability_map.csv", FIELDS)
    heat_maps(rows, psis, tau0s, out / "stability_map.html")
    for name in BUDGET:
        errs = np.array([r["err"] for r in rows if r["method"] == name])
        rel = np.array([r["rel_err_impulse"] for r in rows if r["method"] == name])
        print(f"{name:30s} median err {np.median(errs):.1e}  worst {np.max(errs):.1e}  "
              f"worst rel impulse err {np.max(rel):.1e}")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
