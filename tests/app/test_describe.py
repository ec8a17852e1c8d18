"""What a screen reader hears of the plots (`app.page.describe`), without a browser:
the phase's start announced is where core's phase changes, and the descriptions carry
core's numbers."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.page.describe import announcement, descriptions, phase_start
from core import Contact, Phase


@pytest.mark.parametrize(("psi", "tau0"), [(0.5, 0.5236), (1.0, 0.5236), (1.7, -0.4),
                                           (2.414, 0.5236), (20.0, 1.2), (1e4, 0.1)])
def test_a_phase_starts_where_cores_phase_changes(psi: float, tau0: float) -> None:
    """At every time of the contact, the start announced is not after that time, core's
    phase there is the phase of that time from the start on, and just before it core
    has another phase, or the contact has not begun."""
    c = Contact(psi, tau0)
    taus = np.linspace(c.tau0, c.tau_end, 801)[1:-1]
    for tau in taus:
        phase, start = int(c.phase(tau)), phase_start(c, tau)
        assert c.tau0 <= start <= tau
        after = np.linspace(start, tau, 9)[1:]
        assert (c.phase(after) == phase).all(), (tau, start)
        before = start - 1e-9 * max(1.0, abs(start))
        assert start == c.tau0 or int(c.phase(before)) != phase, (tau, start)


def test_phase_starts_are_cores_boundaries() -> None:
    """Slip from tau0, partial stick from pi/2 (the end of loading), counter-slip from
    tau1 (eq 31); no phase outside the contact."""
    c = Contact(2.414, 0.5236)
    assert phase_start(c, 1.0) == c.tau0 and int(c.phase(1.0)) == Phase.SLIP
    assert phase_start(c, 1.6) == math.pi / 2 and int(c.phase(1.6)) == Phase.PARTIAL_STICK
    tau = (c.tau1 + c.tau_end) / 2
    assert phase_start(c, tau) == c.tau1 and int(c.phase(tau)) == Phase.COUNTER_SLIP
    assert math.isnan(phase_start(c, 0.1))
    assert announcement(c, 1.6) == "Partial stick from τ = 1.571 rad"
    assert announcement(c, tau) == f"Counter-slip from τ = {c.tau1:.3f} rad"


def test_descriptions_carry_cores_numbers() -> None:
    c, tau = Contact(3.7, 0.3), 2.1
    d = descriptions(c, tau, 2)
    T, P = float(c.tangential_force(tau)), float(c.normal_force(tau))
    a, b = float(c.contact_radius(tau)), float(c.stick_radius(tau))
    assert d["spheres"].endswith(f"P = {P:.3f} P0, T = {T:+.3f} T0")
    assert f"contact radius {a:.3f} a*, stick radius {b:.3f} a*" in d["disc"]
    assert f"a = {a:.3f} a*, b = {b:.3f} a*" in d["curves"]
    assert d["traction"].startswith("Traction profile at τ = 2.100 rad: partial stick"
                                    if int(c.phase(tau)) == Phase.PARTIAL_STICK else
                                    "Traction profile at τ = 2.100 rad: counter-slip")
