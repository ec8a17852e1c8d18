"""Command line of the DEM bench (docs/dem_check.md):

    python -m core.dem_check cases                        # the documented cases
    python -m core.dem_check export DIR                   # test vectors + index.json
    python -m core.dem_check score FILE.csv --case NAME   # score a history (tau, T, P)
    python -m core.dem_check deck --case NAME --model M   # the LAMMPS input deck
    python -m core.dem_check lammps --case NAME --model M --steps N   # run lmp, score it
    python -m core.dem_check impact --test 4 --material alumina --model mindlin --json
                                                          # Chung & Ooi's impacts (docs/impact.md)

A bad argument or a malformed file exits with status 2 and one line naming the problem.
"""

from __future__ import annotations

import argparse
import json
import sys

from core.dem_check import impact_cli, lammps
from core.dem_check.case import CASES, Case, case_named
from core.dem_check.exact import dissipated_energy
from core.dem_check.score import DemScore, score
from core.dem_check.vectors import export, read_history


def format_score(s: DemScore) -> str:
    """The score as aligned lines."""
    return "\n".join([
        f"impulse ratio        {s.impulse_ratio:.7f}  (exact {s.exact_impulse_ratio:.7f}, "
        f"error {s.impulse_ratio_error:+.3e}, {100 * s.impulse_ratio_relative_error:+.3f} %)",
        f"worst |T - T_exact|  {s.max_T_error:.3e} T0 at tau = {s.worst_tau:.4f} "
        f"({s.worst_phase})",
        f"worst |P - P_exact|  {s.max_P_error:.3e} P0",
        f"dissipated energy    {s.dissipated_energy:.6e} T0 u0  (exact "
        f"{s.exact_dissipated_energy:.6e}, error {s.energy_error:+.3e})",
        f"energy gain          {s.energy_gain:.3e} T0 u0",
        f"Coulomb excess       {s.coulomb_excess:.3e} T0",
    ])


def _case(args: argparse.Namespace, header: dict[str, str] | None = None) -> Case:
    if args.case:
        return case_named(args.case)
    if header and header.get("name") in CASES:
        return CASES[header["name"]]
    if args.psi is not None and args.tau0 is not None:
        return Case(args.psi, args.tau0, args.mu, args.nu)
    raise ValueError("say which case: --case NAME (python -m core.dem_check cases) or "
                     "--psi and --tau0")


def _emit(args: argparse.Namespace, s: DemScore) -> None:
    print(json.dumps(s.as_dict(), indent=2) if args.json else format_score(s))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m core.dem_check",
                                     description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("cases", help="list the documented cases")
    p = sub.add_parser("export", help="write the exact test vectors into DIR")
    p.add_argument("directory")
    for name in ("score", "deck", "lammps"):
        p = sub.add_parser(name)
        if name == "score":
            p.add_argument("file", help="CSV with columns tau, T (T/T0), P (P/P0)")
        p.add_argument("--case", help="a case of `cases`")
        p.add_argument("--psi", type=float)
        p.add_argument("--tau0", type=float)
        p.add_argument("--mu", type=float, default=0.2)
        p.add_argument("--nu", type=float, default=0.3)
        if name != "score":
            p.add_argument("--model", default="mindlin", choices=list(lammps.MODELS))
            p.add_argument("--steps", type=int, default=20000)
        if name != "deck":
            p.add_argument("--json", action="store_true", help="the score as JSON")
    p = sub.add_parser("impact", help="an impact test of Chung & Ooi: exact and LAMMPS")
    impact_cli.add_arguments(p)
    args = parser.parse_args(argv)
    try:
        if args.command == "impact":
            return impact_cli.main(args)
        if args.command == "cases":
            for name, c in CASES.items():
                print(f"{name:15s} psi = {c.psi:<10.6g} tau0 = {c.tau0:<8.5g} impulse ratio "
                      f"{c.contact.impulse_ratio:.7f}  D = {dissipated_energy(c):.6e} T0 u0")
        elif args.command == "export":
            print(export(args.directory))
        elif args.command == "score":
            header, cols = read_history(args.file)
            _emit(args, score(_case(args, header), cols["tau"], cols["T"], cols["P"]))
        elif args.command == "deck":
            print(lammps.deck(_case(args), args.model, args.steps), end="")
        else:
            run = lammps.run(_case(args), args.model, args.steps)
            print(f"# LAMMPS {run.version}, {run.model}, {run.steps} steps, "
                  f"{run.seconds:.2f} s", file=sys.stderr)
            _emit(args, score(run.case, run.tau, run.T, run.P))
    except (ValueError, OSError, lammps.LammpsNotFound, lammps.LammpsFailed) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
