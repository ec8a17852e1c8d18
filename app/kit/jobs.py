"""One background job runner for every session of a server process, fair to each.

The Methods and Motor cards compute for much longer than a slider's move (numba kernels
that release the GIL, so the event loop serves other sessions meanwhile). They run here,
on one worker thread per process, so that sliders never wait for them and the work in
flight is bounded:

- each owner (a card of one session) has at most one job waiting: a newer one replaces
  it, keeping its place in the line;
- waiting owners are served in turn (round-robin), so a session that submits often
  delays no other by more than one job of its own: there is no process-wide cap that a
  crowd could fill and a bystander be refused by;
- an owner's waiting job is dropped by `cancel` (its session ended).

Each job's outcome goes to its `done` callback on the session's event loop (`later`), a
value or the exception it raised: a card's status always ends.
"""

from __future__ import annotations

import logging
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Any

import panel as pn
from bokeh.document import Document
from panel.io.state import set_curdoc

log = logging.getLogger(__name__)


def later(doc: Document | None, fn: Callable[[], Any]) -> None:
    """Run `fn` on the event loop of `doc`'s session, with the document locked (Panel's
    `state.execute`, scheduled): where a worker thread hands a result to a session, or a
    widget's own change must wait until the browser's change has been handled."""
    with set_curdoc(doc):
        pn.state.execute(fn, schedule=True)


class JobRunner:
    """Runs jobs on one worker thread, one waiting job per owner, owners in turn."""

    def __init__(self, name: str = "jobs") -> None:
        self._name = name
        self._cond = threading.Condition()
        #: owner -> (job, done, doc), in the order the owners joined the line
        self._waiting: OrderedDict[Hashable, tuple] = OrderedDict()
        self._thread: threading.Thread | None = None

    def submit(self, owner: Hashable, job: Callable[[], Any],
               done: Callable[[Any], None]) -> None:
        """Run `job()` in turn, then `done(result)` (or `done(exception)`) on the event
        loop of the current session's document; replaces `owner`'s waiting job."""
        with self._cond:
            self._waiting[owner] = (job, done, pn.state.curdoc)
            if self._thread is None:
                self._thread = threading.Thread(target=self._work, name=self._name,
                                                daemon=True)
                self._thread.start()
            self._cond.notify_all()

    def cancel(self, owner: Hashable) -> None:
        """Drop `owner`'s waiting job, if any (a running one finishes)."""
        with self._cond:
            self._waiting.pop(owner, None)

    def _work(self) -> None:
        while True:
            with self._cond:
                while not self._waiting:
                    self._cond.wait()
                _, (job, done, doc) = self._waiting.popitem(last=False)
            try:
                result = job()
            except Exception as err:  # the job's own failure, shown by its owner
                log.debug("background job failed: %s", err)
                result = err
            try:
                later(doc, lambda done=done, result=result: done(result))
            except Exception as err:  # (the session ended meanwhile)
                log.debug("background job's session is gone: %s", err)


#: The process's runner (the Methods and Motor cards of every session).
RUNNER = JobRunner()
