"""Chung & Ooi's impact tests: the exact reference (core.impact) against Debian's LAMMPS,
every tangential model, and against Kharaz et al.'s experiment; the time per impact of
each code (docs/impact.md).

    python -m benchmarks.core.impact            # tests 4-8, all models (~8 min)
    python -m benchmarks.core.impact --quick    # test 4 only (~3 min)
    python -m benchmarks.core.impact --write    # also benchmarks/results/impact.md, .csv

Prints the tables of docs/impact.md: per test, material and model, the worst and mean
|LAMMPS - exact| of each curve and the incidence of the worst; the published curves and
the experiment against the reference; per model the incidences where it departs from the
reference by more than the experiment's scatter; the time per impact.
"""

from __future__ import annotations

import argparse
import csv
import math
import statistics
from pathlib import Path

import numpy as np

from core.dem_check import impact as bench
from core.dem_check.impact_cases import DEFAULT_INCIDENCE, TESTS, impact_test
from core.dem_check.impact_data import published
from core.dem_check.lammps import MODELS, version

RESULTS = Path(__file__).resolve().parents[1] / "results"
CURVES = ("tangential_cor", "rebound_spin", "rebound_angle", "contact_point_cor")
UNITS = {"tangential_cor": "", "rebound_spin": " rad/s", "rebound_angle": " deg",
         "contact_point_cor": ""}


def fmt(v: float) -> str:
    return "-" if not math.isfinite(v) else f"{v:.3g}"


def score_rows(test: int, material: str, inc: tuple[float, ...], ex: bench.Curves,
               runs: dict[str, bench.Curves]) -> list[dict[str, object]]:
    rows = []
    for model, lm in runs.items():
        for q in CURVES:
            s = bench.score_curve(q, inc, lm.get(q), ex.get(q))
            rows.append({"test": test, "material": material, "model": model, "quantity": q,
                         "worst": s.worst, "at_deg": s.worst_incidence, "mean": s.mean,
                         "worst_relative": s.worst_relative})
    return rows


def scores_table(rows: list[dict[str, object]]) -> list[str]:
    out = ["| test | material | model | " + " | ".join(
        f"{q} worst (at deg) / mean" for q in CURVES) + " |",
        "|---|---|---|" + "---:|" * len(CURVES)]
    keys = sorted({(r["test"], r["material"], r["model"]) for r in rows},
                  key=lambda k: (k[0], k[1], list(MODELS).index(k[2])))
    for key in keys:
        cells = []
        for q in CURVES:
            r = next(x for x in rows if (x["test"], x["material"], x["model"]) == key
                     and x["quantity"] == q)
            cells.append("-" if not math.isfinite(r["worst"]) else
                         f"{fmt(r['worst'])} ({r['at_deg']:g}) / {fmt(r['mean'])}")
        out.append(f"| {key[0]} | {key[1]} | `{key[2]}` | " + " | ".join(cells) + " |")
    return out


def experiment_tables(ex_grid: bench.Curves, runs: dict[str, bench.Curves]
                      ) -> tuple[list[str], list[str]]:
    """Published curves and Kharaz's points against the reference (alumina, test 4), and
    per model the departure ranges beyond the experiment's scatter."""
    pub = ["| series | quantity | worst (at deg) | mean | points |", "|---|---|---:|---:|---:|"]
    scatter: dict[str, float] = {}
    for q in ("tangential_cor", "rebound_spin", "rebound_angle"):
        for series in ("alumina", "experiment"):
            inc, val = published(q, series)
            ref = bench.exact_curves(4, "alumina", inc).get(q)
            s = bench.score_curve(q, inc, val, ref)
            pub.append(f"| {series} | {q} | {fmt(s.worst)} ({s.worst_incidence:.1f}) | "
                       f"{fmt(s.mean)} | {inc.size} |")
            if series == "experiment":
                scatter[q] = float(np.sqrt(np.mean((val - ref) ** 2)))
    dep = ["| model | " + " | ".join(f"{q} (scatter {fmt(scatter[q])}{UNITS[q]})"
                                    for q in scatter) + " |",
           "|---|" + "---|" * len(scatter)]
    inc = ex_grid.incidence_deg
    for model, lm in runs.items():
        cells = []
        for q in scatter:
            ranges = bench.departure_range(inc, lm.get(q), ex_grid.get(q), scatter[q])
            cells.append(", ".join(f"{a:g}-{b:g}" if a != b else f"{a:g}" for a, b in ranges)
                         or "none")
        dep.append(f"| `{model}` | " + " | ".join(cells) + " |")
    return pub, dep


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="test 4 only")
    parser.add_argument("--write", action="store_true", help="write benchmarks/results/")
    parser.add_argument("--steps", type=int, default=bench.DEFAULT_STEPS)
    args = parser.parse_args()
    inc = DEFAULT_INCIDENCE
    tests = (4,) if args.quick else tuple(TESTS)
    rows: list[dict[str, object]] = []
    t_exact: list[float] = []
    t_lammps: list[float] = []
    alumina = None
    for test in tests:
        for material in impact_test(test).materials:
            ex = bench.exact_curves(test, material, inc)
            t_exact += [r.seconds for r in ex.rebounds]
            runs = {}
            for model in MODELS:
                runs[model] = bench.lammps_curves(test, material, model, inc, args.steps)
                t_lammps += [r.seconds for r in runs[model].rebounds]
            rows += score_rows(test, material, inc, ex, runs)
            if (test, material) == (4, "alumina"):
                alumina = (ex, runs)
            print(f"test {test} {material}: done", flush=True)
    lines = [f"LAMMPS {version()}, {args.steps} steps per Hertz contact time; reference: "
             "2000 springs, tol 1e-9", ""]
    lines += [*scores_table(rows), ""]
    if alumina is not None:
        pub, dep = experiment_tables(*alumina)
        lines += [*pub, "", *dep, ""]
    lines += [f"time per impact: reference median {statistics.median(t_exact):.3f} s "
              f"({min(t_exact):.3f}-{max(t_exact):.3f}), LAMMPS run (deck, lmp, parse) "
              f"median {statistics.median(t_lammps):.3f} s "
              f"({min(t_lammps):.3f}-{max(t_lammps):.3f}); {len(t_exact)} and "
              f"{len(t_lammps)} impacts in this run"]
    text = "\n".join(lines)
    print(text)
    if args.write:
        RESULTS.mkdir(exist_ok=True)
        (RESULTS / "impact.md").write_text(text + "\n")
        with (RESULTS / "impact.csv").open("w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
        print(f"wrote {RESULTS / 'impact.md'} and impact.csv")


if __name__ == "__main__":
    main()
