"""The log filter of a closed websocket's queued messages (app/page/limits.py)."""

from __future__ import annotations

import logging
import sys

from bokeh.server.connection import ServerConnection

from app.page.limits import (
    ACCESS_LOGGER,
    BAD_SIGNATURE,
    CLOSED_SEND,
    PROTOCOL_LOGGER,
    WS_LOGGER,
    Burst,
    Cap,
    ClientLines,
    bad_signature,
    client_of,
    closed_send,
    detached_session,
    quiet_closed_connections,
    raised_in,
    refused_token,
)


def detached_error() -> tuple:
    """The exc_info of Bokeh's own AssertionError: the session of a connection that
    was detached (what each message queued on a closed websocket raises)."""
    class Session:  # what a connection asks of its session
        def subscribe(self, connection) -> None: ...
        def unsubscribe(self, connection) -> None: ...

    conn = ServerConnection(None, None, None, Session())
    conn.detach_session()  # what Bokeh does when the websocket closes
    try:
        conn.session  # noqa: B018
    except AssertionError:
        return sys.exc_info()
    raise AssertionError("Bokeh's connection no longer asserts a session")


def record(msg: str = "error handling message", exc_info=None, name=PROTOCOL_LOGGER,
           args=()) -> logging.LogRecord:
    return logging.LogRecord(name, logging.ERROR, __file__, 1, msg, args, exc_info)


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_matchers_pick_only_the_closed_connection_records():
    assert detached_session(record(exc_info=detached_error()))
    try:
        raise AssertionError("another assertion")
    except AssertionError:
        other = sys.exc_info()
    assert not detached_session(record(exc_info=other))
    assert not detached_session(record())
    assert closed_send(record(CLOSED_SEND))
    assert not closed_send(record("Failed sending %s", args=("x",)))


def opening() -> None:
    from bokeh.protocol.exceptions import ProtocolError

    raise ProtocolError("Invalid token signature")


def test_refused_tokens_are_told_by_where_they_were_raised():
    try:
        opening()
    except Exception:
        here = sys.exc_info()
    assert raised_in(record(exc_info=here), type(here[1]), "opening", "tests/app/test_limits.py")
    assert not raised_in(record(exc_info=here), AssertionError, "opening",
                         "tests/app/test_limits.py")
    assert not raised_in(record(exc_info=here), type(here[1]), "open",
                         "tests/app/test_limits.py")
    # Bokeh's own is raised by its websocket handler's `open`, not here
    assert not refused_token(record(exc_info=here))
    assert bad_signature(record(BAD_SIGNATURE, args=("abc",), name=WS_LOGGER))
    assert not bad_signature(record("Token for session had a valid signature"))


def test_burst_logs_one_line_per_window_and_counts_the_rest():
    clock = Clock()
    f = Burst(detached_session, "dropped", window=10.0, clock=clock)
    err = detached_error()
    first = f.filter(record(exc_info=err))
    assert isinstance(first, logging.LogRecord)
    assert first.exc_info is None and first.exc_text is None
    assert first.getMessage() == "dropped (further ones within 10 s not logged)"
    for t in range(1, 977):  # the 977 of issue 22, all within the window
        clock.now = t * 0.005
        assert f.filter(record(exc_info=err)) is False
    assert f.dropped == 976
    clock.now = 20.0
    line = f.filter(record(exc_info=err))
    assert line.getMessage() == ("dropped (further ones within 10 s not logged; 976 more "
                                 "like it in the previous 10 s not logged)")
    assert f.dropped == 0
    plain = record("something else")  # passes unchanged, its traceback too
    assert f.filter(plain) is True


def test_quiet_closed_connections_turns_a_flood_into_one_line(caplog):
    filters = quiet_closed_connections(window=60.0)
    try:
        log = logging.getLogger(PROTOCOL_LOGGER)
        err = detached_error()
        with caplog.at_level(logging.INFO, logger=PROTOCOL_LOGGER):
            for _ in range(50):
                log.error("error handling message", exc_info=err)
            log.error("a real error")
        lines = [r for r in caplog.records if r.name == PROTOCOL_LOGGER]
        assert [r.getMessage().split(" (")[0] for r in lines] == [
            "messages that arrived on a websocket after it closed were dropped",
            "a real error"]
        assert lines[0].exc_info is None
        assert "Traceback" not in caplog.text
    finally:
        for name, f in filters:
            logging.getLogger(name).removeFilter(f)


def test_the_access_log_writes_at_most_its_cap_per_window_and_says_what_it_dropped():
    now = [0.0]
    cap = Cap(3, window=60.0, clock=lambda: now[0])

    def line(n: int) -> logging.LogRecord:
        return logging.makeLogRecord({"name": "tornado.access", "levelno": logging.INFO,
                                      "msg": "%d GET /main/ws (%s) %.2fms",
                                      "args": (101, "127.0.0.1", n)})

    passed = [cap.filter(line(n)) for n in range(10)]
    assert passed[:3] == [True] * 3 and not any(passed[3:])
    assert cap.dropped == 7
    now[0] = 59.9  # the same window: still dropped
    assert cap.filter(line(10)) is False
    now[0] = 60.0  # a new window: its first line says how many were not written
    first = cap.filter(line(11))
    assert first.getMessage() == ("101 GET /main/ws (127.0.0.1) 11.00ms (8 lines of this "
                                  "log before it not written: more than 3 within 60 s)")
    assert cap.filter(line(12)) is True and cap.dropped == 0


def test_quiet_closed_connections_caps_the_access_log():
    filters = quiet_closed_connections()
    try:
        access = [f for name, f in filters if name == ACCESS_LOGGER]
        # refusals per client per burst, then a client's lines, then the cap over all
        assert [type(f) for f in access] == [Burst, ClientLines, Cap]
        assert access[0].key is client_of
        caps = [f for f in access if isinstance(f, Cap)]
        assert len(caps) == 1 and caps[0] in logging.getLogger(ACCESS_LOGGER).filters
    finally:
        for name, f in filters:
            logging.getLogger(name).removeFilter(f)
