"""Page loads per client address, refused before any session is made.

A page load's HTML costs the server CPU (a session and its shell, and Panel's rendering
of the page: `app.page.guard.serve_page`), most of it on the event loop that serves
every open session.  A script fetching the page in a loop would keep the process busy
and slow every lecture on it.  `PAGES` gives each client address a burst of page loads
refilled at a steady rate; past it, or once the address has no page build left
(`app.page.guard.BUILDS`: its page would only show a note), Panel's authorization hook
(`authorize`, ``pn.config.authorize_callback``, run before the session is made)
redirects the client to `BusyPage`, which answers 429 with a short page that opens the
explorer at the same link again once the address may load a page.  A refusal costs a
few ms, spread over two small requests.

The shipped nginx limits page loads per address as well (docs/deploy.md, "Rate
limits"), with the same burst and rate.
"""

from __future__ import annotations

import html
import math
from typing import Any
from urllib.parse import urlencode, urlsplit

import panel as pn
from tornado.web import RequestHandler

from app.page.bucket import CLASS_SIZE, AddressLimit

#: Page loads at once per visitor of a class behind one address: opening the link, one
#: reload, one to spare.
PAGES_PER_VISITOR = 3


def pages_burst(class_size: int) -> float:
    """The page loads at once per address for a class of `class_size` behind it."""
    return float(PAGES_PER_VISITOR * class_size)


#: The page loads of this server process, per client address: 120 at once (a class of
#: `CLASS_SIZE`, `pages_burst`), then one a second.
PAGES = AddressLimit(burst=pages_burst(CLASS_SIZE), rate=1.0)

#: The explorer's own path, below the server's prefix (the only page `BusyPage` sends to).
APP_PATH = "/main"

#: Where a client past its page loads is sent, below the server's prefix.
BUSY_PATH = f"{APP_PATH}/busy"


def authorize(user: Any, path: str) -> bool | str:
    """Panel's authorization callback: True while the client's address has page loads
    left (`PAGES`) and a page build (`app.page.guard.BUILDS`, not taken here: the
    page's explorer takes it), else the URL of `BusyPage` for the link it asked for,
    to open again once both are there.  Panel runs it for each page request, with the
    request's session context as current document, before the session is made."""
    from app.page import guard

    request = pn.state.curdoc.session_context.request
    client = str(request.remote_ip)
    building = guard.BUILDS.retry_after(client)
    if building <= 0.0 and PAGES.allow(client):
        return True
    path = path.rstrip("/")
    prefix = path[: -len(APP_PATH)] if path.endswith(APP_PATH) else ""
    after = max(building, PAGES.retry_after(client))
    query = urlencode({"after": max(1, math.ceil(after)),
                       "next": link(getattr(request, "uri", "") or "", prefix)})
    return f"{prefix}{BUSY_PATH}?{query}"


def link(uri: str, prefix: str = "") -> str:
    """`uri` if it is a link to the explorer on this server (its path, then nothing or
    a query), else the explorer's plain address: the busy page never sends elsewhere."""
    parts = urlsplit(uri)
    app = f"{prefix}{APP_PATH}"
    if parts.scheme or parts.netloc or parts.path not in (app, f"{app}/"):
        return app
    return f"{app}?{parts.query}" if parts.query else app


class BusyPage(RequestHandler):
    """429 with a short page: too many pages were opened from this address; the page
    opens the explorer at the visitor's link again after ``after`` seconds (Retry-After
    and a meta refresh; no script)."""

    def initialize(self, prefix: str = "") -> None:
        self.prefix = prefix

    def get(self) -> None:
        try:
            after = min(max(int(self.get_argument("after", "1")), 1), 3600)
        except ValueError:
            after = 1
        target = html.escape(link(self.get_argument("next", ""), self.prefix), quote=True)
        self.set_status(429)
        self.set_header("Retry-After", str(after))
        self.set_header("Cache-Control", "no-store")
        self.set_header("Content-Type", "text/html; charset=UTF-8")
        self.finish(
            "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
            f"<meta http-equiv='refresh' content='{after}; url={target}'>"
            "<title>Zharii contact explorer</title></head><body>"
            "<h1>Zharii contact explorer</h1><p role='alert'>Too many pages were opened "
            f"from your network just now. The explorer opens again in {after} s "
            f"(<a href='{target}'>open it</a>).</p></body></html>")
