"""SI inputs to the dimensionless problem and back (eqs 4, 9, 10, 23, 37, 41)."""

import dataclasses
import itertools
import math

import mpmath as mp
import numpy as np
import pytest
from scipy.integrate import quad

from core import DOMAIN, DRY_MU, MATERIALS, Contact

# A steel pair in a 40 kHz motor: R = 5 mm, H = 1 um, u0 = 0.8 um, h = 0.5 um.
SI = {
    "R": 5e-3,
    "G": 79.3e9,
    "nu": 0.29,
    "mu": 0.2,
    "H": 1e-6,
    "u0": 0.8e-6,
    "h": 0.5e-6,
    "omega": 2 * math.pi * 40e3,
}


def test_dimensionless_parameters_from_si() -> None:
    c = Contact.from_physical(**SI)
    assert c.tau0 == pytest.approx(math.pi / 6, rel=1e-15)  # sin tau0 = h / H = 1/2
    psi = 2 * (1 - 0.29) * 0.8e-6 / (0.2 * (2 - 0.29) * 1e-6)
    assert c.psi == pytest.approx(psi, rel=1e-15)
    assert math.tan(c.theta) == pytest.approx(0.8, rel=1e-14)  # theta = arctan(u0 / H)


def test_scales_against_the_paper_in_mpmath() -> None:
    s = Contact.from_physical(**SI).scales
    with mp.workdps(30):
        R, G, nu, mu, H, h, w = (mp.mpf(SI[k]) for k in ("R", "G", "nu", "mu", "H", "h", "omega"))
        T0 = mu * 2 * mp.sqrt(2) * G / (3 * (1 - nu)) * mp.sqrt(R) * H**1.5  # eq 37
        a_star = mp.sqrt(R * (H - h) / 2)
        p_star = 4 * G * a_star / ((1 - nu) * mp.pi * R)
        s0 = h / H
        F = (1 + s0) * (1 + 3 * s0) * mp.ellipk((1 - s0) / 2) - 8 * s0 * mp.ellipe((1 - s0) / 2)
        P_imp = 8 * G * mp.sqrt(R) * H**1.5 * F / (9 * (1 - nu) * w)  # eq 10
    assert s.T0 == pytest.approx(float(T0), rel=1e-14)
    assert s.P0 == pytest.approx(float(T0 / mu), rel=1e-14)
    assert s.a_star == pytest.approx(float(a_star), rel=1e-14)
    assert s.p_star == pytest.approx(float(p_star), rel=1e-14)
    assert s.traction_star == pytest.approx(float(mu * p_star), rel=1e-14)
    assert s.normal_impulse == pytest.approx(float(P_imp), rel=1e-13)
    assert s.period == pytest.approx(25e-6, rel=1e-15)
    assert s.alpha_star == pytest.approx(0.5e-6, rel=1e-15)


def test_physical_force_and_impulse_by_quadrature_in_time() -> None:
    """Integrate T(t) in newtons over seconds; compare with the impulse in N s."""
    c = Contact.from_physical(**SI)
    s, w = c.scales, SI["omega"]
    t0, t1 = c.tau0 / w, c.tau_end / w
    T_imp, _ = quad(
        lambda t: s.T0 * float(c.tangential_force(w * t)),
        t0,
        t1,
        points=[math.pi / 2 / w, c.tau1 / w],
        epsabs=0,
        epsrel=1e-12,
        limit=200,
    )
    P_imp, _ = quad(
        lambda t: s.P0 * float(c.normal_force(w * t)), t0, t1, epsabs=0, epsrel=1e-12, limit=200
    )
    assert T_imp == pytest.approx(s.tangential_impulse, rel=1e-10)
    assert P_imp == pytest.approx(s.normal_impulse, rel=1e-10)


def test_hertz_in_si_matches_eq_5_to_7() -> None:
    """At tau = pi/2 the Hertz force (eq 9) and radius (eq 5) agree with each other."""
    c = Contact.from_physical(**SI)
    s = c.scales
    P = s.P0 * float(c.normal_force(math.pi / 2))
    a_eq5 = (3 * (1 - SI["nu"]) * SI["R"] * P / (8 * SI["G"])) ** (1 / 3)
    assert s.a_star * float(c.contact_radius(math.pi / 2)) == pytest.approx(a_eq5, rel=1e-14)
    alpha = s.alpha_star * float(c.approach(math.pi / 2))
    assert alpha == pytest.approx(2 * a_eq5**2 / SI["R"], rel=1e-14)  # eq 7


def test_preload_and_grazing_inputs() -> None:
    pre = Contact.from_physical(**{**SI, "h": -0.5e-6})
    assert pre.tau0 == pytest.approx(-math.pi / 6, rel=1e-15)
    graze = Contact.from_physical(**{**SI, "h": 1e-6 * (1 - 1e-12)})
    assert math.pi / 2 - graze.tau0 == pytest.approx(math.sqrt(2e-12), rel=1e-4)


def test_materials_are_valid_inputs() -> None:
    for name, mu in DRY_MU.items():
        m = MATERIALS[name]
        c = Contact.from_physical(**{**SI, "G": m.G, "nu": m.nu, "mu": mu})
        assert c.scales is not None and c.scales.T0 > 0, name
        assert np.isfinite(c.impulse_ratio)


def test_explorer_materials_are_the_handbook_values() -> None:
    # G (Pa), nu of core.MATERIALS and the typical dry mu of the explorer's four
    assert {k: (MATERIALS[k].G, MATERIALS[k].nu, mu) for k, mu in DRY_MU.items()} == {
        "steel": (79.3e9, 0.29, 0.2), "aluminium": (26.0e9, 0.33, 0.3),
        "glass": (28.7e9, 0.22, 0.3), "PZT ceramic": (24.0e9, 0.31, 0.2)}
    assert all(MATERIALS[k].source for k in DRY_MU)


def test_dimensionless_contact_has_no_scales() -> None:
    assert Contact(1.0, 0.5).scales is None
    assert Contact.from_physical(**SI) == Contact(
        Contact.from_physical(**SI).psi, Contact.from_physical(**SI).tau0, 0.2, 0.29
    )


def test_every_scale_is_finite_over_the_whole_domain() -> None:
    """Every corner of the SI box of core.DOMAIN (u0 from 0 to the largest psi allows, h
    from near -H to near H): every scale finite, the elastic ones positive."""
    edges = {name: (DOMAIN[name].lo, DOMAIN[name].hi) for name in ("R", "G", "H", "omega")}
    edges["nu"] = (math.nextafter(-1.0, 0.0), 0.5)
    edges["mu"] = (5e-324, DOMAIN["mu"].hi)
    for corner in itertools.product(*edges.values()):
        si = dict(zip(edges, corner, strict=True))
        H, mu, nu = si["H"], si["mu"], si["nu"]
        u0_max = min(DOMAIN["u0"].hi, 0.999 * 1e12 * mu * (2 - nu) * H / (2 * (1 - nu)))
        for u0, h in itertools.product((0.0, u0_max), (-H * (1 - 1e-15), 0.0, H * (1 - 1e-16))):
            with np.errstate(all="raise", under="ignore"):
                s = Contact.from_physical(**si, u0=u0, h=h).scales
            values = [getattr(s, f.name) for f in dataclasses.fields(s) if f.name != "inputs"]
            assert all(math.isfinite(v) and v >= 0 for v in values), (si, u0, h, s)
            assert min(s.P0, s.a_star, s.p_star, s.alpha_star, s.normal_impulse, s.period) > 0
