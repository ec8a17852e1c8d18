"""Helpers of the tests of the job runner and of the cards that use it, on the runner's
public API only (`JobRunner.submit`, `cancel` and what the jobs themselves do)."""

from __future__ import annotations

import threading
from collections.abc import Callable, Hashable
from typing import Any

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


def drained(runner: JobRunner, timeout: float = 60.0) -> bool:
    """Wait until every job submitted so far has run and its `done` been handed to its
    session: a job submitted now joins the line after every owner waiting (owners are
    served in turn), so once it runs they all have; whether it did within `timeout` s."""
    ran = threading.Event()
    runner.submit(object(), ran.set, lambda _: None)
    return ran.wait(timeout)


class Watched:
    """What the cards asked of `runner` while watched (``with Watched(runner) as jobs``):
    `waiting`, the owners whose newest job was submitted and has neither run nor been
    cancelled, and `ran`, the owners whose jobs ran, in order (from their submits, their
    cancels and the jobs themselves running; the runner is restored at the end)."""

    def __init__(self, runner: JobRunner) -> None:
        self.runner = runner
        self.ran: list[Hashable] = []
        self._newest: dict[Hashable, object] = {}  # owner -> its newest job's mark
        self._lock = threading.Lock()

    @property
    def waiting(self) -> int:
        """How many owners have a job submitted, not yet run and not cancelled."""
        with self._lock:
            return len(self._newest)

    def __enter__(self) -> Watched:
        submit, cancel = self.runner.submit, self.runner.cancel

        def watched_submit(owner: Hashable, job: Callable[[], Any],
                           done: Callable[[Any], None]) -> None:
            mark = object()

            def run() -> Any:
                with self._lock:
                    if self._newest.get(owner) is mark:
                        del self._newest[owner]
                    self.ran.append(owner)
                return job()

            with self._lock:
                self._newest[owner] = mark
            submit(owner, run, done)

        def watched_cancel(owner: Hashable) -> None:
            with self._lock:
                self._newest.pop(owner, None)
            cancel(owner)

        self.runner.submit, self.runner.cancel = watched_submit, watched_cancel
        return self

    def __exit__(self, *exc: object) -> None:
        del self.runner.submit, self.runner.cancel  # (the class's methods again)
