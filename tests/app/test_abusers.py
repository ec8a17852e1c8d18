"""Abusive clients of a served explorer cost a few log lines, not one per request
(`app.page.limits`), and whole-document pulls are bounded: one per websocket
(`app.page.websocket`), a few per session (`app.page.pulls`).

The server is test_sessions' (app/serve.py's settings, on a thread of this process), with
the log filters the server installs at start (`quiet_closed_connections`); what reaches
the log is what the filters let through to pytest's handler."""

from __future__ import annotations

import asyncio
import json
import logging
import time
import urllib.request

import pytest
from bokeh.util.token import generate_jwt_token, generate_session_id
from bokeh_client import Tab
from test_sessions import pages_thrown_freely, served  # noqa: F401 (fixtures)
from tornado.httpclient import AsyncHTTPClient, HTTPClientError
from tornado.websocket import WebSocketClosedError

import app.page.gate
from app.page.bucket import AddressLimit
from app.page.limits import (
    ACCESS_LOGGER,
    CLIENT_LINES,
    PROTOCOL_LOGGER,
    WEBSOCKET_LOGGER,
    quiet_closed_connections,
)
from app.page.websocket import CLOSE_CODE, OnePullHandler

#: The loggers an abuser could fill (Tornado's access log and its errors, Bokeh's, ours).
LOGGERS = (ACCESS_LOGGER, "tornado.application", "tornado.general", "bokeh", "app")


class Records(logging.Handler):
    """Every record that reaches a logger it is a handler of, kept once (`records`)."""

    def __init__(self) -> None:
        super().__init__(logging.INFO)
        self.records: list[logging.LogRecord] = []
        self._kept: set[int] = set()  # (a record reaching two of its loggers: once)

    def emit(self, record: logging.LogRecord) -> None:
        if id(record) not in self._kept:
            self._kept.add(id(record))
            self.records.append(record)


@pytest.fixture
def log():
    """The records that pass the server's log filters (the filters fresh for the test: no
    earlier burst in them), caught by a handler of the test's own on the root logger at
    INFO and on every logger an abuser could fill, each at INFO (not pytest's capture,
    whose handler's level another test or library may have set higher, nor those
    loggers' own levels, which distributed's import sets to CRITICAL for Tornado's, nor
    their propagation, which Bokeh turns off for its own once it logs)."""
    filters = quiet_closed_connections()
    names = (None, *LOGGERS)
    levels = {name: logging.getLogger(name).level for name in names}
    records = Records()
    for name in names:
        logging.getLogger(name).setLevel(logging.INFO)
        logging.getLogger(name).addHandler(records)
    try:
        yield records
    finally:
        for name in names:
            logging.getLogger(name).removeHandler(records)
        for name, level in levels.items():
            logging.getLogger(name).setLevel(level)
        for name, f in filters:
            logging.getLogger(name).removeFilter(f)


def lines(log, *names: str) -> list[str]:
    """The messages of the records `log` captured from the loggers `names` (or below them) that the
    server writes: the access log's, ours (app.*) and the others' warnings and errors
    (its log shows no INFO line of Bokeh's websocket handler or of Panel's sessions)."""
    return [r.getMessage() for r in log.records
            if any(r.name == n or r.name.startswith(n + ".") for n in names)
            and (r.levelno >= logging.WARNING or r.name == ACCESS_LOGGER
                 or r.name.startswith("app."))]


def settled(log, quiet: float = 0.3, limit: float = 10.0) -> None:
    """Wait until `log` has captured no record for `quiet` s (the server's thread is done
    logging what the client did)."""
    end, n, since = time.monotonic() + limit, len(log.records), time.monotonic()
    while time.monotonic() < end and time.monotonic() - since < quiet:
        time.sleep(0.05)
        if len(log.records) != n:
            n, since = len(log.records), time.monotonic()


def test_the_served_websocket_handler_is_the_one_pull_handler(served) -> None:  # noqa: F811
    """`app.serve.server_options` installs it in Panel's place (a subclass of it)."""
    from bokeh.server.urls import per_app_patterns
    from panel.io.server import WSHandler

    (handler,) = [h for p, h, *_ in per_app_patterns if p == r"/ws"]
    assert handler is OnePullHandler and issubclass(handler, WSHandler)


def test_a_second_pull_doc_closes_the_websocket_with_one_log_line(served, log) -> None:  # noqa: F811
    """BokehJS pulls the document once per websocket; a client that sends more
    PULL-DOC requests on one gets its connection closed at the second (close code
    1008), with no reply to it, and the server logs one line."""
    url, _ = served

    async def spam() -> tuple[list[str], int | None]:
        tab = Tab(url, AsyncHTTPClient())
        await tab.open()  # (the page's own pull)
        await tab.quiet(0.3)
        try:
            for _ in range(10):
                try:
                    await tab.send("PULL-DOC-REQ", {})
                except WebSocketClosedError:  # (closed at the second)
                    break
            kinds = []
            with pytest.raises(ConnectionError, match="closed"):
                while True:
                    header, _ = await tab.read()
                    kinds.append(header["msgtype"])
            return kinds, tab.conn.close_code
        finally:
            tab.close()

    kinds, code = asyncio.run(spam())
    assert "PULL-DOC-REPLY" not in kinds and "ERROR" not in kinds, kinds
    assert code == CLOSE_CODE
    settled(log)
    closed = lines(log, WEBSOCKET_LOGGER)
    assert len(closed) == 1, closed
    assert "127.0.0.1" in closed[0] and "PULL-DOC number 2" in closed[0]
    assert "Traceback" not in " ".join(lines(log, *LOGGERS))
    assert lines(log, PROTOCOL_LOGGER, "bokeh.server.views.ws") == []


def test_whole_document_pulls_past_a_sessions_burst_are_refused(served, log) -> None:  # noqa: F811
    """A script's PULL-DOC requests (each answered with the whole document, ~100 ms of
    CPU to serialize), one per new websocket of one session, are answered up to the
    session's burst, the page's own pull included (`app.page.pulls`), and refused past
    it with Bokeh's error reply; the log gets one line for the burst, not a traceback
    per refusal."""
    from app.page.pulls import BURST

    url, _ = served
    sent = 10

    async def pull(token: str) -> tuple[str, str]:
        tab = Tab(url, AsyncHTTPClient())
        try:
            await tab.connect(token)
            await tab.send("PULL-DOC-REQ", {})
            while True:
                header, content = await tab.read(30)
                if header["msgtype"] in ("PULL-DOC-REPLY", "ERROR"):
                    return header["msgtype"], content
        finally:
            tab.close()

    async def spam() -> list[tuple[str, str]]:
        page = Tab(url, AsyncHTTPClient())
        await page.open()  # (the page's own pull)
        try:
            return [await pull(page.token) for _ in range(sent)]
        finally:
            page.close()

    replies = asyncio.run(spam())
    kinds = [k for k, _ in replies]
    answered = int(BURST) - 1
    assert kinds == ["PULL-DOC-REPLY"] * answered + ["ERROR"] * (sent - answered)
    assert all(len(c) > 100_000 for k, c in replies if k == "PULL-DOC-REPLY")
    assert all("PullRefused" in json.loads(c)["text"] for k, c in replies if k == "ERROR")
    settled(log)
    refused = [r for r in log.records if r.name == PROTOCOL_LOGGER]
    assert len(refused) == 1 and refused[0].exc_info is None, [r.getMessage() for r in refused]
    assert "pulls past their session's limit" in refused[0].getMessage()


@pytest.mark.parametrize("signed_with", [None, b"another-key-of-at-least-thirty-two-chars"],
                         ids=["unsigned", "another key"])
def test_websockets_with_invented_session_ids_are_one_log_line(served, log,  # noqa: F811
                                                               signed_with) -> None:
    """200 websockets naming session ids this server did not sign (unsigned, or signed
    with another key) are refused with 403 before their handshake and cost the log one
    line: the first refusal's, which the next line after the burst counts."""
    url, server = served
    before = len(server.get_sessions("/main"))
    signed = signed_with is not None

    async def invent() -> list[int]:
        codes = []
        for _ in range(200):
            token = generate_jwt_token(generate_session_id(signed_with, signed=signed),
                                       signed_with, signed=signed)
            tab = Tab(url, AsyncHTTPClient())
            try:
                await tab.connect(token)
                codes.append(101)
            except HTTPClientError as err:
                codes.append(err.code)
            finally:
                tab.close()
        return codes

    codes = asyncio.run(invent())
    assert codes == [403] * 200
    settled(log)
    written = lines(log, *LOGGERS)
    assert len(written) == 1, written
    assert written[0].startswith("403 GET /main/ws (127.0.0.1)") and "refused" in written[0]
    assert len(server.get_sessions("/main")) <= before  # (none made for them)


def test_a_page_loop_past_its_page_loads_is_a_few_log_lines(served, log,  # noqa: F811
                                                            monkeypatch) -> None:
    """A script fetching the page in a loop: its first page loads are logged as Tornado
    logs them, each refusal past its address's page loads (429, held back for
    `app.page.gate.HOLD_S`: here not at all) is not: 150 loads write 3 lines."""
    url, _ = served
    monkeypatch.setattr(app.page.gate, "PAGES", AddressLimit(burst=2, rate=1e-6))
    monkeypatch.setattr(app.page.gate, "HOLD_S", 0.0)
    codes = []
    for _ in range(150):
        try:
            with urllib.request.urlopen(url, timeout=30) as r:
                codes.append(r.status)
        except urllib.error.HTTPError as err:
            codes.append(err.code)
    assert codes == [200] * 2 + [429] * 148
    settled(log)
    written = lines(log, *LOGGERS)
    assert len(written) == 3, written
    assert all(w.startswith("200 GET /main (127.0.0.1)") for w in written[:2])
    assert written[2].startswith("429 GET /main (127.0.0.1)") and "refused" in written[2]


def test_a_clients_lines_past_its_burst_are_counted_in_its_next_line(served, log,  # noqa: F811
                                                                    monkeypatch) -> None:
    """A client's requests that are not refused are logged `CLIENT_LINES` at once, then
    one every 20 s; the first line after a drop says how many were not written."""
    url, _ = served
    base = url.rsplit("/", 1)[0]
    for _ in range(int(CLIENT_LINES) + 30):
        with urllib.request.urlopen(f"{base}/liveness", timeout=30) as r:
            assert r.status == 200
    settled(log)
    written = lines(log, ACCESS_LOGGER)
    assert len(written) == int(CLIENT_LINES), written
    assert all(w.startswith("200 GET /liveness (127.0.0.1)") for w in written)
    (limit,) = [f for f in logging.getLogger(ACCESS_LOGGER).filters
                if type(f).__name__ == "ClientLines"]
    monkeypatch.setattr(limit.limit, "rate", 1e9)  # (as if 20 s had passed)
    with urllib.request.urlopen(f"{base}/liveness", timeout=30) as r:
        assert r.status == 200
    settled(log)
    last = lines(log, ACCESS_LOGGER)[-1]
    assert last.startswith("200 GET /liveness (127.0.0.1)")
    assert "(30 lines of 127.0.0.1 before it not written" in last
