"""Sessions end without a trace: a Bokeh/Panel server in this process serves the explorer
(with app/serve.py's settings, shorter lifetimes), pages are loaded with and without their
websocket ever connecting, and once the server has discarded the sessions no explorer,
state, scene or document of theirs is left (gc-level evidence)."""

from __future__ import annotations

import asyncio
import gc
import json
import threading
import time
import tracemalloc
import urllib.request

import pytest
from bokeh.document import Document
from bokeh_client import Tab
from explorer_browser import free_port
from panel.io.server import get_server
from tornado.httpclient import AsyncHTTPClient
from tornado.ioloop import IOLoop

from app.contact.state import ExplorerState
from app.methods import MethodsScene
from app.page.explorer import Explorer
from app.serve import applications, parse_args, server_options

LIFETIME_MS = 1500  # unused sessions are discarded after this (app/serve.py: 20 s)
SECRET_KEY = b"a-test-key-of-at-least-thirty-two-characters"  # signs the session ids


@pytest.fixture(autouse=True)
def pages_thrown_freely(monkeypatch):
    """The served explorer's limit of pages thrown per client (`app.page.gate.THROWN`)
    out of the way: `visit` closes each page as soon as it has it, as a script does
    (the tests of that limit set their own)."""
    import app.page.gate
    from app.page.bucket import ThrownPages

    monkeypatch.setattr(app.page.gate, "THROWN", ThrownPages(
        burst=1e6, rate=1.0, within=app.page.gate.THROWN_WITHIN_S))


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
    """Load the page at `url` as a browser does (`bokeh_client.Tab`: the HTML, the
    websocket, the document, ``document_ready``, what is built into the page) and close
    it.  With `targets`, LookupError unless the explorer's ψ slider and plots came
    (naming the server's refusal or failure note if that came instead)."""
    async def go() -> None:
        tab = Tab(url, AsyncHTTPClient())
        try:
            await tab.open(targets)
        finally:
            tab.close()

    asyncio.run(go())


def new_session(server, before: set[str]):
    """The one session of `server` whose id is not in `before`."""
    (session,) = [s for s in server.get_sessions("/main") if s.id not in before]
    return session


#: The psi moves whose memory is measured (after 200 to warm up), each answered before
#: the next (~0.1 s each with tracemalloc on).
MOVES = 300
#: The move made before each snapshot.
LAST_PSI = 2.0

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


@pytest.mark.slow
def test_slider_moves_in_one_session_hold_no_more_python_memory(served) -> None:
    """`MOVES` psi moves over Bokeh's protocol (`bokeh_client.Tab`, each answered by
    the plots' new data before the next) leave the Python heap where it was: tracemalloc
    sees no growth beyond a few arrays' worth (what the server's RSS adds over a long
    soak is the allocator's, see docs/deploy.md)."""
    url, _ = served

    async def moves() -> int:
        tab = Tab(url, AsyncHTTPClient())
        await tab.open()

        async def snapshot() -> tracemalloc.Snapshot:
            # the same last move before each (what a move leaves in flight is its size)
            await tab.moved(LAST_PSI)
            await tab.quiet(0.3)
            gc.collect()
            return tracemalloc.take_snapshot()

        try:
            for _ in range(200):  # warm: caches, the first arrays of each size
                await tab.moved()
            tracemalloc.start()
            before = await snapshot()
            for _ in range(MOVES):
                await tab.moved()
            after = await snapshot()
            tracemalloc.stop()
        finally:
            tab.close()
        return sum(s.size_diff for s in after.compare_to(before, "filename"))

    grown = asyncio.run(moves())
    assert grown < 100_000, f"{MOVES} moves left {grown} bytes of Python objects behind"


def _one_move(url: str, listen: float = 0.0) -> tuple[list[str], list[str], float]:
    """One psi move from a loaded page (`bokeh_client.Tab`, which sends `document_ready`
    as BokehJS does): the PATCH-DOCs up to the one with the plots' new data, those that
    follow within `listen` s, and the psi sent."""
    async def move() -> tuple[list[str], list[str], float]:
        tab = Tab(url, AsyncHTTPClient())
        await tab.open()
        try:
            await tab.quiet(0.5)  # what the page's load sends, until a quiet 0.5 s
            patches, psi = await tab.moved()
            later = await tab.quiet(listen) if listen else []
            return patches, [c for h, c in later if h["msgtype"] == "PATCH-DOC"], psi
        finally:
            tab.close()

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
    from bokeh.util.token import generate_jwt_token, generate_session_id

    async def load() -> str:
        tab = Tab(url, AsyncHTTPClient())
        try:  # a session no page was made for (its id signed with the server's key)
            await tab.load(generate_jwt_token(
                generate_session_id(SECRET_KEY, signed=True), SECRET_KEY, signed=True))
            return json.dumps(tab.doc)
        finally:
            tab.close()

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

    signed = signed_with is not None
    token = generate_jwt_token(generate_session_id(signed_with, signed=signed),
                               signed_with, signed=signed)
    before = len(server.get_sessions("/main"))

    async def pull() -> str:
        tab = Tab(url, AsyncHTTPClient())
        try:
            return await tab.pull(token)
        finally:
            tab.close()

    with pytest.raises(Exception):  # noqa: B017 (closed or refused, as the client sees it)
        asyncio.run(pull())
    assert len(server.get_sessions("/main")) == before

