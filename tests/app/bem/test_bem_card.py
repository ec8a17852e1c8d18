"""The "How exact is the model?" card without a browser (`app.bem.BemCard`): nothing is
built or computed until it is opened and Compute pressed; the run goes to the job runner
and its sources then hold core.bem's numbers; a contact met again runs nothing; a
changed contact is said to be not the result's; a too-large request is refused with its
command line; the card follows tau; a closed card drops its waiting run; a failed run
ends the progress and says why."""

from __future__ import annotations

import math

import numpy as np
import pytest
from jobs_helpers import Watched, blocked, drained

import app.bem.data
from app.bem import BemCard, data
from app.kit.jobs import RUNNER
from core import Contact

PSI, TAU0 = 1 + math.sqrt(2), math.pi / 6
CONTACT = Contact(PSI, TAU0, mu=0.2, nu=0.3)
OTHER = Contact(PSI, TAU0, mu=0.3, nu=0.3)
TAU = 17 * math.pi / 24


@pytest.fixture(scope="module")
def runs() -> dict:
    """core.bem's runs of the two contacts, once per module (by key)."""
    keys = [data.request(c, data.RESOLUTIONS[0]) for c in (CONTACT, OTHER)]
    return {k: data.compute(k) for k in keys}


@pytest.fixture
def computed(runs, monkeypatch: pytest.MonkeyPatch) -> list:
    """The card's runs, counted: each key the card computes is appended (and its
    run, computed by core.bem once per module, returned)."""
    asked: list = []

    def compute(key):
        asked.append(key)
        return runs[key]

    monkeypatch.setattr(app.bem.data, "compute", compute)
    return asked


def opened(contact: Contact = CONTACT, tau: float = TAU) -> BemCard:
    card = BemCard(contact, tau)
    card.card.collapsed = False
    return card


def wait() -> None:
    assert drained(RUNNER, 60)


def test_nothing_is_built_or_computed_until_opened_and_asked(computed) -> None:
    card = BemCard(CONTACT, TAU)
    assert not card.built
    card.update(OTHER, 2.0)  # follows the page without building anything
    card.card.collapsed = False
    assert card.built
    wait()
    assert computed == [] and card.result is None
    assert card.sources["T"].data["T"] == []
    assert card.status.object.startswith("Nothing computed yet: press Compute")
    # the map is drawn at once, from the app's CSV
    rows = data.read_map()
    np.testing.assert_array_equal(card.sources["map_nu"].data["err"],
                                  [r.worst_T_error for r in data.identical(rows)])
    assert card.sources["map_current"].data == {"nu": [0.3],
                                                "err": [data.map_at(rows, 0.3)]}
    card.close()


def test_compute_shows_core_bems_run_and_a_second_request_runs_nothing(computed,
                                                                       runs) -> None:
    card = opened()
    card.compute_button.clicks += 1
    assert card.progress.busy and card.status.object.startswith("computing the referee")
    wait()
    key = data.request(CONTACT, data.RESOLUTIONS[0])
    run = runs[key]
    assert computed == [key] and not card.progress.busy
    np.testing.assert_array_equal(card.sources["T"].data["T"], run.T)
    f = data.field_columns(run, TAU)
    np.testing.assert_array_equal(card.sources["referee"].data["pt"][0], f["referee"]["pt"][0])
    np.testing.assert_array_equal(card.sources["closed"].data["pt"][0], f["closed"]["pt"][0])
    np.testing.assert_array_equal(card.sources["stuck"].data["x"], f["stuck"]["x"])
    assert card.tau_mark.location == f["readout"]["tau"]
    assert f"{run.worst_T_error:.2g} T₀" in card.status.object
    with Watched(RUNNER) as jobs:
        card.compute_button.clicks += 1  # the same contact again: from the cache
    assert jobs.waiting == 0 and not card.progress.busy
    wait()
    assert computed == [key]
    card.close()


def test_a_changed_contact_is_not_the_results_and_one_met_again_is_shown_from_cache(
        computed, runs) -> None:
    card = opened()
    card.compute()
    wait()
    first = card.result
    card.update(OTHER, TAU)
    assert card.result is first  # still shown, and said to be the previous contact's
    assert "This result is of the previous contact (ψ = 2.414, τ₀ = 0.5236, μ = 0.2" in (
        card.status.object)
    card.compute()
    wait()
    assert card.result.key.mu == 0.3 and "previous" not in card.status.object
    card.update(CONTACT, TAU)  # met before: shown at once, nothing run
    assert card.result is first and "previous" not in card.status.object
    np.testing.assert_array_equal(card.sources["T"].data["T"], first.T)
    assert len(computed) == 2
    card.close()


def test_the_card_follows_tau_on_the_runs_steps(computed, runs) -> None:
    card = opened()
    card.compute()
    wait()
    card.update(CONTACT, 1.2)
    run = card.result
    f = data.field_columns(run, 1.2)
    assert card.tau_mark.location == f["readout"]["tau"] == run.tau[data.step_at(run, 1.2)]
    np.testing.assert_array_equal(card.sources["referee"].data["py"][0], f["referee"]["py"][0])
    assert f"At τ = {f['readout']['tau']:.4f} rad" in card.readout.object
    assert len(computed) == 1
    card.close()


def test_a_too_large_request_is_refused_with_the_command_line(computed) -> None:
    card = opened()
    card.resolution.value = data.COMMAND_LINE_ONLY
    with Watched(RUNNER) as jobs:
        card.compute()
    assert jobs.waiting == 0 and not card.progress.busy
    wait()
    assert computed == []
    assert "is more than this page runs" in card.message.object
    assert (f"python -m core.bem paper --psi {PSI!r} --tau0 {TAU0!r} --mu 0.2 --nu 0.3 "
            "--grid 64 --steps 200 --json") in card.message.object
    card.resolution.value = data.RESOLUTIONS[0]
    card.compute()  # an accepted request clears the refusal
    assert card.message.object == ""
    wait()
    card.close()


def test_a_contact_outside_the_referees_nu_is_refused_where_compute_is(computed) -> None:
    card = opened(Contact(PSI, TAU0, mu=0.2, nu=0.5))
    card.compute()
    wait()
    assert computed == [] and "the referee takes nu in [0, 0.5)" in card.message.object
    assert card.sources["map_current"].data == {"nu": [], "err": []}
    card.close()


def test_a_closed_card_drops_its_waiting_run_and_asks_for_nothing_more(computed) -> None:
    card = opened()
    gate = blocked(RUNNER)
    try:
        with Watched(RUNNER) as jobs:
            card.compute()
            assert jobs.waiting == 1 and card.progress.busy
            card.close()
            assert jobs.waiting == 0
            card.compute()
            assert jobs.waiting == 0
    finally:
        gate.set()
    wait()
    assert computed == [] and card.result is None


def test_a_failed_run_ends_the_progress_and_says_why(monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(key):
        raise RuntimeError("out of memory")

    monkeypatch.setattr(app.bem.data, "compute", broken)
    card = opened()
    card.compute()
    wait()
    assert not card.progress.busy
    assert card.message.object == "⚠ the referee could not run: out of memory"
    card.close()


def test_a_contact_changed_while_its_run_is_on_its_way_is_said_when_it_arrives(
        computed) -> None:
    card = opened()
    gate = blocked(RUNNER)
    try:
        card.compute()
        card.update(OTHER, TAU)  # the status still says the run is on its way
        assert card.progress.busy and card.status.object.startswith("computing the referee")
    finally:
        gate.set()
    wait()
    assert card.result.key.same_contact(CONTACT) and not card.progress.busy
    assert "This result is of the previous contact" in card.status.object
    card.close()
