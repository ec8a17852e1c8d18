"""The ``impact`` subcommand of ``python -m core.dem_check`` (docs/impact.md):

    python -m core.dem_check impact --test 4 --material alumina --model mindlin --json
    python -m core.dem_check impact --test 5 --material steel --incidence 10 30 60

prints, over the incidences (5 to 85 deg by default), the exact reference and LAMMPS'
model: with ``--json`` one object {"incidence_deg": [...], "exact": {...}, "lammps":
{...}}, each of exact and lammps holding lists tangential_cor (centre of mass),
rebound_spin (rad/s, positive in the rolling sense), rebound_angle (deg, of the contact
point, Chung & Ooi's), contact_point_cor, normal_cor and contact_time (s), and "scores"
per quantity (worst and mean |lammps - exact| and where); ``--no-lammps`` leaves LAMMPS
out ("lammps": null). A bad argument exits with status 2 and one line.
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from core.dem_check import impact as bench
from core.dem_check.impact_cases import DEFAULT_INCIDENCE, TESTS, impact_test
from core.dem_check.lammps import MODELS, LammpsFailed, LammpsNotFound


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The subcommand's options."""
    p.add_argument("--test", type=int, default=4, help=f"one of {', '.join(map(str, TESTS))}")
    p.add_argument("--material", help="a material of the test (default: its first)")
    p.add_argument("--model", default="mindlin", help=f"LAMMPS model: {', '.join(MODELS)}")
    p.add_argument("--incidence", type=float, nargs="+", default=list(DEFAULT_INCIDENCE),
                   help="incidences (deg), default 5 to 85 by 5")
    p.add_argument("--steps", type=int, default=bench.DEFAULT_STEPS,
                   help="LAMMPS steps per Hertz contact time")
    p.add_argument("--springs", type=int, default=2000, help="springs of the reference")
    p.add_argument("--tol", type=float, default=1e-9, help="tolerance of the reference")
    p.add_argument("--no-lammps", action="store_true", help="the exact reference only")
    p.add_argument("--json", action="store_true", help="one JSON object")


def _table(inc: tuple[float, ...], ex: bench.Curves, lm: bench.Curves | None) -> str:
    lines = ["incidence  exact: e_t    spin (rad/s)  angle (deg)" +
             ("  | lammps: e_t    spin (rad/s)  angle (deg)" if lm else "")]
    for i, th in enumerate(inc):
        a = ex.rebounds[i]
        row = f"{th:8.3f}  {a.tangential_cor:10.6f}  {a.rebound_spin:12.5g}  " \
              f"{a.rebound_angle:11.5f}"
        if lm:
            b = lm.rebounds[i]
            row += f"  | {b.tangential_cor:10.6f}  {b.rebound_spin:12.5g}  " \
                   f"{b.rebound_angle:11.5f}"
        lines.append(row)
    return "\n".join(lines)


def _finite(v: object) -> object:
    """v with every non-finite float replaced by None (JSON has no nan)."""
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [_finite(x) for x in v]
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v


def main(args: argparse.Namespace) -> int:
    """Run the subcommand; 2 with one line on stderr for a bad argument or a failed run."""
    try:
        test = impact_test(args.test)
        material = args.material or test.materials[0]
        test.impact(material, 45.0)  # validates the material
        if args.model not in MODELS:
            raise ValueError(f"model must be one of {', '.join(MODELS)}, got {args.model!r}")
        inc = bench.check_incidences(args.incidence)
        ex = bench.exact_curves(args.test, material, inc, args.springs, args.tol)
        lm = None if args.no_lammps else bench.lammps_curves(args.test, material, args.model,
                                                             inc, args.steps)
    except (ValueError, OSError, LammpsNotFound, LammpsFailed, RuntimeError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if args.json:
        out: dict[str, object] = {
            "test": args.test, "material": material, "model": args.model,
            "incidence_deg": list(inc), "exact": ex.as_dict(),
            "lammps": lm.as_dict() if lm else None}
        if lm:
            out["scores"] = {q: bench.score_curve(q, inc, lm.get(q), ex.get(q)).as_dict()
                             for q in bench.QUANTITIES}
        print(json.dumps(_finite(out), indent=1, allow_nan=False))
    else:
        print(f"# test {args.test} ({test.title}), {material}"
              + (f", LAMMPS {args.model}" if lm else ""))
        print(_table(inc, ex, lm))
    return 0


__all__ = ["add_arguments", "main"]
