"""Cost of the boundary-element referee (``core.bem``): CPU time per time step of the
paper's loading for grids of 16 to 256 elements across the largest contact diameter,
fitted against N log N (N the number of elements of the grid), the memory it holds, and
the full contact at 64 elements across and 200 steps (the target: at most 20 s on one
core).

CPU time (``time.process_time``) is measured rather than wall time: the machine is shared,
and one process uses one core. Per-step times come from a march of ``--steps`` steps over
the whole contact (psi = 1 + sqrt 2, tau0 = pi / 6, nu = 0.3, beta = 0), so they average
the cheap full-slip steps and the dearer partial-stick ones.

Run: ``.venv/bin/python -m benchmarks.core.bem [--grids 16 32 64 128 256] [--steps 20]
[--full] [--write]`` (``--write``: benchmarks/results/bem_speed.json and .md).
"""

from __future__ import annotations

import argparse
import json
import math
import resource
from pathlib import Path

import numpy as np

from core.bem.grid import Grid
from core.bem.paper import run_paper

RESULTS = Path(__file__).resolve().parents[1] / "results"
PSI, TAU0, NU = 1 + math.sqrt(2), math.pi / 6, 0.3


def held_bytes(across: int) -> int:
    """Bytes of the arrays one march holds: six kernel spectra (complex, the padded rfft
    size) and about twenty M x M fields (state, slips, work arrays)."""
    import scipy.fft as sfft

    m = Grid(across).size
    length = sfft.next_fast_len(2 * m - 1, real=True)
    return 6 * 16 * length * (length // 2 + 1) + 20 * 8 * m * m


def per_step(across: int, steps: int) -> dict:
    """One contact of ``steps`` steps on the grid: CPU seconds per step and the grid."""
    r = run_paper(PSI, TAU0, NU, grid=across, steps=steps)
    m = r.grid.size
    return {"across": across, "M": m, "N": m * m, "steps": steps,
            "cpu_per_step": r.cpu_seconds / steps, "wall_per_step": r.seconds / steps,
            "held_MB": held_bytes(across) / 1e6,
            "peak_rss_MB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e3}


def fit(rows: list[dict]) -> dict:
    """c of t = c N log N (least squares in log space over the rows) and the exponent of
    a free power law t ~ N^k."""
    n = np.array([r["N"] for r in rows], float)
    t = np.array([r["cpu_per_step"] for r in rows])
    c = float(np.exp(np.mean(np.log(t / (n * np.log(n))))))
    k = float(np.polyfit(np.log(n), np.log(t), 1)[0])
    spread = float(np.max(np.abs(np.log(t / (c * n * np.log(n))))))
    return {"c_NlogN": c, "power_law_exponent": k, "worst_log_misfit": spread}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grids", type=int, nargs="+", default=[16, 32, 64, 128, 256])
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--full", action="store_true",
                    help="also the full contact at 64 across and 200 steps")
    ap.add_argument("--write", action="store_true")
    a = ap.parse_args()
    rows = []
    for n in a.grids:
        rows.append(per_step(n, a.steps))
        r = rows[-1]
        print(f"{n:4d} across (M = {r['M']}, N = {r['N']}): {r['cpu_per_step'] * 1e3:8.1f} ms"
              f" CPU per step, {r['held_MB']:.1f} MB held, peak RSS {r['peak_rss_MB']:.0f} MB",
              flush=True)
    out = {"rows": rows, "fit": fit(rows) if len(rows) > 1 else None}
    if out["fit"]:
        f = out["fit"]
        print(f"t = {f['c_NlogN']:.3g} N log N s per step (worst misfit "
              f"{math.exp(f['worst_log_misfit']):.2f}x); free power law N^"
              f"{f['power_law_exponent']:.2f}")
    if a.full:
        r = run_paper(PSI, TAU0, NU, grid=64, steps=200)
        out["full_64_200"] = {"cpu_seconds": r.cpu_seconds, "wall_seconds": r.seconds,
                              "worst_T_error": r.worst_T_error}
        print(f"full contact, 64 across, 200 steps: {r.cpu_seconds:.1f} s CPU "
              f"({r.seconds:.1f} s wall)")
    if a.write:
        (RESULTS / "bem_speed.json").write_text(json.dumps(out, indent=2) + "\n")
        lines = ["| across | M | N | CPU ms / step | held MB |", "|---|---|---|---|---|"]
        lines += [f"| {r['across']} | {r['M']} | {r['N']} | {r['cpu_per_step'] * 1e3:.1f} |"
                  f" {r['held_MB']:.1f} |" for r in rows]
        if out["fit"]:
            lines.append("")
            lines.append(f"Fit: t = {out['fit']['c_NlogN']:.3g} N log N s per step; free "
                         f"power law N^{out['fit']['power_law_exponent']:.2f}.")
        if "full_64_200" in out:
            lines.append(f"Full contact at 64 across, 200 steps: "
                         f"{out['full_64_200']['cpu_seconds']:.1f} s CPU.")
        (RESULTS / "bem_speed.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
