"""No link, typed value or client message blanks a page or breaks a session (`app.page.guard`).

In process: whole-page builds over every query key the app reads (the explorer's, the SI
inputs', the motor's, the view) with extreme, non-finite, huge-integer, empty and
malformed values (hypothesis), each asserting a built page whose URL reads back without a
refusal; values a script can send through the websocket (NaN, inf, out of range) refused
once at the widget, without recursion. Served: the links that blanked the page before.
"""

from __future__ import annotations

import logging
import math
import sys
import time
import urllib.error
import urllib.request

import pytest
from bokeh.document import Document
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_sessions import (  # noqa: F401 (served, pages_thrown_freely: fixtures)
    new_session,
    pages_thrown_freely,
    served,
    visit,
)

import app.page.guard
from app.contact.query import parse_query
from app.contact.state import QUERY_KEYS
from app.motor import QUERY_KEYS as MOTOR_KEYS
from app.motor import MotorScene
from app.page.bucket import AddressLimit
from app.page.explorer import Explorer
from app.page.guard import SafeLocation, build_page, quoted

#: The links of issue 22 that answered an empty page, and their neighbours.
BAD_LINKS = [
    "tau0=1.57079632679", "tau0=1.5707963267948963", "tau0=-1.5707963267948963",
    "motor_N=5e-324", "motor_delta=1e300", "motor_N=1e-300", "x=" + "1" * 5000,
    "?psi=1", "psi=" + "9" * 5000, "psi=1e12&tau0=1.5707963267948963", "view=%00",
    "psi=nan", "tau=inf", "motor_x0=-0", "motor_L=1e308&motor_x0=1e307",
]

KEYS = [*QUERY_KEYS, *MOTOR_KEYS, "view", "bokeh-session-id", "", "?psi"]

TEXTS = st.one_of(
    st.sampled_from(["", " ", "nan", "-nan", "inf", "-inf", "1e308", "-1e308", "5e-324",
                     "-5e-324", "0", "-0", "1", "0.5", "1.5707963267948966",
                     "1.57079632679", "-1.5707963267948963", "1e12", "1e13", "1e300",
                     "1e-300", "0x10", "1_000", "１", "true", "[1]", "{}", "'", "<b>",
                     "9" * 5000, "fig6e", "present", "steel", "custom"]),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(min_value=-10**40, max_value=10**40).map(str),
    st.text(max_size=30),
)

QUERIES = st.dictionaries(st.sampled_from(KEYS), st.lists(TEXTS, min_size=1, max_size=2),
                          max_size=6)


def session_args(query: dict[str, list[str]]) -> dict[str, list[bytes]]:
    """`query` as Bokeh hands a served page its arguments (`pn.state.session_args`)."""
    return {k: [v.encode("utf-8", "surrogatepass") for v in vs] for k, vs in query.items()}


def assert_page(explorer: Explorer, page) -> None:
    """The page is built (every model made), its state is one core accepts, and the URL
    the page writes reads back without a refusal."""
    root = page.get_root(Document())
    assert root is not None
    explorer.state.contact()  # (raises if the state is not a contact)
    _, messages = parse_query(explorer.state.query())
    assert not messages, messages
    if explorer.motor is not None:
        probe = MotorScene()
        assert not probe.apply_query(explorer.motor.query())
        probe.close()
    explorer.close(None)


@pytest.mark.parametrize("link", BAD_LINKS)
def test_the_links_that_blanked_the_page_build_one(link: str) -> None:
    query: dict[str, list[str]] = {}
    for part in link.split("&"):
        key, _, value = part.partition("=")
        query.setdefault(key, []).append(value)
    explorer, page = build_page(session_args(query))
    assert_page(explorer, page)


@pytest.mark.slow
@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(QUERIES)
def test_any_query_builds_a_page(query: dict[str, list[str]]) -> None:
    explorer, page = build_page(session_args(query))
    assert_page(explorer, page)


def test_a_failed_build_shows_the_defaults_and_says_why() -> None:
    explorer, page = build_page({"motor_N": [b"5e-324"]})
    assert_page(explorer, page)
    assert explorer.message.visible
    assert "motor_N" in explorer.message.object or "N" in explorer.message.object


def test_messages_quote_a_long_value_in_part() -> None:
    explorer, _ = build_page({"x": [b"1" * 5000]})
    assert explorer.message.visible
    assert len(explorer.message.object) < 600
    assert len(quoted("1" * 5000)) <= 130


@pytest.mark.parametrize("uri", ["/main??psi=1", "/main?x=" + "1" * 5000, "/main?psi=[1",
                                 "/main?a={&b=[[["])
def test_the_location_reads_any_url(uri: str) -> None:
    loc = SafeLocation(search=uri.partition("?")[2] and "?" + uri.partition("?")[2])
    assert isinstance(loc.query_params, dict)


@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf, 1e300, -1e300])
@pytest.mark.parametrize("slider", ["psi", "tau0", "mu", "nu", "tau", "speed"])
def test_a_value_no_browser_sends_is_refused_once(slider: str, value: float) -> None:
    """NaN used to recurse until Python's limit (nan != nan) in the state's handler."""
    ex = Explorer()
    before = {k: getattr(ex.state, k) for k in ("psi", "tau0", "mu", "nu", "tau", "speed")}
    widget = getattr(ex.contact.controls, f"{slider}_slider")
    target = getattr(widget, "_slider", widget)  # the browser's range input
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(400)  # a recursion would show as RecursionError quickly
    try:
        target.value = value
    finally:
        sys.setrecursionlimit(limit)
    after = {k: getattr(ex.state, k) for k in before}
    assert after == before  # (+-1e300 is outside every one of these domains too)


@pytest.mark.parametrize("link", ["?tau0=1.57079632679", "??psi=1",
                                  "?x=" + "1" * 5000, "?motor_N=5e-324", "?view=present"])
def test_served_links_build_the_explorer(served, link: str, caplog) -> None:  # noqa: F811
    """Over HTTP and the websocket, as a browser loads the page: the explorer is built
    into the page (before, the page build raised and the session's document was empty),
    and nothing raised while it was (the presentation view leaves sliders off the page)."""
    url, server = served
    before = {s.id for s in server.get_sessions("/main")}
    full = "view=present" not in link  # (the presentation: no T(τ) plot)
    with caplog.at_level(logging.ERROR):
        visit(url + link, targets=full)  # (LookupError unless the ψ slider and plots came)
    assert not [rec for rec in caplog.records if rec.levelno >= logging.ERROR], \
        [rec.getMessage() for rec in caplog.records]
    doc = new_session(server, before).document
    names = {m.name for m in doc.roots}
    assert "location" in names
    assert doc.select_one({"name": "force"}) is not None or not full, names
    assert len(doc.models) > 100  # (the shell alone: ~10)


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def test_a_client_has_its_burst_then_its_rate_and_others_are_unaffected() -> None:
    clock = Clock()
    limit = AddressLimit(burst=3, rate=0.5, clock=clock)
    assert [limit.allow("a") for _ in range(4)] == [True, True, True, False]
    assert limit.allow("b")  # another address has its own bucket
    assert limit.retry_after("a") == pytest.approx(2.0)
    clock.now = 1.9
    assert not limit.allow("a")
    clock.now = 2.1
    assert limit.allow("a") and not limit.allow("a")
    clock.now = 100.0  # refilled to the burst, not beyond
    assert [limit.allow("a") for _ in range(4)] == [True, True, True, False]


def test_the_limit_forgets_idle_clients_and_stays_bounded() -> None:
    clock = Clock()
    limit = AddressLimit(burst=2, rate=1.0, clients=10, clock=clock)
    for i in range(10):
        limit.allow(f"c{i}")
    clock.now = 5.0  # every bucket full again: forgettable
    for i in range(10, 100):
        limit.allow(f"c{i}")
    assert len(limit._buckets) <= 10


@pytest.mark.parametrize("address, key", [
    ("203.0.113.7", "203.0.113.7"), ("::ffff:203.0.113.7", "203.0.113.7"),
    ("2001:db8:1:2:aaaa::1", "2001:db8:1:2::/64"),
    ("2001:db8:1:2:ffff:ffff:ffff:ffff", "2001:db8:1:2::/64"),
    ("2001:db8:1:3::1", "2001:db8:1:3::/64"), ("fe80::1%eth0", "fe80::/64"),
    ("not an address", "not an address")])
def test_a_client_is_an_ipv4_address_or_an_ipv6_64(address: str, key: str) -> None:
    """One machine may use any address of its IPv6 /64: the /64 is the client."""
    from app.page.bucket import client_key

    assert client_key(address) == key


def test_pages_thrown_away_are_counted_and_kept_ones_are_not() -> None:
    """A page closed while its explorer is built, or within `within` s of its being sent,
    takes one from its client's bucket; a page kept longer, or never built here, none."""
    from app.page.bucket import ThrownPages

    clock = Clock()
    thrown = ThrownPages(burst=2, rate=0.1, within=3.0, remember=60.0, clock=clock)
    thrown.building("kept", "school")
    thrown.sent("kept")
    clock.now = 3.5  # (the pupil looked at it)
    thrown.closed("kept")
    thrown.closed("never built here")
    assert thrown.retry_after("school") == 0.0
    thrown.building("a", "script")
    thrown.closed("a")  # (while built)
    thrown.building("b", "script")
    thrown.sent("b")
    clock.now = 5.0
    thrown.closed("b")  # (1.5 s after it was sent)
    assert thrown.retry_after("school") == 0.0
    assert thrown.retry_after("script") == pytest.approx(8.5)  # (one every 10 s, from 3.5 s)
    clock.now = 15.0
    assert thrown.retry_after("script") == 0.0
    thrown.building("old", "script")
    clock.now = 80.0  # (forgotten after `remember`, once another page is built)
    thrown.building("new", "script")
    thrown.closed("old")
    assert thrown.retry_after("script") == 0.0


def test_a_client_throwing_its_pages_away_waits_for_its_next_page(served,  # noqa: F811
                                                                  monkeypatch) -> None:
    """Pages loaded and closed as soon as they come (a script in a loop) use up the
    client's thrown pages (`app.page.gate.THROWN`): its next page is held back until
    one is refilled (here never: `app.page.gate.THROWN_HOLD_S`) before any session is
    made, then served (never refused);
    pages kept open (a class) take none of them and are answered at once."""
    import asyncio

    from bokeh_client import Tab
    from tornado.httpclient import AsyncHTTPClient

    import app.page.gate
    from app.page.bucket import ThrownPages

    url, server = served
    monkeypatch.setattr(app.page.gate, "THROWN", ThrownPages(burst=2, rate=1e-6, within=3.0))
    monkeypatch.setattr(app.page.gate, "THROWN_HOLD_S", 1.5)

    async def kept(n: int) -> None:
        tabs = [Tab(url, AsyncHTTPClient()) for _ in range(n)]
        try:
            for tab in tabs:
                await tab.open()
            await asyncio.sleep(3.5)  # (looked at)
        finally:
            for tab in tabs:
                tab.close()

    asyncio.run(kept(3))
    assert app.page.gate.THROWN.retry_after("127.0.0.1") == 0.0
    visit(url)
    visit(url)  # (its two thrown pages)
    end = time.monotonic() + 30  # (until the server has seen the websockets close)
    while app.page.gate.THROWN.retry_after("127.0.0.1") == 0.0 and time.monotonic() < end:
        time.sleep(0.05)
    assert app.page.gate.THROWN.retry_after("127.0.0.1") > 0.0
    before = {s.id for s in server.get_sessions("/main")}
    start = time.monotonic()
    with urllib.request.urlopen(url, timeout=60) as answer:
        assert answer.status == 200
    assert time.monotonic() - start >= 1.5  # (held back, then served)
    assert {s.id for s in server.get_sessions("/main")} - before  # (its session made)


def test_a_page_loaded_before_its_clients_builds_ran_out_gets_the_short_page(
        served, monkeypatch) -> None:  # noqa: F811
    """A page whose HTML was served while its address had a build left, but whose
    explorer would be built once they are spent (a class loading the page at once), gets
    the short note in place of the explorer."""
    import asyncio

    from bokeh_client import REFUSED, TOKEN, Tab
    from tornado.httpclient import AsyncHTTPClient

    url, server = served
    monkeypatch.setattr(app.page.guard, "BUILDS", AddressLimit(burst=2, rate=1e-6))
    before = {s.id for s in server.get_sessions("/main")}
    with urllib.request.urlopen(url, timeout=60) as r:  # (the HTML: builds left)
        token = TOKEN.search(r.read().decode()).group(1)
    visit(url)
    visit(url)  # (the address's builds spent)

    async def late() -> None:
        tab = Tab(url, AsyncHTTPClient())
        try:
            await tab.load(token)
        finally:
            tab.close()

    with pytest.raises(LookupError, match=REFUSED):
        asyncio.run(late())
    (refused,) = [s for s in server.get_sessions("/main") if s.id not in before
                  and "Too many pages" in " ".join(str(getattr(m, "text", ""))
                                                   for m in s.document.models)]
    texts = " ".join(str(getattr(m, "text", "")) for m in refused.document.models)
    assert "Too many pages were opened from your network" in texts
    assert "Please reload this page in" in texts


def test_a_client_past_its_page_builds_gets_the_busy_page(served,  # noqa: F811
                                                          monkeypatch) -> None:
    """Past its address's page builds a page load is answered with the busy page (429,
    opening the visitor's link again once a build is there) before any session is made:
    its page would only show a note."""
    import app.page.gate

    url, server = served
    monkeypatch.setattr(app.page.guard, "BUILDS", AddressLimit(burst=2, rate=0.02))
    monkeypatch.setattr(app.page.gate, "HOLD_S", 0.0)
    visit(url)
    visit(url)
    before = {s.id for s in server.get_sessions("/main")}
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(url + "?psi=3", timeout=60)
    assert refused.value.code == 429
    assert refused.value.url == url + "?psi=3"  # (answered there: no redirect)
    assert 1 <= int(refused.value.headers["Retry-After"]) <= 50  # (a build every 50 s)
    assert "url=/main?psi=3'" in refused.value.read().decode()
    assert {s.id for s in server.get_sessions("/main")} <= before


def test_behind_a_proxy_the_client_is_the_last_forwarded_hop() -> None:
    """Behind the shipped nginx every request comes from nginx's address: the page-build
    limit per address would be one limit for a whole class unless the server reads the
    client's address from X-Forwarded-For (`--behind-proxy`, set by the shipped compose
    and replica set-ups; never without a proxy, or a client could name any address)."""
    from app.serve import parse_args, server_options

    assert server_options(parse_args(["--behind-proxy"]))["use_xheaders"] is True
    assert server_options(parse_args([]))["use_xheaders"] is False


def test_a_page_build_does_not_hold_up_the_server(served, monkeypatch) -> None:  # noqa: F811
    """While one page's explorer is being built (held here until the server has
    answered), the server answers other requests: builds run on a worker thread, not on
    the event loop that serves the open sessions (`app.page.guard.serve_page`)."""
    import threading

    url, _ = served
    building, release = threading.Event(), threading.Event()
    threads = []
    build = app.page.guard.build_page

    def held_build(query):
        threads.append(threading.current_thread())
        building.set()
        assert release.wait(30), "the test never released the build"
        return build(query)

    monkeypatch.setattr(app.page.guard, "build_page", held_build)
    page = threading.Thread(target=visit, args=(url,))
    page.start()
    try:
        assert building.wait(30), "no page build started"
        liveness = url.rsplit("/", 1)[0] + "/liveness"
        with urllib.request.urlopen(liveness, timeout=10) as r:  # the loop answers
            assert r.status == 200
    finally:
        release.set()
        page.join(60)
    assert threads[0] is not threading.main_thread()
    assert threads[0].name.startswith("asyncio")  # the event loop's worker threads


def test_a_page_whose_websocket_never_opens_builds_nothing(served, monkeypatch) -> None:  # noqa: F811
    """A page load whose browser never opens its websocket (a link preview, a crawler,
    a script fetching the page in a loop) builds no explorer: its HTML holds the page's
    shell only.  A browser's load builds one."""
    url, server = served
    built = []
    build = app.page.guard.build_page
    monkeypatch.setattr(app.page.guard, "build_page", lambda q: built.append(q) or build(q))
    for _ in range(3):
        before = {s.id for s in server.get_sessions("/main")}
        with urllib.request.urlopen(url, timeout=60) as r:
            assert r.status == 200
        doc = new_session(server, before).document
        assert doc.select_one({"name": "force"}) is None
    assert built == []
    visit(url)
    assert len(built) == 1


def test_a_sessions_pulls_have_their_burst_then_their_rate() -> None:
    from bokeh.document import Document

    from app.page.pulls import PullGuard, PullRefused

    clock = Clock()
    doc = Document()
    doc.add_root(PullGuard(burst=2, rate=0.5, clock=clock))
    doc.to_json()
    doc.to_json()
    with pytest.raises(PullRefused):
        doc.to_json()
    clock.now = 1.9
    with pytest.raises(PullRefused):
        doc.to_json()
    clock.now = 2.1  # one pull back
    doc.to_json()
    with pytest.raises(PullRefused):
        doc.to_json()


def test_a_page_that_cannot_be_served_shows_no_traceback(served, monkeypatch, caplog,  # noqa: F811
                                                          capsys) -> None:
    """Whatever raises while the explorer is put into the page, the visitor gets a short
    note and the server one log line: Panel would print the traceback and show it on
    the page (it catches what an on-load callback raises)."""
    from bokeh_client import FAILED

    url, server = served

    def broken(self, shell, page=None):
        raise LookupError("a part of the page was not found")

    monkeypatch.setattr(Explorer, "attach", broken)
    before = {s.id for s in server.get_sessions("/main")}
    with caplog.at_level(logging.INFO, logger="app.page.guard"), \
            pytest.raises(LookupError, match=FAILED):
        visit(url)
    session = new_session(server, before)
    texts = [getattr(m, "text", "") or "" for m in session.document.models]
    assert any("could not be shown" in t for t in texts), texts
    assert not any("Traceback" in t or "LookupError" in t for t in texts)
    assert "Traceback" not in capsys.readouterr().out
    lines = [rec for rec in caplog.records if rec.name == "app.page.guard"]
    assert len(lines) == 1 and lines[0].exc_info is None
    assert "LookupError: 'a part of the page was not found'" in lines[0].getMessage()


def test_a_page_whose_shell_cannot_be_served_shows_no_traceback(served, monkeypatch,  # noqa: F811
                                                                caplog) -> None:
    """The same when the page's shell itself cannot be made: the page's HTML then holds
    the short note, and the server logs one line."""
    url, server = served

    def broken(location):
        raise LookupError("no shell")

    monkeypatch.setattr(app.page.guard, "serve_shell", broken)
    before = {s.id for s in server.get_sessions("/main")}
    with caplog.at_level(logging.INFO, logger="app.page.guard"), \
            urllib.request.urlopen(url) as r:
        assert r.status == 200
    texts = [getattr(m, "text", "") or "" for m in new_session(server, before).document.models]
    assert any("could not be shown" in t for t in texts), texts
    lines = [rec for rec in caplog.records if rec.name == "app.page.guard"]
    assert len(lines) == 1 and lines[0].exc_info is None
    assert "LookupError: 'no shell'" in lines[0].getMessage()


def test_past_its_page_loads_a_client_gets_the_busy_page_and_no_session(served,  # noqa: F811
                                                                          monkeypatch) -> None:
    """A script fetching the page in a loop: past its address's page loads
    (`app.page.gate.PAGES`) the request is answered, before any session is made, with
    the busy page (429, Retry-After), which opens the same link again when it may; the
    answer is held back for `HOLD_S`, so that a loop asks at most once per `HOLD_S`."""
    import time
    import urllib.error

    import app.page.gate

    url, server = served
    monkeypatch.setattr(app.page.gate, "PAGES", AddressLimit(burst=2, rate=0.01))
    monkeypatch.setattr(app.page.gate, "HOLD_S", 0.5)
    link = url + "?psi=2&tau0=0.4"
    for _ in range(2):
        with urllib.request.urlopen(link, timeout=60) as r:
            assert r.status == 200
    before = {s.id for s in server.get_sessions("/main")}
    asked = time.monotonic()
    with pytest.raises(urllib.error.HTTPError) as refused:
        urllib.request.urlopen(link, timeout=60)
    assert time.monotonic() - asked >= 0.5  # (held back)
    assert refused.value.code == 429
    assert refused.value.url == link  # (answered there: no redirect)
    after = int(refused.value.headers["Retry-After"])
    assert 60 <= after <= 100  # (a load every 100 s)
    body = refused.value.read().decode()
    assert "Too many pages were opened from your network" in body
    assert f"content='{after}; url=/main?psi=2&amp;tau0=0.4'" in body  # (the visitor's link)
    assert {s.id for s in server.get_sessions("/main")} <= before  # (none made; old ones go)


@pytest.mark.parametrize("uri, expected", [
    ("/main?psi=2&tau0=0.4", "/main?psi=2&tau0=0.4"), ("/main/", "/main"),
    ("/main", "/main"), ("https://elsewhere.example/main", "/main"),
    ("//elsewhere.example/main", "/main"), ("/admin", "/main"), ("/main/ws", "/main"),
    ("javascript:alert(1)", "/main"), ("", "/main")])
def test_the_busy_page_sends_only_to_the_explorer(uri: str, expected: str) -> None:
    from app.page.gate import busy_page, link

    assert link(uri) == expected
    assert link(uri.replace("/main", "/x/main", 1), "/x") == expected.replace("/main", "/x/main")
    escaped = expected.replace("&", "&amp;")
    assert (f"content='7; url={escaped}'" in busy_page(7, expected)
            and f"href='{escaped}'" in busy_page(7, expected))


def test_the_limits_are_sized_for_the_class_behind_one_address(monkeypatch) -> None:
    """`--class-size N`: N page builds and 3N page loads at once per address (a whole
    school behind one NAT raises it, with nginx's burst); nonsense refused.  Without it
    (and under `panel serve app/main.py`) the limits are those of the default class."""
    import app.page.gate
    from app.page.bucket import CLASS_SIZE, ThrownPages
    from app.serve import parse_args, size_limits

    assert (app.page.guard.BUILDS.burst, app.page.gate.PAGES.burst,
            app.page.gate.thrown_burst(CLASS_SIZE)) == (40, 120, 3)
    monkeypatch.setattr(app.page.guard, "BUILDS", AddressLimit(burst=1.0, rate=0.25))
    monkeypatch.setattr(app.page.gate, "PAGES", AddressLimit(burst=1.0, rate=1.0))
    monkeypatch.setattr(app.page.gate, "THROWN", ThrownPages(burst=1.0, rate=1.0, within=3.0))
    size_limits(parse_args(["--class-size", "200"]).class_size)
    assert app.page.guard.BUILDS.burst == 200 and app.page.gate.PAGES.burst == 600
    assert app.page.gate.THROWN.limit.burst == 12
    assert [app.page.guard.BUILDS.allow("school") for _ in range(201)].count(True) == 200
    size_limits(parse_args(["--class-size", "2"]).class_size)
    assert app.page.gate.THROWN.limit.burst == 3  # (at least 3)
    size_limits(parse_args([]).class_size)
    assert app.page.guard.BUILDS.burst == CLASS_SIZE == 40 and app.page.gate.PAGES.burst == 120
    assert app.page.gate.THROWN.limit.burst == 3
    for bad in ("0", "-3", "1000001"):
        with pytest.raises(SystemExit):
            parse_args(["--class-size", bad])
