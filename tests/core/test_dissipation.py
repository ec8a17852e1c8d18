"""Exact friction dissipation of a held contact (core.dissipation; docs/physics.md 11.2):
the energy against a quadrature of int (T/T0) cos tau dtau and 60-digit mpmath, the
density against a 30-digit quadrature in time of |tau_u| |slip velocity| built from the
paper's formulas, its integral against the energy, zero in the stick zone, and the MDR's
friction loss of a held rotor (an independent method)."""

import itertools
import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import quad

from core import Contact, Phase
from core.motor import moving_rotor

CASES = [(1 + math.sqrt(2), math.pi / 6), (1.0 + 1e-6, 0.3), (1.2, -1.0), (6.46, 0.1),
         (30.0, -0.5), (1e4, 1.2), (1e9, math.pi / 2 - 1e-6), (2.0, -math.pi / 2 + 1e-6)]


def energy_mp(psi: float, tau0: float) -> mp.mpf:
    with mp.workdps(60):
        c = 1 - mp.sin(mp.mpf(tau0))
        p = mp.mpf(psi)
        return mp.mpf(4) / 5 * c ** mp.mpf(2.5) * (p - 1) / (p + 1) if p > 1 else mp.mpf(0)


@pytest.mark.parametrize(("psi", "tau0"), CASES)
def test_energy_against_mpmath(psi: float, tau0: float) -> None:
    assert Contact(psi, tau0).dissipated_energy == pytest.approx(float(energy_mp(psi, tau0)),
                                                                 rel=2e-15, abs=0)


@pytest.mark.parametrize(("psi", "tau0"), CASES[:6])
def test_energy_is_the_work_of_the_drive(psi: float, tau0: float) -> None:
    """D / (T0 u0) = int (T / T0) cos tau dtau, by adaptive quadrature phase by phase."""
    c = Contact(psi, tau0)
    cuts = [c.tau0, math.pi / 2, c.tau1, c.tau_end]
    work = sum(quad(lambda t: float(c.tangential_force(t)) * math.cos(t), a, b,
                    epsabs=1e-16, epsrel=1e-12, limit=200)[0]
               for a, b in itertools.pairwise(cuts) if b > a)
    # the loading and unloading halves (each ~ (2/5)(1 - s0)^(5/2)) cancel for psi near 1:
    # the quadrature is good to ~1e-13 of them
    scale = 0.4 * (1 - math.sin(tau0)) ** 2.5
    assert c.dissipated_energy == pytest.approx(work, rel=1e-10, abs=1e-13 * scale)


@pytest.mark.parametrize(("psi", "tau0"), [(0.0, 0.3), (0.4, math.pi / 6), (1.0, -1.2)])
def test_full_stick_dissipates_nothing(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    assert c.dissipated_energy == 0.0
    assert not c.dissipation_density(np.linspace(0, 1, 11)).any()
    assert not c.dissipation_rate(np.linspace(0, 1, 11)[:, None], c.tau_grid(50)).any()
    # the drive's work does vanish: loading and unloading cancel
    work = quad(lambda t: float(c.tangential_force(t)) * math.cos(t), c.tau0, c.tau_end)[0]
    assert abs(work) < 1e-12


def density_mp(psi: float, tau0: float, r: float) -> float:
    """q(r) in T0 u0 / (pi a*^2) by 30-digit quadrature in time of the friction power
    (3/2) c^(3/2) / psi |t| |S| from eqs 6-8, 24, 30, 31 and the velocity field of eq 14,
    written out here independently of core."""
    with mp.workdps(30):
        p, t0, r = mp.mpf(psi), mp.mpf(tau0), mp.mpf(r)
        s0 = mp.sin(t0)
        c = 1 - s0
        s1 = 1 - 2 * c / (p + 1)
        tau1 = mp.pi - mp.asin(s1)

        def power(tau: mp.mpf) -> mp.mpf:
            a2 = (mp.sin(tau) - s0) / c
            if a2 <= r * r:
                return mp.mpf(0)
            t = mp.sqrt(a2 - r * r)  # |traction| / (mu p*) in every slipping phase
            if tau <= mp.pi / 2:
                slip = (p - 1) * mp.cos(tau)
            elif tau < tau1:
                b = mp.sqrt(max((p + 1) / 2 * (mp.sin(tau) - s1) / c, 0))
                if r <= b:
                    return mp.mpf(0)
                g = mp.asin(b / r)  # eq 14 outside the stick disc
                slip = mp.cos(tau) * (p - (2 / mp.pi) * (-mp.pi / 2 + (p + 1) * g))
            else:
                slip = (p + 1) * mp.cos(tau)
            return mp.mpf(3) / 2 * c ** mp.mpf(1.5) / p * t * abs(slip)

        enter = mp.asin(min(s0 + c * r * r, 1))
        leave_b = mp.pi - mp.asin(min(s1 + 2 * c * r * r / (p + 1), 1))
        cuts = sorted({enter, mp.pi / 2, leave_b, tau1, mp.pi - enter})
        return float(mp.quad(power, cuts))


@pytest.mark.parametrize(("psi", "tau0"), [CASES[0], CASES[2], CASES[3], CASES[4]])
@pytest.mark.parametrize("r", [0.0, 0.05, 0.3, 0.55, 0.8, 0.97])
def test_density_against_quadrature_in_time(psi: float, tau0: float, r: float) -> None:
    c = Contact(psi, tau0)
    ref = density_mp(psi, tau0, r)
    assert float(c.dissipation_density(r)) == pytest.approx(ref, rel=1e-9, abs=1e-15)


@pytest.mark.parametrize(("psi", "tau0"), CASES)
def test_density_integrates_to_the_energy(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    kappa = (psi - 1) / (psi + 1)
    total = quad(lambda r: 2 * r * float(c.dissipation_density(r)), 0.0, 1.0,
                 points=[math.sqrt(kappa)], epsabs=0, epsrel=1e-12, limit=400)[0]
    assert total == pytest.approx(c.dissipated_energy, rel=1e-10)
    assert float(c.dissipation_density(1.0)) == 0.0
    assert float(c.dissipation_density(-0.3)) == float(c.dissipation_density(0.3))


@pytest.mark.parametrize(("psi", "tau0"), CASES[:5])
def test_rate_is_zero_in_the_stick_zone_and_integrates_to_the_density(psi: float,
                                                                      tau0: float) -> None:
    c = Contact(psi, tau0)
    tau = c.tau_grid(400)
    r = np.linspace(0.0, 1.0, 201)[:, None]
    w = c.dissipation_rate(r, tau)
    b = c.stick_radius(tau)
    stick = (r < b) | (c.phase(tau) == Phase.FULL_STICK)
    assert stick.any() and not w[np.broadcast_to(stick, w.shape)].any()
    assert np.all(w >= 0.0)
    for ri in (0.2, 0.6):
        cuts = [c.tau0, math.pi / 2, c.tau1, c.tau_end]
        q = sum(quad(lambda t, ri=ri: float(c.dissipation_rate(ri, t)), a, b_,
                     epsabs=1e-15, epsrel=1e-11, limit=400)[0]
                for a, b_ in itertools.pairwise(cuts) if b_ > a)
        assert q == pytest.approx(float(c.dissipation_density(ri)), rel=1e-8)


def response(r: np.ndarray, c: float) -> np.ndarray:
    """g(r, c) of eq 14: pi/2 inside r <= c, arcsin(c / r) outside."""
    return np.where(r <= c, np.pi / 2, np.arcsin(np.minimum(c / np.maximum(r, 1e-300), 1)))


def test_rate_is_traction_times_slip_speed_of_eq_14() -> None:
    """The rate against |tau_u| |v1 - v2| with the traction from Contact.traction and the
    slip velocity of the Coulomb certificate's form (kappa_a g(r, a) + kappa_b ...)."""
    psi, tau0 = 1 + math.sqrt(2), math.pi / 6
    c = Contact(psi, tau0)
    cc = 1 - math.sin(tau0)
    for tau in (0.8, 1.4, 1.9, 2.2, 2.5):
        r = np.linspace(0.0, 0.99, 50)
        a, b, ph = float(c.contact_radius(tau)), float(c.stick_radius(tau)), int(c.phase(tau))
        ka, kb = {Phase.SLIP: (1, 0), Phase.PARTIAL_STICK: (-1, 2),
                  Phase.COUNTER_SLIP: (-1, 0)}[ph]
        slip = np.cos(tau) * (psi - 2 / np.pi * (ka * response(r, a)
                                                 + kb * (psi + 1) / 2 * response(r, b)))
        expect = 1.5 * cc**1.5 / psi * np.abs(c.traction(r, tau)) * np.abs(slip) * (r < a)
        np.testing.assert_allclose(c.dissipation_rate(r, tau), expect, rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize(("psi", "tau0"), [(1 + math.sqrt(2), math.pi / 6), (30.0, -0.5),
                                           (1.5, 1.2), (300.0, 0.4)])
def test_mdr_friction_loss_of_a_held_rotor(psi: float, tau0: float) -> None:
    """The MDR's slip work at v = 0 (units mu N omega u0) is D / int (P/P0) dtau, with
    int (P / P0) dtau = (2 sqrt 2 / 3) F(tau0) (eq 10): an independent method."""
    c = Contact(psi, tau0)
    loss = float(moving_rotor(psi, tau0, 0.0).friction_loss)
    assert loss == pytest.approx(c.dissipated_energy / (2 * math.sqrt(2) / 3 * c.F0), rel=2e-4)


def test_si_scales_of_the_dissipation() -> None:
    si = dict(R=5e-3, G=79.3e9, nu=0.29, mu=0.2, H=1e-6, u0=0.8e-6, h=0.5e-6,
              omega=2 * math.pi * 40e3)
    s = Contact.from_physical(**si).scales
    assert s.energy == pytest.approx(s.T0 * si["u0"], rel=1e-15)
    assert s.energy_density == pytest.approx(s.energy / (math.pi * s.a_star**2), rel=1e-15)


def test_excess_integral_series_meets_the_closed_form() -> None:
    from core.dissipation import DELTA_SERIES_BELOW, excess_integral
    with mp.workdps(40):
        for m in (1e-12, 0.01, 0.2, DELTA_SERIES_BELOW - 1e-12, DELTA_SERIES_BELOW, 0.6,
                  1 - 1e-9):
            ref = (mp.quad(lambda f, m=m: (1 - m * mp.sin(f) ** 2) ** 1.5, [0, mp.pi / 2])
                   - mp.pi / 2 * (1 - mp.mpf(m)) ** 1.5)
            got = float(excess_integral(np.array(m), np.array(1 - m)))
            assert got == pytest.approx(float(ref), rel=3e-15)
