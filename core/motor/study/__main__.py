"""The design study's command line (docs/study.md).

    python -m core.motor.study run SPEC.toml [--scheduler ADDR] [--workers N] [--out DIR]
                                             [--set NAME=VALUE ...] [--at STORE:MERIT]
    python -m core.motor.study summary STORE [--pareto MERIT,MERIT] [--top N]
    python -m core.motor.study export STORE --csv [PATH]
    python -m core.motor.study compare STORE STORE

run: compute the study into NAME-KEY.zarr in --out (default: the spec's folder); an
interrupted run (Ctrl-C) resumes where it stopped. --scheduler (or DASK_SCHEDULER_ADDRESS)
uses an existing Dask cluster, else a LocalCluster of --workers processes. --set changes
a value of [design]; --at STORE:MERIT takes the swept values of STORE's best design for
MERIT (e.g. its x0 and preload) into [design]. summary: the best design per figure of
merit and the Pareto front of two. export: every design as CSV. compare: exit 0 if the
two stores hold the same values bit for bit.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

import numpy as np

from core.motor.designs import MERITS
from core.motor.study import store, summary
from core.motor.study.chunks import VARIABLES
from core.motor.study.run import run_study, scheduler_address
from core.motor.study.spec import MATERIAL_AXES, StudySpec, load_spec


def _value(text: str) -> object:
    try:
        return float(text)
    except ValueError:
        return text


def _with_design(spec: StudySpec, changes: dict[str, object]) -> StudySpec:
    fields = {f.name for f in dataclasses.fields(spec.base)}
    unknown = set(changes) - fields
    if unknown:
        raise ValueError(f"--set: unknown design value(s) {', '.join(sorted(unknown))}")
    return dataclasses.replace(spec, base=dataclasses.replace(spec.base, **changes))


def _at_best(spec: StudySpec, text: str) -> StudySpec:
    where, _, merit = text.rpartition(":")
    if not where or not merit:
        raise ValueError(f"--at {text!r}: expected STORE:MERIT")
    row = summary.best(store.open_study(where), merit)
    if row is None:
        raise ValueError(f"--at: {where} has no design with {merit}")
    other = store.spec_of(where)
    swept = {a.name for a in spec.axes}
    changes = {}
    for a in other.axes:
        if a.name not in swept:
            value = row[a.name]
            changes[a.name] = str(value) if a.name in MATERIAL_AXES else float(value)
    print(f"at the best {merit} of {where}: "
          + ", ".join(f"{k} = {v:.6g}" if isinstance(v, float) else f"{k} = {v}"
                      for k, v in changes.items()))
    return _with_design(spec, changes)


def cmd_run(args: argparse.Namespace) -> int:
    spec = load_spec(args.spec)
    if args.set:
        changes = {}
        for item in args.set:
            name, eq, value = item.partition("=")
            if not eq:
                raise ValueError(f"--set {item!r}: expected NAME=VALUE")
            changes[name.strip()] = _value(value.strip())
        spec = _with_design(spec, changes)
    if args.at:
        spec = _at_best(spec, args.at)
    folder = Path(args.out) if args.out else Path(args.spec).resolve().parent
    where = scheduler_address(args.scheduler) or f"a LocalCluster of {args.workers or 'all'} " \
                                                 "worker processes"
    print(f"study {spec.name}: {spec.size} designs over {' x '.join(map(str, spec.shape))} "
          f"({', '.join(a.name for a in spec.axes)}), chunks of {spec.chunk_shape}, on {where}")
    try:
        result = run_study(spec, folder, scheduler=args.scheduler, workers=args.workers,
                           progress=not args.quiet)
    except KeyboardInterrupt:
        print(f"\ninterrupted: the finished chunks are in {spec.store_path(folder)}; run the "
              "same command again to resume", file=sys.stderr)
        return 130
    rate = result.designs / result.seconds if result.seconds else float("nan")
    print(f"{result.path}: {result.computed} chunks computed, {result.reused} reused, of "
          f"{result.chunks}; {result.designs} designs in {result.seconds:.1f} s "
          f"({rate:.1f} designs/s)")
    return 0


def _row_text(row, names: list[str]) -> str:
    parts = []
    for n in names:
        v = row[n]
        parts.append(f"{n} = {v}" if isinstance(v, str) else f"{n} = {float(v):.6g}")
    return ", ".join(parts)


def cmd_summary(args: argparse.Namespace) -> int:
    ds = store.open_study(args.store)
    axes = list(ds.sizes)
    units = {n: ds[n].attrs.get("units", "") for n in list(VARIABLES) + axes}
    print(f"{args.store}: {ds.attrs['finished']} of {ds.attrs['chunks']} chunks finished, "
          f"{int(np.prod(list(ds.sizes.values())))} designs over {', '.join(axes)}")
    print("\nbest design per figure of merit:")
    for merit in MERITS:
        row = summary.best(ds, merit)
        if row is None:
            print(f"  {merit}: none")
            continue
        unit = "" if units[merit] == "1" else f" {units[merit]}"
        print(f"  {merit} = {float(row[merit]):.6g}{unit} at {_row_text(row, axes)}")
    first, _, second = args.pareto.partition(",")
    front = summary.pareto(ds, first.strip(), second.strip())
    print(f"\nPareto front of {first} ({units[first]}) and {second} ({units[second]}): "
          f"{len(front)} designs" + (f", the first {args.top}" if len(front) > args.top else ""))
    for _, row in front.head(args.top).iterrows():
        print(f"  {first} = {float(row[first]):.6g}, {second} = {float(row[second]):.6g} at "
              f"{_row_text(row, axes)}")
    return 0


def cmd_export(args: argparse.Namespace) -> int:
    ds = store.open_study(args.store)
    target = args.csv or str(Path(args.store).with_suffix(".csv"))
    path = summary.export_csv(ds, target)
    print(f"{path}: {int(np.prod(list(ds.sizes.values())))} designs")
    return 0


def cmd_compare(args: argparse.Namespace) -> int:
    a, b = store.open_study(args.first), store.open_study(args.second)
    differ = [n for n in list(VARIABLES) + list(a.sizes)
              if n not in b or a[n].values.tobytes() != b[n].values.tobytes()]
    if differ:
        print(f"the stores differ in {', '.join(differ)}")
        return 1
    print(f"the stores hold the same values bit for bit ({len(VARIABLES)} variables, "
          f"{int(np.prod(list(a.sizes.values())))} designs)")
    return 0


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m core.motor.study",
                                     description="Design studies of the motor on Dask.")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("run", help="compute a study (resumes an interrupted one)")
    p.add_argument("spec", help="the study's TOML spec")
    p.add_argument("--scheduler", help="an existing Dask scheduler, tcp://HOST:8786 "
                   "(default DASK_SCHEDULER_ADDRESS, else a LocalCluster)")
    p.add_argument("--workers", type=int, help="LocalCluster worker processes (default: "
                   "one per CPU)")
    p.add_argument("--out", help="folder of the store (default: the spec's)")
    p.add_argument("--set", action="append", metavar="NAME=VALUE",
                   help="change a value of the spec's [design]")
    p.add_argument("--at", metavar="STORE:MERIT", help="take STORE's best design for MERIT "
                   "into [design]")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_run)
    p = sub.add_parser("summary", help="best designs and a Pareto front")
    p.add_argument("store")
    p.add_argument("--pareto", default="stall_thrust,no_load_speed", metavar="A,B",
                   help="two figures of merit (default stall_thrust,no_load_speed)")
    p.add_argument("--top", type=int, default=20, help="front rows shown (default 20)")
    p.set_defaults(func=cmd_summary)
    p = sub.add_parser("export", help="every design as CSV")
    p.add_argument("store")
    p.add_argument("--csv", nargs="?", const="", required=True, metavar="PATH",
                   help="the CSV file (default: STORE with .csv)")
    p.set_defaults(func=cmd_export)
    p = sub.add_parser("compare", help="are two stores equal bit for bit?")
    p.add_argument("first")
    p.add_argument("second")
    p.set_defaults(func=cmd_compare)
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
