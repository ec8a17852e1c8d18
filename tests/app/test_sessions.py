"""Sessions end without a trace: a Bokeh/Panel server in this process serves the explorer
(with app/serve.py's settings, shorter lifetimes), pages are loaded with and without their
websocket ever connecting, and once the server has discarded the sessions no explorer,
state, scene or document of theirs is left (gc-level evidence)."""

from __future__ import annotations

import asyncio
import gc
import json
import logging
import sys
import threading
import time
import tracemalloc
import urllib.request
from pathlib import Path

import pytest
from bokeh.document import Document
from explorer_browser import free_port
from panel.io.server import get_server
from tornado.httpclient import AsyncHTTPClient
from tornado.ioloop import IOLoop

from app.contact.state import ExplorerState
from app.methods import MethodsScene
from app.page.explorer import Explorer
from app.serve import applications, parse_args, server_options

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "benchmarks" / "app"))  # (its load_test.Session: a browser's load)

LIFETIME_MS = 1500  # unused sessions are discarded after this (app/serve.py: 20 s)
SECRET_KEY = b"a-test-key-of-at-least-thirty-two-characters"  # signs the session ids


@pytest.fixture(scope="module")
def served():
    """The explorer served by a server on a thread of this process; its URL and server."""
    port = free_port()
    opts = server_options(parse_args(["--port", str(port),
                                      "--allow-websocket-origin", f"127.0.0.1:{port}"]))
    opts.update(unused_session_lifetime_milliseconds=LIFETIME_MS,
                check_unused_sessions_milliseconds=300, secret_key=SECRET_KEY)
    box: dict = {}

    def run() -> None:
        asyncio.set_event_loop(asyncio.new_event_loop())
        loop = IOLoop.current()
        box["server"] = get_server(applications(), loop=loop, start=False, **opts)
        box["loop"] = loop
        box["server"].start()
        loop.start()

    thread = threading.Thread(target=run, daemon=True)
    thread.start()
    url = f"http://127.0.0.1:{port}/main"
    deadline = time.monotonic() + 60
    while "server" not in box and time.monotonic() < deadline:
        time.sleep(0.1)
    yield url, box["server"]
    box["loop"].add_callback(box["loop"].stop)
    thread.join(10)


def _alive(kind: type, *, but: tuple = ()) -> int:
    """How many objects of `kind` are alive, those in `but` (other tests') not counted."""
    gc.collect()
    # type(), not isinstance(): a dead weak proxy among gc's objects raises on isinstance
    return sum(type(o) is kind and not any(o is b for b in but) for o in gc.get_objects())


def _wait_for_no_sessions(server, timeout: float = 30.0) -> None:
    deadline = time.monotonic() + timeout
    while server.get_sessions("/main") and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not server.get_sessions("/main"), "the server kept its sessions"
    # and let the server's loop finish what it was doing (a session's destruction runs
    # there: its objects are still referenced until it returns)
    done = threading.Event()
    server.io_loop.add_callback(done.set)
    assert done.wait(10), "the server's loop did not come round"


def _load(url: str) -> None:
    with urllib.request.urlopen(url) as r:
        assert r.status == 200


def visit(url: str, targets: bool = True) -> None:
    """Load the page at `url` as a browser does (benchmarks/app/load_test.py's client:
    the HTML, the websocket, the document, ``document_ready``, what is built into the
    page) and close it.  With `targets`, LookupError unless the explorer's ψ slider and
    plots came (naming the server's refusal or failure note if that came instead)."""
    sys.path.insert(0, str(ROOT / "benchmarks" / "app"))
    from load_test import Session

    async def go() -> None:
        session = Session(url, AsyncHTTPClient(), 10.0, None)
        try:
            await session.open(targets)
        finally:
            session.close()

    asyncio.run(go())


def new_session(server, before: set[str]):
    """The one session of `server` whose id is not in `before`."""
    (session,) = [s for s in server.get_sessions("/main") if s.id not in before]
    return session


KINDS = (Explorer, ExplorerState, MethodsScene, Document)


@pytest.mark.slow
def test_sessions_leave_nothing_behind(served) -> None:
    url, server = served
    gc.collect()
    elsewhere = tuple(o for o in gc.get_objects() if type(o) is Explorer)  # other tests'
    _load(url)  # warm up: imports, caches, the first session's lazy state
    _wait_for_no_sessions(server)
    before = {k: _alive(k, but=elsewhere) for k in KINDS}
    for _ in range(6):
        _load(url)  # a link preview: the websocket never connects
    for _ in range(4):
        visit(url)  # a visit: the explorer is built, then the tab closes
    assert len(server.get_sessions("/main")) >= 1
    _wait_for_no_sessions(server)
    after = {k: _alive(k, but=elsewhere) for k in KINDS}
    assert after == before, f"sessions left objects behind: {before} -> {after}"
    assert before[Explorer] == 0  # the warm-up session's explorer is gone too


def test_slider_moves_in_one_session_hold_no_more_python_memory(served) -> None:
    """A thousand psi moves over Bokeh's protocol (benchmarks/app/load_test.py's client) leave
    the Python heap where it was: tracemalloc sees no growth beyond a few arrays' worth
    (what the server's RSS adds over a long soak is the allocator's, see docs/deploy.md)."""
    url, _ = served
    sys.path.insert(0, str(ROOT / "benchmarks" / "app"))
    from load_test import Session

    async def moves() -> int:
        session = Session(url, AsyncHTTPClient(), 10.0, None)
        await session.open()
        try:
            for _ in range(200):  # warm: caches, the first arrays of each size
                await session.move()
            gc.collect()
            tracemalloc.start()
            before = tracemalloc.take_snapshot()
            for _ in range(1000):
                await session.move()
            gc.collect()
            after = tracemalloc.take_snapshot()
            tracemalloc.stop()
        finally:
            session.close()
        return sum(s.size_diff for s in after.compare_to(before, "filename"))

    grown = asyncio.run(moves())
    assert grown < 100_000, f"1000 moves left {grown} bytes of Python objects behind"


def _one_move(url: str, listen: float = 0.0) -> tuple[list[str], list[str], float]:
    """One psi move from a loaded page (benchmarks/app/load_test.py's client, which sends
    `document_ready` as BokehJS does): the PATCH-DOCs up to the one with the plots' new
    data, those that follow within `listen` s, and the psi sent."""
    sys.path.insert(0, str(ROOT / "benchmarks" / "app"))
    from load_test import Session

    async def move() -> tuple[list[str], list[str], float]:
        session = Session(url, AsyncHTTPClient(), 10.0, None)
        await session.open()
        session._reader.cancel()  # read the replies here instead
        try:
            while True:  # what the page's load sends, until a quiet 0.5 s
                try:
                    await asyncio.wait_for(session._read(), 0.5)
                except TimeoutError:
                    break
            await session.move()
            patches = []
            while not any(session.force_ref in p for p in patches):
                header, content = await asyncio.wait_for(session._read(), 10)
                if header["msgtype"] == "PATCH-DOC":
                    patches.append(content)
            later = []
            deadline = time.monotonic() + listen
            while (left := deadline - time.monotonic()) > 0:
                try:
                    header, content = await asyncio.wait_for(session._read(), left)
                except TimeoutError:
                    break
                if header["msgtype"] == "PATCH-DOC":
                    later.append(content)
            return patches, later, session.value
        finally:
            session.close()

    return asyncio.run(move())


def test_a_slider_move_comes_back_as_one_message(served) -> None:
    """A psi move comes back as ONE message holding both the psi box's new text and the
    plots' new data (app/widgets.py applies the browser's value under `hold`): Bokeh
    builds each message's serializer over the whole document."""
    patches, _, psi = _one_move(served[0])
    assert len(patches) == 1, f"a move came back as {len(patches)} messages"
    # the psi box's text (a string, where the slider's value is a number), with the plots
    assert f'"attr":"value","new":"{psi:.6g}"' in patches[0]


def test_a_slider_move_sends_its_url_in_its_one_message(served) -> None:
    """The page's URL query travels in the move's one message (`app.page.url.UrlWriter`:
    the browser writes it into the address bar), and no message follows it, the URL's
    delay (`URL_DELAY_S`) and more later: every message costs the server a serializer
    over the whole document."""
    from app.page.explorer import URL_DELAY_S

    patches, later, psi = _one_move(served[0], listen=3 * URL_DELAY_S + 0.5)
    assert len(patches) == 1, f"a move came back as {len(patches)} messages"
    assert later == [], f"{len(later)} messages followed the move's: {later}"
    query = [e["new"] for e in json.loads(patches[0])["events"] if e.get("attr") == "query"]
    assert len(query) == 1, "the move's message holds no URL query"
    assert ["psi", repr(psi)] in json.loads(query[0])  # (the pairs' JSON)


def test_a_session_built_for_its_websocket_alone_has_the_servers_stylesheets(served) -> None:
    """With `--num-procs` above 1 a page's websocket may reach a process that did not
    serve the page; that process builds the session's document for the websocket alone,
    without rendering the page.  Its stylesheets, the shell's and the explorer's built
    into it, must still be the server's own copies: Panel's CDN is refused by the page's
    Content-Security-Policy (the page showed unstyled, 233 refusals in the console) and
    out of reach offline."""
    url, _ = served
    sys.path.insert(0, str(ROOT / "benchmarks" / "app"))
    from bokeh.util.token import generate_jwt_token, generate_session_id
    from load_test import Session

    async def load() -> str:
        session = Session(url, AsyncHTTPClient(), 10.0, None)
        try:  # a session no page was made for (its id signed with the server's key)
            await session.load(generate_jwt_token(
                generate_session_id(SECRET_KEY, signed=True), SECRET_KEY, signed=True))
            return json.dumps(session.doc)
        finally:
            session.close()

    doc = asyncio.run(load())
    assert "cdn.holoviz.org" not in doc
    assert "static/extensions/panel/css/listpanel.css" in doc
    assert "static/extensions/panel/css/button.css" in doc  # (the explorer's buttons)


@pytest.mark.parametrize("signed_with", [None, b"another-key-of-at-least-thirty-two-chars"])
def test_a_session_id_the_server_did_not_issue_is_refused(served, signed_with) -> None:
    """A websocket naming an invented session id (unsigned, or signed with another key)
    is closed before any document is built: no client can have documents built without
    loading a page (before, 200 of 200 invented ids each built one)."""
    url, server = served
    from bokeh.util.token import generate_jwt_token, generate_session_id

    sys.path.insert(0, str(ROOT / "benchmarks" / "app"))
    from load_test import Session

    signed = signed_with is not None
    token = generate_jwt_token(generate_session_id(signed_with, signed=signed),
                               signed_with, signed=signed)
    before = len(server.get_sessions("/main"))

    async def pull() -> str:
        session = Session(url, AsyncHTTPClient(), 10.0, None)
        try:
            return await session.pull(token)
        finally:
            session.close()

    with pytest.raises(Exception):  # noqa: B017 (closed or refused, as the client sees it)
        asyncio.run(pull())
    assert len(server.get_sessions("/main")) == before


def test_whole_document_pulls_past_a_sessions_burst_are_refused(served, caplog) -> None:
    """A script's PULL-DOC requests (each answered with the whole document, ~100 ms of
    CPU to serialize) are answered up to the session's burst, the page's own pull
    included (`app.page.pulls`), and refused past it with Bokeh's error reply; the log
    gets one line for the burst, not a traceback per refusal."""
    from app.page.limits import PROTOCOL_LOGGER, quiet_closed_connections
    from app.page.pulls import BURST

    sys.path.insert(0, str(ROOT / "benchmarks" / "app"))
    from load_test import Session

    sent = 10

    async def spam() -> list[tuple[str, str]]:
        session = Session(served[0], AsyncHTTPClient(), 10.0, None)
        await session.open()  # (the page's own pull)
        session._reader.cancel()  # read the replies here instead
        try:
            for _ in range(sent):
                await session._send("PULL-DOC-REQ", {})
            replies = []
            while len(replies) < sent:
                header, content = await asyncio.wait_for(session._read(), 30)
                if header["msgtype"] in ("PULL-DOC-REPLY", "ERROR"):
                    replies.append((header["msgtype"], content))
            return replies
        finally:
            session.close()

    filters = quiet_closed_connections()
    try:
        with caplog.at_level(logging.ERROR, logger=PROTOCOL_LOGGER):
            replies = asyncio.run(spam())
    finally:
        for name, f in filters:
            logging.getLogger(name).removeFilter(f)
    kinds = [k for k, _ in replies]
    answered = int(BURST) - 1
    assert kinds == ["PULL-DOC-REPLY"] * answered + ["ERROR"] * (sent - answered)
    assert all(len(c) > 100_000 for k, c in replies if k == "PULL-DOC-REPLY")
    assert all("PullRefused" in json.loads(c)["text"] for k, c in replies if k == "ERROR")
    lines = [r for r in caplog.records if r.name == PROTOCOL_LOGGER]
    assert len(lines) == 1 and lines[0].exc_info is None, [r.getMessage() for r in lines]
    assert "pulls past their session's limit" in lines[0].getMessage()
