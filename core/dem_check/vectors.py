"""Exact test vectors as self-describing files, and the reader of a DEM code's history.

``export(directory)`` writes, for every case of ``CASES``:

* ``NAME.csv``: the exact contact, dimensionless, on about ``POINTS`` times holding tau0,
  pi/2, tau1 and pi - tau0 (columns ``COLUMNS``);
* ``NAME.lj.csv``: the same contact as the LAMMPS deck runs it (``core/dem_check/deck.in``,
  lj units, ``LJ_STEPS`` steps): step, time, the driven centre's position and velocity, and
  the exact force on the held sphere (columns ``LJ_COLUMNS``);

and ``index.json`` (schema ``SCHEMA``, version ``SCHEMA_VERSION``) listing the cases, their
parameters, exact scalars, units and files. Every CSV starts with a block of ``# key: value``
lines (schema, case, units, one line per column), then one header row, then the numbers
(17 significant digits: the float64 values exactly).

``read_history(path)`` reads a CSV of that form (the header block optional) and returns its
columns, ``parse_history(text)`` the same from text in memory (an upload); malformed files
raise ValueError naming the file, row and column.
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Iterable
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from core.dem_check.case import CASES, NOTES, Case
from core.dem_check.exact import Reference, exact
from core.dem_check.score import MAX_SAMPLES

SCHEMA = "zharii-dem-vectors"
SCHEMA_VERSION = 1
POINTS = 2000
LJ_STEPS = 4000
MAX_BYTES = 512 * 2**20

COLUMNS: dict[str, str] = {
    "tau": "omega t (rad); contact from tau0 to pi - tau0 (eq 4)",
    "drive": "u_x0 / u0 = sin tau: tangential position of the driven centre (eq 3)",
    "approach": "alpha / H = sin tau - sin tau0: approach of the centres (eq 8)",
    "T": "T / T0: tangential force on the held sphere, along the drive (eqs 38, 39)",
    "P": "P / P0: normal force, P0 = T0 / mu (eq 9)",
    "phase": "0 none, 1 full stick, 2 slip, 3 partial stick, 4 counter-slip",
    "work": "W / (T0 u0): work of the drive since tau0, integral of T d(sin tau)",
}
LJ_COLUMNS: dict[str, str] = {
    "step": "time step k; tau = tau0 + k dt",
    "time": "k dt (lj time, omega = 1)",
    "x": "x of the driven (lower) centre; the held centre is at (0, 0, 2)",
    "z": "z of the driven centre: the centre distance is 2 - alpha exactly",
    "vx": "(x(t) - x(t - dt)) / dt, the velocity the deck gives LAMMPS",
    "vz": "(z(t) - z(t - dt)) / dt",
    "fx": "exact tangential force on the held sphere, mu T / T0 (T0 = mu)",
    "fz": "exact normal force on the held sphere, P / P0 (P0 = 1)",
}


def lj_scales(case: Case, steps: int = LJ_STEPS) -> dict[str, float]:
    """The deck's lj values for ``case``: R = 1, H = 1e-7, omega = 1, G and E making
    P0 = 1 (eq 9), u0 (eq 23), the Mindlin stiffness 8 G_eff a* of linear_history, dt."""
    R, H = 1.0, 1e-7
    G = 3.0 * (1.0 - case.nu) / (2.0 * math.sqrt(2.0 * R) * H**1.5)
    a_star = math.sqrt(0.5 * R * H * (1.0 - math.sin(case.tau0)))
    return {"R": R, "H": H, "omega": 1.0, "G": G, "E": 2.0 * G * (1.0 + case.nu),
            "nu": case.nu, "mu": case.mu, "u0": case.drive_ratio * H, "P0": 1.0,
            "T0": case.mu, "a_star": a_star, "kt_linear_history": 4.0 * G / (2.0 - case.nu)
            * a_star, "dt": (math.pi - 2.0 * case.tau0) / steps, "steps": steps}


def lj_table(case: Case, steps: int = LJ_STEPS) -> dict[str, NDArray[np.float64]]:
    """The columns of ``NAME.lj.csv``: the deck's path and the exact forces at its steps."""
    sc = lj_scales(case, steps)
    k = np.arange(steps + 1, dtype=np.float64)
    tau = case.tau0 + k * sc["dt"]
    c = case.contact
    alpha = sc["H"] * (np.sin(tau) - math.sin(case.tau0))
    x = sc["u0"] * np.sin(tau)
    z = (alpha * (4.0 - alpha) + x * x) / (2.0 + np.sqrt((2.0 - alpha) ** 2 - x * x))
    v = {name: np.concatenate(([0.0], np.diff(q) / sc["dt"])) for name, q in
         (("vx", x), ("vz", z))}
    return {"step": k, "time": k * sc["dt"], "x": x, "z": z, **v,
            "fx": case.mu * c.tangential_force(tau), "fz": c.normal_force(tau)}


def _case_meta(name: str, case: Case, ref: Reference) -> dict[str, object]:
    c = case.contact
    return {"name": name, "note": NOTES.get(name, ""), "psi": case.psi, "tau0": case.tau0,
            "mu": case.mu, "nu": case.nu, "tau_end": case.tau_end,
            "tau1": None if case.psi <= 1 else c.tau1, "impulse_ratio": ref.impulse_ratio,
            "dissipated_energy": ref.dissipated_energy, "loading_work": case.loading_work}


def _write_csv(path: Path, header: dict[str, object], columns: dict[str, str],
               table: dict[str, NDArray]) -> None:
    with path.open("w", newline="") as f:
        for key, value in header.items():
            f.write(f"# {key}: {value}\n")
        for col, text in columns.items():
            f.write(f"# column {col}: {text}\n")
        f.write(",".join(columns) + "\n")
        rows = np.column_stack([np.asarray(table[c], dtype=np.float64) for c in columns])
        ints = {i for i, c in enumerate(columns) if c in ("phase", "step")}
        for row in rows:
            f.write(",".join(str(int(v)) if i in ints else f"{v:.17g}"
                             for i, v in enumerate(row)) + "\n")


def export(directory: str | Path, cases: dict[str, Case] | None = None) -> Path:
    """Write the vectors of ``cases`` (default ``CASES``) into ``directory`` (created if
    missing); returns the path of ``index.json``."""
    out = Path(directory)
    out.mkdir(parents=True, exist_ok=True)
    entries = []
    for name, case in (cases or CASES).items():
        ref = exact(case, POINTS)
        meta = _case_meta(name, case, ref)
        common = {"schema": f"{SCHEMA} {SCHEMA_VERSION}", "generator":
                  "python -m core.dem_check export", **{k: v for k, v in meta.items()
                                                          if v is not None}}
        table = {"tau": ref.tau, "drive": ref.drive, "approach": ref.approach, "T": ref.T,
                 "P": ref.P, "phase": ref.phase, "work": ref.work}
        _write_csv(out / f"{name}.csv", {**common, "units": "dimensionless: T in T0, P in "
                                         "P0 = T0 / mu, work in T0 u0"}, COLUMNS, table)
        sc = lj_scales(case)
        _write_csv(out / f"{name}.lj.csv", {**common, "units": "LAMMPS lj, as deck.in: "
                                            + ", ".join(f"{k} = {v!r}" for k, v in
                                                        sc.items())}, LJ_COLUMNS,
                   lj_table(case))
        entries.append({**meta, "files": {"dimensionless": f"{name}.csv",
                                          "lj": f"{name}.lj.csv"}, "lj": sc})
    index = {"schema": SCHEMA, "schema_version": SCHEMA_VERSION,
             "generator": "python -m core.dem_check export",
             "source": "Zharii (1996), Int. J. Engng Sci. 34(5) 537-548: closed form of core",
             "columns": COLUMNS, "lj_columns": LJ_COLUMNS, "cases": entries}
    path = out / "index.json"
    path.write_text(json.dumps(index, indent=2) + "\n")
    return path


def read_history(path: str | Path, required: tuple[str, ...] = ("tau", "T", "P")
                 ) -> tuple[dict[str, str], dict[str, NDArray[np.float64]]]:
    """(header, columns) of a CSV file: the ``# key: value`` lines before the header row,
    and the ``required`` columns (at least) as float arrays. ValueError naming the file
    and the row or column for a missing column, a short or long row, a cell that is not a
    number, more than ``MAX_SAMPLES`` rows or a file larger than ``MAX_BYTES``."""
    p = Path(path)
    size = p.stat().st_size
    if size > MAX_BYTES:
        raise ValueError(f"{p}: {size} bytes, more than the {MAX_BYTES} accepted")
    with p.open(newline="") as f:
        return _parse_lines(f, str(p), required, MAX_SAMPLES, finite=False)


def parse_history(text: str, required: tuple[str, ...] = ("tau", "T", "P"), *,
                  source: str = "the text", max_rows: int = MAX_SAMPLES
                  ) -> tuple[dict[str, str], dict[str, NDArray[np.float64]]]:
    """``read_history`` of a CSV held in memory (an upload, never written to disk): the
    same (header, columns) and the same refusals, each a ValueError naming ``source``
    and the line or column; also more than ``max_rows`` data rows, and a cell of a
    ``required`` column that is a number but not a finite one (nan, inf)."""
    return _parse_lines(io.StringIO(text, newline=""), source, required, max_rows,
                        finite=True)


def _parse_lines(lines: Iterable[str], source: str, required: tuple[str, ...],
                 max_rows: int, *, finite: bool
                 ) -> tuple[dict[str, str], dict[str, NDArray[np.float64]]]:
    """The parser of ``read_history`` and ``parse_history`` over the lines of a CSV."""
    header: dict[str, str] = {}
    numbered = iter(enumerate(lines, start=1))
    first: tuple[int, str] | None = None
    for lineno, line in numbered:
        if line.startswith("#"):
            key, _, value = line[1:].partition(":")
            header[key.strip()] = value.strip()
        elif line.strip():
            first = lineno, line
            break
    if first is None:
        raise ValueError(f"{source}: no header row (expected columns {', '.join(required)})")
    lineno, line = first
    names = [n.strip() for n in _cells(source, lineno, line)]
    missing = [c for c in required if c not in names]
    if missing:
        raise ValueError(f"{source}, line {lineno}: no column {missing[0]!r} in the header "
                         f"row (columns: {', '.join(names)})")
    checked = [i for i, n in enumerate(names) if n in required] if finite else []
    rows: list[list[float]] = []
    for lineno, line in numbered:
        if not line.strip():
            continue
        row = _cells(source, lineno, line)
        if len(row) != len(names):
            raise ValueError(f"{source}, line {lineno}: {len(row)} values, expected "
                             f"{len(names)} ({', '.join(names)})")
        try:
            values = [float(v) for v in row]
        except ValueError:
            bad = next(i for i, v in enumerate(row) if not _is_float(v))
            raise ValueError(f"{source}, line {lineno}, column {names[bad]!r}: "
                             f"{row[bad]!r} is not a number") from None
        for i in checked:
            if not math.isfinite(values[i]):
                raise ValueError(f"{source}, line {lineno}, column {names[i]!r}: "
                                 f"{row[i].strip()!r} is not a finite number")
        rows.append(values)
        if len(rows) > max_rows:
            raise ValueError(f"{source}: more than {max_rows} rows")
    if not rows:
        raise ValueError(f"{source}: no data rows after the header row")
    table = np.array(rows, dtype=np.float64)
    return header, {n: table[:, i] for i, n in enumerate(names)}


def _cells(source: str, lineno: int, line: str) -> list[str]:
    """The cells of one CSV line; ValueError naming the line if the csv module refuses
    it (a field beyond its size limit, a bare carriage return inside a field)."""
    try:
        return next(csv.reader([line]))
    except csv.Error as err:
        raise ValueError(f"{source}, line {lineno}: not a CSV line ({err})") from None


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
