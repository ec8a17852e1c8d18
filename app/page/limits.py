"""One log line per burst, not a traceback per message: a websocket closed with messages
still queued, websockets naming a session id this server did not sign, and whole-document
pulls past their session's limit (`app.page.pulls`).

A client that sends many messages without waiting for the answers (e.g. PULL-DOC
requests in a loop) and then closes leaves them in the server's read buffer.  Tornado
goes on handing them to Bokeh after the connection has closed and Bokeh has detached its
session; for each, Bokeh 3.10 logs an ``AssertionError`` traceback
(``bokeh.server.protocol_handler``: ``error handling message``, raised by
``ServerConnection.session``) and a warning that its error reply could not be sent
(``bokeh.server.views.ws``), and once the queue is done Tornado logs one more traceback
of the same assertion for the connection's second close (``tornado.application``:
``Uncaught exception GET /main/ws``).  Nothing is lost: the client is gone.

A websocket whose token is not signed with the server's key is refused before any
document is built, but Bokeh logs an error naming the session id and then raises
``ProtocolError`` from the handler's ``open``, which Tornado logs as an uncaught
exception with its traceback: 17 lines for each attempt, ~3,300 attempts in 20 s from
one client on loopback.

`quiet_closed_connections` puts a `Burst` filter on each of those three loggers: the
first such record of a burst is logged as one line without its traceback, the others
within `Burst.window` seconds are dropped and counted in the next burst's line.  Other
records of these loggers pass unchanged.  Public APIs only: `logging.Filter` on the
named loggers, the record's exception and its traceback's last frame.
"""

from __future__ import annotations

import logging
import threading
import time
import traceback
from collections.abc import Callable

#: The loggers whose records of a closed connection's queued messages are summarised.
PROTOCOL_LOGGER = "bokeh.server.protocol_handler"
WS_LOGGER = "bokeh.server.views.ws"
TORNADO_LOGGER = "tornado.application"

#: Bokeh's warning for a reply written to a closed websocket (its exact text).
CLOSED_SEND = "Failed sending message as connection was closed"

#: Bokeh's error for a websocket token not signed with the server's key (its format).
BAD_SIGNATURE = "Token for session %r had invalid signature"


def raised_in(record: logging.LogRecord, error: type[BaseException], function: str,
              path: str) -> bool:
    """Whether `record` carries an `error` raised in `function` of the file ending with
    `path` (the last frame of its traceback)."""
    exc = record.exc_info
    if not exc or not isinstance(exc[1], error) or exc[2] is None:
        return False
    last = traceback.extract_tb(exc[2])[-1]
    return last.name == function and last.filename.replace("\\", "/").endswith(path)


def detached_session(record: logging.LogRecord) -> bool:
    """Whether `record` carries Bokeh's AssertionError for a connection whose session
    was already detached (raised in ``bokeh/server/connection.py``'s ``session``)."""
    return raised_in(record, AssertionError, "session", "bokeh/server/connection.py")


def refused_token(record: logging.LogRecord) -> bool:
    """Whether `record` carries the ProtocolError Bokeh raises opening a websocket whose
    token is not signed with the server's key (logged by Tornado as uncaught)."""
    from bokeh.protocol.exceptions import ProtocolError

    return raised_in(record, ProtocolError, "open", "bokeh/server/views/ws.py")


def refused_pull(record: logging.LogRecord) -> bool:
    """Whether `record` carries the refusal of a whole-document pull past its session's
    limit (`app.page.pulls.PullRefused`, logged by Bokeh as an error handling it)."""
    from app.page.pulls import PullRefused

    return raised_in(record, PullRefused, "to_serializable", "app/page/pulls.py")


def bad_signature(record: logging.LogRecord) -> bool:
    """Whether `record` is Bokeh's error for a token with an invalid signature."""
    return record.msg == BAD_SIGNATURE


def closed_send(record: logging.LogRecord) -> bool:
    """Whether `record` is Bokeh's warning of a reply to a closed websocket."""
    return record.msg == CLOSED_SEND and not record.args


class Burst(logging.Filter):
    """Logs the first record that `match`es in each `window` s as one line (`summary`,
    then how many were dropped since the previous such line; no traceback) and drops the
    others; records that do not match pass unchanged."""

    def __init__(self, match: Callable[[logging.LogRecord], bool], summary: str,
                 window: float = 10.0, clock: Callable[[], float] = time.monotonic) -> None:
        super().__init__()
        self.match, self.summary, self.window, self._clock = match, summary, window, clock
        self._started: float | None = None  # when the current burst's line was logged
        self.dropped = 0  # records dropped since that line
        self._lock = threading.Lock()

    def filter(self, record: logging.LogRecord) -> bool | logging.LogRecord:
        if not self.match(record):
            return True
        now = self._clock()
        with self._lock:
            if self._started is not None and now - self._started < self.window:
                self.dropped += 1
                return False
            self._started, dropped, self.dropped = now, self.dropped, 0
        more = (f"; {dropped} more like it in the previous {self.window:g} s not logged"
                if dropped else "")
        return logging.makeLogRecord({
            **record.__dict__, "msg": f"{self.summary} (further ones within "
                                      f"{self.window:g} s not logged{more})",
            "args": (), "exc_info": None, "exc_text": None, "stack_info": None})


def quiet_closed_connections(window: float = 10.0) -> list[tuple[str, Burst]]:
    """Put a `Burst` filter on each logger that writes lines per message queued on a
    closed websocket or per websocket refused for its token's signature; returns the
    (logger name, filter) pairs (call once, at start)."""
    filters = [
        (PROTOCOL_LOGGER, Burst(detached_session, "messages that arrived on a websocket "
                                "after it closed were dropped (Bokeh's AssertionError)",
                                window)),
        (PROTOCOL_LOGGER, Burst(refused_pull, "whole-document pulls past their session's "
                                "limit were refused", window)),
        (WS_LOGGER, Burst(closed_send, "replies to a closed websocket were dropped",
                          window)),
        (TORNADO_LOGGER, Burst(detached_session, "a websocket closed with messages "
                               "queued (Bokeh's AssertionError on its second close)",
                               window)),
        (WS_LOGGER, Burst(bad_signature, "websockets refused: session token not signed "
                          "with this server's key", window)),
        (TORNADO_LOGGER, Burst(refused_token, "websockets refused: session token not "
                               "signed with this server's key (Bokeh's ProtocolError)",
                               window)),
    ]
    for name, f in filters:
        logging.getLogger(name).addFilter(f)
    return filters
