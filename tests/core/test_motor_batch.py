"""The batched figures of merit (core.motor.designs) against the scalar API they batch:
design by design over random designs of core.MOTOR_DOMAIN, and the compiled pieces
(drive grid, march, sum) against the numpy code they replace, bit for bit."""

import importlib
import math

import numpy as np
import pytest

from core.materials import MATERIALS
from core.motor import (
    Motor,
    Rod,
    best_efficiency,
    moving_rotor,
    moving_wear_rate,
    no_load_speed,
    operating_point,
    operating_speed,
)
from core.motor.designs import MERITS, contact_merits, design_merits
from core.motor.load import operating_efficiency
from core.numerics import mdr
from core.numerics.loading import drive_grid, one_minus_s0, relative_drive, rise
from core.validation import MOTOR_DOMAIN

designs = importlib.import_module("core.motor.designs")

#: A coarse MDR for the many random designs (the equality holds at any resolution).
COARSE = {"springs": 24, "steps": 64}
RTOL = 1e-12


def same(a: float, b: float) -> bool:
    """a and b agree to RTOL relative, or are both nan."""
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return abs(a - b) <= RTOL * max(abs(a), abs(b))


def log_uniform(rng: np.random.Generator, lo: float, hi: float) -> float:
    return float(10.0 ** rng.uniform(math.log10(lo), math.log10(hi)))


def random_design(rng: np.random.Generator) -> tuple[Motor, float, float]:
    """A motor, contact point and load drawn across MOTOR_DOMAIN and DOMAIN: rod, rotor
    and rod face each anywhere in their rows, the preload drawn through the load factor
    Phi at the rod's centre (log-uniform in [1e-3, 7.999]) so that most designs open,
    x0 anywhere on the rod, the load up to 1.2 times the stall thrust (some beyond it)."""
    while True:
        L = log_uniform(rng, 1e-6, 1e2)
        rod = Rod(half_length=L, thickness=min(L * log_uniform(rng, 1e-3, 0.5), 1e2),
                  nu_rod=float(rng.uniform(-0.95, 0.5)), amplitude=log_uniform(rng, 1e-12, 0.1),
                  frequency=log_uniform(rng, 1e-3, 1e9))
        R, G = log_uniform(rng, 1e-9, 1e3), log_uniform(rng, 1.0, 1e13)
        nu, mu = float(rng.uniform(-0.95, 0.5)), log_uniform(rng, 1e-2, 10.0)
        face = {}
        if rng.random() < 0.5:
            face = {"rod_G": log_uniform(rng, 1.0, 1e13), "rod_nu": float(rng.uniform(-0.9, 0.5)),
                    "rod_R": math.inf if rng.random() < 0.5 else log_uniform(rng, 1e-9, 1e3)}
        probe = Motor(rod, R=R, G=G, nu=nu, mu=mu, preload=1e-12, **face)
        R_eq, G_eq, nu_eq = probe.equivalent
        H = abs(rod.vertical_amplitude)
        phi = log_uniform(rng, 1e-3, 7.999)
        preload = phi * 4.0 * G_eq * math.sqrt(R_eq) * H ** 1.5 / (9.0 * math.pi * (1.0 - nu_eq))
        if not MOTOR_DOMAIN["preload"].contains(preload):
            continue
        try:
            m = Motor(rod, R=R, G=G, nu=nu, mu=mu, preload=preload, **face)
        except ValueError:
            continue
        x0 = L * float(rng.uniform(-0.999, 0.999))
        stall = abs(float(m.stall_thrust(x0)))
        return m, x0, float(rng.uniform(0.0, 1.2)) * (stall if stall > 0.0 else mu * preload)


def scalar_merits(m: Motor, x0: float, load: float, k: float, hard: float,
                  **res: int) -> dict[str, float]:
    """Every merit of one design from the scalar API, nan where it raises."""
    out = dict.fromkeys(MERITS, math.nan)
    out["stall_thrust"] = abs(float(m.stall_thrust(x0)))
    p = m.profile(x0)
    psi, tau0 = float(p.psi), float(p.tau0)
    scale = m.rod.omega * abs(float(m.rod.u0(x0)))
    try:
        out["no_load_speed"] = no_load_speed(psi, tau0, **res) * scale
    except (ValueError, RuntimeError):
        return out
    b = best_efficiency(psi, tau0, **res)
    out["best_efficiency"], out["best_speed"] = b.efficiency, b.v * scale
    out["best_thrust"] = b.thrust_ratio * (m.mu * m.preload)
    try:
        op = operating_point(m, x0, load, **res)
    except ValueError:
        return out
    out["load_speed"], out["load_efficiency"] = op.speed, op.efficiency
    out["load_power"] = op.output_power
    held = moving_rotor(psi, tau0, op.v, **res)
    out["wear_rate"] = float(moving_wear_rate(m, x0, held, k, hard))
    return out


def test_design_merits_equal_the_scalar_api_over_random_designs() -> None:
    rng = np.random.default_rng(41)
    cases = [random_design(rng) for _ in range(300)]
    k, hard = 1e-6, 2e9
    got = design_merits([c[0] for c in cases], [c[1] for c in cases], [c[2] for c in cases],
                        k, hard, **COARSE)
    moving = solved = 0
    for i, (m, x0, load) in enumerate(cases):
        ref = scalar_merits(m, x0, load, k, hard, **COARSE)
        for name in MERITS:
            value = float(getattr(got, name)[i])
            assert same(value, ref[name]), (i, name, value, ref[name])
        moving += not math.isnan(ref["no_load_speed"])
        solved += not math.isnan(ref["load_speed"])
    assert moving >= 150 and solved >= 50  # the designs exercise every branch
    assert (got.evaluations[~np.isnan(got.no_load_speed)] > 2).all()


def test_design_merits_at_the_default_resolution() -> None:
    """The README's rotor, a steel ball on PZT-4 and one with psi <= 1, at the default
    MDR (200 springs, 600 steps): every merit equal to the scalar API."""
    rod = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
    steel, pzt = MATERIALS["steel"], MATERIALS["PZT-4"]
    motors = [Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05),
              Motor(rod, R=5e-3, G=steel.G, nu=steel.nu, mu=0.2, preload=0.05,
                    rod_G=pzt.G, rod_nu=pzt.nu, rod_R=math.inf)]
    cases = [(motors[0], -0.2e-3, 4e-3), (motors[0], -10e-3, 0.2e-3),
             (motors[1], -2e-3, 1e-3), (motors[1], 1e-4, 0.0)]
    got = design_merits([c[0] for c in cases], [c[1] for c in cases], [c[2] for c in cases],
                        1e-6, 2e9)
    for i, (m, x0, load) in enumerate(cases):
        ref = scalar_merits(m, x0, load, 1e-6, 2e9)
        for name in MERITS:
            assert same(float(getattr(got, name)[i]), ref[name]), (i, name)
    # the README's numbers (x0 = -0.2 mm): 9.17 mN stall, 14.5 mm/s, 69.4 % at 4.75 mm/s
    assert got.stall_thrust[0] == pytest.approx(9.17e-3, rel=1e-3)
    assert got.no_load_speed[0] == pytest.approx(14.5e-3, rel=2e-3)
    assert got.best_efficiency[0] == pytest.approx(0.694, abs=1e-3)
    assert got.best_speed[0] == pytest.approx(4.75e-3, rel=2e-3)
    assert got.load_speed[0] == pytest.approx(9.28e-3, rel=2e-3)  # docs/motor.md
    assert got.load_efficiency[0] == pytest.approx(0.496, abs=1e-3)


def test_contact_merits_equal_the_scalar_api() -> None:
    rng = np.random.default_rng(7)
    psi = 10.0 ** rng.uniform(-5, 12, 120)
    tau0 = rng.uniform(-1.55, 1.55, 120)
    ell = rng.uniform(0.0, 1.0, 120)
    ell[::7] = np.nan
    got = contact_merits(psi, tau0, ell, **COARSE)
    for i in range(psi.size):
        p, t = float(psi[i]), float(tau0[i])
        try:
            v0 = no_load_speed(p, t, **COARSE)
        except ValueError:  # no sign change at this coarse resolution: nan in the batch
            v0 = math.nan
        assert same(float(got.no_load_speed[i]), v0)
        if p > 1.0 and math.isnan(v0):
            assert math.isnan(got.best_speed[i])
        else:
            b = best_efficiency(p, t, **COARSE)
            assert same(float(got.best_speed[i]), b.v)
            assert same(float(got.best_efficiency[i]), b.efficiency)
            assert same(float(got.best_thrust_ratio[i]), b.thrust_ratio)
        if math.isnan(ell[i]):
            assert math.isnan(got.load_speed[i])
            continue
        try:
            v = operating_speed(p, t, float(ell[i]), **COARSE)
        except ValueError:
            assert math.isnan(got.load_speed[i])
            continue
        res = moving_rotor(p, t, v, **COARSE)
        assert same(float(got.load_speed[i]), v)
        loss = float(res.friction_loss)
        assert same(float(got.load_efficiency[i]), operating_efficiency(p, v, ell[i], loss))
        assert same(float(got.load_output_power[i]), float(ell[i]) * v)  # l v, not v r(v)
        assert same(float(got.load_friction_loss[i]), float(res.friction_loss))


def _spring_rule(x, d, drive, scale):
    """(T, P, S, u) of ``mdr.march``'s rule (module docstring of core.numerics.mdr) in
    plain Python, one spring at a time with the held/entering test inside the loop, the
    sums in the springs' order; u the springs' displacements at the end."""
    n, nt = x.size, d.size
    u = np.zeros(n)
    T, P, S = np.zeros(nt), np.zeros(nt), np.zeros(nt)
    m_prev, d_prev, drive_prev = 0, d[0], drive[0]
    for k in range(nt):
        du = drive[k] - drive_prev
        m = int(np.count_nonzero(d[k] - x * x > 0.0))
        u[m:] = 0.0
        t_sum = p_sum = s_sum = 0.0
        for i in range(m):
            w = d[k] - x[i] * x[i]
            if i < m_prev:
                trial = u[i] + du
            else:
                frac = (x[i] * x[i] - d_prev) / (d[k] - d_prev) if d[k] != d_prev else 0.0
                trial = drive[k] - (drive_prev + min(max(frac, 0.0), 1.0) * du)
            margin = w - abs(trial)
            if margin < 0.0:
                s_sum += 0.5 * (max(d_prev - x[i] * x[i], 0.0) + w) * (-margin)
                trial = w if trial > 0.0 else -w
            u[i] = trial
            t_sum += trial
            p_sum += w
        T[k], P[k], S[k] = scale * t_sum, scale * p_sum, scale * s_sum
        m_prev, d_prev, drive_prev = m, d[k], drive[k]
    return T, P, S, u


def test_compiled_pieces_are_the_numpy_code_bit_for_bit() -> None:
    """The drive grid, the march and ndarray.sum, compiled, give the very same floats
    (so the solvers built on them take the very same steps); the march without the stick
    radius (the kernel's call) gives the floats of ``mdr.march``; against its spring rule
    written out, every spring's displacement is the same float and the sums over the
    springs (in the vector lanes' order, ``mdr._held``) agree to rounding."""
    rng = np.random.default_rng(3)
    x = mdr.spring_positions(37)
    checked = touched = 0
    for _ in range(200):
        psi = float(10.0 ** rng.uniform(-5, 6))
        tau0 = float(rng.uniform(-1.55, 1.55))
        v = float(rng.choice([0.0, rng.uniform(0, 0.2), rng.uniform(0, 3.0)]))
        n = int(rng.integers(4, 300))
        tau = drive_grid(psi, tau0, v, n)
        np.testing.assert_array_equal(designs._drive_grid(psi, tau0, v, n), tau)
        c0 = one_minus_s0(tau0)
        d = np.maximum(rise(tau, tau0), 0.0) / c0
        d[0] = d[-1] = 0.0
        drive = psi / c0 * relative_drive(tau, tau0, v)
        u = np.zeros(37)
        T, P, _, S = mdr.march(x, d, drive, 0.3, u)
        out = [np.empty(tau.size) for _ in range(3)]
        u_kernel = np.zeros(37)
        mdr.march_into(x, x * x, d, drive, 0.3, u_kernel, *out, None)  # the kernel
        for a, b in zip(out, (T, P, S), strict=True):
            np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(u_kernel, u)
        if checked < 40:  # the spring rule written out, one test per spring
            *sums, _ = _spring_rule(x, d, drive, 0.3)
            half = tau.size // 2  # the contact open: the springs' displacements there
            u_half = np.zeros(37)
            mdr.march_into(x, x * x, d[:half], drive[:half], 0.3, u_half,
                           *(np.empty(half) for _ in range(3)), None)
            u_rule = _spring_rule(x, d[:half], drive[:half], 0.3)[3]
            np.testing.assert_array_equal(u_half, u_rule)
            touched += np.count_nonzero(u_rule)
            for a, b in zip((T, P, S), sums, strict=True):
                # 37 terms of either sign: rounding of order 37 eps of the largest sum
                np.testing.assert_allclose(a, b, rtol=0.0, atol=1e-14 * np.abs(b).max())
            checked += 1
    assert touched > 200  # springs in contact, sticking or sliding, compared
    for n in [*range(0, 300), 577, 1023, 4097]:
        a = rng.standard_normal(n) * 10.0 ** rng.uniform(-3, 3, n)
        assert designs._sum(a) == a.sum()


def test_bad_inputs_are_refused_by_name() -> None:
    rod = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
    m = Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05)
    with pytest.raises(ValueError, match=r"x0\[1\] = 0.03 is outside the allowed range"):
        design_merits(m, [0.001, 0.03])
    with pytest.raises(ValueError, match=r"load\[0\] = -1 is outside"):
        design_merits(m, [0.001, 0.002], [-1.0, 0.0])
    with pytest.raises(ValueError, match="hardness = 1 is outside"):
        design_merits(m, 0.001, 0.0, 1e-6, 1.0)
    with pytest.raises(ValueError, match=r"psi\[0\] = 1e-06 is outside"):
        contact_merits([1e-6], [0.3])
    with pytest.raises(ValueError, match="tau0 = 2 is outside"):
        contact_merits(1.0, 2.0)
    with pytest.raises(ValueError, match="one per design"):
        design_merits([m], [0.001, 0.002])
    out = design_merits(m, [0.0, -0.002], 1.0)  # psi = 0 at the centre; 1 N > mu N
    assert out.stall_thrust[0] == 0.0 and np.isnan(out.no_load_speed[0])
    assert out.no_load_speed[1] > 0.0 and np.isnan(out.load_speed[1])
    heavy = Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.5)  # Phi >= 8 near the ends
    out = design_merits(heavy, [0.0005, -0.0199])
    assert np.isfinite(out.stall_thrust[0]) and np.isnan(out.stall_thrust[1])


def test_arguments_broadcast_together_or_are_refused_by_name() -> None:
    """Both APIs broadcast their arguments by one rule: a scalar load with an array of
    contacts gives the contacts' shape; shapes that do not broadcast are named."""
    got = contact_merits([[2.0], [3.0]], [0.1, 0.2, 0.3], 0.2, **COARSE)
    assert got.no_load_speed.shape == (2, 3)
    assert np.all(got.load_ratio == 0.2)
    with pytest.raises(ValueError, match=r"psi \(2,\), tau0 \(3,\), load_ratio \(\) do not"):
        contact_merits([2.0, 3.0], [0.1, 0.2, 0.3], **COARSE)
    rod = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
    m = Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05)
    with pytest.raises(ValueError, match=r"x0 \(2,\), load \(3,\)"):
        design_merits(m, [-1e-3, -2e-3], [0.0, 1e-3, 2e-3], **COARSE)


def test_zero_load_delivers_exactly_no_power() -> None:
    """At zero load the output power F_L V and the efficiency are exactly 0, in the
    scalar API and the kernel alike (the rotor runs at its no-load speed)."""
    rod = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
    m = Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05)
    x0 = [-0.2e-3, -1e-3, -8e-3]
    got = design_merits(m, x0, 0.0, **COARSE)
    for i, x in enumerate(x0):
        op = operating_point(m, x, 0.0, **COARSE)
        assert op.output_power == 0.0 and op.efficiency == 0.0
        assert got.load_power[i] == 0.0 and got.load_efficiency[i] == 0.0
        assert op.speed > 0.0 and op.input_power > 0.0
        assert same(float(got.load_speed[i]), op.speed)
        assert same(float(got.no_load_speed[i]), op.speed)
    c = contact_merits([0.5, 2.0], [0.3, 0.5], 0.0, **COARSE)
    assert np.all(c.load_output_power == 0.0) and np.all(c.load_efficiency == 0.0)
