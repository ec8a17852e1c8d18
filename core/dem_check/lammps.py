"""Run a case in the real LAMMPS (``lmp``, pair_style granular) and read T / T0, P / P0 of
the held sphere at every step.

``run(case, model, steps)`` fills the deck ``core/dem_check/deck.in`` (a plain LAMMPS input,
documented line by line, that a DEM user can run as it is with ``lmp -in deck.in -var ...``)
with the case, runs ``lmp`` in a temporary directory and parses its output. Geometry and
units (lj; the deck's header): R = 1, H = 1e-7 R, omega = 1, and G chosen so that P0 = 1,
T0 = mu. The force on the held sphere is split along the line of centres (P) and across it
(T) with the positions LAMMPS reports, so that the tilt of the line of centres (u0 / 2R, a
few 1e-8 rad) does not leak P into T. What is left of the geometry is below 1e-7 of T0:
rounding of the centre distance (2R to 1 ulp against an approach of ~1e-7 R) and the tilt's
second order.

Debian's package: ``sudo apt-get install lammps`` (``make lammps``); the 2022 package is
the LAMMPS stable release of 29 Sep 2021 (update 2).
"""

from __future__ import annotations

import math
import re
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from importlib.resources import files
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from core.dem_check.case import Case

#: LAMMPS tangential models and the numba copy of each in ``core.numerics.dem``.
MODELS: dict[str, str] = {
    "linear_history": "lammps_linear_history",
    "mindlin": "lammps_mindlin",
    "mindlin/force": "lammps_mindlin_force",
    "mindlin_rescale": "lammps_mindlin_rescale",
    "mindlin_rescale/force": "lammps_mindlin_rescale_force",
}
MAX_STEPS = 10**7
INSTALL_HINT = ("install Debian's LAMMPS with `make lammps` (or `sudo apt-get install "
                "lammps`), or pass lmp=/path/to/lmp")


class LammpsNotFound(RuntimeError):
    """No ``lmp`` executable; the message says how to install one."""


class LammpsFailed(RuntimeError):
    """``lmp`` ran and failed; the message carries the end of its output."""


@dataclass(frozen=True)
class LammpsRun:
    """One contact of ``case`` run by LAMMPS: T / T0 and P / P0 of the held sphere at the
    times tau = tau0 + k (pi - 2 tau0) / steps, k = 0 .. steps (the step's force is at the
    step's positions)."""

    case: Case
    model: str
    steps: int
    tau: NDArray[np.float64]
    T: NDArray[np.float64]
    P: NDArray[np.float64]
    deck: str = field(repr=False)
    version: str
    seconds: float  # wall time of lmp alone


def template() -> str:
    """The deck's text as shipped (defaults: the paper's psi = 2.414, tau0 = pi/6)."""
    return files("core.dem_check").joinpath("deck.in").read_text()


def _check_model(model: str) -> str:
    if model not in MODELS:
        raise ValueError(f"model must be one of {', '.join(MODELS)}; got {model!r}")
    return model


def _check_steps(steps: object) -> int:
    if isinstance(steps, bool) or not isinstance(steps, int | np.integer) or not (
            10 <= steps <= MAX_STEPS):
        raise ValueError(f"steps must be an integer in [10, {MAX_STEPS}], got {steps!r}")
    return int(steps)


def deck(case: Case, model: str = "mindlin", steps: int = 20000,
         out: str = "forces.txt") -> str:
    """The input deck of ``case``: the template with its ``variable ... index`` defaults
    set to the case, the model, the step count and the output file name."""
    values = {"psi": repr(case.psi), "tau0": repr(case.tau0), "mu": repr(case.mu),
              "nu": repr(case.nu), "model": _check_model(model),
              "steps": str(_check_steps(steps)), "out": out}
    text = template()
    for name, value in values.items():
        text, n = re.subn(rf"^(variable {name}\s+index )\S+", rf"\g<1>{value}", text,
                          count=1, flags=re.M)
        if n != 1:  # the shipped template always has them
            raise RuntimeError(f"deck.in has no 'variable {name} index' line")
    return text


def find_lmp(lmp: str | None = None) -> str:
    """The path of ``lmp`` (or of the executable given); ``LammpsNotFound`` saying how to
    install it otherwise."""
    path = shutil.which(lmp or "lmp")
    if path is None:
        raise LammpsNotFound(f"LAMMPS executable {lmp or 'lmp'!r} not found: {INSTALL_HINT}")
    return path


def version(lmp: str | None = None) -> str:
    """The release line of ``lmp -h``, e.g. '29 Sep 2021 - Update 2'."""
    head = subprocess.run([find_lmp(lmp), "-h"], capture_output=True, text=True,
                          timeout=60).stdout
    m = re.search(r"Large-scale Atomic/Molecular Massively Parallel Simulator - (.+)", head)
    return m.group(1).strip() if m else "unknown"


def forces(case: Case, steps: int, table: NDArray[np.float64]
           ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """(tau, T / T0, P / P0) from the deck's output rows (step, fx, fz, x, z): the force on
    the held sphere at (0, 0, 2) along n = (-x, 2 - z) / |(-x, 2 - z)|, the unit vector
    from the driven centre to it (P), and along the tangent t = (n_z, -n_x) (T, positive
    along the drive). R = 1, P0 = 1 and T0 = mu in the deck's units."""
    step, fx, fz, x, z = table.T
    r = np.hypot(x, 2.0 - z)
    nx, nz = -x / r, (2.0 - z) / r
    dt = (math.pi - 2.0 * case.tau0) / steps
    return case.tau0 + step * dt, (fx * nz - fz * nx) / case.mu, fx * nx + fz * nz


def read_output(path: Path, steps: int) -> NDArray[np.float64]:
    """The rows of the deck's ``fix print`` file: steps + 1 rows of 5 numbers."""
    table = np.loadtxt(path, comments="#", ndmin=2)
    if table.shape != (steps + 1, 5):
        raise LammpsFailed(f"{path}: expected {steps + 1} rows of 5 numbers, got "
                           f"{table.shape[0]} rows of {table.shape[1]}")
    return table


def run(case: Case, model: str = "mindlin", steps: int = 20000, *, lmp: str | None = None,
        timeout: float = 600.0) -> LammpsRun:
    """Run one contact of ``case`` with LAMMPS' tangential ``model`` (one of ``MODELS``) in
    ``steps`` time steps; see the module docstring. ``LammpsNotFound`` without ``lmp``,
    ``LammpsFailed`` with LAMMPS' error if the run fails."""
    exe = find_lmp(lmp)
    text = deck(case, model, steps)
    with tempfile.TemporaryDirectory(prefix="dem_check_") as tmp:
        (Path(tmp) / "deck.in").write_text(text)
        start = time.perf_counter()
        done = subprocess.run([exe, "-in", "deck.in", "-log", "none", "-nocite"], cwd=tmp,
                              capture_output=True, text=True, timeout=timeout)
        seconds = time.perf_counter() - start
        if done.returncode != 0:
            tail = "\n".join((done.stdout + done.stderr).strip().splitlines()[-6:])
            raise LammpsFailed(f"lmp failed (exit {done.returncode}) on {model}, {case}:\n"
                               f"{tail}")
        table = read_output(Path(tmp) / "forces.txt", steps)
        m = re.search(r"LAMMPS \((.+)\)", done.stdout)
    tau, T, P = forces(case, steps, table)
    return LammpsRun(case=case, model=model, steps=steps, tau=tau, T=T, P=P, deck=text,
                     version=m.group(1) if m else "unknown", seconds=seconds)
