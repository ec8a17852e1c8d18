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
  stability_map.html   Bokeh heat maps of log10(error), one per method

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
    "mdr": 200,
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


def heat_maps(rows: list[dict], psis, tau0s, path: Path) -> None:
    from bokeh.io import save
    from bokeh.layouts import column, gridplot
    from bokeh.models import (
        ColorBar,
        ColumnDataSource,
        Div,
        HoverTool,
        LinearColorMapper,
        TabPanel,
        Tabs,
    )
    from bokeh.palettes import Viridis256
    from bokeh.plotting import figure
    from bokeh.resources import INLINE

    xs = [f"{p:.3g}" for p in psis]
    ys = [f"{t:.4g}" for t in tau0s]
    mapper = LinearColorMapper(palette=Viridis256, low=-16, high=0, nan_color="red")

    def grid(field: str, label: str):
        figs = []
        for name in BUDGET:
            sel = [r for r in rows if r["method"] == name]
            err = np.array([r[field] for r in sel], dtype=float)
            src = ColumnDataSource(dict(
                x=[f"{r['psi']:.3g}" for r in sel], y=[f"{r['tau0']:.4g}" for r in sel],
                logerr=np.log10(np.maximum(err, FLOOR)), err=err,
            ))
            fig = figure(title=f"{name} (resolution {BUDGET[name]})", x_range=xs,
                         y_range=ys, width=470, height=330, x_axis_label="psi",
                         y_axis_label="tau0", toolbar_location=None)
            fig.rect("x", "y", width=1, height=1, source=src, line_color=None,
                     fill_color={"field": "logerr", "transform": mapper})
            fig.xaxis.major_label_orientation = 1.0
            fig.add_layout(ColorBar(color_mapper=mapper, width=8, title="log10"), "right")
            fig.add_tools(HoverTool(tooltips=[("psi", "@x"), ("tau0", "@y"),
                                              (label, "@err{0.0e}")]))
            figs.append(fig)
        return gridplot(figs, ncols=3)

    intro = Div(text=(
        "<p>Error of each method against the closed form of <code>core</code> over "
        "(psi, tau0), each method at a fixed resolution. Colour: log10 of the error "
        "(yellow = 1, dark = 1e-16). <b>textbook</b> is the closed form as printed "
        "(eq 11 with ellipk/ellipe, tau1 = pi - arcsin(...)).</p>"), width=1300)
    tabs = Tabs(tabs=[
        TabPanel(child=grid("err", "max(T error, impulse error)"), title="combined error"),
        TabPanel(child=grid("rel_err_impulse", "relative impulse error"),
                 title="relative impulse error"),
    ])
    save(column(intro, tabs), filename=str(path), resources=INLINE,
         title="Stability map of the numerical methods")


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
