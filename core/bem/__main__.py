"""Command line of the boundary-element referee: one JSON object per run.

    python -m core.bem cattaneo --nu NU --load Q --grid N [--mu MU] [--steps K] --json
    python -m core.bem spence --beta B --mu MU --grid N [--nu NU] [--stages K] --json
    python -m core.bem paper --psi PSI --tau0 TAU0 --nu NU [--beta B] [--mu MU] --grid N
                             [--steps K] --json
    python -m core.bem map [--grids N1 N2] [--steps K] [--csv PATH]

``--grid`` counts elements across the largest contact diameter. Bad arguments: a message
naming the argument on stderr and exit status 2.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time


def _finite(x: float) -> float | None:
    """x, or None (JSON null) when it is nan."""
    return None if isinstance(x, float) and math.isnan(x) else x


def _cattaneo(a: argparse.Namespace) -> dict:
    from core.bem.cases import cattaneo

    r = cattaneo(a.nu, a.load, a.grid, mu=a.mu, steps=a.steps)
    return {"shift_ratio": r.shift_ratio, "stick_radius": r.stick_radius,
            "transverse_fraction": r.transverse_fraction,
            "elements_across": r.elements_across, "seconds": r.seconds}


def _spence(a: argparse.Namespace) -> dict:
    from core.bem.cases import spence

    r = spence(a.beta, a.mu, a.grid, nu=a.nu, stages=a.stages)
    return {"stick_radius": r.stick_radius, "elements_across": r.elements_across,
            "stages": r.stages, "seconds": r.seconds}


def _paper(a: argparse.Namespace) -> dict:
    from core.bem.paper import run_paper

    r = run_paper(a.psi, a.tau0, a.nu, beta=a.beta, mu=a.mu, grid=a.grid, steps=a.steps)
    return {"worst_T_error": r.worst_T_error, "impulse_ratio": r.impulse_ratio,
            "impulse_ratio_closed": r.impulse_ratio_closed,
            "dissipation_ratio": _finite(r.dissipation_ratio),
            "dissipation": r.dissipation, "dissipation_closed": r.closed.dissipated_energy,
            "worst_stick_error": r.worst_stick_error,
            "elements_across": r.grid.elements_across, "steps": len(r.tau) - 1,
            "seconds": r.seconds, "cpu_seconds": r.cpu_seconds}


def _map(a: argparse.Namespace) -> dict:
    from core.bem.error_map import beta_threshold, error_map, write_csv

    t0 = time.perf_counter()
    rows = error_map(grids=tuple(a.grids), steps=a.steps, psi=a.psi, tau0=a.tau0, mu=a.mu,
                     progress=sys.stderr)
    if a.csv:
        write_csv(rows, a.csv)
    threshold = beta_threshold(rows)
    return {"rows": [r.as_dict() for r in rows],
            "beta_at_1pct_T0": None if math.isinf(threshold) else threshold,
            "seconds": time.perf_counter() - t0}


def parser() -> argparse.ArgumentParser:
    """The argument parser (argparse exits with status 2 on a malformed command line)."""
    ap = argparse.ArgumentParser(prog="python -m core.bem", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="case", required=True)
    c = sub.add_parser("cattaneo", help="Cattaneo-Mindlin shift of a Hertz contact")
    c.add_argument("--nu", type=float, required=True)
    c.add_argument("--load", type=float, required=True, help="Q / (mu P), in [0, 1)")
    c.add_argument("--mu", type=float, default=0.4)
    c.add_argument("--steps", type=int, default=1)
    s = sub.add_parser("spence", help="Spence's compression of dissimilar bodies")
    s.add_argument("--beta", type=float, required=True)
    s.add_argument("--mu", type=float, required=True)
    s.add_argument("--nu", type=float, default=None)
    s.add_argument("--stages", type=int, default=None)
    p = sub.add_parser("paper", help="the paper's intermittent loading")
    p.add_argument("--psi", type=float, required=True)
    p.add_argument("--tau0", type=float, required=True)
    p.add_argument("--nu", type=float, required=True)
    p.add_argument("--beta", type=float, default=0.0)
    p.add_argument("--mu", type=float, default=0.2)
    p.add_argument("--steps", type=int, default=200)
    m = sub.add_parser("map", help="the closed form's error over nu and beta")
    m.add_argument("--grids", type=int, nargs=2, default=[32, 64])
    m.add_argument("--steps", type=int, default=200)
    m.add_argument("--psi", type=float, default=2.414213562373095)
    m.add_argument("--tau0", type=float, default=math.pi / 6)
    m.add_argument("--mu", type=float, default=0.2)
    m.add_argument("--csv", default=None)
    for sp in (c, s, p):
        sp.add_argument("--grid", type=int, required=True,
                        help="elements across the largest contact diameter")
    for sp in (c, s, p, m):
        sp.add_argument("--json", action="store_true", help="print one JSON object")
    return ap


def main(argv: list[str] | None = None) -> int:
    """Run one case; print its JSON object. Returns the exit status."""
    ap = parser()
    a = ap.parse_args(argv)
    run = {"cattaneo": _cattaneo, "spence": _spence, "paper": _paper, "map": _map}[a.case]
    try:
        out = run(a)
    except ValueError as err:
        print(f"python -m core.bem {a.case}: error: {err}", file=sys.stderr)
        return 2
    print(json.dumps(out) if a.json else json.dumps(out, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
