"""A helper of the tests of the job runner and of the cards that use it."""

from __future__ import annotations

import threading

from app.kit.jobs import JobRunner


def blocked(runner: JobRunner) -> threading.Event:
    """Occupy the runner's worker (another session's job) until the returned event is
    set."""
    gate, started = threading.Event(), threading.Event()

    def hold() -> None:
        started.set()
        gate.wait(30)

    runner.submit("another session", hold, lambda _: None)
    assert started.wait(30)
    return gate
