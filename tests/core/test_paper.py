"""The paper's published numbers (Zharii 1996, Figs 4, 7, 8 and eq 23, 35)."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from core import Contact, impulse_ratio
from core.elliptic import quartic_integral

TAU0 = math.pi / 6  # H = 2h in every figure


def test_critical_angle_is_13_65_degrees_for_mu_02_nu_03() -> None:
    c = Contact(1.0, TAU0, mu=0.2, nu=0.3)
    assert round(math.degrees(c.theta0), 2) == 13.65
    assert c.theta == pytest.approx(c.theta0, rel=1e-15)  # psi = 1 is theta = theta0


def test_fig4_tau1_is_three_quarters_pi_for_psi_sqrt2_plus_1() -> None:
    assert Contact(math.sqrt(2) + 1, TAU0).tau1 == pytest.approx(3 * math.pi / 4, rel=1e-15)


@pytest.mark.parametrize(
    ("printed_psi", "tau1"),
    [(2.41, 3 * math.pi / 4), (6.46, 2 * math.pi / 3), (28.35, 7 * math.pi / 12)],
)
def test_fig7b_psi_values_give_the_printed_tau1(printed_psi: float, tau1: float) -> None:
    """The exact psi for each tau1 of Fig. 7b rounds to the value printed in the paper."""
    exact_psi = 2 * (1 - math.sin(TAU0)) / (1 - math.sin(tau1)) - 1  # eq 31 solved for psi
    assert round(exact_psi, 2) == printed_psi
    assert Contact(exact_psi, TAU0).tau1 == pytest.approx(tau1, rel=1e-14)
    # and the printed, rounded psi lands within the printed precision
    assert abs(Contact(printed_psi, TAU0).tau1 - tau1) < 2e-3


def test_fig7a_small_angles_are_psi_times_the_normal_force() -> None:
    for psi in (0.4, 0.8, 1.0):
        c = Contact(psi, TAU0)
        tau = c.tau_grid(200)
        np.testing.assert_allclose(
            c.tangential_force(tau), psi * c.normal_force(tau), rtol=1e-15, atol=1e-16
        )
        assert (c.phase(tau) == 1).all()


def test_fig8_impulse_is_largest_at_psi_1() -> None:
    psi = np.linspace(0.0, 30.0, 30001)
    ratio = impulse_ratio(psi, TAU0)
    assert psi[np.argmax(ratio)] == 1.0
    assert ratio.max() == 1.0
    assert np.all(np.diff(ratio[psi >= 1]) < 0)  # decreasing after the peak
    assert np.all(np.diff(ratio[psi <= 1]) > 0)


@pytest.mark.parametrize("tau0", [TAU0, 0.0, 1.2, -0.9])
def test_impulse_decays_like_inverse_sqrt_psi(tau0: float) -> None:
    """Eq 41 for large psi: ratio ~ sqrt(2/psi) J(0) / J(m0), J(0) = 3 pi / 16."""
    m0 = (1 - math.sin(tau0)) / 2
    limit = math.sqrt(2) * (3 * math.pi / 16) / float(quartic_integral(m0))
    psi = np.array([1e4, 1e6, 1e8, 1e12])
    scaled = impulse_ratio(psi, tau0) * np.sqrt(psi)
    assert np.all(np.abs(scaled / limit - 1) < 3 / psi**0.5)
    assert abs(scaled[-1] / limit - 1) < 1e-9


@pytest.mark.parametrize("psi", [1.5, 2.414, 28.35, 1e3, 1e6, 1e10])
def test_eq35_partial_stick_duration_for_large_psi(psi: float) -> None:
    c = Contact(psi, TAU0)
    approx = 2 * math.sqrt((1 - math.sin(TAU0)) / psi)
    assert (c.tau1 - math.pi / 2) / approx == pytest.approx(1.0, abs=2 / psi)


def test_eq10_identity_integral_of_force_is_the_elliptic_closed_form() -> None:
    """int (sin tau - s0)^(3/2) dtau over the contact = (2 sqrt 2 / 3) F(tau0)."""
    for tau0 in (TAU0, 0.0, 1.4, -1.2):
        c = Contact(1.0, tau0)
        integral, _ = quad(
            lambda t, c=c: float(c.normal_force(t)),
            tau0,
            math.pi - tau0,
            epsabs=1e-14,
            epsrel=1e-13,
            limit=200,
        )
        assert integral == pytest.approx(2 * math.sqrt(2) / 3 * c.F0, rel=1e-11)
