"""Every page build guarded: whatever a link holds, the visitor gets a page.

`build_page` builds one session's explorer from the page's URL and, if anything raises
while reading the URL or building a scene, builds the default explorer instead with a
message saying why; the server logs one line (no traceback per request).

`serve_page` refuses, cheaply, a client that has had too many pages built (`BuildLimit`).

The URL is read through `SafeLocation`, Panel's `Location` whose query parser takes any
text: Panel's own fails on some links that a browser sends as they are (a doubled
``??``, an integer of more than 4,300 digits), and before the page exists.
"""

from __future__ import annotations

import logging
import math
import reprlib
import threading
import time
from collections.abc import Callable, Mapping
from typing import Any

import panel as pn
from panel.io.location import Location

from app.page import bucket
from app.page.explorer import Explorer
from app.page.memory import SessionMemory
from app.page.pulls import PullGuard

log = logging.getLogger(__name__)

#: How much of a text from the URL a message or a log line quotes (characters).
QUOTE_CHARS = 120

_quote = reprlib.Repr(maxstring=QUOTE_CHARS, maxother=QUOTE_CHARS)


def quoted(value: Any) -> str:
    """`value` as a short text for a message or a log line (long texts cut in the
    middle with '...')."""
    return _quote.repr(value)


class SafeLocation(Location):
    """Panel's `Location` (the page's URL, read and written) whose `query_params` never
    raise: a query Panel cannot parse reads as empty (the explorer reads the query
    itself, from the request's arguments, and writes it whole)."""

    @property
    def query_params(self) -> dict[str, Any]:
        try:
            return super().query_params
        except ValueError:
            return {}


def location_of(request: Any) -> SafeLocation:
    """The page's location from its HTTP request (Bokeh's session request); an empty one
    (the explorer then writes the URL afresh) when Panel cannot split the URL."""
    try:
        return SafeLocation.from_request(request)
    except ValueError as err:
        log.info("unreadable URL %s (%s): written afresh", quoted(getattr(request, "uri", "")),
                 err)
        return SafeLocation()


def build_page(query: Mapping[str, Any], location: SafeLocation | None
               ) -> tuple[Explorer, pn.Column]:
    """The explorer for URL `query` (as `pn.state.session_args` gives it) and its page;
    if building them raises, the default explorer with a message naming what failed."""
    try:
        explorer = Explorer(query=dict(query), location=location)
        return explorer, explorer.view()
    except Exception as err:
        log.warning("page build failed for %s: %s: %s (the defaults are shown)",
                    quoted(dict(query)), type(err).__name__, quoted(str(err)))
        explorer = Explorer(location=location)
        explorer.show_messages([f"This link could not be shown ({type(err).__name__}: "
                                f"{err}); the default contact is shown instead."])
        return explorer, explorer.view()


class BuildLimit:
    """How many pages one client address may have built: a token bucket of `burst`
    builds, refilled at `rate` per second.

    A page build takes ~0.4 s of CPU on a worker thread (`app.serve.applications`),
    which the sessions already open share the interpreter with: a client loading pages
    in a loop would slow every lecture on its process.  Past its bucket a client gets
    `refusal_page`, which costs a few ms.  `burst` is sized for a class behind one
    address (a school's NAT) opening the page at once; `rate` for that class reloading
    now and then.  Idle clients' buckets are forgotten (at most `clients` are kept).
    """

    def __init__(self, burst: float = 40.0, rate: float = 0.25, clients: int = 10_000,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.burst, self.rate, self.clients, self._clock = burst, rate, clients, clock
        self._buckets: dict[str, tuple[float, float]] = {}  # address -> (tokens, when)
        self._lock = threading.Lock()

    def allow(self, client: str) -> bool:
        """Take one build from `client`'s bucket; False (nothing taken) when it is empty."""
        now = self._clock()
        with self._lock:
            tokens, when = self._buckets.get(client, (self.burst, now))
            if len(self._buckets) >= self.clients and client not in self._buckets:
                self._forget_full(now)
            tokens, taken = bucket.take(tokens, now - when, self.burst, self.rate)
            self._buckets[client] = (tokens, now)
            return taken

    def retry_after(self, client: str) -> float:
        """Seconds until `client` may have a page built again."""
        with self._lock:
            tokens, when = self._buckets.get(client, (self.burst, self._clock()))
        return max(0.0, (1.0 - tokens) / self.rate - (self._clock() - when))

    def _forget_full(self, now: float) -> None:
        full = [c for c, (tokens, when) in self._buckets.items()
                if tokens + (now - when) * self.rate >= self.burst]
        for c in full or list(self._buckets)[: len(self._buckets) // 2]:
            del self._buckets[c]


#: The page builds of this server process, per client address.
BUILDS = BuildLimit()

#: The open sessions of this server process, kept out of the garbage collector's walks.
MEMORY = SessionMemory()


def refusal_page(seconds: float) -> pn.Column:
    """The page a client gets past its page builds: what happened and when to retry."""
    return pn.Column(pn.pane.HTML(
        "<h1>Zharii contact explorer</h1><p role='alert'>Too many pages were opened from "
        f"your network just now. Please reload this page in {math.ceil(seconds)} s.</p>"))


def failure_page() -> pn.Column:
    """The page a client gets when its page could not be served at all: what happened
    (the server logged why; the visitor sees no traceback)."""
    return pn.Column(pn.pane.HTML(
        "<h1>Zharii contact explorer</h1><p role='alert'>This page could not be shown. "
        "Please reload it; if it fails again, open the explorer's address without "
        "anything after <code>?</code>.</p>"))


def gone(request: Any) -> bool:
    """Whether the client of `request` (Bokeh's session request) has hung up: the HTTP
    connection of its page load is closed.  A websocket's request, whose connection the
    websocket has taken over, is never gone."""
    stream = getattr(getattr(request, "connection", None), "stream", None)
    return stream is not None and stream.closed()


def serve_page() -> None:
    """Build the page of the session being created (the server's application)
    from its URL, guarded as `build_page` says, and mark it servable; a client past its
    page builds (`BUILDS`) gets `refusal_page` instead, and one that has hung up while
    its build waited for a worker nothing (its session is discarded unused).  Whatever
    else raises gives `failure_page` and one log line: nothing raises out of here
    (Panel would print the traceback and show it to the visitor).  A built
    session's objects are kept out of the garbage collector's walks while it is open
    (`MEMORY`)."""
    doc = pn.state.curdoc
    pulls = PullGuard()
    doc.add_root(pulls)  # (first: serialized before the rest, see app.page.pulls)
    request = doc.session_context.request
    client = str(request.remote_ip)
    if gone(request):
        log.debug("page not built for %s: the client has gone", client)
        return
    if not BUILDS.allow(client):
        log.debug("page refused to %s: past its page builds", client)
        refusal_page(BUILDS.retry_after(client)).servable(title="Zharii contact explorer")
        return
    try:
        explorer, page = build_page(pn.state.session_args, location_of(request))
        explorer.servable(page)
    except Exception as err:  # (Panel would show the visitor the traceback)
        log.error("page could not be served to %s for %s: %s: %s (a short page instead)",
                  client, quoted(dict(pn.state.session_args)), type(err).__name__,
                  quoted(str(err)))
        doc.clear()
        doc.add_root(pulls)
        failure_page().servable(title="Zharii contact explorer")
        return
    pn.state.on_session_destroyed(lambda _: MEMORY.closed())
    MEMORY.built()
