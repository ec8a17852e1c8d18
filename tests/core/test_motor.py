"""The motor (core.motor): the rod's drive (eqs 1, 2), tau0 from the preload (eq 10) and the
stall thrust (eq 41 along the rod). References: the paper's formulas by hand, per-point
scipy brentq on core's F, 60-digit mpmath on eq 11 as printed, and core.Contact's SI
scales."""

from __future__ import annotations

import itertools
import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.optimize import brentq

from core import Contact
from core.contact import impulse_ratio
from core.elliptic import impulse_factor
from core.motor import PHI_MAX, Motor, MotorProfile, Rod, balance

L, DELTA, NU_ROD, A, FREQ = 0.02, 4e-3, 0.3, 10e-6, 40e3
R, G, NU, MU, N = 5e-3, 24e9, 0.31, 0.2, 0.05


@pytest.fixture
def rod() -> Rod:
    return Rod(half_length=L, thickness=DELTA, nu_rod=NU_ROD, amplitude=A, frequency=FREQ)


@pytest.fixture
def motor(rod: Rod) -> Motor:
    return Motor(rod, R=R, G=G, nu=NU, mu=MU, preload=N)


def along(n: int = 401, edge: float = 1e-9) -> np.ndarray:
    """n points over (-L, L), symmetric about 0 and holding 0, up to L (1 - edge)."""
    half = np.linspace(0.0, L * (1.0 - edge), n // 2 + 1)
    return np.concatenate([-half[:0:-1], half])


# ---- the rod (eqs 1, 2) ---------------------------------------------------------------
@pytest.mark.parametrize("x0", [-0.75 * L, -L / 2, -L / 3, -1e-7, 0.0, L / 4, 0.9 * L])
def test_drive_is_eqs_1_and_2_by_hand(motor: Motor, x0: float) -> None:
    q = math.pi * x0 / (2 * L)
    u0 = -A * math.sin(q)                                     # eq 1, time shifted by T/2
    H = NU_ROD * math.pi * DELTA / (4 * L) * A * math.cos(q)  # eq 2 at y = delta / 2
    tan_theta0 = MU * (2 - NU) / (2 * (1 - NU))               # eq 23
    assert motor.rod.u0(x0) == pytest.approx(u0, rel=1e-14, abs=1e-30)
    assert motor.rod.H(x0) == pytest.approx(H, rel=1e-14)
    assert motor.psi(x0) == pytest.approx(abs(u0) / H / tan_theta0, rel=1e-14, abs=1e-30)
    assert motor.rod.tan_theta(x0) == pytest.approx(
        4 * L / (NU_ROD * math.pi * DELTA) * abs(math.tan(q)), rel=1e-14, abs=1e-30
    )


def test_drive_at_the_half_length_and_the_centre(motor: Motor) -> None:
    # x0 = -L/2: sin = -cos = -1/sqrt 2; psi = (4 L / (nu_r pi delta)) / tan theta0 there
    tan_theta0 = MU * (2 - NU) / (2 * (1 - NU))
    assert motor.rod.u0(-L / 2) == pytest.approx(A / math.sqrt(2), rel=1e-15)
    assert motor.psi(-L / 2) == pytest.approx(
        4 * L / (NU_ROD * math.pi * DELTA) / tan_theta0, rel=1e-14
    )
    assert motor.rod.H(0.0) == motor.rod.vertical_amplitude
    assert motor.psi(0.0) == 0.0 and motor.rod.u0(0.0) == 0.0


def test_H_keeps_its_relative_accuracy_at_the_ends(rod: Rod) -> None:
    with mp.workdps(50):
        for gap in (1e-3, 1e-8, 1e-13):
            x0 = L - gap
            exact = (mp.mpf(NU_ROD) * mp.pi * mp.mpf(DELTA) / (4 * mp.mpf(L)) * mp.mpf(A)
                     * mp.cos(mp.pi * mp.mpf(x0) / (2 * mp.mpf(L))))
            assert float(rod.H(x0)) == pytest.approx(float(exact), rel=1e-13)


def test_psi_is_one_where_the_paper_says_and_the_thrust_is_largest_there(motor: Motor) -> None:
    tan_theta0 = MU * (2 - NU) / (2 * (1 - NU))
    x1 = 2 * L / math.pi * math.atan(NU_ROD * math.pi * DELTA * tan_theta0 / (4 * L))
    assert motor.psi(-x1) == pytest.approx(1.0, rel=1e-14)
    # eq 41 is 1 at psi = 1 whatever tau0: the stall thrust is mu N there, its maximum
    assert motor.stall_thrust(-x1) == pytest.approx(MU * N, rel=1e-13)
    assert motor.stall_thrust(x1) == pytest.approx(-MU * N, rel=1e-13)
    x0 = along(4001)
    assert np.nanmax(np.abs(motor.stall_thrust(x0))) <= MU * N * (1 + 1e-15)


# ---- tau0 from the mean-force balance (eq 10) ------------------------------------------
def _brentq_tau0(phi: float) -> float:
    def f(t0: float) -> float:
        e = math.pi / 2 - t0
        return float(impulse_factor(math.sin(e / 2) ** 2, math.cos(e / 2) ** 2)) - phi
    return brentq(f, -math.pi / 2 + 1e-15, math.pi / 2 - 1e-15, xtol=1e-15, rtol=1e-15)


def _mpmath_tau0(phi: float) -> mp.mpf:
    """Bisection at 60 digits on eq 11 exactly as printed (K, E with parameter
    k0^2 = (1 - s0) / 2); no code of core involved."""
    with mp.workdps(60):
        target = mp.mpf(phi)

        def F(t0: mp.mpf) -> mp.mpf:
            s0 = mp.sin(t0)
            m = (1 - s0) / 2
            return (1 + s0) * (1 + 3 * s0) * mp.ellipk(m) - 8 * s0 * mp.ellipe(m)

        lo, hi = -mp.pi / 2, mp.pi / 2  # F(lo) = 8 > target > F(hi) = 0
        for _ in range(90):
            mid = (lo + hi) / 2
            if F(mid) > target:
                lo = mid
            else:
                hi = mid
        return (lo + hi) / 2


def test_tau0_agrees_with_brentq_per_point(motor: Motor) -> None:
    x0 = along(81)
    phi, tau0 = motor.load_factor(x0), motor.tau0(x0)
    opens = phi < PHI_MAX
    assert opens.sum() > 60 and not opens.all()  # both regions are exercised
    ref = np.array([_brentq_tau0(p) for p in phi[opens]])
    np.testing.assert_allclose(tau0[opens], ref, rtol=0, atol=1e-12)


@pytest.mark.parametrize(
    "phi", [1e-300, 1e-30, 1e-8, 1e-3, 0.1, 0.4442, 1.0, 2.0, 4.0, 7.0, 7.9, 8 - 1e-6]
)
def test_balance_agrees_with_60_digit_mpmath(phi: float) -> None:
    m0, mc0 = balance.solve(np.array([phi]))
    tau0 = float(balance.tau0_of(m0, mc0)[0])
    assert abs(tau0 - float(_mpmath_tau0(phi))) < 1e-12
    # and in the variable that can be small: e = pi/2 - tau0 (grazing), relative
    e = float(mp.pi / 2 - _mpmath_tau0(phi))
    assert 2 * math.asin(math.sqrt(m0[0])) == pytest.approx(e, rel=1e-12)


def test_tau0_round_trips_through_eq_10(motor: Motor) -> None:
    x0 = along(2001)
    p = motor.profile(x0)
    ok = p.opens
    F0 = impulse_factor(p.m0[ok], 1.0 - p.m0[ok])
    np.testing.assert_allclose(F0, p.load_factor[ok], rtol=1e-13)
    # through core's SI path: the mean normal force of the contact is the preload
    for x in (-0.015, -0.003, 0.0, 1e-9, 0.011):
        s = motor.contact(x).scales
        assert s.normal_impulse / s.period == pytest.approx(N, rel=1e-12)


def test_balance_over_the_whole_range_of_phi() -> None:
    phi = np.concatenate([np.logspace(-300, -1, 300), np.linspace(0.1, 7.9, 600),
                          PHI_MAX - np.logspace(-14, -1, 100)])
    m0, mc0 = balance.solve(phi)
    np.testing.assert_allclose(impulse_factor(m0, mc0), phi, rtol=3e-14)
    order = np.argsort(phi)
    steps = np.diff(m0[order])
    assert np.all(steps[phi[order][1:] < 7.99] >= 0)  # monotone, as F is, and within
    assert np.all(steps >= -1e-15)  # the rounding of F (~1e-15 absolute) up to Phi = 8
    assert np.all((m0 > 0) & (mc0 > 0))
    np.testing.assert_allclose(m0 + mc0, 1.0, rtol=0, atol=4.5e-16)  # two roundings
    tau0 = balance.tau0_of(m0, mc0)
    assert np.all((tau0 > -math.pi / 2) & (tau0 <= math.pi / 2))  # pi/2: e < 1e-16


def test_the_starting_table_is_as_good_as_the_solver_assumes() -> None:
    """The first Newton step uses the table's start and slope: both are checked here over
    Phi < 7.9, where the solver trusts them (relative error 1e-8 and 3e-7)."""
    phi = np.concatenate([np.logspace(-300, -1, 300), np.linspace(0.1, 7.9, 20001)])
    m0, mc0 = balance.solve(phi)
    m, mc, d = balance._start(phi)
    assert np.max(np.abs(m / m0 - 1)) < 1e-8 and np.max(np.abs(mc / mc0 - 1)) < 1e-8
    exact = balance.slope(m0, mc0, impulse_factor(m0, mc0))
    assert np.max(np.abs(d / exact - 1)) < 3e-7


def test_the_slope_is_dF_dm() -> None:
    """dF/dm against 50-digit mpmath differentiation of F = 12 m^2 J(m)."""
    m = np.array([1e-6, 0.01, 0.049, 0.051, 0.3, 0.7, 0.99, 1 - 1e-6, 1 - 1e-12])
    mc = np.array([1 - 1e-6, 0.99, 0.951, 0.949, 0.7, 0.3, 0.01, 1e-6, 1e-12])
    exact = balance.slope(m, mc, impulse_factor(m, mc))
    with mp.workdps(50):
        def F(x: mp.mpf) -> mp.mpf:
            return 12 * x**2 * (2 * (2 * x - 1) * mp.ellipe(x)
                                + (1 - x) * (2 - 3 * x) * mp.ellipk(x)) / (3 * x**2)
        ref = [float(mp.diff(F, 1 - mp.mpf(c))) for c in mc]
    np.testing.assert_allclose(exact, ref, rtol=1e-9)  # the solver needs ~1e-6


def test_balance_has_no_root_from_eight_on() -> None:
    m0, mc0 = balance.solve(np.array([PHI_MAX, 9.0, 1e300, np.inf, np.nan]))
    assert np.isnan(m0).all() and np.isnan(mc0).all()
    assert np.isnan(balance.tau0_of(m0, mc0)).all()


# ---- stall thrust ------------------------------------------------------------------------
def test_stall_thrust_is_antisymmetric_and_signed(motor: Motor) -> None:
    x0 = along(1001)
    f = motor.stall_thrust(x0)
    np.testing.assert_array_equal(f, -f[::-1])  # exactly: x0 enters through |x0| and a sign
    centre = x0.size // 2
    assert x0[centre] == 0.0 and f[centre] == 0.0 and not np.signbit(f[centre])
    opens = motor.opens(x0)
    left = (x0 < 0) & opens
    assert (f[left] > 0).all() and (f[(x0 > 0) & opens] < 0).all()  # ccw for x0 < 0
    assert (np.abs(f[opens]) <= MU * N).all()


def test_stall_thrust_is_mu_N_times_core_impulse_ratio(motor: Motor) -> None:
    for x in (-0.018, -0.012, -0.004, -1e-4, -1e-6, 3e-6, 0.009):
        c = motor.contact(x)
        expected = MU * N * float(impulse_ratio(c.psi, c.tau0, MU, NU))
        f = float(motor.stall_thrust(x))
        assert abs(f) == pytest.approx(expected, rel=1e-12)
        assert c.scales.tangential_impulse / c.scales.period == pytest.approx(abs(f), rel=1e-12)
        assert math.copysign(1.0, f) == (1.0 if x < 0 else -1.0)


@pytest.mark.parametrize("x", [-0.017, -0.008, -2e-4, -1e-6, 0.005])
def test_mean_forces_by_quadrature_of_core_T_and_P(motor: Motor, x: float) -> None:
    """Independent of eqs 10, 41: integrate core's P(tau) and T(tau) (eqs 9, 38, 39) over
    one contact and divide by the period. The mean normal force is the preload, the mean
    tangential force the stall thrust."""
    c = motor.contact(x)
    s = c.scales
    cuts = [c.tau0, math.pi / 2] + ([c.tau1] if c.psi > 1 else []) + [c.tau_end]

    def mean(f: object) -> float:
        return sum(quad(lambda t: float(f(t)), a, b, epsabs=0, epsrel=1e-13, limit=200)[0]
                   for a, b in itertools.pairwise(cuts)) / (2 * math.pi)

    assert s.P0 * mean(c.normal_force) == pytest.approx(N, rel=1e-11)
    F_t = float(motor.stall_thrust(x))
    assert s.T0 * mean(c.tangential_force) == pytest.approx(abs(F_t), rel=1e-10)


def test_small_angles_near_the_centre_give_mu_N_psi(motor: Motor) -> None:
    x0 = np.array([-1e-6, -1e-5, 1e-5])
    p = motor.profile(x0)
    assert (p.psi <= 1).all()
    np.testing.assert_allclose(np.abs(p.stall_thrust), MU * N * p.psi, rtol=1e-15)


def test_never_opening_region_is_nan_and_flagged(motor: Motor) -> None:
    x0 = np.array([-L * (1 - 1e-9), -0.0199, 0.0199, L * (1 - 1e-12)])
    p = motor.profile(x0)
    assert not p.opens.any()
    assert (p.load_factor >= PHI_MAX).all()
    for name in ("m0", "tau0", "h", "impulse_ratio", "thrust_ratio", "stall_thrust"):
        assert np.isnan(getattr(p, name)).all(), name
    assert np.isfinite(p.psi).all() and np.isfinite(p.H).all()  # the drive is still known
    with pytest.raises(ValueError, match="never opens"):
        motor.contact(-0.0199)


def test_a_preload_too_heavy_for_any_point_gives_nan_everywhere(rod: Rod) -> None:
    heavy = Motor(rod, R=R, G=G, nu=NU, mu=MU, preload=1e3)
    assert np.isnan(heavy.stall_thrust(along(51))).all()
    assert not heavy.opens(0.0)
    flat = Rod(half_length=L, thickness=DELTA, nu_rod=0.0, amplitude=A, frequency=FREQ)
    assert np.isnan(Motor(flat, R=R, G=G, nu=NU, mu=MU, preload=N).stall_thrust(along(51))).all()


def test_auxetic_rod_turns_the_other_way(motor: Motor) -> None:
    aux = Rod(half_length=L, thickness=DELTA, nu_rod=-NU_ROD, amplitude=A, frequency=FREQ)
    m_aux = Motor(aux, R=R, G=G, nu=NU, mu=MU, preload=N)
    x0 = along(41)
    np.testing.assert_array_equal(m_aux.stall_thrust(x0), -motor.stall_thrust(x0))


def test_profile_matches_the_single_methods_and_is_read_only(motor: Motor) -> None:
    x0 = along(101).reshape(-1, 1)[:100].reshape(10, 10)
    p = motor.profile(x0)
    assert isinstance(p, MotorProfile) and p.stall_thrust.shape == (10, 10)
    np.testing.assert_array_equal(p.psi, motor.psi(x0))
    np.testing.assert_array_equal(p.tau0, motor.tau0(x0))
    np.testing.assert_array_equal(p.stall_thrust, motor.stall_thrust(x0))
    np.testing.assert_array_equal(p.thrust_ratio * (MU * N), p.stall_thrust)
    np.testing.assert_allclose(p.h, p.H * np.sin(p.tau0), rtol=1e-12, atol=1e-25)
    with pytest.raises(ValueError):
        p.tau0[0, 0] = 1.0
    scalar = motor.profile(-0.01)
    assert scalar.tau0.shape == () and float(scalar.tau0) == float(motor.tau0(-0.01))
    assert motor.stall_thrust([-0.01, 0.01]).shape == (2,)


def test_si_scaling_of_the_stall_thrust(rod: Rod) -> None:
    """F_t = mu N r(psi, tau0); at fixed psi and tau0 (same Phi, same angles) it scales with
    mu N: doubling N and scaling G by 2 keeps Phi, so the thrust doubles exactly."""
    m1 = Motor(rod, R=R, G=G, nu=NU, mu=MU, preload=N)
    m2 = Motor(rod, R=R, G=2 * G, nu=NU, mu=MU, preload=2 * N)
    x0 = along(61)
    np.testing.assert_allclose(m2.stall_thrust(x0), 2 * m1.stall_thrust(x0), rtol=1e-14)


def _log(lo: float, hi: float) -> st.SearchStrategy[float]:
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0**e)


@settings(max_examples=60, deadline=None)
@given(
    L_=_log(1e-3, 1.0), delta_ratio=_log(1e-3, 0.5), A=_log(1e-8, 1e-4),
    nu_rod=st.floats(-0.99, 0.5), R_=_log(1e-4, 1.0), G_=_log(1e8, 1e12),
    nu=st.floats(-0.99, 0.5), mu=_log(1e-3, 3.0), N_=_log(1e-8, 1e3),
)
def test_properties_over_random_motors(L_: float, delta_ratio: float, A: float,
                                       nu_rod: float, R_: float, G_: float, nu: float,
                                       mu: float, N_: float) -> None:
    """Any motor: the thrust is odd in x0, within mu N, nan exactly where the contact never
    opens, and tau0 satisfies the balance of eq 10 there."""
    rod = Rod(half_length=L_, thickness=delta_ratio * L_, nu_rod=nu_rod, amplitude=A,
              frequency=FREQ)
    motor = Motor(rod, R=R_, G=G_, nu=nu, mu=mu, preload=N_)
    half = L_ * np.linspace(0.0, 1.0 - 1e-6, 101)
    x0 = np.concatenate([-half[:0:-1], half])
    p = motor.profile(x0)
    np.testing.assert_array_equal(p.stall_thrust, -p.stall_thrust[::-1])
    np.testing.assert_array_equal(np.isnan(p.stall_thrust), p.load_factor >= PHI_MAX)
    assert np.all(np.abs(p.stall_thrust[p.opens]) <= mu * N_ * (1 + 1e-15))
    ok = p.opens
    np.testing.assert_allclose(impulse_factor(p.m0[ok], 1 - p.m0[ok]), p.load_factor[ok],
                               rtol=3e-14)
    assert np.all((p.tau0[ok] > -math.pi / 2) & (p.tau0[ok] <= math.pi / 2))


# ---- bad input ---------------------------------------------------------------------------
ROD = {"half_length": L, "thickness": DELTA, "nu_rod": NU_ROD, "amplitude": A, "frequency": FREQ}


@pytest.mark.parametrize(
    ("name", "value", "shown"),
    [
        ("half_length", 0.0, "(0, inf)"),
        ("half_length", -1.0, "-1"),
        ("thickness", math.nan, "nan"),
        ("amplitude", math.inf, "inf"),
        ("frequency", 0.0, "(0, inf)"),
        ("frequency", "40e3", "'40e3'"),
        ("amplitude", True, "True"),
        ("nu_rod", 0.51, "(-1, 0.5]"),
        ("nu_rod", -1.0, "-1"),
    ],
)
def test_rod_rejects_bad_parameters(name: str, value: object, shown: str) -> None:
    with pytest.raises(ValueError, match=rf"\b{name}\b") as err:
        Rod(**{**ROD, name: value})
    assert shown in str(err.value)


@pytest.mark.parametrize(
    ("name", "value"),
    [("R", 0.0), ("R", -5e-3), ("G", 0.0), ("G", math.nan), ("nu", 0.6), ("nu", -1.0),
     ("mu", 0.0), ("mu", -0.2), ("preload", 0.0), ("preload", -1.0), ("preload", math.inf),
     ("preload", "1")],
)
def test_motor_rejects_bad_parameters(rod: Rod, name: str, value: object) -> None:
    kwargs = {"R": R, "G": G, "nu": NU, "mu": MU, "preload": N, name: value}
    with pytest.raises(ValueError, match=rf"\b{name}\b") as err:
        Motor(rod, **kwargs)
    assert "allowed range" in str(err.value) or "must be" in str(err.value)


def test_motor_needs_a_rod() -> None:
    with pytest.raises(ValueError, match="rod"):
        Motor(ROD, R=R, G=G, nu=NU, mu=MU, preload=N)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("x0", "shown"),
    [(L, "x0 = 0.02"), (-L, "x0 = -0.02"), (2 * L, "x0 = 0.04"), (math.nan, "x0 must be"),
     ([0.0, 0.01, 0.03], "x0[2] = 0.03"), ([[0.0], [-math.inf]], "x0[1, 0]")],
)
def test_x0_must_lie_inside_the_rod(motor: Motor, x0: object, shown: str) -> None:
    for method in (motor.psi, motor.tau0, motor.stall_thrust, motor.profile, motor.rod.H):
        with pytest.raises(ValueError, match=r"\(-0\.02, 0\.02\)") as err:
            method(x0)
        assert shown in str(err.value)


@pytest.mark.parametrize("x0", ["0.01", [True, False], 1j, [[0.0], [0.0, 1.0]], None])
def test_x0_must_be_real_numbers(motor: Motor, x0: object) -> None:
    with pytest.raises(ValueError, match="x0"):
        motor.stall_thrust(x0)


def test_contact_takes_one_point(motor: Motor) -> None:
    with pytest.raises(ValueError, match="one number"):
        motor.contact([0.0, 0.01])
    assert isinstance(motor.contact(0.0), Contact)
