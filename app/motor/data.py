"""What the Motor card shows, as columns and results from `core.motor` (no Bokeh or
Panel here): the rod and its stall thrust, the thrust-speed and efficiency curves at x0
(resolved near the best efficiency, which is computed, not read off the points), the
operating point under a load, the start-up from rest, and Archard wear along the rod.

Everything that costs more than a few ms is one job (`compute`) that the card runs on
the job runner; its parts are cached (bounded `lru_cache`), so that a move of x0 does not
recompute the wear along the rod, nor a change of load the curve.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from core.motor import (
    BestEfficiency,
    Motor,
    MotorProfile,
    MovingRotor,
    OperatingPoint,
    StartUp,
    WearProfile,
    best_efficiency,
    full_slip_speed,
    moving_rotor,
    no_load_speed,
    operating_point,
    start_up,
    wear_along_rod,
)
from core.validation import MOTOR_DOMAIN

#: Points along the rod for the drawing and the stall-thrust curve, clustered towards the
#: centre, where the thrust peaks (psi = 1 lies within ~1 % of L of the centre):
#: x = L sinh(c t) / sinh(c), t uniform in (-1, 1); spacing ~6e-5 L at the centre.
ROD_POINTS, ROD_CLUSTER = 1001, 6.0
#: Points along the rod for the wear rate (each costs the dissipation density on 513
#: radii).
WEAR_POINTS = 301
#: Speeds on the thrust-speed curve from stall to full counter-slip, and more inside
#: (0, v0), where the efficiency is defined (the best efficiency is one of the speeds).
SPEED_POINTS, EFFICIENCY_POINTS = 24, 40
#: Significant digits of psi, tau0, mu, nu in the cache key of a thrust-speed curve
#: (the curve is computed at the rounded values: 1e-12 relative, far below its 1e-4).
KEY_DIGITS = 12
CACHE_SIZE = 256


def rod_grid(half_length: float, points: int = ROD_POINTS) -> np.ndarray:
    """`points` points x (m) inside (-L, L), clustered towards the centre."""
    t = np.linspace(-1.0, 1.0, points + 2)[1:-1]
    return half_length * (np.sinh(ROD_CLUSTER * t) / math.sinh(ROD_CLUSTER))


def invalid_runs(x: np.ndarray, opens: np.ndarray, half_length: float
                 ) -> tuple[list[float], list[float]]:
    """(left, right) of each run of points of x (sorted) where the contact never opens,
    a run that reaches the first or last point extended to the rod's end."""
    left: list[float] = []
    right: list[float] = []
    closed = np.concatenate([[False], ~opens, [False]])
    edges = np.flatnonzero(np.diff(closed.astype(np.int8)))
    for i, j in zip(edges[::2], edges[1::2] - 1, strict=True):
        left.append(-half_length if i == 0 else float(x[i]))
        right.append(half_length if j == x.size - 1 else float(x[j]))
    return left, right


def magnifications(motor: Motor) -> tuple[float, float]:
    """(k_u, k_H): the drawing magnifies u0 to 0.35 delta at the rod's end and H to
    0.3 delta at its centre."""
    rod = motor.rod
    return (0.35 * rod.thickness / rod.amplitude,
            0.3 * rod.thickness / max(abs(rod.vertical_amplitude), 1e-300))


def rod_columns(motor: Motor, p: MotorProfile) -> dict[str, np.ndarray]:
    """The rod's drawing on the points of `p` (mm; amplitudes magnified): its top and
    bottom faces at the peak of H, and u0 as a dashed wave."""
    k_u, k_H = magnifications(motor)
    half = 0.5 * motor.rod.thickness * 1e3
    return {"x": p.x0, "x_mm": p.x0 * 1e3, "u0_um": p.u0 * 1e6, "H_um": p.H * 1e6,
            "top": half + k_H * p.H * 1e3, "bottom": -half - k_H * p.H * 1e3,
            "wave": k_u * p.u0 * 1e3}


def rotor_centre(motor: Motor, x0: float) -> tuple[float, float]:
    """(x, y) of the rotor's centre in the drawing (mm): resting on the rod's drawn top
    face at x0 (its peak, H magnified as in `rod_columns`)."""
    _, k_H = magnifications(motor)
    top = 0.5 * motor.rod.thickness + k_H * float(motor.rod.H(x0))
    return x0 * 1e3, (top + motor.R) * 1e3


def end_notes(left: list[float], right: list[float]) -> dict[str, list]:
    """Labels (x in mm, y in mN) for the runs (mm) where the contact never opens: why
    the thrust does not reach the rod's ends."""
    return {"x_mm": [0.5 * (a + b) for a, b in zip(left, right, strict=True)],
            "y": [0.0] * len(left),
            "text": ["contact never opens:\nnormal motion H too small\nfor the preload "
                     "(Φ ≥ 8)"] * len(left)}


# ------------------------------------------------------------------ at the contact x0

@dataclass(frozen=True)
class SpeedCurve:
    """The thrust-speed curve of one contact (dimensionless, from core's moving-rotor
    MDR on `speeds`), its no-load speed v0, its point of best efficiency (one of the
    speeds), and the wall time (s) it took."""

    curve: MovingRotor
    no_load: float
    best: BestEfficiency
    seconds: float


def contact_key(psi: float, tau0: float, mu: float, nu: float) -> tuple[float, ...]:
    """(psi, tau0, mu, nu) rounded to KEY_DIGITS significant digits: the cache key, and
    the values the curve is computed at."""
    return tuple(float(f"{x:.{KEY_DIGITS}g}") for x in (psi, tau0, mu, nu))


def speeds(psi: float, tau0: float, v0: float, best: float) -> np.ndarray:
    """The speeds of a curve: SPEED_POINTS from 0 to the full-slip speed, EFFICIENCY_POINTS
    inside (0, v0), v0 and the best efficiency's speed; sorted, distinct."""
    v = np.concatenate([np.linspace(0.0, full_slip_speed(psi, tau0), SPEED_POINTS),
                        np.linspace(0.0, v0, EFFICIENCY_POINTS + 2), [best]])
    return np.unique(v)


@lru_cache(maxsize=CACHE_SIZE)
def speed_curve(psi: float, tau0: float, mu: float, nu: float) -> SpeedCurve:
    """Core's `moving_rotor` at `speeds`, `no_load_speed` and `best_efficiency` at
    (psi, tau0, mu, nu) (pass a `contact_key`); cached, bounded."""
    start = time.perf_counter()
    v0 = no_load_speed(psi, tau0, mu=mu, nu=nu)
    best = best_efficiency(psi, tau0, mu=mu, nu=nu)
    curve = moving_rotor(psi, tau0, speeds(psi, tau0, v0, best.v), mu=mu, nu=nu)
    return SpeedCurve(curve, v0, best, time.perf_counter() - start)


def scales(motor: Motor, x0: float) -> tuple[float, float, float]:
    """(m/s per unit of v, N per unit of r, W per unit of power) at x0: omega |u0|,
    mu N and mu N omega |u0| (core's scales of `MovingRotor`)."""
    speed = motor.rod.omega * abs(float(motor.rod.u0(x0)))
    force = motor.mu * motor.preload
    return speed, force, force * speed


def no_curve(motor: Motor, x0: float, p: MotorProfile) -> str:
    """Why there is no thrust-speed curve at x0, in plain words ('' if there is one)."""
    at = f"x₀ = {x0 * 1e3:.6g} mm"
    if not p.opens:
        return (f"The contact never opens at {at} (Φ = {float(p.load_factor):.3g} ≥ 8): the "
                "model does not apply there, and there is no thrust.")
    if not MOTOR_DOMAIN["psi_moving"].contains(float(p.psi)):
        if float(p.psi) < 1.0:
            return (f"At {at} the rod barely moves along x (ψ = {float(p.psi):.3g}): at its "
                    "centre it does not at all, and drives nothing: move the rotor off "
                    "the centre.")
        return f"At {at} ψ = {float(p.psi):.3g} is beyond the moving rotor's range."
    return ""


@dataclass(frozen=True)
class AtX0:
    """What the card computes at x0: the curve (None, with `note` saying why, where
    there is none), the operating point and the start-up under the load (None, with a
    note in plain words, where the load stalls the rotor)."""

    key: tuple[float, ...] | None
    curve: SpeedCurve | None
    note: str
    point: OperatingPoint | None
    point_note: str
    start: StartUp | None
    start_note: str


@dataclass(frozen=True)
class Request:
    """One job's inputs in SI: the motor, x0 (m), the load (N) and rotor mass (kg),
    Archard's coefficient and hardness (Pa)."""

    motor: Motor
    x0: float
    load: float
    mass: float
    wear_coefficient: float
    hardness: float


@dataclass(frozen=True)
class Results:
    """A job's results: at x0, and the wear along the rod."""

    at_x0: AtX0
    wear: WearProfile


def stalled(motor: Motor, x0: float, p: MotorProfile, load: float) -> str:
    """The refusal of a load above the stall thrust, in plain words (N)."""
    stall = abs(float(p.stall_thrust))
    return (f"F_L = {load:.6g} N is more than the stall thrust at x₀ = {x0 * 1e3:.6g} mm "
            f"({stall:.4g} N): the rotor cannot move; lower the load or move the rotor.")


@lru_cache(maxsize=CACHE_SIZE)
def at_x0(motor: Motor, x0: float, load: float, mass: float) -> AtX0:
    """The curve, the operating point and the start-up at x0 (m) for a load (N) and a
    rotor mass (kg)."""
    p = motor.profile(x0)
    note = no_curve(motor, x0, p)
    if note:
        return AtX0(None, None, note, None, note, None, note)
    key = contact_key(float(p.psi), float(p.tau0), motor.mu, motor.equivalent[2])
    curve = speed_curve(*key)
    try:
        point, point_note = operating_point(motor, x0, load), ""
    except ValueError:
        point, point_note = None, stalled(motor, x0, p, load)
    try:
        start, start_note = start_up(motor, x0, mass, load), ""
    except ValueError:
        start, start_note = None, stalled(motor, x0, p, load)
    return AtX0(key, curve, "", point, point_note, start, start_note)


@lru_cache(maxsize=32)
def wear(motor: Motor, wear_coefficient: float, hardness: float) -> WearProfile:
    """Archard wear along the rod (`core.motor.wear_along_rod`) on WEAR_POINTS points."""
    x = rod_grid(motor.rod.half_length, WEAR_POINTS)
    return wear_along_rod(motor, x, wear_coefficient, hardness)


def compute(r: Request) -> Results:
    """The job: everything the card shows that costs more than a few ms."""
    return Results(at_x0(r.motor, r.x0, r.load, r.mass),
                   wear(r.motor, r.wear_coefficient, r.hardness))
