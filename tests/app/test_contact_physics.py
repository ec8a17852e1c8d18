"""The physical drive (drive = angle: psi follows from theta, mu and nu, eq 23), its
URL keys, the note on mu and nu, and the spheres' period strip (no browser)."""

from __future__ import annotations

import html
import math

import numpy as np
import pytest

from app.contact import spheres
from app.contact.controls import DRIVE_NOTES
from app.contact.query import parse_query
from app.contact.state import ExplorerState, drive_angle, drive_ratio
from app.page.explorer import Explorer
from core import Contact


def test_mu_moves_the_phases_with_the_drive_angle_held() -> None:
    ex = Explorer()
    s = ex.state
    before = np.asarray(ex.contact.force.source.data["T"]).copy()
    s.mu = 0.5  # psi held: T(tau) and the phases stay as they were
    np.testing.assert_array_equal(ex.contact.force.source.data["T"], before)
    s.drive = "angle"
    assert s.psi == Contact(s.psi, s.tau0, mu=0.5, nu=0.3).psi  # switching keeps psi
    theta, slipping = s.theta, Contact(s.psi, s.tau0, mu=0.5, nu=0.3)
    s.mu = 2.0  # more friction, the same drive: psi 2.414 -> 0.604
    psi = math.tan(math.radians(theta)) / math.tan(Contact(1.0, s.tau0, mu=2.0).theta0)
    assert s.psi == drive_ratio(theta, 2.0, 0.3) and math.isclose(s.psi, psi, rel_tol=1e-14)
    c = Contact(s.psi, s.tau0, mu=2.0, nu=0.3)
    np.testing.assert_array_equal(ex.contact.force.source.data["T"],
                                  c.tangential_force(c.tau_grid(400)))
    assert not np.array_equal(ex.contact.force.source.data["T"], before)
    # slip while loading (psi > 1) became full stick (psi <= 1): the phase at pi/4
    assert (int(slipping.phase(math.pi / 4)), int(c.phase(math.pi / 4))) == (2, 1)


def test_theta_follows_psi_in_psi_mode() -> None:
    s = Explorer().state
    s.psi = 3.0
    assert s.theta == drive_angle(3.0, s.mu, s.nu) == math.degrees(
        Contact(3.0, s.tau0, mu=s.mu, nu=s.nu).theta)


def test_the_url_keeps_the_drive_and_theta() -> None:
    ex = Explorer()
    ex.state.param.update(drive="angle")
    ex.state.param.update(theta=40.0, mu=0.35)
    q = ex.state.query()
    assert q["drive"] == "angle" and q["theta"] == "40.0"
    values, messages = parse_query(q)
    assert not messages
    fresh = ExplorerState(**values)
    assert (fresh.drive, fresh.theta, fresh.psi, fresh.mu) == ("angle", 40.0, ex.state.psi, 0.35)


def test_refused_drive_values() -> None:
    _, messages = parse_query({"drive": "sideways"})
    assert messages == ["drive = 'sideways' is unknown (known: psi, angle)"]
    values, messages = parse_query({"drive": "angle", "theta": "91"})
    assert values["theta"] != 91.0 and "theta = 91" in messages[0]
    values, messages = parse_query({"theta": "30"})
    assert "theta" not in values and "ignored" in messages[0]


def test_the_note_says_why_mu_and_nu_change_nothing_with_psi_held() -> None:
    ex = Explorer()
    note = ex.contact.controls.drive_note
    assert note.object == html.escape(DRIVE_NOTES["psi"]) and "unchanged" in note.object
    ex.state.drive = "angle"
    assert note.object == html.escape(DRIVE_NOTES["angle"])
    assert ex.contact.controls.psi_slider.disabled
    assert not ex.contact.controls.theta_slider.disabled


def test_spheres_apart_in_the_gap() -> None:
    c = Contact(2.414, math.pi / 6)
    d = spheres.drawing(c, np.array([3 * math.pi / 2]))
    assert d["spheres_lower"]["y"].max() < d["spheres_upper"]["y"].min()
    np.testing.assert_array_equal(d["spheres_forces"]["head"], 0)
    ex = Explorer()
    marker = ex.contact.spheres.sources["spheres_period_marker"].data
    assert marker["x"] == [float(spheres.strip_x(ex.state.tau))]
    shaded = ex.contact.spheres.period_contact.data["x"]
    assert min(shaded) == float(spheres.strip_x(c.tau0))


def test_a_slider_move_and_what_follows_from_it_are_one_batch() -> None:
    """A move of the psi slider sets psi and theta (eq 23) together: every watcher of
    the state is called once, and sees the corrected state; a move of the tau0 slider
    clamps tau into the new contact in the same batch."""
    ex = Explorer()
    s = ex.state
    seen: list[tuple] = []
    s.param.watch(lambda *events: seen.append(
        (tuple(sorted(e.name for e in events)), s.psi, s.theta, s.tau)),
        ["psi", "theta", "tau", "tau0"])
    ex.contact.controls.psi_slider.value = 3.0
    assert seen == [(("psi", "theta"), 3.0, drive_angle(3.0, s.mu, s.nu), s.tau)]
    assert s.contact() is ex.state.current  # (the state keeps the contact it made)
    seen.clear()
    s.tau = 2.5
    seen.clear()
    ex.contact.controls.tau0_slider.value = 1.0  # tau = 2.5 is past the end pi - 1
    assert seen == [(("tau", "tau0"), 3.0, s.theta, math.pi - 1.0)]
    seen.clear()
    ex.contact.controls.theta_slider.value = s.theta  # (a widget following the state)
    assert seen == []


@pytest.mark.parametrize("mu", [0.2, 3.0])
def test_the_forces_are_drawn_to_one_scale_within_their_coulomb_bound(mu: float) -> None:
    """P and T in one physical unit: slipping, the T arrow reaches the bound +-mu P drawn
    about its foot (it was as long as P: T / T0 and P / P0 on one scale); in partial
    stick it stays inside; the longer of P and mu P is ARROW long; a tiny T keeps its
    label."""
    c = Contact(2.414, math.pi / 6, mu=mu)
    taus = np.array([c.tau0 + 1e-9, math.pi / 3, math.pi / 2, 2.2])
    phases = c.phase(taus)
    d = spheres.drawing(c, taus)
    f, bound = d["spheres_forces"], d["spheres_bound"]
    P_len = f["y1"][:, 0] - f["y0"][:, 0]
    T_len = f["x1"][:, 1] - f["x0"][:, 1]
    reach = bound["x1"][:, 1] - f["x0"][:, 1]  # +mu P, from the arrows' foot
    np.testing.assert_allclose(reach, mu * P_len, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(bound["x1"][:, 0] - f["x0"][:, 1], -reach, rtol=1e-12)
    slipping = phases == 2  # (Phase.SLIP: |T| = mu P, eq 38)
    sticking = phases == 3  # (Phase.PARTIAL_STICK: |T| < mu P)
    assert slipping.any() and sticking.any()
    np.testing.assert_allclose(np.abs(T_len[slipping]), reach[slipping], rtol=1e-12)
    assert np.all(np.abs(T_len[sticking]) < reach[sticking])
    largest = float(c.normal_force(math.pi / 2)) * spheres.force_unit(c)
    assert max(1.0, mu) * largest == pytest.approx(spheres.ARROW, rel=1e-12)
    assert f["label"][0, 1] == f"T = {float(c.tangential_force(taus[0])):+.3g} T₀"
    assert spheres.BOUND_WORDS in Explorer().contact.spheres.h_label.text
