"""Whole-document pulls, limited per session.

A client's ``PULL-DOC-REQ`` message asks the server for its session's whole document:
all its models serialized, on one of Bokeh's worker threads (the costliest reply the
server sends). BokehJS sends one per connection: a connection that sends a second one is
closed (`app.page.websocket.OnePullHandler`). A script can still open new connections to
its session, each pulling once. What every pull does see is the document being
serialized (`bokeh.document.Document.to_json`), root by root, in the order they were
added.

`PullGuard` is a root of no display (a Bokeh `DataModel`) added first to each session's
document: it is serialized before anything else of the document, and only when the
whole document is (a change of the document sends only what changed).  Each time it
takes one pull from the session's bucket (`burst` pulls, refilled at `rate` per
second); past it, it raises `PullRefused`, which ends that serialization before the
expensive part: Bokeh answers the request with an error message and logs it (one line
per burst: `app.page.limits.quiet_closed_connections`).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from bokeh.core.serialization import Serializer
from bokeh.model import DataModel

from app.page import bucket

#: A session's pulls: its page's own and a few reconnections at once, then one a minute.
BURST, RATE = 4.0, 1.0 / 60.0


class PullRefused(RuntimeError):
    """A whole-document pull past the session's bucket."""


class PullGuard(DataModel):
    """Counts the whole-document serializations of its document and refuses those past
    a bucket of `burst`, refilled at `rate` per second (see the module docstring)."""

    def __init__(self, burst: float = BURST, rate: float = RATE,
                 clock: Callable[[], float] = time.monotonic, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self._burst, self._rate, self._clock = burst, rate, clock
        self._tokens, self._when = burst, clock()
        self._lock = threading.Lock()

    def take(self) -> bool:
        """Take one pull from the bucket; False (nothing taken) when it is empty."""
        with self._lock:
            now = self._clock()
            self._tokens, taken = bucket.take(self._tokens, now - self._when, self._burst,
                                              self._rate)
            self._when = now
            return taken

    def to_serializable(self, serializer: Serializer) -> Any:
        """Bokeh's representation of the model, if the bucket has a pull left."""
        if not self.take():
            raise PullRefused("whole-document pulls past this session's limit")
        return super().to_serializable(serializer)
