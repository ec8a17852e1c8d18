"""LAMMPS' five tangential models on every documented case, run once and shipped as
package data (`app/dem/lammps/NAME.csv`), so that the card never runs LAMMPS.

Regenerate them with Debian's LAMMPS (`lmp`, `make lammps`; about a minute)::

    .venv/bin/python -m app.dem.overlays

Each case is run by `core.dem_check.lammps.run` at `STEPS` steps per contact for every
model of `core.dem_check.lammps.MODELS`, and every `STRIDE`-th step is kept (both ends
of the contact included). A file opens with a `# key: value` block (case, generator,
LAMMPS version, steps, stride, one line per column), then the columns `tau` and one per
model (T / T0 of the held sphere), tau with 17 significant digits (the run's floats
exactly), T with `DIGITS`; `core.dem_check`'s own reader reads it (`load`, once per
process).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass
from functools import cache
from importlib.resources import files
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from core.dem_check import CASES, lammps
from core.dem_check.vectors import read_history

STEPS = 4000
STRIDE = 10
DIGITS = 12
#: The overlays' directory (package data).
DIRECTORY = Path(str(files("app.dem").joinpath("lammps")))


@dataclass(frozen=True)
class Overlays:
    """One case's LAMMPS runs: the times kept and T / T0 of each model at them."""

    tau: NDArray[np.float64]
    T: dict[str, NDArray[np.float64]]  # model -> T / T0
    version: str  # LAMMPS' release
    steps: int  # steps per contact of the runs


def path(name: str) -> Path:
    """The overlay file of case `name`."""
    return DIRECTORY / f"{name}.csv"


def text(name: str, runs: dict[str, lammps.LammpsRun]) -> str:
    """The overlay file of case `name` from its runs (one per model, one step count)."""
    first = next(iter(runs.values()))
    keep = slice(None, None, STRIDE)
    head = {"name": name, "generator": "python -m app.dem.overlays",
            "lammps": first.version, "steps": first.steps, "stride": STRIDE,
            "column tau": "omega t (rad): every stride-th step of the run",
            **{f"column {m}": f"T / T0 of LAMMPS' tangential model {m}" for m in runs}}
    lines = [f"# {k}: {v}" for k, v in head.items()]
    lines.append(",".join(["tau", *runs]))
    table = np.column_stack([first.tau[keep], *(r.T[keep] for r in runs.values())])
    lines += [f"{row[0]:.17g}," + ",".join(f"{v:.{DIGITS}g}" for v in row[1:])
              for row in table]
    return "\n".join(lines) + "\n"


def generate(steps: int = STEPS, lmp: str | None = None) -> list[Path]:
    """Run every case with every model and write the overlay files."""
    DIRECTORY.mkdir(exist_ok=True)
    written = []
    for name, case in CASES.items():
        runs = {m: lammps.run(case, m, steps, lmp=lmp) for m in lammps.MODELS}
        path(name).write_text(text(name, runs))
        written.append(path(name))
    return written


@cache
def load(name: str) -> Overlays:
    """The overlays of case `name` (read once per process); ValueError for a name that
    is not a documented case."""
    if name not in CASES:
        raise ValueError(f"no case named {name!r}; the cases are: {', '.join(CASES)}")
    header, columns = read_history(path(name), required=("tau", *lammps.MODELS))
    return Overlays(tau=columns["tau"], T={m: columns[m] for m in lammps.MODELS},
                    version=header["lammps"], steps=int(header["steps"]))


def main() -> int:
    try:
        for p in generate():
            print(p)
    except (lammps.LammpsNotFound, lammps.LammpsFailed) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
