"""The closed form's error against the boundary-element referee, mapped over the material
pair for the paper's loading: identical bodies over nu in [0, 0.5) (Cattaneo-Mindlin's
neglected transverse traction), and dissimilar ones over Dundurs' beta (Goodman's
neglected coupling): a sweep of beta at fixed nu and every pair of the motor's materials
(``core.MOTOR_MATERIALS``; body 1, the held one, first in the table's order; beta and
nu_eq from ``core.physical``).

Every row is run on two grids; the difference between them is the row's grid-convergence
estimate (the error of the coarser figure, an upper estimate for the finer one).

Two measures of the closed form's error: against the referee directly (``worst_T_error``
and the like: the model's error plus the referee's discretisation error), and against the
referee's own run at nu = 0, beta = 0 on the same grid and time steps (``*_model``), where
the closed form is exact: T / T0, the impulse ratio and D / (T0 u0) of the closed form do
not depend on nu for given psi and tau0, so the referee's change from that run is the
model's error with most of the discretisation error cancelled.
"""

from __future__ import annotations

import csv
import itertools
import math
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import TextIO

import numpy as np

from core.bem.pair import Pair
from core.bem.paper import PaperRun, run_paper
from core.materials import MATERIALS, MOTOR_MATERIALS

#: Poisson ratios of the identical-body rows, and the beta sweep (at SWEEP_NU).
NUS = (0.0, 0.1, 0.2, 0.3, 0.4, 0.45, 0.49)
BETAS = (0.05, 0.1, 0.2, 0.3, 0.4, 0.45)
SWEEP_NU = 0.3


@dataclass(frozen=True)
class MapRow:
    """One material pair: its label, nu (effective), beta, and for the fine grid the worst
    |T - T_closed| / T0, the impulse ratio's error (referee minus eq 41), the dissipation
    ratio (referee over closed form; nan for psi <= 1), the worst stick-radius error
    (units a*), and against the referee at nu = 0, beta = 0 (module docstring) the worst
    |T - T_ref| / T0, the impulse ratio's change and the dissipation's ratio, each with
    ``*_grid`` = |fine - coarse|; the two grids and the seconds."""

    label: str
    nu: float
    beta: float
    worst_T_error: float
    worst_T_error_grid: float
    impulse_error: float
    impulse_error_grid: float
    dissipation_ratio: float
    dissipation_ratio_grid: float
    stick_error: float
    stick_error_grid: float
    worst_T_model: float
    worst_T_model_grid: float
    impulse_model: float
    impulse_model_grid: float
    dissipation_model: float
    dissipation_model_grid: float
    coarse: int
    fine: int
    seconds: float

    def as_dict(self) -> dict:
        """The row as a dict with nan as None (JSON null)."""
        return {k: (None if isinstance(v, float) and math.isnan(v) else v)
                for k, v in asdict(self).items()}


def cases() -> list[tuple[str, Pair]]:
    """(label, pair) of every row: identical bodies over NUS, the beta sweep, the motor's
    materials' pairs."""
    rows = [(f"identical nu={nu:g}", Pair(nu)) for nu in NUS]
    rows += [(f"sweep nu={SWEEP_NU:g} beta={b:g}", Pair(SWEEP_NU, b)) for b in BETAS]
    for a, b in itertools.combinations(MOTOR_MATERIALS, 2):
        m1, m2 = MATERIALS[a], MATERIALS[b]
        rows.append((f"{a} on {b}", Pair.of(m1.G, m1.nu, m2.G, m2.nu)))
    return rows


def map_row(label: str, pair: Pair, *, grids: tuple[int, int] = (32, 64), steps: int = 200,
            psi: float = 2.414213562373095, tau0: float = math.pi / 6,
            mu: float = 0.2, reference: tuple[PaperRun, PaperRun] | None = None) -> MapRow:
    """The row of one pair: the paper's loading on two grids (``core.bem.paper``);
    ``reference``: the runs at nu = 0, beta = 0 on the same grids (run if None)."""
    runs = [run_paper(psi, tau0, pair.nu, beta=pair.beta, mu=mu, grid=n, steps=steps)
            for n in grids]
    refs = reference or tuple(run_paper(psi, tau0, 0.0, mu=mu, grid=n, steps=steps)
                              for n in grids)

    def both(get):  # the fine figure and its grid estimate
        fine, coarse = get(runs[1], refs[1]), get(runs[0], refs[0])
        return fine, abs(fine - coarse)

    t, tg = both(lambda r, _: r.worst_T_error)
    i, ig = both(lambda r, _: r.impulse_ratio - r.impulse_ratio_closed)
    d, dg = both(lambda r, _: r.dissipation_ratio)
    s, sg = both(lambda r, _: r.worst_stick_error)
    tm, tmg = both(lambda r, q: float(np.abs(r.T - q.T).max()))
    im, img = both(lambda r, q: r.impulse_ratio - q.impulse_ratio)
    dm, dmg = both(lambda r, q: r.dissipation / q.dissipation if q.dissipation > 0
                   else math.nan)
    return MapRow(label, pair.nu, pair.beta, t, tg, i, ig, d, dg, s, sg, tm, tmg, im, img,
                  dm, dmg, grids[0], grids[1], sum(r.seconds for r in runs))


def error_map(*, grids: tuple[int, int] = (32, 64), steps: int = 200,
              psi: float = 2.414213562373095, tau0: float = math.pi / 6,
              mu: float = 0.2, progress: TextIO | None = None) -> list[MapRow]:
    """Every row of ``cases`` (each row's label written to ``progress`` when done)."""
    rows = []
    refs = tuple(run_paper(psi, tau0, 0.0, mu=mu, grid=n, steps=steps) for n in grids)
    for label, pair in cases():
        rows.append(map_row(label, pair, grids=grids, steps=steps, psi=psi, tau0=tau0,
                            mu=mu, reference=refs))
        if progress is not None:
            print(f"{label}: worst T error {rows[-1].worst_T_error:.3g} T0, model "
                  f"{rows[-1].worst_T_model:.3g} T0 "
                  f"({rows[-1].seconds:.0f} s)", file=progress, flush=True)
    return rows


def write_csv(rows: list[MapRow], path: str | Path) -> None:
    """The rows as CSV (a header of the field names)."""
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(asdict(rows[0])))
        w.writeheader()
        for r in rows:
            w.writerow(asdict(r))


def beta_threshold(rows: list[MapRow], level: float = 0.01) -> float:
    """The |beta| at which the sweep's worst T error against the referee at nu = 0,
    beta = 0 (``worst_T_model``) first reaches ``level`` (units T0),
    by linear interpolation in |beta| between the sweep's rows; inf when it never does
    within the sweep."""
    sweep = sorted((abs(r.beta), r.worst_T_model) for r in rows if r.label.startswith("sweep"))
    base = next((r.worst_T_model for r in rows if r.label == f"identical nu={SWEEP_NU:g}"),
                0.0)
    sweep = [(0.0, base), *sweep]
    for (b0, e0), (b1, e1) in itertools.pairwise(sweep):
        if e0 < level <= e1:
            return b0 + (level - e0) * (b1 - b0) / (e1 - e0)
    return math.inf


def read_csv(path: str | Path) -> list[MapRow]:
    """The rows written by ``write_csv``."""
    with open(path, newline="") as fh:
        out = []
        for d in csv.DictReader(fh):
            kw = {k: (v if k == "label" else int(v) if k in ("coarse", "fine") else float(v))
                  for k, v in d.items()}
            out.append(MapRow(**kw))
        return out


def markdown(rows: list[MapRow]) -> str:
    """The map as a Markdown table: each figure on the fine grid with its grid estimate
    (+- |fine - coarse|)."""

    def pm(v: float, g: float, fmt: str = ".2g") -> str:
        return "-" if math.isnan(v) else f"{v:{fmt}} +- {g:.1g}"

    head = ("| pair | nu | beta | T err. vs referee at nu=beta=0 (T0) | T err. vs closed "
            "form (T0) | impulse ratio change | dissipation ratio - 1 | stick radius err. "
            "(a*) |")
    lines = [head, "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(
            f"| {r.label} | {r.nu:.3f} | {r.beta:+.3f} | "
            f"{pm(r.worst_T_model, r.worst_T_model_grid)} | "
            f"{pm(r.worst_T_error, r.worst_T_error_grid)} | "
            f"{pm(r.impulse_model, r.impulse_model_grid)} | "
            f"{pm(r.dissipation_model - 1, r.dissipation_model_grid)} | "
            f"{pm(r.stick_error, r.stick_error_grid)} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    import sys

    table = read_csv(sys.argv[1])
    print(markdown(table))
    print(f"|beta| at which the T error passes 1 % of T0: {beta_threshold(table):.3f}")
