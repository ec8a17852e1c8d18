"""Contact.at(tau): the quantities of one contact, each computed on first use and kept.

Keeping them must never show: every quantity is bit for bit what it is when computed
alone, whatever order they are asked in, and no quantity can be changed in place
(some are inputs of others)."""

import math
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from core import Contact, Phase, batch, curve

QUANTITIES = ("clock", "phase", "approach", "contact_radius", "stick_radius", "normal_force",
              "tangential_force", "centre_displacement", "centre_velocity",
              "lower_centre_displacement", "lower_centre_velocity")
CASES = [(0.4, math.pi / 6), (1.0, -0.9), (2.414, -0.9), (28.35, 1.5), (1e6, 0.3)]


def _times(c: Contact) -> np.ndarray:
    # a grid through every phase, plus times outside contact and a period away
    return np.concatenate([c.tau_grid(301), [c.tau0 - 0.1, c.tau_end + 0.2, 1.0 + 2 * math.pi]])


@pytest.mark.parametrize(("psi", "tau0"), CASES)
def test_shared_quantities_equal_each_computed_alone(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    tau = _times(c)
    alone = {q: getattr(c.at(tau), q) for q in QUANTITIES}  # a fresh timeline each
    for order in (QUANTITIES, QUANTITIES[::-1]):
        shared = c.at(tau)
        for q in order:
            np.testing.assert_array_equal(getattr(shared, q), alone[q], err_msg=q)
    # and they are the values of the Contact methods, which are plain formulas
    k = math.sqrt(2 / (psi + 1))
    a2 = np.maximum((1 - alone["clock"]) * (1 + alone["clock"]), 0)
    np.testing.assert_array_equal(alone["approach"], a2)
    scale = (1 - math.sin(tau0)) ** 1.5
    inside = np.abs(alone["clock"]) <= 1
    assert np.all(alone["tangential_force"][~inside] == 0)
    if psi > 1:  # T = +a^3 (slip), 2b^3 - a^3 (partial stick), -a^3 (counter-slip) in T0
        b2 = np.where(alone["phase"] == 3, 1 - (alone["clock"] / k) ** 2, 0)
        sign = np.where(alone["clock"] > 0, -1.0, 1.0)
        expected = scale * (sign * a2**1.5 + 2 * b2**1.5)
        np.testing.assert_allclose(alone["tangential_force"], expected, rtol=1e-12, atol=1e-15)


def test_quantities_are_read_only_and_have_the_shape_of_tau() -> None:
    c = Contact(2.414, math.pi / 6)
    line = c.at(np.linspace(0.5, 2.5, 12).reshape(3, 4))
    for q in QUANTITIES:
        values = getattr(line, q)
        assert values.shape == (3, 4), q
        with pytest.raises(ValueError, match="read-only"):
            values[0, 0] = 1.0
    assert c.at(1.0).tangential_force.shape == ()
    assert c.tangential_force([1.0, 2.0]).shape == (2,)


@pytest.mark.parametrize(("psi", "tau0"), CASES)
def test_one_time_is_computed_once_in_every_shape_and_equals_the_times_alone(
        psi: float, tau0: float, monkeypatch) -> None:
    """A view asks many quantities at the time it shows, one method at a time and in
    several shapes (a scalar, one element, a column): each quantity of that time is one
    compiled pass, shared, and bit for bit what a grid of times gives at it."""
    from core import kernels

    runs = []
    rows = kernels.rows
    monkeypatch.setattr(kernels, "rows", lambda q, *args: (runs.append(q), rows(q, *args)))
    c = Contact(psi, tau0)
    tau = float(np.mean([c.tau0, c.tau_end]))
    grid = np.array([c.tau0 - 0.1, tau, c.tau_end])
    on_grid = {q: getattr(c.at(grid), q)[1] for q in QUANTITIES}
    traction = c.traction(0.1, grid)[1]
    runs.clear()
    for shape in [(), (1,), (1, 1), (), (1,)]:
        times = np.full(shape, tau)
        for q in QUANTITIES:
            values = getattr(c.at(times), q)
            assert values.shape == shape and not values.flags.writeable, (shape, q)
            assert values.tobytes() == on_grid[q].tobytes(), (shape, q)
        assert c.phase(times).tobytes() == on_grid["phase"].tobytes()
        assert c.traction(0.1, times).tobytes() == traction.tobytes()
    assert sorted(runs) == sorted(set(runs))  # each kernel quantity once
    assert c.at(tau) is c.at(np.float64(tau)) is c.at([tau][0])
    # the time is held as a copy: changing the caller's array changes nothing
    times = np.array([tau])
    line = c.at(times)
    times[0] = c.tau0 - 1.0
    assert c.at(np.array([tau])) is line and line.tau[0] == tau
    assert c.at(times).phase[0] == Phase.NO_CONTACT


def test_a_contact_keeps_a_few_single_times() -> None:
    from core.contact import INSTANTS

    c = Contact(2.414, math.pi / 6)
    taus = np.linspace(0.6, 2.5, 3 * INSTANTS)
    for t in taus:
        np.testing.assert_array_equal(c.at(t).tangential_force, c.at(taus).tangential_force[
            list(taus).index(t)])
    lines, passes = c._instants
    assert len(lines) <= INSTANTS and len(passes) <= INSTANTS


def test_threads_asking_one_contact_at_single_times_get_its_values() -> None:
    """The Methods worker and the page may ask one contact at once: the kept times are
    changed by one dict operation at a time, never iterated."""
    import threading

    c = Contact(2.414, math.pi / 6)
    taus = np.linspace(0.6, 2.5, 40)
    expected = c.at(taus).tangential_force
    errors = []

    def ask(offset: int) -> None:
        try:
            for k in range(2000):
                i = (k * 7 + offset) % taus.size
                if c.tangential_force(taus[i]).tobytes() != expected[i].tobytes():
                    errors.append(i)
        except Exception as err:  # (a dict changed while iterated would land here)
            errors.append(err)

    threads = [threading.Thread(target=ask, args=(n,)) for n in range(4)]
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # (threads switch between almost any two steps)
    try:
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        sys.setswitchinterval(interval)
    assert errors == []


def test_long_two_dimensional_arrays_give_the_values_of_each_row() -> None:
    c = Contact(28.35, -0.9)
    tau = np.linspace(-1.0, 4.0, 2 * 40_000).reshape(2, -1)
    line = c.at(tau)
    for q in QUANTITIES[1:]:
        values = getattr(c, q)(tau)
        np.testing.assert_array_equal(values, getattr(line, q), err_msg=q)
        assert values.shape == tau.shape and not values.flags.writeable, q
        for row in range(2):
            np.testing.assert_array_equal(values[row], getattr(c, q)(tau[row]), err_msg=q)


@settings(max_examples=300, deadline=None)
@given(st.floats(1.0 + 1e-9, 1e8), st.floats(-1.55, 1.55))
def test_counter_slip_starts_at_the_tau1_core_reports(psi: float, tau0: float) -> None:
    """One rule for the boundary (eq 31): at tau = Contact.tau1 every quantity says
    counter-slip (phase 4, b = 0 exactly, T = -mu P, eq 33), through Contact, Timeline,
    core.batch and core.curve alike; just before it, partial stick still has b > 0."""
    c = Contact(psi, tau0)
    t1 = c.tau1
    line = c.at(np.array([t1]))
    assert int(line.phase[0]) == Phase.COUNTER_SLIP
    assert line.stick_radius[0] == 0.0
    assert line.tangential_force[0] == pytest.approx(-line.normal_force[0], rel=1e-14,
                                                     abs=1e-300)
    assert int(batch.phase(psi, tau0, t1)) == Phase.COUNTER_SLIP
    rows, _ = curve(psi, tau0)
    at_t1 = rows[0] == t1
    assert at_t1.any() and (rows[2][at_t1] == 0.0).all()  # tau1 is a grid point
    before = t1 - 1e-6 * (t1 - math.pi / 2)
    if before > math.pi / 2 and c.tau1 < c.tau_end:
        assert int(c.phase(before)) == Phase.PARTIAL_STICK and c.stick_radius(before) > 0
