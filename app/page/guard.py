"""Every page build guarded: whatever a link holds, the visitor gets a page.

A page load has two steps (`serve_page`). The page's HTML holds a shell only (a column
saying the explorer is loading: `serve_shell`); the explorer is built into it once the
browser has loaded the page and opened its websocket (`fill`), so that a page fetched
without its websocket (a link preview, a crawler, a script in a loop) builds nothing.

`build_page` builds one session's explorer from the page's URL and, if anything raises
while reading the URL or building a scene, builds the default explorer instead with a
message saying why; the server logs one line (no traceback per request).  `fill`
refuses, cheaply, a client that has had too many pages built (`BUILDS`), and tells
`app.page.gate.THROWN` which session was built for which client.

The URL is read through `SafeLocation`, Panel's `Location` whose query parser takes any
text: Panel's own fails on some links that a browser sends as they are (a doubled
``??``, an integer of more than 4,300 digits), and before the page exists.
"""

from __future__ import annotations

import logging
import math
import reprlib
from collections.abc import Mapping
from functools import partial
from typing import Any

import panel as pn
from panel.io.location import Location
from panel.io.resources import get_dist_path

from app.page import gate, layout
from app.page.bucket import CLASS_SIZE, AddressLimit, client_key
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


def build_page(query: Mapping[str, Any]) -> tuple[Explorer, pn.Column]:
    """The explorer for URL `query` (as `pn.state.session_args` gives it) and its page;
    if building them raises, the default explorer with a message naming what failed."""
    try:
        explorer = Explorer(query=dict(query))
        return explorer, explorer.view()
    except Exception as err:
        log.warning("page build failed for %s: %s: %s (the defaults are shown)",
                    quoted(dict(query)), type(err).__name__, quoted(str(err)))
        explorer = Explorer()
        explorer.show_messages([f"This link could not be shown ({type(err).__name__}: "
                                f"{err}); the default contact is shown instead."])
        return explorer, explorer.view()


#: The page builds of this server process, per client address: a build is the costliest
#: work of a page load, on a worker thread (`fill`), which the sessions already open share the
#: interpreter with, so a client loading pages in a loop would slow every lecture on
#: its process; past its bucket a client's page loads are refused before any session is
#: made (`app.page.gate.GatedDocHandler`), and a page loaded before the bucket ran out
#: gets `refusal_note` instead of the explorer, which costs little
#: (``python -m benchmarks.app.page_load`` times both).
#: `CLASS_SIZE` at once: a class behind one address (a
#: school's NAT) opening the page; then one every 4 s: that class reloading now and then.
BUILDS = AddressLimit(burst=float(CLASS_SIZE), rate=0.25)

#: The open sessions of this server process, kept out of the garbage collector's walks.
MEMORY = SessionMemory()


HEADING = "<h1>Zharii contact explorer</h1>"


def loading_note() -> pn.pane.HTML:
    """What the page shows until its explorer is built."""
    return pn.pane.HTML(f"{HEADING}<p role='status'>Loading the explorer…</p>")


def refusal_note(seconds: float) -> pn.pane.HTML:
    """What a client past its page builds gets: what happened and when to retry."""
    return pn.pane.HTML(
        f"{HEADING}<p role='alert'>Too many pages were opened from your network just now. "
        f"Please reload this page in {math.ceil(seconds)} s.</p>")


def failure_note() -> pn.pane.HTML:
    """What a client gets when its page could not be served at all: what happened (the
    server logged why; the visitor sees no traceback)."""
    return pn.pane.HTML(
        f"{HEADING}<p role='alert'>This page could not be shown. Please reload it; if it "
        "fails again, open the explorer's address without anything after "
        "<code>?</code>.</p>")


def serve_shell(location: SafeLocation | None) -> pn.Column:
    """The session's page as its HTML holds it: a column showing `loading_note`, into
    which `fill` puts the explorer; the page's title, its meta tags and its URL
    (`location`, Panel's, kept in step with the browser's address bar).

    Panel points its components' stylesheets at its CDN until it renders the page's
    HTML, and then at the server's own copies; what is added to the document later (the
    explorer), and a document built for a websocket alone (with `--num-procs` above 1
    a page's websocket may reach another process), keeps them on the CDN unless the
    document says where they are, which it does here (the page's Content-Security-Policy
    refuses the CDN, and an offline classroom cannot reach it)."""
    doc = pn.state.curdoc
    doc.template_variables.setdefault("dist_url", get_dist_path(cdn=False))
    shell = pn.Column(loading_note(), sizing_mode="stretch_width", margin=0)
    shell.servable(title=layout.TITLE, location=location or True)
    doc.template_variables["meta"] = layout.META
    return shell


def fill(shell: pn.Column, client: str, query: Mapping[str, Any], page: str = "") -> None:
    """Build the explorer for URL `query` into `shell` (`serve_shell`), guarded as
    `build_page` says; a client past its page builds (`BUILDS`) gets `refusal_note`
    instead; the build is told to `app.page.gate.THROWN` as session `page`'s (a page
    closed while it is built, or soon after, counts against its client).  Whatever else raises gives
    `failure_note` and one log line.  A built session's objects are kept out of the
    garbage collector's walks while it is open (`MEMORY`)."""
    if not BUILDS.allow(client):
        log.debug("page refused to %s: past its page builds", client)
        shell.objects = [refusal_note(BUILDS.retry_after(client))]
        return
    gate.THROWN.building(page, client)
    try:
        explorer, view = build_page(query)
        explorer.attach(shell, view)
    except Exception as err:  # (Panel would show the visitor the traceback)
        log.error("page could not be served to %s for %s: %s: %s (a short page instead)",
                  client, quoted(dict(query)), type(err).__name__, quoted(str(err)))
        shell.objects = [failure_note()]
        return
    pn.state.on_session_destroyed(lambda _: MEMORY.closed())
    MEMORY.built()
    gate.THROWN.sent(page)


def serve_page() -> None:
    """Serve the session being created (the server's application): its page's HTML
    holds only `serve_shell`'s column; the explorer is built into it by `fill` once the
    browser has loaded the page (its websocket open, the column shown: Panel's
    ``onload``), on one of Bokeh's worker threads with the session's document locked,
    and sent to the browser as one change of the document.  A page load whose browser
    never opens its websocket (a link preview, a crawler, a script fetching the page in
    a loop) builds nothing (its cost is Panel's rendering of the HTML, a few tens of
    ms).  Nothing raises out of here (Panel would print the traceback and show it to
    the visitor)."""
    doc = pn.state.curdoc
    pulls = PullGuard()
    doc.add_root(pulls)  # (first: serialized before the rest, see app.page.pulls)
    request = doc.session_context.request
    query = dict(pn.state.session_args)
    try:
        shell = serve_shell(location_of(request))
    except Exception as err:  # (Panel would show the visitor the traceback)
        log.error("page could not be served for %s: %s: %s (a short page instead)",
                  quoted(query), type(err).__name__, quoted(str(err)))
        doc.clear()
        doc.add_root(pulls)
        pn.Column(failure_note()).servable(title=layout.TITLE)
        return
    pn.state.onload(partial(fill, shell, client_key(str(request.remote_ip)), query,
                            doc.session_context.id))
