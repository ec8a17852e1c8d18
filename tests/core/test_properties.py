"""Properties over random parameters (hypothesis): continuity, slip at +-mu P, Coulomb's
law, the contact centre returning home, and impulses by quadrature."""

import itertools
import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from core import Contact, coulomb_certificate

psi_any = st.one_of(
    st.floats(0.0, 1.0), st.floats(1.0, 50.0), st.floats(0.0, 12.0).map(lambda x: 10.0**x)
)
psi_slip = st.one_of(st.floats(1.0 + 1e-9, 50.0), st.floats(1.7, 12.0).map(lambda x: 10.0**x))
tau0s = st.floats(-math.pi / 2 + 1e-6, math.pi / 2 - 1e-6)
mus = st.floats(0.01, 2.0)
nus = st.floats(-0.99, 0.5)


@settings(max_examples=200, deadline=None)
@given(psi=psi_slip, tau0=tau0s)
def test_force_is_continuous_at_pi_2_and_tau1(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    for t in (math.pi / 2, c.tau1):
        h = 1e-9 * (c.tau1 - math.pi / 2)
        left, right = c.tangential_force(np.array([t - h, t + h]))
        slope = 3.0 * (1 - math.sin(tau0)) ** 0.5 * (psi + 1) ** 1.5  # generous |dT/dtau|
        assert abs(left - right) <= 2 * h * slope + 1e-15


@settings(max_examples=200, deadline=None)
@given(psi=psi_slip, tau0=tau0s)
def test_slip_phases_carry_plus_minus_mu_p(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    tau = c.tau_grid(300)
    T, P, ph = c.tangential_force(tau), c.normal_force(tau), c.phase(tau)
    np.testing.assert_array_equal(T[ph == 2], P[ph == 2])
    np.testing.assert_array_equal(T[ph == 4], -P[ph == 4])
    assert np.all(np.abs(T) <= P * (1 + 1e-15))  # |T| <= mu P always


@settings(max_examples=60, deadline=None)
@given(psi=psi_any, tau0=tau0s, mu=mus, nu=nus)
def test_coulomb_certificate_holds(psi: float, tau0: float, mu: float, nu: float) -> None:
    report = coulomb_certificate(Contact(psi, tau0, mu, nu), n_r=101, n_tau=151)
    assert report.worst <= 1e-12, report


@settings(max_examples=200, deadline=None)
@given(psi=psi_any, tau0=tau0s)
def test_contact_centre_returns_home(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    u2 = c.centre_displacement(np.array([c.tau0, c.tau_end]))
    scale = (1 - math.sin(tau0)) / 2
    # pi - tau0 is rounded to a float: u2 there is truly ~ |cos tau0| ulp / 2, not 0.
    rounding = abs(math.cos(tau0)) * math.ulp(c.tau_end)
    assert abs(u2[0]) <= 1e-15 * scale
    assert abs(u2[1]) <= 1e-15 * scale + rounding


@settings(max_examples=40, deadline=None)
@given(psi=psi_any, tau0=st.floats(-1.4, 1.4))
def test_integral_of_force_equals_impulse_closed_form(psi: float, tau0: float) -> None:
    """int T/T0 dtau = (2 sqrt 2 / 3) F(tau0) T_imp/(mu P_imp) (eqs 10, 41)."""
    c = Contact(psi, tau0)
    # one quadrature per smooth piece: T has kinks at pi/2 and tau1, and tau1 may lie
    # arbitrarily close to the end of contact (psi -> 1+)
    edges = sorted({c.tau0, math.pi / 2, c.tau_end, *([c.tau1] if psi > 1 else [])})
    integral = sum(
        quad(lambda t: float(c.tangential_force(t)), lo, hi, epsabs=1e-14, epsrel=1e-12,
             limit=400)[0]
        for lo, hi in itertools.pairwise(edges)
    )
    expected = 2 * math.sqrt(2) / 3 * c.F0 * c.impulse_ratio
    assert abs(integral - expected) <= 1e-9 * c.F0 + 1e-14


@settings(max_examples=100, deadline=None)
@given(psi=psi_any, tau0=tau0s, k=st.integers(-50, 50))
def test_every_period_repeats_the_same_contact(psi: float, tau0: float, k: int) -> None:
    c = Contact(psi, tau0)
    tau = np.linspace(c.tau0, c.tau_end, 7)[1:-1]
    np.testing.assert_allclose(
        c.tangential_force(tau + 2 * math.pi * k), c.tangential_force(tau), rtol=0, atol=1e-12
    )
