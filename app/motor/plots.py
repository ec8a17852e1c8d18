"""The job's results (`app.motor.data.Results`) drawn into the Motor card's figures
(`app.motor.figures.MotorFigures`), and the texts that go with them (HTML)."""

from __future__ import annotations

import math

import numpy as np

import app.motor.data as data
from app.kit.figures import fit_range
from app.kit.widgets import text_html
from app.kit.wire import inline
from app.motor.figures import BEST_COLOR, NO_LOAD_COLOR, MotorFigures
from core.motor import Motor


def empty(*sources) -> None:
    for s in sources:
        s.data = {k: [] for k in s.data}


def curve(f: MotorFigures, motor: Motor, x0: float, at: data.AtX0) -> str:
    """Draw the thrust-speed and efficiency curves at x0; the status text."""
    if at.curve is None:
        empty(f.speed, f.marks)
        return text_html(at.note)
    speed, force, _ = data.scales(motor, x0)
    result = at.curve
    c = result.curve
    V = c.v * speed * 1e3
    thrust = c.thrust_ratio * force * 1e3
    eta = c.efficiency * 100.0
    f.speed.data = inline({"v": c.v, "thrust_ratio": c.thrust_ratio,
                           "efficiency": c.efficiency, "V_mm_s": V, "thrust_mN": thrust,
                           "efficiency_pct": eta})
    b = result.best
    f.marks.data = {"V_mm_s": [result.no_load * speed * 1e3, b.v * speed * 1e3],
                    "thrust_mN": [0.0, b.thrust_ratio * force * 1e3],
                    "efficiency_pct": [math.nan, b.efficiency * 100.0],
                    "label": [NO_LOAD_COLOR, BEST_COLOR]}
    f.speed_figure.x_range.start, f.speed_figure.x_range.end = 0.0, float(V[-1])
    fit_range(f.speed_figure.y_range, thrust, pad=0.05)
    fit_range(f.efficiency_figure.y_range, [0.0], eta, pad=0.05)
    psi, tau0 = at.key[:2]
    return (f"ψ = {psi:.6g}, τ₀ = {tau0:.4f} rad: no-load speed "
            f"<b>{result.no_load * speed * 1e3:.4g} mm/s</b> (pink); best efficiency "
            f"<b>{b.efficiency * 100:.3g} %</b> at {b.v * speed * 1e3:.4g} mm/s, "
            f"{b.thrust_ratio * force * 1e3:.4g} mN (yellow). {c.v.size} speeds by MDR "
            f"in {result.seconds * 1e3:.0f} ms.")


def load(f: MotorFigures, at: data.AtX0) -> str:
    """Mark the operating point and draw the start-up; the operating point's text."""
    p = at.point
    if p is None:
        empty(f.operating)
    else:
        f.operating.data = {"V_mm_s": [p.speed * 1e3], "thrust_mN": [p.load * 1e3],
                            "efficiency_pct": [p.efficiency * 100.0]}
    s = at.start
    if s is None:
        empty(f.start)
    else:
        f.start.data = inline({"t_ms": s.t * 1e3, "V_mm_s": s.speed * 1e3})
    if p is None:
        return text_html(at.point_note)
    text = (f"Under F_L = {p.load:.4g} N: speed <b>{p.speed * 1e3:.4g} mm/s</b>, output "
            f"power <b>{p.output_power * 1e3:.4g} mW</b>, efficiency "
            f"<b>{p.efficiency * 100:.3g} %</b> (white square).")
    if s is not None:
        text += (f" From rest it reaches 90 % of that speed in {s.t90 * 1e3:.3g} ms, 99 % "
                 f"in {s.t99 * 1e3:.3g} ms ({s.periods_per_unit:.3g} rod periods per "
                 "time unit: the steady curve applies when this is large).")
    return text


def wear(f: MotorFigures, w: data.WearProfile) -> None:
    """Draw the wear rate along the rod (µm per hour)."""
    f.wear.data = inline({"x_mm": w.x0 * 1e3, "peak_um_h": w.peak_depth_rate * 1e6,
                          "centre_um_h": w.centre_depth_rate * 1e6})


def deepest(w: data.WearProfile) -> str:
    """Where the rod wears most (the largest peak depth rate), as text."""
    if not np.isfinite(w.peak_depth_rate).any():
        return ""
    i = int(np.nanargmax(w.peak_depth_rate))
    return (f"The rod wears most at x₀ = {w.x0[i] * 1e3:.3g} mm: "
            f"{w.peak_depth_rate[i] * 1e6:.3g} µm per hour of operation.")
