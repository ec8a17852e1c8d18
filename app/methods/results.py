"""The numerical methods' benchmark results the Methods card shows, and their downloads.

`benchmarks/core/methods.py` and `benchmarks/core/stability_map.py` write
speed_accuracy.csv and stability_map.csv to `benchmarks/results/`;
`python -m app.methods.publish benchmarks/results --publish` (`make bench-charts`)
copies them into the app's package data, `app/results/` (`RESULTS`), read here through
`importlib.resources`.  A download of either file opens with the explorer's header block
(`app.contact.export`): what it holds, the source, the app's version, the command that wrote it
and each column with its unit.
"""

from __future__ import annotations

from dataclasses import dataclass
from importlib import resources

import numpy as np

from app.contact import export

#: The results the explorer shows (speed_accuracy.csv, stability_map.csv): package
#: data of `app`.
RESULTS = resources.files("app") / "results"
#: Errors are drawn at FLOOR at least (a log axis has no 0).
FLOOR = 1e-17


def read_rows(path) -> list[dict]:
    """The rows of a results CSV file (a path or a `RESULTS` entry), each column as
    numpy reads it: whole numbers as int, other numbers as float, text as str."""
    with path.open(newline="") as fh:
        table = np.atleast_1d(np.genfromtxt(fh, delimiter=",", names=True, dtype=None,
                                            encoding="utf-8", comments="#"))
    return [dict(zip(table.dtype.names, row, strict=True)) for row in table.tolist()]


@dataclass(frozen=True)
class ResultsFile:
    """A results file: what it holds, the command that writes it, and each column's
    meaning with its unit ('' if dimensionless or text)."""

    title: str
    command: str
    columns: dict[str, tuple[str, str]]


_METHOD = ("method", ("", "the method (core.numerics.METHODS; closed_form: core.curve)"))
_CASE = {"psi": ("", "drive ratio tan theta / tan theta0 of the case (Zharii 1996, eq 23)"),
         "tau0": ("rad", "start of contact of the case (Zharii 1996, eq 4)")}
_ERRORS = {
    "err_T": ("", "max |T - T_exact| / T0 over the method's times (T0: Zharii 1996, eq 37)"),
    "err_impulse": ("", "|impulse ratio - exact| (T_imp / (mu P_imp), Zharii 1996, eq 41)"),
}

FILES: dict[str, ResultsFile] = {
    "speed_accuracy.csv": ResultsFile(
        "speed against accuracy of the numerical methods of core.numerics and the closed "
        "form, one row per run and case",
        "python -m benchmarks.core.methods",
        {_METHOD[0]: _METHOD[1],
         "resolution": ("", "springs (mdr), rings (annulus), points or time steps per "
                            "contact (the DEM rules), nodes (quadratures)"),
         "steps": ("", "time steps per contact of mdr (0: not a stepping method)"),
         **_CASE,
         "regime": ("", "psi <= 1, psi > 1 (tau0 = pi/6), grazing (tau0 = 1.5) or "
                        "preload (tau0 = -0.9)"),
         "points": ("", "times at which the method returns T"),
         "wall_time": ("s", "time per contact, one call from Python (best of several "
                            "windows; compilation excluded)"),
         **_ERRORS,
         "err_b": ("", "max |b - b_exact| / a* of the stick radius (nan: not computed)"),
         "err": ("", "combined error max(err_T, err_impulse)"),
         "err_rel": ("", "relative error max(err_T / max |T_exact|, err_impulse / exact "
                         "impulse ratio)")}),
    "stability_map.csv": ResultsFile(
        "stability map: the error of each method at a fixed resolution over a (psi, tau0) "
        "grid, one row per method and cell",
        "python -m benchmarks.core.stability_map",
        {_METHOD[0]: _METHOD[1],
         "resolution": ("", "the method's fixed resolution (springs, rings or steps)"),
         **_CASE,
         "err": ("", "combined error max(err_T, err_impulse)"),
         **_ERRORS,
         "rel_err_impulse": ("", "err_impulse / |exact impulse ratio|"),
         "wall_time": ("s", "time of the run")}),
}


def header(name: str) -> list[str]:
    """The comment lines (without '# ') of results file `name`: what it holds, the
    source, the app's version, the command that wrote it, the columns with units."""
    f = FILES[name]
    with (RESULTS / name).open(newline="") as fh:
        names = fh.readline().strip().split(",")
    return [f"Zharii 1996 explorer: {f.title}",
            f"source: {export.SOURCE}",
            f"app: zharii-contact {export.app_version()}",
            f"command: {f.command} (from the repository's root; app/results/ holds the "
            "copy `make bench-charts` published)",
            "columns:",
            *(f"  {n}{f' ({f.columns[n][0]})' if f.columns[n][0] else ''}: "
              f"{f.columns[n][1]}" for n in names)]


def download_text(name: str) -> str:
    """Results file `name` with its header block ('# ' lines) before its rows."""
    body = (RESULTS / name).read_text(encoding="utf-8")
    return "".join(f"# {line}\n" for line in header(name)) + body
