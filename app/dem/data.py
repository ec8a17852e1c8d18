"""The numbers of the "Check a DEM code" card, without Bokeh or Panel: the plot's columns
(the exact T(tau) of `core.dem_check.exact`, LAMMPS' precomputed runs, the visitor's
history), the reading and scoring of an uploaded CSV, the score table's rows and the
texts offered for download.

Everything from the browser is checked here: a case name against `CASES`, an upload's
bytes against `MAX_UPLOAD_BYTES` before they are read, then as UTF-8 text without
control characters, then by `core.dem_check`'s own CSV reader (`parse_history`) in
memory; every refusal is a ValueError whose message the visitor can act on.
"""

from __future__ import annotations

import math
import re
import tempfile
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from app.dem import overlays
from core.dem_check import CASES, DemScore, exact, lammps, score
from core.dem_check.case import NOTES
from core.dem_check.vectors import export, parse_history

DEFAULT_CASE = "fig7_psi2.41"
DEFAULT_MODELS = ("mindlin", "mindlin/force")
#: Points of the exact curve over the contact (`core.dem_check.exact`).
EXACT_POINTS = 1000
#: The largest upload read, in bytes (2 MiB: about 33,000 rows of three 17-digit
#: numbers). The browser refuses a larger file before sending it
#: and sends a smaller one in pieces (`app.dem.upload`), each well under the 512 KiB
#: websocket message cap of `app.serve`.
MAX_UPLOAD_BYTES = 2 * 1024 * 1024
#: The most data rows an upload may hold.
MAX_UPLOAD_ROWS = 50_000
#: The most points of an upload drawn (every k-th sample beyond it; the score uses all).
MAX_PLOT_POINTS = 4000
#: How an upload is named in messages.
SOURCE = "your file"
#: The deck's steps per contact in the download (`core.dem_check.lammps.deck`).
DECK_STEPS = 20000
#: A model's colour (colour-blind safe, each at least 2.3:1 on white).
COLORS = {"linear_history": "#999933", "mindlin": "#E69F00", "mindlin/force": "#0072B2",
          "mindlin_rescale": "#009E73", "mindlin_rescale/force": "#CC79A7"}
#: The colour of the visitor's history.
UPLOAD_COLOR = "#D55E00"
#: Characters no text CSV holds (C0 controls but tab, line feed, carriage return).
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")


@dataclass(frozen=True)
class History:
    """A visitor's history of one contact: tau (rad), T / T0, P / P0, as read."""

    tau: NDArray[np.float64]
    T: NDArray[np.float64]
    P: NDArray[np.float64]
    header: dict[str, str] = field(default_factory=dict)  # the file's `# key: value` lines


def check_case(name: object) -> str:
    """`name` if it names a documented case; ValueError listing the cases otherwise."""
    if not isinstance(name, str) or name not in CASES:
        raise ValueError(f"no case named {str(name)[:40]!r}; the cases are: "
                         f"{', '.join(CASES)}")
    return name


def check_models(models: object) -> list[str]:
    """`models` as a list of LAMMPS model names, in `lammps.MODELS`' order; ValueError
    naming one that is not a model."""
    if not isinstance(models, list | tuple):
        raise ValueError("the models must be a list of names")
    for m in models:
        if not isinstance(m, str) or m not in lammps.MODELS:
            raise ValueError(f"no LAMMPS model named {str(m)[:40]!r}; the models are: "
                             f"{', '.join(lammps.MODELS)}")
    return [m for m in lammps.MODELS if m in models]


def case_note(name: str) -> str:
    """What case `name` tests, with its parameters, in plain words."""
    c = CASES[check_case(name)]
    return f"ψ = {c.psi:.6g}, τ₀ = {c.tau0:.6g} rad, μ = {c.mu:g}, ν = {c.nu:g}: {NOTES[name]}"


def exact_columns(name: str) -> dict[str, NDArray[np.float64]]:
    """The exact contact of case `name` (`core.dem_check.exact` on `EXACT_POINTS`
    times): tau, T / T0, and the Coulomb bounds +-P / P0 (T0 = mu P0)."""
    ref = exact(CASES[check_case(name)], EXACT_POINTS)
    return {"tau": ref.tau, "T": ref.T, "P": ref.P, "minus_P": -ref.P}


def overlay_columns(name: str, models: list[str]) -> dict[str, list]:
    """LAMMPS' runs of case `name` for `models` (a multi-line's columns: xs, ys, label,
    color), from the precomputed overlays."""
    runs = overlays.load(check_case(name))
    chosen = check_models(models)
    return {"xs": [runs.tau] * len(chosen), "ys": [runs.T[m] for m in chosen],
            "label": [f"LAMMPS {m}" for m in chosen], "color": [COLORS[m] for m in chosen]}


def overlay_note(name: str) -> str:
    """Where the overlays of case `name` come from."""
    runs = overlays.load(check_case(name))
    return (f"LAMMPS {runs.version}, pair_style granular, {runs.steps} steps per contact "
            f"(every {overlays.STRIDE}th drawn), run with this case's deck")


def read_upload(data: object) -> History:
    """The history in an uploaded file's bytes `data`: at most `MAX_UPLOAD_BYTES`,
    UTF-8 text, a CSV with columns tau, T, P (`core.dem_check.vectors.parse_history`,
    at most `MAX_UPLOAD_ROWS` rows). ValueError saying what is wrong and where."""
    text = upload_text(data, "a header row tau,T,P and the rows of one contact")
    header, columns = parse_history(text, source=SOURCE, max_rows=MAX_UPLOAD_ROWS)
    return History(columns["tau"], columns["T"], columns["P"], header)


def upload_text(data: object, needs: str) -> str:
    """An uploaded file's bytes `data` as text: at most `MAX_UPLOAD_BYTES`, not empty
    (`needs`: what it must hold, said when it is), UTF-8 without control characters.
    ValueError saying what is wrong and where."""
    if not isinstance(data, bytes):
        raise ValueError("upload one CSV file")
    if len(data) > MAX_UPLOAD_BYTES:
        raise ValueError(too_big(len(data)))
    if not data.strip():
        raise ValueError(f"{SOURCE} is empty: it needs {needs}")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise ValueError(f"{SOURCE} is not a text CSV (byte {err.start + 1} is not "
                         "UTF-8)") from None
    bad = _CONTROL.search(text)
    if bad:
        line = text.count("\n", 0, bad.start()) + 1
        raise ValueError(f"{SOURCE} is not a text CSV (line {line} holds the control "
                         f"character {ord(bad.group()):#04x})")
    return text


def too_big(size: int, max_bytes: int = MAX_UPLOAD_BYTES) -> str:
    """Why a file of `size` bytes is refused (more than `max_bytes`)."""
    return (f"{SOURCE} has {size:,} bytes, more than the {max_bytes:,} accepted: keep "
            "every k-th step")


def size_text(n: int) -> str:
    """`n` bytes as a reader says it: '2 MiB', '360 KiB', '900 bytes'."""
    for unit, scale in (("MiB", 1024 ** 2), ("KiB", 1024)):
        if n >= scale and n % scale == 0:
            return f"{n // scale:,} {unit}"
    return f"{n:,} bytes"


def score_history(name: str, history: History) -> DemScore:
    """`core.dem_check.score` of `history` against case `name`; ValueError (what the
    history lacks, e.g. tau not covering the contact) otherwise."""
    try:
        return score(CASES[check_case(name)], history.tau, history.T, history.P)
    except ValueError as err:
        where = " (x[k]: the k-th data row, from 0)" if re.search(r"\[\d+\]", str(err)) else ""
        raise ValueError(f"{SOURCE} cannot be scored against {name}: {err}{where}") from None


def score_rows(s: DemScore) -> list[tuple[str, str]]:
    """The score table: (quantity, value) rows, in T0, P0 and T0 u0 (docs/dem_check.md)."""
    w = s.loading_work
    return [
        ("impulse ratio T_imp / (μ P_imp)",
         f"{s.impulse_ratio:.7f} (exact {s.exact_impulse_ratio:.7f})"),
        ("impulse-ratio error",
         f"{s.impulse_ratio_error:+.3e} ({100 * s.impulse_ratio_relative_error:+.3f} %)"),
        ("worst |T − T_exact|",
         f"{s.max_T_error:.3e} T₀ at τ = {s.worst_tau:.4f} rad ({s.worst_phase})"),
        ("dissipated energy",
         f"{s.dissipated_energy:.4e} T₀u₀ (exact {s.exact_dissipated_energy:.4e})"),
        ("energy error", f"{s.energy_error:+.3e} T₀u₀ ({s.energy_error / w:+.4f} W_L)"),
        ("energy gain", f"{s.energy_gain:.3e} T₀u₀"),
        ("Coulomb excess max(|T| − μP)", f"{s.coulomb_excess:.3e} T₀"),
        ("worst |P − P_exact|", f"{s.max_P_error:.3e} P₀"),
    ]


def upload_columns(history: History | None) -> dict[str, NDArray[np.float64]]:
    """The history's tau and T to draw (at most about `MAX_PLOT_POINTS`, the last
    sample always kept); empty columns for None."""
    if history is None:
        return {"tau": np.empty(0), "T": np.empty(0)}
    n = history.tau.size
    keep = np.unique(np.append(np.arange(0, n, math.ceil(n / MAX_PLOT_POINTS)), n - 1))
    return {"tau": history.tau[keep], "T": history.T[keep]}


@cache
def vectors_text(name: str) -> str:
    """The test vectors of case `name`, `NAME.csv` of `python -m core.dem_check export`
    (written by `core.dem_check`'s export into a temporary directory, once per process
    and case)."""
    check_case(name)
    with tempfile.TemporaryDirectory(prefix="dem_vectors_") as tmp:
        export(tmp, {name: CASES[name]})
        return (Path(tmp) / f"{name}.csv").read_text()


def vectors_filename(name: str) -> str:
    """The test vectors' file name."""
    return f"{check_case(name)}.csv"


def deck_model(models: list[str]) -> str:
    """The model the deck is written for: the first chosen one, or LAMMPS' `mindlin`."""
    chosen = check_models(models)
    return chosen[0] if chosen else "mindlin"


def deck_text(name: str, model: str) -> str:
    """The LAMMPS input deck of case `name` for `model` at `DECK_STEPS` steps."""
    return lammps.deck(CASES[check_case(name)], model, DECK_STEPS)


def deck_filename(name: str, model: str) -> str:
    """The deck's file name, e.g. 'fig7_psi2.41.mindlin_force.in'."""
    return f"{check_case(name)}.{model.replace('/', '_')}.in"
