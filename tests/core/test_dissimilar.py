"""Two dissimilar bodies under Goodman's approximation (docs/physics.md, section 11.1):
the identical case unchanged bit for bit, psi and the scales against the effective
constants E*, G*, R written out in mpmath, psi independent of the radii, Dundurs' beta,
the motor's balance with the effective constants, each body's own centre motion against
Cerruti's displacement under the closed-form traction, the presets, and bad input."""

import dataclasses
import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import quad

from core import MATERIALS, MOTOR_MATERIALS, Contact, dundurs_beta, equivalent_pair
from core.elliptic import impulse_factor
from core.motor import Motor, Rod
from core.physical import BETA_WARN, beta_warning, upper_share

SI = {"R": 5e-3, "G": 79.3e9, "nu": 0.29, "mu": 0.2, "H": 1e-6, "u0": 0.8e-6, "h": 0.5e-6,
      "omega": 2 * math.pi * 40e3}
PZT = MATERIALS["PZT-4"]
SECOND = {"R2": math.inf, "G2": PZT.G, "nu2": PZT.nu}


def effective(G1: float, nu1: float, R1: float, G2: float, nu2: float, R2: float):
    """E*, G*, R of the brief's formulas, in 40-digit mpmath."""
    with mp.workdps(40):
        G1, nu1, R1, G2, nu2 = (mp.mpf(x) for x in (G1, nu1, R1, G2, nu2))
        E = 1 / ((1 - nu1) / (2 * G1) + (1 - nu2) / (2 * G2))
        Gs = 1 / ((2 - nu1) / G1 + (2 - nu2) / G2)
        R = 1 / (1 / R1 + (0 if math.isinf(R2) else 1 / mp.mpf(R2)))
        return E, Gs, R


def test_identical_bodies_reproduce_the_paper_bit_for_bit() -> None:
    base = Contact.from_physical(**SI)
    for extra in ({}, {"R2": SI["R"], "G2": SI["G"], "nu2": SI["nu"]}, {"G2": None}):
        c = Contact.from_physical(**SI, **extra)
        assert c == base
        for f in dataclasses.fields(base.scales):
            if f.name != "inputs":
                assert getattr(c.scales, f.name) == getattr(base.scales, f.name), f.name
    assert base.scales.beta == 0.0
    assert equivalent_pair(5e-3, 79.3e9, 0.29) == (5e-3, 79.3e9, 0.29)


@pytest.mark.parametrize("second", [SECOND, {"R2": 2e-3, "G2": 152e9, "nu2": 0.22},
                                    {"R2": 1.0, "G2": 1.6e9, "nu2": 0.45},
                                    {"G2": 1e3, "nu2": -0.9}])
def test_psi_and_scales_use_the_effective_constants(second: dict) -> None:
    c = Contact.from_physical(**SI, **second)
    R2 = second.get("R2", SI["R"])
    E, Gs, Re = effective(SI["G"], SI["nu"], SI["R"], second["G2"], second["nu2"], R2)
    with mp.workdps(40):
        H, h, u0, mu = (mp.mpf(SI[k]) for k in ("H", "h", "u0", "mu"))
        psi = 4 * Gs * u0 / (mu * E * H)
        P0 = mp.mpf(4) / 3 * E * mp.sqrt(Re) * H**1.5  # Hertz: P = (4/3) E* R^(1/2) alpha^(3/2)
        a_star = mp.sqrt(Re * (H - h))
        p_star = 2 * E * a_star / (mp.pi * Re)
        theta0 = mp.atan(mu * E / (4 * Gs))
    assert c.psi == pytest.approx(float(psi), rel=2e-15)
    assert c.theta0 == pytest.approx(float(theta0), rel=2e-15)
    s = c.scales
    assert s.P0 == pytest.approx(float(P0), rel=3e-15)
    assert s.T0 == pytest.approx(float(mu * P0), rel=3e-15)
    assert s.a_star == pytest.approx(float(a_star), rel=3e-15)
    assert s.p_star == pytest.approx(float(p_star), rel=3e-15)


def test_psi_does_not_depend_on_the_radii() -> None:
    psis = {Contact.from_physical(**{**SI, "R": R}, R2=R2, G2=PZT.G, nu2=PZT.nu).psi
            for R in (1e-4, 5e-3, 2.0) for R2 in (1e-3, 0.1, math.inf)}
    assert max(psis) - min(psis) <= 4e-16 * max(psis)


def test_dundurs_beta() -> None:
    G1, nu1, G2, nu2 = SI["G"], SI["nu"], PZT.G, PZT.nu
    with mp.workdps(30):
        ref = (((1 - 2 * mp.mpf(nu1)) / G1 - (1 - 2 * mp.mpf(nu2)) / G2)
               / (2 * ((1 - mp.mpf(nu1)) / G1 + (1 - mp.mpf(nu2)) / G2)))
    assert dundurs_beta(G1, nu1, G2, nu2) == pytest.approx(float(ref), rel=1e-14)
    assert dundurs_beta(G2, nu2, G1, nu1) == -dundurs_beta(G1, nu1, G2, nu2)
    assert dundurs_beta(G1, nu1, G1, nu1) == 0.0
    assert dundurs_beta(1e9, 0.5, 2e9, 0.5) == 0.0  # incompressible bodies do not couple
    assert dundurs_beta(1.0, 0.0, 1e13, 0.3) == pytest.approx(0.5, rel=1e-12)  # rigid on nu=0
    assert Contact.from_physical(**SI, **SECOND).scales.beta == pytest.approx(float(ref))
    assert beta_warning(BETA_WARN) is None
    assert "Goodman" in beta_warning(-0.26) and "docs/bem.md" in beta_warning(0.3)
    assert Contact.from_physical(**SI, G2=1e3, nu2=0.0).scales.beta_warning is not None


def test_dundurs_beta_bound_over_the_domain() -> None:
    """|beta| < 3/4 for nu in (-1, 1/2] (the bound (1 - 2 nu)/(2 (1 - nu)) of a body
    against a rigid one tends to 3/4 as nu -> -1), and |beta| <= 1/2 when both nu >= 0."""
    assert dundurs_beta(79.3e9, 0.29, 1e3, -0.9) == pytest.approx(-2.8 / 3.8, rel=1e-6)
    extreme = dundurs_beta(1.0, math.nextafter(-1.0, 0.0), 1e13, 0.5)
    assert 0.7499 < extreme < 0.75
    rng = np.random.default_rng(7)
    G = 10.0 ** rng.uniform(0, 13, (2, 20000))
    nu = rng.uniform(-1, 0.5, (2, 20000))
    beta = np.array([dundurs_beta(*row) for row in zip(G[0], nu[0], G[1], nu[1],
                                                      strict=True)])
    assert np.abs(beta).max() < 0.75
    positive = (nu >= 0).all(axis=0)
    assert np.abs(beta[positive]).max() <= 0.5


def cerruti_centre(c: Contact, tau: float, G: float, nu: float) -> float:
    """The elastic displacement (m) of the surface point r = 0 of a half-space (G, nu)
    under the contact's traction at tau: Cerruti's point-force solution integrated over
    the disc, u_x(0) = (2 - nu) / (2 G) int_0^a tau_u(r) dr (exact at r = 0, where the
    non-axisymmetric terms vanish), by quadrature of ``Contact.traction``."""
    s = c.scales
    a, b = float(c.contact_radius(tau)), float(c.stick_radius(tau))
    points = [b] if 0.0 < b < a else None
    integral = quad(lambda r: float(c.traction(r, tau)), 0.0, a, points=points,
                    epsabs=1e-15, epsrel=1e-13, limit=200)[0]
    return (2.0 - nu) / (2.0 * G) * s.traction_star * s.a_star * integral


@pytest.mark.parametrize("second", [{}, SECOND, {"R2": 2e-3, "G2": 152e9, "nu2": 0.22},
                                    {"G2": 1e3, "nu2": -0.9}])
@pytest.mark.parametrize("u0", [0.8e-6, 0.1e-6])  # psi > 1 and psi <= 1
def test_each_body_moves_by_its_own_compliance(second: dict, u0: float) -> None:
    """The upper body's centre (R, G, nu) and the lower one's (R2, G2, nu2) against
    Cerruti's displacement of each body under the closed-form traction, and their
    velocities against its central difference in time, in every phase."""
    c = Contact.from_physical(**{**SI, "u0": u0}, **second)
    G2, nu2 = second.get("G2", SI["G"]), second.get("nu2", SI["nu"])
    taus = [0.7, 1.2, 2.0, 2.5] if c.psi <= 1 else [
        0.7, 1.2, math.pi / 2 + 0.3 * (c.tau1 - math.pi / 2), c.tau1 + 0.05, 2.5]
    step = 1e-4
    for tau in taus:
        for G, nu, moved, speed in ((SI["G"], SI["nu"], c.centre_displacement,
                                     c.centre_velocity),
                                    (G2, nu2, c.lower_centre_displacement,
                                     c.lower_centre_velocity)):
            sign = 1.0 if moved == c.centre_displacement else -1.0
            u = sign * cerruti_centre(c, tau, G, nu)
            assert float(moved(tau)) * u0 == pytest.approx(u, rel=1e-12, abs=1e-25), tau
            du = sign * (cerruti_centre(c, tau + step, G, nu)
                         - cerruti_centre(c, tau - step, G, nu)) / (2 * step)
            assert float(speed(tau)) * u0 == pytest.approx(du, rel=1e-6), tau
    # the relative displacement is the equivalent pair's, whatever the share
    pair = Contact(c.psi, c.tau0, c.mu, c.nu)
    tau = np.linspace(c.tau0, c.tau_end, 50)
    np.testing.assert_allclose(c.centre_displacement(tau) - c.lower_centre_displacement(tau),
                               2 * pair.centre_displacement(tau), rtol=1e-15, atol=1e-17)


def test_identical_bodies_centre_motion_bit_for_bit() -> None:
    tau = np.linspace(-0.5, 3.5, 401)
    pair = Contact.from_physical(**SI)
    same = Contact.from_physical(**SI, R2=SI["R"], G2=SI["G"], nu2=SI["nu"])
    plain = Contact(pair.psi, pair.tau0, pair.mu, pair.nu)
    assert pair.upper_share == same.upper_share == upper_share(1.0, 0.3) == 0.5
    for c in (pair, same):
        for name in ("centre_displacement", "centre_velocity"):
            np.testing.assert_array_equal(getattr(c, name)(tau), getattr(plain, name)(tau))
            np.testing.assert_array_equal(getattr(c, "lower_" + name)(tau),
                                          -getattr(plain, name)(tau))
            np.testing.assert_array_equal(getattr(c.at(tau), name), getattr(plain, name)(tau))


def test_steel_ball_on_pzt4_moves_0566_of_the_pair() -> None:
    """The figure of docs/physics.md section 11.1: a steel ball on PZT-4 takes
    2 lambda = 0.566 of the equivalent pair's centre motion, the PZT-4 face 1.434."""
    c = Contact.from_physical(**SI, **SECOND)
    pair = Contact(c.psi, c.tau0, c.mu, c.nu)
    lam = ((2 - SI["nu"]) / SI["G"]) / ((2 - SI["nu"]) / SI["G"] + (2 - PZT.nu) / PZT.G)
    assert c.upper_share == pytest.approx(lam, rel=1e-15)
    assert 2 * lam == pytest.approx(0.566, abs=5e-4)
    tau = 1.0
    assert float(c.centre_displacement(tau)) == pytest.approx(
        2 * lam * float(pair.centre_displacement(tau)), rel=1e-15)
    with pytest.raises(ValueError, match="upper_share"):
        Contact(1.0, 0.3, upper_share=1.0)


ROD = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
ROTOR = {"R": 5e-3, "G": 79.3e9, "nu": 0.29, "mu": 0.2, "preload": 0.05}


def test_motor_identical_rod_is_the_paper_bit_for_bit() -> None:
    x0 = np.linspace(-0.0199, 0.0199, 201)
    a = Motor(ROD, **ROTOR).profile(x0)
    b = Motor(ROD, **ROTOR, rod_G=ROTOR["G"], rod_nu=ROTOR["nu"], rod_R=ROTOR["R"]).profile(x0)
    for f in dataclasses.fields(a):
        np.testing.assert_array_equal(getattr(a, f.name), getattr(b, f.name))


def test_motor_balance_uses_the_effective_constants() -> None:
    m = Motor(ROD, **ROTOR, rod_G=PZT.G, rod_nu=PZT.nu, rod_R=math.inf)
    x0 = np.linspace(-0.015, 0.015, 31)
    p = m.profile(x0)
    E, Gs, Re = effective(ROTOR["G"], ROTOR["nu"], ROTOR["R"], PZT.G, PZT.nu, math.inf)
    E, Gs, Re = float(E), float(Gs), float(Re)
    # P_imp = 2 pi N / omega with eq 10 in E*, R: F(tau0) = 9 pi N / (4 E* (2 R)^(1/2) H^(3/2))
    phi = 9 * math.pi * ROTOR["preload"] / (4 * E * math.sqrt(2 * Re) * p.H**1.5)
    np.testing.assert_allclose(p.load_factor, phi, rtol=1e-14)
    np.testing.assert_allclose(impulse_factor(p.m0, 1 - p.m0), phi, rtol=3e-14)
    np.testing.assert_allclose(p.psi, 4 * Gs * np.abs(p.u0) / (ROTOR["mu"] * E * p.H),
                               rtol=1e-14)
    assert float(p.beta) == m.beta == pytest.approx(-0.0950, abs=5e-4)  # steel on PZT-4
    c = m.contact(-0.002)
    assert c.psi == pytest.approx(float(m.psi(-0.002)), rel=1e-14)
    assert c.scales.normal_impulse / c.scales.period == pytest.approx(ROTOR["preload"],
                                                                      rel=1e-12)


def test_presets_are_consistent() -> None:
    assert PZT.G == pytest.approx(1 / (2 * (12.3e-12 + 4.05e-12)), rel=1e-15)
    assert PZT.nu == pytest.approx(4.05 / 12.3, rel=1e-15)
    assert MATERIALS["alumina"].E == pytest.approx(370e9, rel=0.01)
    assert MATERIALS["phosphor bronze"].E == pytest.approx(110e9, rel=0.01)
    assert MATERIALS["aluminium"].E == pytest.approx(68.9e9, rel=0.01)  # 6061-T6
    assert MATERIALS["glass"].E == pytest.approx(70e9, rel=0.01)  # soda-lime
    assert MATERIALS["PZT ceramic"].E == pytest.approx(63e9, rel=0.01)
    assert MOTOR_MATERIALS == ("PZT-4", "PZT-8", "alumina", "steel", "phosphor bronze",
                               "PEEK composite")
    for mat in MATERIALS.values():
        assert 1e8 < mat.G < 1e12 and -1 < mat.nu <= 0.5 and mat.hardness > 0 and mat.source


@pytest.mark.parametrize(("kwargs", "name"), [
    ({"G2": 0.0}, "G2"), ({"G2": math.nan}, "G2"), ({"nu2": 0.6}, "nu2"),
    ({"nu2": -1.0}, "nu2"), ({"R2": 0.0}, "R2"), ({"R2": -math.inf}, "R2"),
    ({"R2": "inf"}, "R2"), ({"R2": 10**400}, "R2"), ({"G2": True}, "G2")])
def test_bad_second_body_is_refused(kwargs: dict, name: str) -> None:
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        Contact.from_physical(**SI, **kwargs)


@pytest.mark.parametrize(("kwargs", "name"), [
    ({"rod_G": -1.0}, "rod_G"), ({"rod_nu": 0.51}, "rod_nu"), ({"rod_R": 0.0}, "rod_R"),
    ({"rod_R": math.nan}, "rod_R"), ({"rod_G": "x"}, "rod_G")])
def test_bad_rod_body_is_refused(kwargs: dict, name: str) -> None:
    with pytest.raises(ValueError, match=rf"^{name}\b"):
        Motor(ROD, **ROTOR, **kwargs)
