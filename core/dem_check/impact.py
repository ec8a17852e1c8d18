"""Chung & Ooi's impact tests in the real LAMMPS and in the exact reference, and their
scores.

``run(impact, model)`` fills ``core/dem_check/impact_deck.in`` (pair_style granular, the
same contact code as the paper's-loading bench) with the impact, runs ``lmp`` and reads
the rebound; ``exact(impact)`` is ``core.impact.solve``. ``curves(test, material, model,
incidences)`` gives both over incidence as ``Rebounds`` (tangential restitution of the
centre, rebound spin, rebound angle of the contact point, contact-point restitution,
normal restitution, contact time) and ``score_curve`` compares two curves the way
``core.dem_check.score`` compares force histories: signed differences, worst |difference|
and where (the incidence), mean |difference|.

A flat is emulated by a held sphere of radius 1e4 R1 with the modulus raised by
(1 + R1 / R2)^(1/2), which restores E* R*^(1/2) and G_e R*^(1/2) of the flat exactly (both
Hertz's force and Mindlin's k_t scale with them); what remains is the tilt of the line of
centres as the sphere slides (slide / R2 ~ 1e-6 rad). The pair's moduli are given
directly: 2 E* (1 - nu^2) with the pair's nu makes LAMMPS' E_eff = E* and G_eff = G_e
for a rigid target of the sphere's material or for two identical spheres (the cases of
Chung & Ooi); other pairs are refused. Normal damping for e < 1: LAMMPS' ``damping tsuji``
given the input that makes its normal impact rebound with e (``lammps_tsuji_input``), so
that both codes have the same normal restitution and the scores measure the tangential
models. LAMMPS takes the torque arm as R1 - delta / 2 (the
small-strain reference takes R1), a difference of order alpha* / R1 in the spin (1e-3 in
test 4).
"""

from __future__ import annotations

import math
import re
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from functools import lru_cache
from importlib.resources import files
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from core.dem_check.impact_cases import impact_test
from core.dem_check.lammps import MODELS, LammpsFailed, _check_model, find_lmp
from core.impact import Impact, dashpot, solve, tsuji_coefficient

FLAT_RADIUS = 1e4  # the held sphere standing for a flat, in sphere radii
HERTZ_TIME = 2.9432751  # elastic Hertz contact time in alpha* / v_n
DEFAULT_STEPS = 2000  # LAMMPS time steps per Hertz contact time
QUANTITIES = ("tangential_cor", "rebound_spin", "rebound_angle", "contact_point_cor",
              "normal_cor", "contact_time")


def tsuji_input(e: float, springs: int = 2000, tol: float = 1e-9) -> float:
    """The restitution to give LAMMPS' ``damping tsuji`` so that its dashpot is the
    reference's for e: LAMMPS turns its input into the factor c by Tsuji's polynomial
    (``core.impact.tsuji_coefficient``), which misses the e it is given (0.98 -> 0.9863,
    0.5 -> 0.616 in these runs); the input whose polynomial value is the reference's
    c = gamma / (5/4)^(1/2) (``core.impact.dashpot``) makes both codes one normal model,
    so that the scores measure the tangential models. 1 for e = 1."""
    if e >= 1.0:
        return 1.0
    c = dashpot(e, springs, tol) / math.sqrt(1.25)
    return float(brentq(lambda x: tsuji_coefficient(x) - c, 0.0, 1.0, xtol=1e-15))


def template() -> str:
    """The impact deck as shipped."""
    return files("core.dem_check").joinpath("impact_deck.in").read_text()


def deck_values(impact: Impact, model: str = "mindlin", steps: int = DEFAULT_STEPS,
                e_input: float | None = None) -> dict[str, str]:
    """The deck's variables for ``impact``: geometry, the pair's moduli (module
    docstring), velocities, time step (the Hertz contact time / steps), run length and
    the restitution given to ``damping tsuji`` (``e_input``; ``tsuji_input(e)`` when
    None)."""
    _check_model(model)
    if isinstance(steps, bool) or not isinstance(steps, int) or not 50 <= steps <= 10**6:
        raise ValueError(f"steps must be an integer in [50, 1000000], got {steps!r}")
    t = impact.target
    m1 = impact.material
    if t.material is not None and (t.material != m1 or t.radius != impact.radius):
        raise ValueError("LAMMPS runs take a rigid target or two identical spheres (one "
                         "material and one Poisson ratio for the pair)")
    nu = m1.nu
    R2 = FLAT_RADIUS * impact.radius if t.is_flat else t.radius
    comp = math.sqrt(1.0 + impact.radius / R2) if t.is_flat else 1.0
    Eeff = 2.0 * impact.E_star * (1.0 - nu * nu) * comp
    a_max = math.sqrt(impact.R_star * impact.alpha_star)
    kt = 8.0 * impact.G_e * a_max * comp
    dt = HERTZ_TIME * impact.time_scale / steps
    rho2 = t.material.density if t.free else 1e3 * m1.density
    e_in = float(tsuji_input(impact.e) if e_input is None else e_input)
    return {"R1": repr(impact.radius), "rho1": repr(m1.density), "R2": repr(R2),
            "rho2": repr(rho2), "free": "1" if t.free else "0", "Eeff": repr(Eeff),
            "nu": repr(nu), "mu": repr(impact.mu), "e": repr(e_in),
            "model": model,
            "kt": repr(kt) if model == "linear_history" else "NULL",
            "vx": repr(impact.vx), "vz": repr(impact.vz), "w": repr(impact.w),
            "vx2": repr(impact.vx2), "vz2": repr(impact.vz2), "w2": repr(impact.w2),
            "dt": repr(dt), "steps": str(int(1.4 * steps) + 10), "out": "impact.txt"}


def deck(impact: Impact, model: str = "mindlin", steps: int = DEFAULT_STEPS,
         e_input: float | None = None) -> str:
    """The input deck of ``impact``: the template with its ``index`` defaults set."""
    text = template()
    for name, value in deck_values(impact, model, steps, e_input).items():
        text, n = re.subn(rf"^(variable {name}\s+index )\S+", rf"\g<1>{value}", text,
                          count=1, flags=re.M)
        if n != 1:
            raise RuntimeError(f"impact_deck.in has no 'variable {name} index' line")
    return text


@dataclass(frozen=True)
class Rebound:
    """The rebound of one impact (either code), SI units, spins about y (``core.impact``)."""

    tangential_cor: float  # vx' / vx (nan for vx = 0)
    rebound_spin: float  # w' (rad/s)
    rebound_angle: float  # atan(v_slip' / v_n') (deg)
    contact_point_cor: float  # -v_slip' / v_slip
    normal_cor: float
    contact_time: float  # s
    vx: float
    vz: float
    w2: float = 0.0
    seconds: float = 0.0


def _rebound(impact: Impact, vx: float, vz: float, w: float, vx2: float, vz2: float,
             w2: float, contact_time: float, seconds: float = 0.0) -> Rebound:
    r2 = impact.target.radius if impact.target.free else 0.0
    slip = (vx - impact.radius * w) - (vx2 + r2 * w2)
    vn = vz - vz2
    vs0 = impact.slip_velocity
    return Rebound(
        tangential_cor=vx / impact.vx if impact.vx else math.nan, rebound_spin=w,
        rebound_angle=math.degrees(math.atan2(slip, vn)),
        contact_point_cor=-slip / vs0 if vs0 else math.nan, normal_cor=vn / impact.v_n,
        contact_time=contact_time, vx=vx, vz=vz, w2=w2, seconds=seconds)


def exact(impact: Impact, springs: int = 2000, tol: float = 1e-9) -> Rebound:
    """The exact reference's rebound (``core.impact.solve``)."""
    start = time.perf_counter()
    r = solve(impact, springs, tol)
    return _rebound(impact, r.vx, r.vz, r.w, r.vx2, r.vz2, r.w2, r.contact_time,
                    time.perf_counter() - start)


def run(impact: Impact, model: str = "mindlin", steps: int = DEFAULT_STEPS, *,
        lmp: str | None = None, timeout: float = 600.0) -> Rebound:
    """LAMMPS' rebound for ``impact`` with tangential ``model``; ``steps`` time steps per
    Hertz contact time. ``LammpsNotFound`` without ``lmp``, ``LammpsFailed`` on error."""
    exe = find_lmp(lmp)
    e_in = None if impact.e >= 1.0 else lammps_tsuji_input(impact.e, steps, exe)
    return _run(impact, model, steps, exe, e_in, timeout)


def _run(impact: Impact, model: str, steps: int, exe: str, e_in: float | None,
         timeout: float = 600.0) -> Rebound:
    text = deck(impact, model, steps, e_in)
    values = deck_values(impact, model, steps, e_in)
    with tempfile.TemporaryDirectory(prefix="dem_impact_") as tmp:
        (Path(tmp) / "impact_deck.in").write_text(text)
        start = time.perf_counter()
        done = subprocess.run([exe, "-in", "impact_deck.in", "-log", "none", "-nocite"],
                              cwd=tmp, capture_output=True, text=True, timeout=timeout)
        seconds = time.perf_counter() - start
        if done.returncode != 0:
            tail = "\n".join((done.stdout + done.stderr).strip().splitlines()[-6:])
            raise LammpsFailed(f"lmp failed (exit {done.returncode}) on {model}:\n{tail}")
        table = np.loadtxt(Path(tmp) / "impact.txt", comments="#", ndmin=2)
    if table.shape[1] != 9 or table.shape[0] < 10:
        raise LammpsFailed(f"impact.txt: unexpected shape {table.shape}")
    touching = np.flatnonzero(table[:, 2] != 0.0)
    if touching.size == 0 or touching[-1] >= table.shape[0] - 2:
        raise LammpsFailed("the sphere did not leave the target within the run")
    contact_time = touching.size * float(values["dt"])
    last = table[-1]
    return _rebound(impact, last[3], last[4], last[5], last[6], last[7], last[8],
                    contact_time, seconds)


@lru_cache(maxsize=32)
def lammps_tsuji_input(e: float, steps: int = DEFAULT_STEPS, lmp: str | None = None) -> float:
    """The input of LAMMPS' ``damping tsuji`` with which its normal impact rebounds with
    e (to 1e-7), found by the secant method from ``tsuji_input(e)`` on LAMMPS' own normal
    impact (Tsuji's e depends on nothing else; LAMMPS lets the dashpot pull at the end
    of the contact, where the reference's force stops at zero, so the polynomial's
    inverse alone misses e by 8e-5 at e = 0.98 and by 0.06 at e = 0.5)."""
    from core.impact import Material
    exe = find_lmp(lmp)
    probe = Impact(radius=1e-3, material=Material("probe", 1e10, 0.3, 1000.0), mu=0.1,
                   e=e, vz=-1.0)

    def miss(x: float) -> float:
        return _run(probe, "mindlin", steps, exe, x).normal_cor - e

    x0 = tsuji_input(e)
    x1 = min(x0 + 0.01, 1.0) if x0 < 0.99 else x0 - 0.01
    f0, f1 = miss(x0), miss(x1)
    for _ in range(12):
        if abs(f1) < 1e-7 or f1 == f0:
            break
        x0, x1, f0 = x1, min(max(x1 - f1 * (x1 - x0) / (f1 - f0), 0.0), 0.999999), f1
        f1 = miss(x1)
    return float(x1)


@dataclass(frozen=True)
class Curves:
    """A quantity of ``QUANTITIES`` over incidence for one code."""

    incidence_deg: tuple[float, ...]
    rebounds: tuple[Rebound, ...] = field(repr=False)

    def get(self, name: str) -> NDArray[np.float64]:
        if name not in QUANTITIES:
            raise ValueError(f"quantity must be one of {', '.join(QUANTITIES)}, got {name!r}")
        return np.array([getattr(r, name) for r in self.rebounds])

    def as_dict(self) -> dict[str, list[float | None]]:
        return {q: [None if not math.isfinite(v) else float(v) for v in self.get(q)]
                for q in QUANTITIES}


def check_incidences(values: ArrayLike) -> tuple[float, ...]:
    """Incidences (deg) as a tuple of finite numbers in [0, 90), at least one."""
    try:
        a = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError):
        raise ValueError("incidence must be a list of numbers (deg)") from None
    if a.ndim != 1 or a.size == 0 or a.size > 1000:
        raise ValueError("incidence must be a list of 1 to 1000 angles (deg)")
    bad = np.flatnonzero(~(np.isfinite(a) & (a >= 0) & (a < 90)))
    if bad.size:
        raise ValueError(f"incidence[{bad[0]}] = {float(a[bad[0]])!r} deg is outside "
                         "[0, 90)")
    return tuple(float(v) for v in a)


def exact_curves(test: int, material: str, incidences: ArrayLike, springs: int = 2000,
                 tol: float = 1e-9) -> Curves:
    """The exact reference over the incidences of ``test`` with ``material``."""
    t = impact_test(test)
    inc = check_incidences(incidences)
    return Curves(inc, tuple(exact(t.impact(material, th), springs, tol) for th in inc))


def lammps_curves(test: int, material: str, model: str, incidences: ArrayLike,
                  steps: int = DEFAULT_STEPS, *, lmp: str | None = None) -> Curves:
    """LAMMPS' ``model`` over the incidences of ``test`` with ``material``."""
    t = impact_test(test)
    _check_model(model)
    inc = check_incidences(incidences)
    return Curves(inc, tuple(run(t.impact(material, th), model, steps, lmp=lmp)
                             for th in inc))


@dataclass(frozen=True)
class CurveScore:
    """How far a curve is from the reference over incidence (same incidences)."""

    quantity: str
    worst: float  # max |curve - reference|
    worst_incidence: float  # where (deg)
    mean: float  # mean |curve - reference|
    worst_relative: float  # max |curve - reference| / max |reference|

    def as_dict(self) -> dict[str, float | str]:
        return dict(self.__dict__)


def score_curve(quantity: str, incidence: ArrayLike, curve: ArrayLike, reference: ArrayLike
                ) -> CurveScore:
    """Worst and mean |curve - reference| and where, over the points where both are
    finite (a tangential_cor of an impact without centre tangential velocity is nan)."""
    inc = np.asarray(incidence, dtype=float)
    c = np.asarray(curve, dtype=float)
    r = np.asarray(reference, dtype=float)
    if not inc.shape == c.shape == r.shape or inc.ndim != 1:
        raise ValueError(f"incidence, curve and reference must be 1-d of one length, got "
                         f"{inc.shape}, {c.shape}, {r.shape}")
    ok = np.isfinite(c) & np.isfinite(r)
    if not ok.any():
        return CurveScore(quantity, math.nan, math.nan, math.nan, math.nan)
    diff = np.abs(c[ok] - r[ok])
    k = int(np.argmax(diff))
    scale = float(np.max(np.abs(r[ok])))
    return CurveScore(quantity, float(diff[k]), float(inc[ok][k]), float(diff.mean()),
                      float(diff[k] / scale) if scale else math.nan)


def departure_range(incidence: ArrayLike, curve: ArrayLike, reference: ArrayLike,
                    scatter: float) -> list[tuple[float, float]]:
    """The incidence intervals (deg) where |curve - reference| > scatter, as
    (first, last) sampled incidences of each run of departing points."""
    inc = np.asarray(incidence, dtype=float)
    out = np.abs(np.asarray(curve, float) - np.asarray(reference, float)) > scatter
    runs: list[tuple[float, float]] = []
    start = None
    for i, flag in enumerate(out):
        if flag and start is None:
            start = i
        if (not flag or i == out.size - 1) and start is not None:
            end = i if flag else i - 1
            runs.append((float(inc[start]), float(inc[end])))
            start = None
    return runs


__all__ = ["DEFAULT_STEPS", "MODELS", "QUANTITIES", "CurveScore", "Curves", "Rebound",
           "check_incidences", "deck", "deck_values", "departure_range", "exact",
           "exact_curves", "lammps_curves", "lammps_tsuji_input", "run", "score_curve",
           "template", "tsuji_input"]
