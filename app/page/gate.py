"""Page loads per client, refused before any session is made.

A page load's HTML costs the server CPU (a session and its shell, and Panel's rendering
of the page: `app.page.guard.serve_page`), and once its browser opens the websocket the
explorer is built into it (`app.page.guard.fill`), the costliest work of a page load,
on a worker thread that shares the interpreter with every open session.  A script
loading the page in a loop would keep the process busy and slow every lecture on it.

`GatedDocHandler`, Panel's page handler in its place (`install`), answers a page request
before Panel or Bokeh see it, with 429 and a short page, when its client
(`app.page.bucket.client_key`) has

- no page load left (`PAGES`: a burst of page loads, refilled at a steady rate), or
- no page build left (`app.page.guard.BUILDS`: its page would only show a note);

and it holds back (then serves) the page of a client that has thrown too many pages
away (`THROWN`: closed while their explorer was built or right after it was sent; a pupil
keeps the page open, a script in a loop closes each page as soon as it has it) until
`THROWN` has refilled one, `THROWN_HOLD_S` at most: such a loop builds at most one
explorer per `THROWN_HOLD_S`, and a visitor who closes a few pages quickly (a teacher
trying links, a test) waits for the next one and is never refused.

The refusal (`busy_page`) says when the address may load a page again (``Retry-After``)
and opens the explorer at the same link then (a meta refresh; no script).  It is held
back for up to `HOLD_S` (at most `HELD` at once), so that a client asking again as soon
as it is answered asks at most once per `HOLD_S`: a refusal is one small request.

The shipped nginx limits page loads per address as well (docs/deploy.md, "Rate
limits"), with the same burst and rate.
"""

from __future__ import annotations

import asyncio
import html
import math
from urllib.parse import urlsplit

from panel.io.server import DocHandler

from app.page.bucket import CLASS_SIZE, AddressLimit, ThrownPages, client_key
from app.page.routes import replace_route

#: Page loads at once per visitor of a class behind one address: opening the link, one
#: reload, one to spare.
PAGES_PER_VISITOR = 3


def pages_burst(class_size: int) -> float:
    """The page loads at once per address for a class of `class_size` behind it."""
    return float(PAGES_PER_VISITOR * class_size)


#: The page loads of this server process, per client: 120 at once (a class of
#: `CLASS_SIZE`, `pages_burst`), then one a second.
PAGES = AddressLimit(burst=pages_burst(CLASS_SIZE), rate=1.0)

#: A page closed this soon after its explorer was sent (s), or while it was built, is a
#: thrown page: a browser takes a second or more to show the explorer.
THROWN_WITHIN_S = 3.0


def thrown_burst(class_size: int) -> float:
    """The thrown pages at once per address for a class of `class_size` behind it: one
    pupil in sixteen reloading a page before it has shown (at least 3)."""
    return float(max(3, class_size // 16))


#: The time in which a client's thrown pages refill one (s), and the longest a thrower's
#: page is held back.
THROWN_HOLD_S = 10.0

#: The pages of this server process thrown, per client: 3 at once (a class of
#: `CLASS_SIZE`, `thrown_burst`), then one every `THROWN_HOLD_S`; past them a page is
#: held back.
THROWN = ThrownPages(burst=thrown_burst(CLASS_SIZE), rate=1.0 / THROWN_HOLD_S,
                     within=THROWN_WITHIN_S)

#: The explorer's own path, below the server's prefix.
APP_PATH = "/main"

#: The longest a refusal is held back (s), and the most answers held back at once (past
#: them a refusal is answered at once, a page served at once).
HOLD_S, HELD = 2.0, 256


def refusal_after(client: str) -> float:
    """0 (and one page load taken from `PAGES`) if `client` may load a page now, else the
    seconds until it may: it has page loads left (`PAGES`) and a page build
    (`app.page.guard.BUILDS`, not taken here: the page's explorer takes it)."""
    from app.page import guard

    wait = guard.BUILDS.retry_after(client)
    if wait <= 0.0 and PAGES.allow(client):
        return 0.0
    return max(wait, PAGES.retry_after(client), 1e-3)


def link(uri: str, prefix: str = "") -> str:
    """`uri` if it is a link to the explorer on this server (its path, then nothing or
    a query), else the explorer's plain address: the busy page never sends elsewhere."""
    parts = urlsplit(uri)
    app = f"{prefix}{APP_PATH}"
    if parts.scheme or parts.netloc or parts.path not in (app, f"{app}/"):
        return app
    return f"{app}?{parts.query}" if parts.query else app


def busy_page(after: int, target: str) -> str:
    """The refusal's HTML: too many pages were opened from this address; the page opens
    `target` (escaped here) after `after` s."""
    target = html.escape(target, quote=True)
    return ("<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
            f"<meta http-equiv='refresh' content='{after}; url={target}'>"
            "<title>Zharii contact explorer</title></head><body>"
            "<h1>Zharii contact explorer</h1><p role='alert'>Too many pages were opened "
            f"from your network just now. The explorer opens again in {after} s "
            f"(<a href='{target}'>open it</a>).</p></body></html>")


class GatedDocHandler(DocHandler):
    """Panel's page handler, answering 429 (`busy_page`, ``Retry-After``) before any
    session is made to a client that may not load a page now (`refusal_after`), held
    back for up to `HOLD_S`, and serving a client that threw its pages away (`THROWN`)
    once it may have one built again, `THROWN_HOLD_S` at most (see the module
    docstring)."""

    #: The answers being held back now (of this process).
    held = 0

    @staticmethod
    async def hold(seconds: float) -> bool:
        """Wait `seconds` unless `HELD` answers are held back already; whether it waited."""
        if GatedDocHandler.held >= HELD:
            return False
        GatedDocHandler.held += 1
        try:
            await asyncio.sleep(seconds)
        finally:
            GatedDocHandler.held -= 1
        return True

    async def prepare(self) -> None:
        client = client_key(str(self.request.remote_ip))
        after = refusal_after(client)
        if after <= 0.0:
            if (wait := THROWN.retry_after(client)) > 0.0:
                await self.hold(min(wait, THROWN_HOLD_S))
            await super().prepare()
            return
        if await self.hold(min(after, HOLD_S)):
            after = max(after - HOLD_S, 0.0)
        seconds = min(max(math.ceil(after), 1), 3600)
        self.set_status(429)
        self.set_header("Retry-After", str(seconds))
        self.set_header("Cache-Control", "no-store")
        self.set_header("Content-Type", "text/html; charset=UTF-8")
        self.finish(busy_page(seconds, link(self.request.uri or "", self.application.prefix)))


def install() -> None:
    """Serve every application's page with `GatedDocHandler`: it replaces Panel's page
    handler in Bokeh's per-application URL patterns (call before the server is made;
    calling it again changes nothing)."""
    replace_route(r"/?", GatedDocHandler)
