"""The numbers of the DEM card's "Impacts" tab, without Bokeh or Panel: Chung & Ooi's
(2011) impact tests 4 to 8 (`core.dem_check.impact_cases`) over incidence, for the exact
reference (`core.dem_check.impact.exact`, i.e. `core.impact.solve`), LAMMPS' five
tangential models (`core.dem_check.impact.run`) and the published values of test 4
(`core.dem_check.impact_data.published`); the reading of a visitor's impact results (CSV)
and their score (`core.dem_check.impact.score_curve`).

The card never runs LAMMPS, nor the reference of a whole curve (17 incidences cost 3 to 10 s
on one core): both are computed once and shipped as package data in `app/dem/lammps/`,
`impact_exact_test{N}_{material}.csv` (the reference at `EXACT_INCIDENCE`, 1 to 89 deg by
1) and `impact_lammps_test{N}_{material}.csv` (the five models at Chung & Ooi's 5 to 85 deg
by 5). Regenerate them with Debian's LAMMPS (`lmp`, `make lammps`; about 15 minutes)::

    .venv/bin/python -m app.dem.impacts

An upload is scored against the reference at its own incidences: those of the shipped grid
are read from it, the others solved (`reference_at`, on the job runner: ~0.2-2 s each, so
an upload holds at most `MAX_ROWS` rows).
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from functools import cache

import numpy as np
from numpy.typing import NDArray

from app.dem.data import upload_text
from app.dem.overlays import DIRECTORY
from core.dem_check import impact as bench
from core.dem_check import impact_data
from core.dem_check.impact_cases import DEFAULT_INCIDENCE, TESTS, impact_test
from core.dem_check.lammps import MODELS, LammpsFailed, LammpsNotFound
from core.dem_check.lammps import version as lammps_version
from core.dem_check.vectors import parse_history, read_history

#: The quantities drawn and scored (`core.dem_check.impact.QUANTITIES`' first three).
QUANTITIES = ("tangential_cor", "rebound_spin", "rebound_angle")
#: How each quantity is named on the page, with its unit.
LABELS = {"tangential_cor": "tangential restitution vx'/vx",
          "rebound_spin": "rebound spin ω' (rad/s)",
          "rebound_angle": "rebound angle of the contact point (deg)"}
#: The reference's incidences (deg) in the shipped files.
EXACT_INCIDENCE = tuple(float(a) for a in range(1, 90))
#: LAMMPS' incidences (deg): Chung & Ooi's.
LAMMPS_INCIDENCE = DEFAULT_INCIDENCE
#: The reference's springs and tolerance (`core.dem_check.impact.exact`'s defaults).
SPRINGS, TOL = 2000, 1e-9
#: The most data rows of an uploaded file (each incidence off the shipped grid costs one
#: solve of the reference).
MAX_ROWS = 100
#: How an upload is named in messages.
SOURCE = "your file"
#: The upload's columns.
COLUMNS = ("incidence_deg", *QUANTITIES)
DEFAULT_TEST, DEFAULT_MODEL = 4, "mindlin"


def check_choice(test: object, material: object, model: object = DEFAULT_MODEL
                 ) -> tuple[int, str, str]:
    """(test, material, model) if they name one of Chung & Ooi's tests 4-8, one of its
    materials and one of LAMMPS' tangential models; ValueError naming the one that is
    not."""
    t = impact_test(test)
    if not isinstance(material, str) or material not in t.materials:
        raise ValueError(f"material must be one of {', '.join(t.materials)} for test "
                         f"{t.number}, got {str(material)[:40]!r}")
    if not isinstance(model, str) or model not in MODELS:
        raise ValueError(f"model must be one of {', '.join(MODELS)}, got {str(model)[:40]!r}")
    return t.number, material, model


def combinations() -> list[tuple[int, str]]:
    """Every (test, material) offered."""
    return [(n, m) for n, t in TESTS.items() for m in t.materials]


def exact_path(test: int, material: str):
    """The shipped reference of (test, material)."""
    return DIRECTORY / f"impact_exact_test{test}_{material}.csv"


def lammps_path(test: int, material: str):
    """The shipped LAMMPS runs of (test, material)."""
    return DIRECTORY / f"impact_lammps_test{test}_{material}.csv"


def _column(model: str, quantity: str) -> str:
    return f"{model} {quantity}"


def _header(head: dict[str, object], names: list[str], rows: NDArray[np.float64]) -> str:
    lines = [f"# {k}: {v}" for k, v in head.items()]
    lines.append(",".join(names))
    lines += [",".join(f"{v:.17g}" for v in row) for row in rows]
    return "\n".join(lines) + "\n"


def exact_text(test: int, material: str, curves: bench.Curves) -> str:
    """The reference file of (test, material) from its curves."""
    head = {"name": f"impact_exact_test{test}_{material}", "generator":
            "python -m app.dem.impacts", "what": f"Chung & Ooi test {test} "
            f"({TESTS[test].title}), {material}: core.impact.solve", "springs": SPRINGS,
            "tol": TOL, "units": "incidence_deg deg; tangential_cor vx'/vx of the centre "
            "(nan without centre tangential velocity); rebound_spin rad/s (positive in the "
            "rolling sense); rebound_angle deg, of the contact point"}
    rows = np.column_stack([curves.incidence_deg, *(curves.get(q) for q in QUANTITIES)])
    return _header(head, list(COLUMNS), rows)


def lammps_text(test: int, material: str, runs: dict[str, bench.Curves], version: str,
                steps: int) -> str:
    """The LAMMPS file of (test, material) from one Curves per model."""
    head = {"name": f"impact_lammps_test{test}_{material}", "generator":
            "python -m app.dem.impacts", "what": f"Chung & Ooi test {test} "
            f"({TESTS[test].title}), {material}: core.dem_check.impact.run, pair_style "
            "granular", "lammps": version, "steps": steps,
            "columns": "incidence_deg, then 'MODEL QUANTITY' (units as in the reference file)"}
    first = next(iter(runs.values()))
    names = ["incidence_deg", *(_column(m, q) for m in runs for q in QUANTITIES)]
    rows = np.column_stack([first.incidence_deg,
                            *(c.get(q) for c in runs.values() for q in QUANTITIES)])
    return _header(head, names, rows)


def generate(steps: int = bench.DEFAULT_STEPS, lmp: str | None = None) -> list:
    """Compute and write the reference and LAMMPS files of every (test, material)."""
    version = lammps_version(lmp)
    written = []
    for test, material in combinations():
        ex = bench.exact_curves(test, material, EXACT_INCIDENCE, SPRINGS, TOL)
        exact_path(test, material).write_text(exact_text(test, material, ex))
        runs = {m: bench.lammps_curves(test, material, m, LAMMPS_INCIDENCE, steps, lmp=lmp)
                for m in MODELS}
        lammps_path(test, material).write_text(lammps_text(test, material, runs, version,
                                                           steps))
        written += [exact_path(test, material), lammps_path(test, material)]
        print(f"test {test}, {material}: written", flush=True)
    return written


@dataclass(frozen=True)
class ImpactCurves:
    """One code's curves over incidence: the incidences (deg) and each quantity there."""

    incidence_deg: NDArray[np.float64]
    values: dict[str, NDArray[np.float64]]  # quantity -> values


@cache
def exact_curves(test: int, material: str) -> ImpactCurves:
    """The shipped reference of (test, material) (read once per process)."""
    check_choice(test, material)
    _, cols = read_history(exact_path(test, material), required=COLUMNS)
    return ImpactCurves(cols["incidence_deg"], {q: cols[q] for q in QUANTITIES})


@cache
def _lammps_table(test: int, material: str) -> tuple[dict[str, str], dict]:
    required = ("incidence_deg", *(_column(m, q) for m in MODELS for q in QUANTITIES))
    return read_history(lammps_path(test, material), required=required)


def lammps_curves(test: int, material: str, model: str) -> ImpactCurves:
    """LAMMPS' `model` on (test, material), from the shipped runs."""
    check_choice(test, material, model)
    _, cols = _lammps_table(test, material)
    return ImpactCurves(cols["incidence_deg"],
                        {q: cols[_column(model, q)] for q in QUANTITIES})


def lammps_note(test: int, material: str) -> str:
    """Where the LAMMPS curves come from."""
    head, _ = _lammps_table(*check_choice(test, material)[:2])
    return (f"LAMMPS {head['lammps']}, pair_style granular, {head['steps']} steps per "
            "contact time, precomputed (`python -m app.dem.impacts`); the reference: "
            f"core.impact ({SPRINGS} springs, tolerance {TOL:g}), 1 to 89° by 1°")


def published(test: int, material: str, series: str) -> dict[str, NDArray[np.float64]]:
    """Columns `{q}_x`, `{q}_y` of the published `series` ('published': Chung & Ooi's
    published curve of the material, 'experiment': Kharaz et al.'s measurements, alumina
    only) for test 4, padded with nan to one length; empty columns where core has none."""
    check_choice(test, material)
    if series not in ("published", "experiment"):
        raise ValueError(f"series must be 'published' or 'experiment', got {series!r}")
    name = material if series == "published" else "experiment"
    empty = {f"{q}_{k}": np.empty(0) for q in QUANTITIES for k in "xy"}
    if test != 4 or (series == "experiment" and material != "alumina"):
        return empty
    pairs = {q: impact_data.published(q, name) for q in QUANTITIES}
    n = max(x.size for x, _ in pairs.values())
    out = {}
    for q, (x, y) in pairs.items():
        pad = np.full(n - x.size, np.nan)
        out[f"{q}_x"], out[f"{q}_y"] = np.append(x, pad), np.append(y, pad)
    return out


def columns(curves: ImpactCurves | None) -> dict[str, NDArray[np.float64]]:
    """A figure source's columns: incidence_deg and each quantity (empty for None)."""
    if curves is None:
        return {c: np.empty(0) for c in COLUMNS}
    return {"incidence_deg": curves.incidence_deg, **curves.values}


# ------------------------------------------------------------------ upload


def read_upload(data: object, test: int) -> ImpactCurves:
    """A visitor's impact results in an uploaded file's bytes `data` (the DEM card's
    limits and checks: `app.dem.data.upload_text`), a CSV with columns incidence_deg,
    rebound_spin, rebound_angle and tangential_cor (which tests 6-8 may leave out or give
    as nan: their centre has no tangential velocity), at most `MAX_ROWS` rows, incidences
    in [0, 90) deg. ValueError saying what is wrong and where."""
    impact_test(test)
    text = upload_text(data, "a header row incidence_deg,tangential_cor,rebound_spin,"
                             "rebound_angle and a row per incidence")
    needs_cor = test in (4, 5)
    required = COLUMNS if needs_cor else ("incidence_deg", *QUANTITIES[1:])
    _, cols = parse_history(text, required=required, source=SOURCE, max_rows=MAX_ROWS)
    inc = cols["incidence_deg"]
    bad = np.flatnonzero(~((inc >= 0.0) & (inc < 90.0)))
    if bad.size:
        raise ValueError(f"{SOURCE}, data row {bad[0] + 1}: incidence_deg = "
                         f"{inc[bad[0]]:g} is outside [0, 90) deg")
    cor = cols.get("tangential_cor", np.full(inc.size, np.nan))
    return ImpactCurves(inc, {"tangential_cor": cor, "rebound_spin": cols["rebound_spin"],
                              "rebound_angle": cols["rebound_angle"]})


def reference_at(test: int, material: str, incidence: NDArray[np.float64]
                 ) -> ImpactCurves:
    """The exact reference of (test, material) at `incidence` (deg): the shipped values
    where an incidence is one of `EXACT_INCIDENCE`, `core.dem_check.impact.exact`
    (`SPRINGS`, `TOL`) at the others (slow: run it on the job runner)."""
    grid = exact_curves(test, material)
    t = impact_test(test)
    values = {q: np.empty(incidence.size) for q in QUANTITIES}
    for i, th in enumerate(incidence):
        hit = np.flatnonzero(grid.incidence_deg == th)
        if hit.size:
            for q in QUANTITIES:
                values[q][i] = grid.values[q][hit[0]]
            continue
        r = bench.exact(t.impact(material, float(th)), SPRINGS, TOL)
        for q in QUANTITIES:
            values[q][i] = getattr(r, q)
    return ImpactCurves(np.asarray(incidence, float), values)


def off_grid(incidence: NDArray[np.float64]) -> int:
    """How many of `incidence` need a solve of the reference (not on the shipped grid)."""
    return int(np.count_nonzero(~np.isin(incidence, EXACT_INCIDENCE)))


def scores(curves: ImpactCurves, reference: ImpactCurves) -> dict[str, bench.CurveScore]:
    """Each quantity's `core.dem_check.impact.score_curve` of `curves` against
    `reference` (the same incidences)."""
    return {q: bench.score_curve(q, curves.incidence_deg, curves.values[q],
                                 reference.values[q]) for q in QUANTITIES}


def lammps_scores(test: int, material: str, model: str) -> dict[str, bench.CurveScore]:
    """The shipped LAMMPS `model`'s scores against the shipped reference."""
    lm = lammps_curves(test, material, model)
    return scores(lm, reference_at(test, material, lm.incidence_deg))


def score_text(s: bench.CurveScore) -> str:
    """'worst 0.215 at 5° · mean 0.0206' (or '—' where nothing was comparable)."""
    if not math.isfinite(s.worst):
        return "—"
    return f"worst {s.worst:.3g} at {s.worst_incidence:g}° · mean {s.mean:.3g}"


def score_rows(model: str, lammps: dict[str, bench.CurveScore],
               upload: dict[str, bench.CurveScore] | None) -> list[tuple[str, ...]]:
    """The score table: (quantity, LAMMPS model's score, the upload's score or '')."""
    return [(LABELS[q], score_text(lammps[q]), score_text(upload[q]) if upload else "")
            for q in QUANTITIES]


def main() -> int:
    try:
        for p in generate():
            print(p)
    except (LammpsNotFound, LammpsFailed) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
