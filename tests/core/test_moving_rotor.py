"""The moving rotor (core.motor.moving_rotor): the MDR under the drive relative to a rotor
moving at V = v omega u0. References: core's closed form at v = 0 (eq 41), the annulus
scheme under the same drive (an independent discretisation of the same 3D problem), the
MDR itself at finer resolution (convergence), the energy balance between three
independently computed powers, and the full counter-slip limit (r = -1, p_in = 0,
p_loss = v exactly, from ``full_slip_speed`` on)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest

from core import impulse_ratio
from core.motor import (
    MovingRotor,
    best_efficiency,
    full_slip_speed,
    moving_rotor,
    no_load_speed,
    thrust_speed_curve,
)
from core.motor.moving_rotor import SPRINGS, STEPS
from core.numerics import annulus
from core.numerics.loading import drive_grid, drive_switches, trapezoid

PI6 = math.pi / 6
# psi < 1, psi = 1, the paper's psi of Fig. 7b, deep preload, grazing
STALL_CASES = [
    (0.4, PI6), (0.8, -1.0), (1.0, PI6), (1.0, -1.3), (2.414213562373095, PI6),
    (6.46, PI6), (28.35, PI6), (28.35, 0.0), (5.0, -1.4), (3.0, 1.5), (0.7, 1.569),
    (1e4, 0.3),
]
CURVE_CASES = [(0.5, 0.3), (1.0, 0.0), (2.414, PI6), (28.35, 0.0), (5.0, -1.3), (3.0, 1.4),
               (1e3, -0.5)]


def closed_form(psi: float, tau0: float) -> float:
    return float(impulse_ratio([psi], tau0)[0])


# ---- v = 0: the paper's held rotor ----------------------------------------------------
@pytest.mark.parametrize(("psi", "tau0"), STALL_CASES)
def test_stall_thrust_is_eq_41(psi: float, tau0: float) -> None:
    r = float(moving_rotor(psi, tau0, 0.0).thrust_ratio)
    if psi <= 1.0:  # full stick: T = psi P spring by spring, at any resolution
        assert r == pytest.approx(psi, abs=1e-12)
    assert abs(r - closed_form(psi, tau0)) < 5e-6


@pytest.mark.parametrize(("psi", "tau0"), [(2.414213562373095, PI6), (28.35, 0.0),
                                           (5.0, -1.4)])
def test_stall_error_falls_with_resolution(psi: float, tau0: float) -> None:
    exact = closed_form(psi, tau0)
    errs = [abs(float(moving_rotor(psi, tau0, 0.0, springs=100 * k, steps=300 * k)
                      .thrust_ratio) - exact) for k in (1, 4, 16)]
    assert errs[2] < errs[0] / 16 and errs[1] < 5e-6, errs


@pytest.mark.parametrize(("psi", "tau0"), [(0.3, PI6), (0.9, -1.2), (1.0, 0.0), (1.0, 1.5)])
def test_no_loss_in_full_stick(psi: float, tau0: float) -> None:
    res = moving_rotor(psi, tau0, 0.0)
    assert float(res.friction_loss) <= (1e-15 if psi == 1.0 else 0.0)
    assert abs(float(res.input_power)) < 1e-4  # the stored energy comes back
    assert float(res.efficiency) == 1.0  # the limit v -> 0+ (loss ~ v^2)
    # a slow rotor: 1e-3 of the rod's largest surface speed during contact
    small = moving_rotor(psi, tau0, 1e-3 * math.cos(max(tau0, 0.0)))
    assert float(small.friction_loss) < 1e-5 and float(small.efficiency) > 0.99


def test_held_rotor_above_psi_one_loses_energy() -> None:
    res = moving_rotor(2.414, PI6, 0.0)
    assert float(res.friction_loss) > 0.1 and float(res.efficiency) == 0.0
    assert float(res.input_power) == pytest.approx(float(res.friction_loss), abs=2e-5)


# ---- convergence: the defaults hold r to 1e-4 -------------------------------------------
@pytest.mark.parametrize(("psi", "tau0"), CURVE_CASES)
def test_curve_is_converged_to_1e_4_at_the_defaults(psi: float, tau0: float) -> None:
    v = np.linspace(0.0, full_slip_speed(psi, tau0), 16)
    runs = [moving_rotor(psi, tau0, v, springs=SPRINGS * k, steps=STEPS * k).thrust_ratio
            for k in (1, 2, 4)]
    err_default = np.abs(runs[0] - runs[2]).max()
    err_double = np.abs(runs[1] - runs[2]).max()
    # the finest run is the reference: the error falls (about 4x per doubling, at
    # least 2x), so its own error is below the difference it measures
    assert err_double < err_default / 2 or err_default < 1e-7, (err_default, err_double)
    assert err_default < 3e-5, err_default  # target 1e-4, with a margin


# ---- the annulus scheme under the same drive ---------------------------------------------
def annulus_ratio(psi: float, tau0: float, v: float, rings: int) -> float:
    # 16 steps per ring: with 4 (the default for eq 3) the time-step error of a short,
    # grazing contact would hide the ring count's
    tau, T, P = annulus.moving(psi, tau0, v, rings, 16 * rings)
    return trapezoid(T, tau) / trapezoid(P, tau)


@pytest.mark.parametrize(("psi", "tau0"), [(0.5, 0.3), (1.0, 0.0), (2.414, PI6),
                                           (28.35, 0.0), (5.0, -1.0), (3.0, 1.4)])
def test_annulus_agrees_within_its_convergence_error(psi: float, tau0: float) -> None:
    for frac in (0.1, 0.35, 0.7):
        v = frac * full_slip_speed(psi, tau0)
        r = float(moving_rotor(psi, tau0, v).thrust_ratio)
        a16, a32, a64 = (annulus_ratio(psi, tau0, v, n) for n in (16, 32, 64))
        gap = abs(a64 - r)
        # the annulus converges (first order for psi <= 1, faster above) to the MDR value:
        # its error at 64 rings, about |a64 - a32|, bounds the gap, and the gap closes
        assert gap <= 2.0 * abs(a64 - a32) + 1e-9, (v, r, a16, a32, a64)
        assert gap <= 0.5 * abs(a16 - r) + 1e-9, (v, r, a16, a32, a64)


# ---- energy balance --------------------------------------------------------------------
@pytest.mark.parametrize(("psi", "tau0"), CURVE_CASES)
def test_energy_balance_closes_and_its_error_falls(psi: float, tau0: float) -> None:
    v = np.linspace(0.0, full_slip_speed(psi, tau0), 12)
    res = [moving_rotor(psi, tau0, v, springs=100 * k, steps=300 * k) for k in (1, 2, 4)]
    worst = [float(np.abs(r.energy_residual).max()) for r in res]
    assert worst[1] < 1e-4 * (1 + v[-1]), worst  # the defaults' resolution
    # second order (1/16 over two doublings; first order would give 1/4)
    assert worst[2] < worst[1] < worst[0] and worst[2] < worst[0] / 10, worst
    assert np.all(res[1].friction_loss >= 0.0)


def test_powers_are_their_definitions() -> None:
    v = np.array([0.05, 0.2, 0.4])
    res = moving_rotor(2.414, PI6, v)
    np.testing.assert_array_equal(res.output_power, v * res.thrust_ratio)
    motoring = res.thrust_ratio > 0
    eta = res.output_power / res.input_power
    np.testing.assert_allclose(res.efficiency[motoring], eta[motoring], atol=1e-4)
    assert np.isnan(res.efficiency[~motoring]).all()  # beyond the no-load speed


# ---- large speed: full counter-slip ------------------------------------------------------
@pytest.mark.parametrize(("psi", "tau0"), CURVE_CASES)
def test_full_counter_slip_at_large_speed(psi: float, tau0: float) -> None:
    vf = full_slip_speed(psi, tau0)
    res = moving_rotor(psi, tau0, [0.9 * vf, vf, 1.5 * vf, 40.0 * vf])
    assert res.thrust_ratio[0] > -1.0 + 1e-6  # not yet: the bound is sharp
    np.testing.assert_allclose(res.thrust_ratio[1:], -1.0, atol=1e-12)
    np.testing.assert_allclose(res.input_power[1:], 0.0, atol=1e-4)
    np.testing.assert_allclose(res.friction_loss[1:], res.v[1:], rtol=1e-4)


def test_thrust_falls_with_speed_through_no_load() -> None:
    for psi, tau0 in CURVE_CASES:
        c = thrust_speed_curve(psi, tau0)
        assert c.v.size == 40 and c.v[0] == 0.0
        assert np.all(np.diff(c.thrust_ratio) <= 1e-6), (psi, tau0)
        assert c.thrust_ratio[0] > 0.0 and c.thrust_ratio[-1] == pytest.approx(-1.0)


# ---- no-load speed and best efficiency ---------------------------------------------------
@pytest.mark.parametrize(("psi", "tau0"), [(0.5, 0.3), (2.414, PI6), (28.35, 0.0)])
def test_no_load_speed_is_the_zero_of_the_curve(psi: float, tau0: float) -> None:
    v0 = no_load_speed(psi, tau0)
    r = moving_rotor(psi, tau0, [v0, 0.99 * v0, 1.01 * v0]).thrust_ratio
    assert abs(r[0]) < 1e-8 and r[1] > 0.0 > r[2]
    fine = no_load_speed(psi, tau0, springs=4 * SPRINGS, steps=4 * STEPS)
    assert abs(v0 - fine) < 1e-4


def test_best_efficiency() -> None:
    best = best_efficiency(2.414, PI6)
    v = np.linspace(0.0, no_load_speed(2.414, PI6), 41)
    eta = moving_rotor(2.414, PI6, v).efficiency
    assert 0.0 < best.v < v[-1]
    assert best.efficiency >= np.nanmax(eta) - 1e-6
    assert best.thrust_ratio == pytest.approx(
        float(moving_rotor(2.414, PI6, best.v).thrust_ratio), abs=1e-12)
    stick = best_efficiency(0.5, PI6)  # psi <= 1: the stall limit
    assert (stick.v, stick.efficiency) == (0.0, 1.0)
    assert stick.thrust_ratio == pytest.approx(0.5, abs=1e-12)


# ---- the time grid ---------------------------------------------------------------------
@pytest.mark.parametrize(("psi", "tau0", "v"), [(28.35, 0.0, 0.1), (5.0, -1.0, 0.6),
                                                (0.5, 0.3, 0.4), (3.0, 1.5, 0.2)])
def test_drive_grid_holds_the_reversals_and_switches(psi: float, tau0: float, v: float
                                                     ) -> None:
    grid = drive_grid(psi, tau0, v, 200)
    assert grid[0] == tau0 and grid[-1] == math.pi - tau0 and np.all(np.diff(grid) > 0)
    reversals, switches = drive_switches(psi, tau0, v)
    for t in reversals:  # the relative drive's rate vanishes there
        assert math.cos(t) - v == pytest.approx(0.0, abs=1e-12)
    for t in reversals + switches:
        assert t in grid
    assert abs(grid.size - 201) <= 6


# ---- result and validation -------------------------------------------------------------
def test_result_shape_and_read_only() -> None:
    res = moving_rotor(2.0, 0.1, [[0.0, 0.1], [0.2, 0.3]])
    assert isinstance(res, MovingRotor)
    assert res.thrust_ratio.shape == res.efficiency.shape == (2, 2)
    with pytest.raises(ValueError):
        res.thrust_ratio[0, 0] = 1.0
    scalar = moving_rotor(2.0, 0.1, 0.2)
    assert scalar.thrust_ratio.shape == ()
    assert float(scalar.thrust_ratio) == float(res.thrust_ratio[1, 0])


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"v": -0.1}, r"v = -0\.1 is outside the allowed range \[0, 1e\+06\]"),
    ({"v": [0.1, math.nan]}, r"v\[1\] must be a finite number in \[0, 1e\+06\], got nan"),
    ({"v": [0.0, 2e6]}, r"v\[1\] = 2e\+06 is outside the allowed range"),
    ({"v": "fast"}, r"v must be real numbers in \[0, 1e\+06\], got 'fast'"),
    ({"v": [True]}, r"v must be real numbers .* got dtype bool"),
    ({"v": []}, r"v must be real numbers .* got no value"),
    ({"psi": 0.0}, r"psi = 0 is outside the allowed range \(0, 1e\+12\]"),
    ({"psi": math.inf}, r"psi must be a finite number"),
    ({"tau0": math.pi / 2}, r"tau0 = 1\.5707963267948966 is outside the allowed range "
                            r"\(-1\.5708, 1\.5708\)"),
    ({"mu": 0.0}, r"mu = 0 is outside the allowed range \(0, 1000\]"),
    ({"nu": 0.6}, r"nu = 0\.6 is outside the allowed range \(-1, 0\.5\]"),
    ({"nu": "x"}, r"nu must be a real number in \(-1, 0\.5\], got 'x'"),
    ({"springs": 1}, r"springs must be an integer in \[2, 1000000\], got 1"),
    ({"steps": 2.5}, r"steps must be an integer"),
])
def test_bad_input_is_refused_with_its_name_value_and_range(kwargs: dict, message: str
                                                            ) -> None:
    args = {"psi": 2.0, "tau0": 0.1, "v": 0.1} | kwargs
    with pytest.raises(ValueError, match=message):
        moving_rotor(**args)


def test_curve_and_point_functions_validate() -> None:
    with pytest.raises(ValueError, match="psi = -1 is outside"):
        thrust_speed_curve(-1.0, 0.1)
    with pytest.raises(ValueError, match="v_max = -1 is outside"):
        thrust_speed_curve(2.0, 0.1, v_max=-1.0)
    with pytest.raises(ValueError, match="n must be an integer"):
        thrust_speed_curve(2.0, 0.1, n=1)
    with pytest.raises(ValueError, match="tau0 = 2 is outside"):
        no_load_speed(2.0, 2.0)
    with pytest.raises(ValueError, match=r"mu = -0\.2 is outside"):
        best_efficiency(2.0, 0.1, mu=-0.2)


# ---- the README's Motor example ----------------------------------------------------------
def test_readme_motor_example_runs_and_its_figures_hold() -> None:
    text = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    section = text[text.index("### Motor"):]
    code = re.search(r"```python\n(.*?)```", section, flags=re.S).group(1)
    ns: dict = {}
    exec(compile(code, "README.md (Motor)", "exec"), ns)
    assert (round(ns["psi"], 3), round(ns["tau0"], 3)) == (1.361, 0.528)
    assert round(ns["v0"], 3) == 0.368
    best = ns["best"]
    assert (round(best.v, 3), round(best.efficiency, 3), round(best.thrust_ratio, 3)) == (
        0.120, 0.694, 0.729)
    assert round(ns["speed"], 4) == 0.0395
    m, speed = ns["m"], ns["speed"]
    # the table: stall thrust (mN), no-load speed (mm/s), best efficiency at (mm/s, mN)
    rows = {-0.2e-3: (9.17, 14.5, 69.4, 4.75, 7.29), -10e-3: (1.47, 179, 1.0, 89, 0.74)}
    for x0, (stall, v0_mm, eta_pc, v_best_mm, thrust_best) in rows.items():
        psi, tau0 = float(m.psi(x0)), float(m.tau0(x0))
        speed = m.rod.omega * abs(float(m.rod.u0(x0)))
        mu_n = m.mu * m.preload * 1e3  # mN
        b = best_efficiency(psi, tau0)
        assert float(moving_rotor(psi, tau0, 0.0).thrust_ratio) * mu_n == pytest.approx(
            stall, abs=0.006)
        assert no_load_speed(psi, tau0) * speed * 1e3 == pytest.approx(v0_mm, rel=4e-3)
        assert b.efficiency * 100 == pytest.approx(eta_pc, abs=0.06)
        assert b.v * speed * 1e3 == pytest.approx(v_best_mm, rel=0.01)
        assert b.thrust_ratio * mu_n == pytest.approx(thrust_best, abs=0.006)
