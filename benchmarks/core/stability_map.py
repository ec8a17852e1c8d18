"""Stability map: error of every method over a (psi, tau0) grid at a fixed budget.

Shows where each method breaks down: psi near 1 (the switch between full stick and
partial stick), huge psi (partial stick lasting ~psi^-1/2), grazing contact
(tau0 -> pi/2) and preload (tau0 < 0). The printed closed form (``textbook``: eq 11 with
ellipk/ellipe, tau1 = pi - arcsin(...), sin tau - s0 formed directly) is included as a
method, to show where the formulas as written lose their digits. Reference: core.

Error per cell: max(max |T - T_closed| / T0, |impulse-ratio error|), and the relative
impulse-ratio error separately (the absolute one hides grazing contact, where T ~ 0).

Output (benchmarks/results/, or results/quick/ with --quick), data only:
  stability_map.csv    one row per method and cell; its heat maps (stability_map.html,
                       one per method, with a selector) are the app's: ``make bench-charts``

Usage: .venv/bin/python -m benchmarks.core.stability_map [--quick]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from tqdm import tqdm

from benchmarks.core.results_csv import write_csv
from core import Contact
from core.numerics import METHODS, solve
from core.numerics.metrics import errors

ROOT = Path(__file__).resolve().parents[2]

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


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true",
                        help="6 x 5 grid, output in results/quick/")
    args = parser.parse_args(argv)
    out = ROOT / "benchmarks" / "results"
    psis, tau0s = PSIS, TAU0S
    if args.quick:
        out = out / "quick"
        psis = np.array([0.3, 1.0, 1.01, 30.0, 1e3, 1e4])
        tau0s = np.array([-1.4, 0.0, 1.5, 1.565, 1.569])
    out.mkdir(parents=True, exist_ok=True)
    rows = run(psis, tau0s)
    write_csv(rows, out / "stability_map.csv", FIELDS)
    for name in BUDGET:
        errs = np.array([r["err"] for r in rows if r["method"] == name])
        rel = np.array([r["rel_err_impulse"] for r in rows if r["method"] == name])
        print(f"{name:30s} median err {np.median(errs):.1e}  worst {np.max(errs):.1e}  "
              f"worst rel impulse err {np.max(rel):.1e}")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
