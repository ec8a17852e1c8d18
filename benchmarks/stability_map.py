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

from app.benchmark_charts import (  # noqa: E402
    STABILITY_FIELDS,
    STABILITY_NOTE,
    colour_bar,
    error_mapper,
    stability_data,
    stability_figure,
)
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


def heat_maps(rows: list[dict], path: Path) -> None:
    """The maps of ``app.benchmark_charts``, one per method, as a stand-alone page; the
    quantity's selector runs in the browser."""
    from bokeh.io import save
    from bokeh.layouts import column, gridplot
    from bokeh.models import CustomJS, Div, Select
    from bokeh.plotting import figure
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
    else:
        rows = run(psis, tau0s)
        write_csv(rows, out / "stability_map.csv", FIELDS)
    heat_maps(rows, out / "stability_map.html")
    for name in BUDGET:
        errs = np.array([r["err"] for r in rows if r["method"] == name])
        rel = np.array([r["rel_err_impulse"] for r in rows if r["method"] == name])
        print(f"{name:30s} median err {np.median(errs):.1e}  worst {np.max(errs):.1e}  "
              f"worst rel impulse err {np.max(rel):.1e}")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
