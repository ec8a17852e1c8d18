"""The background job runner (`app.kit.jobs`): one waiting job per owner, owners in turn,
every outcome handed back, nothing left running."""

from __future__ import annotations

import pytest
from jobs_helpers import blocked, drained

from app.kit.jobs import JobRunner


def test_owners_are_served_in_turn_and_a_newer_job_replaces_a_waiting_one() -> None:
    runner, ran, outcomes = JobRunner(), [], {}
    gate = blocked(runner)
    for owner, job in (("a", "a1"), ("b", "b1"), ("a", "a2"), ("c", "c1"), ("a", "a3")):
        runner.submit(owner, lambda job=job: ran.append(job) or job,
                      lambda result, owner=owner: outcomes.setdefault(owner, []).append(result))
    gate.set()
    assert drained(runner, 10)
    # a's newest job ran in a's place in the line (first), then b's and c's
    assert ran == ["a3", "b1", "c1"]
    assert outcomes == {"a": ["a3"], "b": ["b1"], "c": ["c1"]}


def test_a_crowd_delays_a_bystander_by_one_job_each_and_refuses_none() -> None:
    runner, ran = JobRunner(), []
    gate = blocked(runner)
    for i in range(40):  # one session submitting over and over
        runner.submit("busy", lambda i=i: ran.append(("busy", i)), lambda _: None)
    for s in range(20):  # a crowd, one job each
        runner.submit(f"s{s}", lambda s=s: ran.append((f"s{s}",)), lambda _: None)
    runner.submit("bystander", lambda: ran.append(("bystander",)), lambda _: None)
    gate.set()
    assert drained(runner, 10)
    assert ran[0] == ("busy", 39)  # its newest only
    assert ran[-1] == ("bystander",) and len(ran) == 22  # everyone's job ran, once


def test_a_failing_job_hands_back_its_exception() -> None:
    runner, outcome = JobRunner(), []

    def fail() -> None:
        raise ValueError("psi = 0 is outside the allowed range")

    runner.submit("a", fail, outcome.append)
    assert drained(runner, 10)
    assert isinstance(outcome[0], ValueError) and "psi = 0" in str(outcome[0])


def test_cancel_drops_the_waiting_job() -> None:
    runner, ran = JobRunner(), []
    gate = blocked(runner)
    runner.submit("a", lambda: ran.append("a"), lambda _: None)
    runner.submit("b", lambda: ran.append("b"), lambda _: None)
    runner.cancel("a")
    gate.set()
    assert drained(runner, 10)
    assert ran == ["b"]


@pytest.mark.parametrize("jobs", [0, 1, 5])
def test_drained_returns_when_everything_ran(jobs: int) -> None:
    runner, ran = JobRunner(), []
    for i in range(jobs):
        runner.submit(i, lambda i=i: ran.append(i), lambda _: None)
    assert drained(runner, 10)
    assert sorted(ran) == list(range(jobs))
