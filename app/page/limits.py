"""One log line per burst, not a traceback per message: a websocket closed with messages
still queued, websockets naming a session id this server did not sign, whole-document
pulls past their session's limit (`app.page.pulls`) and websockets closed for a second
pull (`app.page.websocket`); and bounds on Tornado's access log, which writes a line per
request (`log_request`): refused requests one line per client per burst (`Burst` with a
key), a client's other lines a dozen at once, then one every 20 s (`ClientLines`), and
all lines at most `ACCESS_LINES` a minute (`Cap`).

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
exception with its traceback: 17 lines for each attempt, thousands of attempts a minute
from one client in a loop.

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
    others; records that do not match pass unchanged.

    With `key` (a record's client, say), each key has bursts of its own (at most `keys`
    are kept; the oldest are forgotten), and `summary` may name the record's own message
    and its key (``{message}``, ``{key}``)."""

    def __init__(self, match: Callable[[logging.LogRecord], bool], summary: str,
                 window: float = 10.0, clock: Callable[[], float] = time.monotonic,
                 key: Callable[[logging.LogRecord], str] | None = None,
                 keys: int = 10_000) -> None:
        super().__init__()
        self.match, self.summary, self.window, self._clock = match, summary, window, clock
        self.key, self.keys = key, keys
        #: per key: when its current burst's line was logged, and the records dropped since
        self._bursts: dict[str, tuple[float, int]] = {}
        self._lock = threading.Lock()

    @property
    def dropped(self) -> int:
        """The records dropped since their burst's line, over every key."""
        with self._lock:
            return sum(n for _, n in self._bursts.values())

    def filter(self, record: logging.LogRecord) -> bool | logging.LogRecord:
        if not self.match(record):
            return True
        key = self.key(record) if self.key else ""
        now = self._clock()
        with self._lock:
            started, dropped = self._bursts.get(key, (None, 0))
            if started is not None and now - started < self.window:
                self._bursts[key] = (started, dropped + 1)
                return False
            self._bursts.pop(key, None)
            if len(self._bursts) >= self.keys:  # (the oldest burst forgotten)
                self._bursts.pop(next(iter(self._bursts)))
            self._bursts[key] = (now, 0)
        more = (f"; {dropped} more like it in the previous {self.window:g} s not logged"
                if dropped else "")
        text = self.summary.format(message=record.getMessage(), key=key)
        return logging.makeLogRecord({
            **record.__dict__, "msg": f"{text} (further ones within {self.window:g} s not "
                                      f"logged{more})",
            "args": (), "exc_info": None, "exc_text": None, "stack_info": None})


class Cap(logging.Filter):
    """Passes at most `limit` records in each `window` s and drops the others; the first
    record passed after a drop says how many were dropped.  For a logger that writes a
    line per request (Tornado's access log: a client opening websockets in a loop, each
    refused, writes hundreds of lines a second), whatever the requests are."""

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

#: The access log's lines per client address: this many at once, then one every
#: 1 / rate s (a script in a loop writes at most 13 lines in 20 s; what is dropped is
#: counted in the client's next line).
CLIENT_LINES, CLIENT_LINES_RATE = 12.0, 1.0 / 20.0

#: The logger of the explorer's websocket handler (`app.page.websocket`).
WEBSOCKET_LOGGER = "app.page.websocket"


def client_of(record: logging.LogRecord) -> str:
    """The client address a record names (``client``, as `log_request` and the
    websocket handler set it), or ""."""
    return str(getattr(record, "client", ""))


def refused(record: logging.LogRecord) -> bool:
    """Whether `record` is an access-log line of a refused request (``refused``, as
    `log_request` sets it)."""
    return bool(getattr(record, "refused", False))


def refusal(status: int, path: str) -> bool:
    """Whether a request of `path` answered `status` was refused: 403 (a websocket from
    another origin, or naming a session this server did not sign), 429 (a page load
    refused: `app.page.gate.GatedDocHandler`) or a redirect of the explorer's page (to a
    login)."""
    from app.page.gate import APP_PATH

    return status in (403, 429) or (status == 302 and path.rstrip("/").endswith(APP_PATH))


def log_request(handler) -> None:
    """Tornado's access log line of a finished request (the application's
    ``log_function``: what Tornado writes, ``STATUS METHOD URI (ADDRESS) TIMEms``, at
    its levels), with the client's address (``client``) and whether it was refused
    (``refused``) for the filters of `quiet_closed_connections`."""
    request = handler.request
    status = handler.get_status()
    level = (logging.INFO if status < 400 else logging.WARNING if status < 500
             else logging.ERROR)
    logging.getLogger(ACCESS_LOGGER).log(
        level, "%d %s %s (%s) %.2fms", status, request.method, request.uri, request.remote_ip,
        1000.0 * request.request_time(),
        extra={"client": str(request.remote_ip), "refused": refusal(status, request.path)})


class ClientLines(logging.Filter):
    """Passes a client's records while its bucket has lines (`limit`, one per record:
    `app.page.bucket.AddressLimit`) and drops the others; the next record passed for it
    says how many were dropped.  Records of no client, and refusals (one line per burst
    already), pass unchanged."""

    def __init__(self, limit) -> None:
        super().__init__()
        self.limit = limit
        self._dropped: dict[str, int] = {}  # per client, since its last line
        self._lock = threading.Lock()

    def filter(self, record: logging.LogRecord) -> bool | logging.LogRecord:
        client = client_of(record)
        if not client or refused(record):
            return True
        with self._lock:
            if not self.limit.allow(client):
                self._dropped[client] = self._dropped.get(client, 0) + 1
                if len(self._dropped) > self.limit.clients:
                    self._dropped.pop(next(iter(self._dropped)))
                return False
            dropped = self._dropped.pop(client, 0)
        if not dropped:
            return True
        return logging.makeLogRecord({
            **record.__dict__, "msg": f"{record.getMessage()} ({dropped} lines of {client} "
                                      f"before it not written: more than "
                                      f"{self.limit.burst:g} at once)", "args": ()})


def quiet_closed_connections(window: float = 10.0) -> list[tuple[str, logging.Filter]]:
    """Put a `Burst` filter on each logger that writes lines per message queued on a
    closed websocket, per websocket refused for its token's signature or per refused
    pull; on Tornado's access log (`log_request`'s lines) one line per client per burst
    of refusals, `CLIENT_LINES` lines per client at once (`ClientLines`) and a `Cap` of
    `ACCESS_LINES` per `ACCESS_WINDOW_S`; one line per client per burst of websockets
    closed for a second pull (`app.page.websocket`).  Returns the (logger name, filter)
    pairs (call once, at start)."""
    from app.page.bucket import AddressLimit

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
        (ACCESS_LOGGER, Burst(refused, "{message}, refused (per client)", window,
                              key=client_of)),
        (ACCESS_LOGGER, ClientLines(AddressLimit(CLIENT_LINES, CLIENT_LINES_RATE))),
        (ACCESS_LOGGER, Cap(ACCESS_LINES, ACCESS_WINDOW_S)),
        (WEBSOCKET_LOGGER, Burst(lambda r: True, "{message}", window, key=client_of)),
    ]
    for name, f in filters:
        logging.getLogger(name).addFilter(f)
    return filters
