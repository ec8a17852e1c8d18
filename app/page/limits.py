"""One log line per burst, not a traceback per message: a websocket closed with messages
still queued, websockets naming a session id this server did not sign, and whole-document
pulls past their session's limit (`app.page.pulls`); and a cap on the lines of Tornado's
access log (`Cap`), which writes one per request, refused or not.

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


class Cap(logging.Filter):
    """Passes at most `limit` records in each `window` s and drops the others; the first
    record passed after a drop says how many were dropped.  For a logger that writes a
    line per request (Tornado's access log: a client opening websockets in a loop, each
    refused, wrote ~650 lines a second), whatever the requests are."""

    def __init__(self, limit: int, window: float = 10.0,
                 clock: Callable[[], float] = time.monotonic) -> None:
        super().__init__()
        self.limit, self.window, self._clock = limit, window, clock
        self._started = -float("inf")  # when the current window began
        self._passed = 0  # records passed in it
        self.dropped = 0  # records dropped since the last one passed
        self._lock = threading.Lock()

    def filter(self, record: logging.LogRecord) -> bool | logging.LogRecord:
        now = self._clock()
        with self._lock:
            if now - self._started >= self.window:
                self._started, self._passed = now, 0
            if self._passed >= self.limit:
                self.dropped += 1
                return False
            self._passed += 1
            dropped, self.dropped = self.dropped, 0
        if not dropped:
            return True
        return logging.makeLogRecord({
            **record.__dict__, "msg": f"{record.getMessage()} ({dropped} lines of this log "
                                      f"before it not written: more than {self.limit} "
                                      f"within {self.window:g} s)",
            "args": ()})


#: Tornado's access log (a line per request) and the lines it may write per minute: a
#: class of 60 loading the page at once (a dozen requests each) is logged whole; a flood
#: writes at most ~17 lines a second.
ACCESS_LOGGER, ACCESS_LINES, ACCESS_WINDOW_S = "tornado.access", 1000, 60.0


def quiet_closed_connections(window: float = 10.0) -> list[tuple[str, logging.Filter]]:
    """Put a `Burst` filter on each logger that writes lines per message queued on a
    closed websocket, per websocket refused for its token's signature or per refused
    pull, and a `Cap` of `ACCESS_LINES` per `ACCESS_WINDOW_S` on Tornado's access log;
    returns the (logger name, filter) pairs (call once, at start)."""
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
        (ACCESS_LOGGER, Cap(ACCESS_LINES, ACCESS_WINDOW_S)),
    ]
    for name, f in filters:
        logging.getLogger(name).addFilter(f)
    return filters
