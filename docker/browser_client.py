"""A browser's side of Bokeh's websocket protocol, as BokehJS speaks it: the client of
the replica smoke check (docker/replicas.py) and of the benchmarks (the load test, its
abuse mode, the CPU-per-move, page-load and memory benchmarks), which import it from
here (the tests have their own, tests/app/bokeh_client.py: tests and benchmarks do not
import each other).

`Session` is one browser tab: ``GET /main`` (cookies kept, so a balancer's sticky
cookie is honoured) and the session token read from the page; the websocket ``/main/ws``
with that token and the page's own ``Origin``; after the server's ``ACK`` a
``PULL-DOC-REQ``, then the ``document_ready`` event BokehJS sends once it has rendered the
page (Panel builds the explorer into the page's shell from then on); in the document it
gets, the ψ slider and the ``ColumnDataSource`` named ``force`` (`find_targets`).  A
move (`Session.move`) sends a ``PATCH-DOC`` setting the slider's value and times the
server's ``PATCH-DOC`` that changes the ``force`` source; one move is in flight at a
time (a tick that finds it unanswered is counted as late).
"""

from __future__ import annotations

import asyncio
import json
import random
import re
import time
from dataclasses import dataclass, field
from http.cookies import SimpleCookie
from urllib.parse import urlsplit

from tornado.httpclient import AsyncHTTPClient, HTTPRequest
from tornado.websocket import WebSocketClosedError, websocket_connect

#: The event BokehJS sends when the page's document is rendered (a PATCH-DOC event).
DOCUMENT_READY = {"kind": "MessageSent", "msg_type": "bokeh_event",
                  "msg_data": {"type": "event", "name": "document_ready",
                               "values": {"type": "map"}}}
TOKEN = re.compile(r'\\?"token\\?":\s*\\?"([^"\\]+)')
#: Texts of the notes a client past its page builds gets, and one whose page could not
#: be served (`app.page.guard.refusal_note`, `failure_note`).
REFUSED = "Too many pages were opened from your network"
FAILED = "This page could not be shown"
PSI_LABEL = re.compile(r"^\s*ψ(\s|=|$)")


# ---------------------------------------------------------------- the document


def models_of(doc_json: dict) -> tuple[dict[str, dict], dict[str, str]]:
    """All model representations in a serialized document, by id, and each one's parent."""
    models: dict[str, dict] = {}
    parent: dict[str, str] = {}

    def walk(obj, owner: str | None) -> None:
        if isinstance(obj, dict):
            if "id" in obj and obj.get("type") == "object":
                mid = obj["id"]
                if "attributes" in obj or mid not in models:
                    models[mid] = obj
                if owner is not None and mid != owner:
                    parent.setdefault(mid, owner)
                owner = mid
            for v in obj.values():
                walk(v, owner)
        elif isinstance(obj, list):
            for v in obj:
                walk(v, owner)

    walk(doc_json, None)
    return models, parent


def strings(obj) -> list[str]:
    """Every text inside `obj` (a serialized model's attributes: dicts, lists, texts)."""
    if isinstance(obj, str):
        return [obj]
    if isinstance(obj, dict):
        return [s for v in obj.values() for s in strings(v)]
    if isinstance(obj, list):
        return [s for v in obj for s in strings(v)]
    return []


def find_targets(doc_json: dict, slider: str | None = None) -> tuple[str, str, float, float]:
    """(slider id, force source id, slider start, slider end) in a pulled document.

    A slider is a BokehJS Slider model, or the values of the app's `LabelledSlider` (the
    `data` of its ReactiveHTML model: value, start, end, step and label).  The ψ slider
    is the slider named ``slider`` (default ``psi``) if there is one; else the slider
    whose title or label, or the label next to it (a text in the smallest layout around
    it that holds no other slider), starts with "ψ".
    """
    models, parent = models_of(doc_json)
    force = [i for i, m in models.items() if m.get("name") == "ColumnDataSource"
             and m.get("attributes", {}).get("name") == "force"]
    if len(force) != 1:
        raise LookupError(f"expected one ColumnDataSource named 'force', found {len(force)}")
    def attrs(i: str) -> dict:
        return models[i].get("attributes", {})

    sliders = [i for i, m in models.items() if m.get("name") == "Slider"
               or {"value", "start", "end", "step", "label"} <= set(attrs(i))]

    wanted = slider or "psi"
    named = [i for i in sliders if attrs(i).get("name") == wanted]
    if slider and not named:
        raise LookupError(f"no slider named {slider!r}")
    if not named:
        descendants: dict[str, set[str]] = {}
        for child in models:
            p = parent.get(child)
            while p is not None:
                descendants.setdefault(p, set()).add(child)
                p = parent.get(p)
        for i in sliders:
            if PSI_LABEL.match(str(attrs(i).get("title") or attrs(i).get("label") or "")):
                named.append(i)
                continue
            p = parent.get(i)
            while p is not None:
                inside = descendants.get(p, set())
                if any(j in inside for j in sliders if j != i):
                    break  # this layout holds other sliders too: not the slider's own
                texts = [s for j in inside if j != i for s in strings(attrs(j))]
                if any(PSI_LABEL.match(s) for s in texts):
                    named.append(i)
                    break
                p = parent.get(p)
    if len(named) != 1:
        raise LookupError(f"expected one ψ slider, found {len(named)} among {len(sliders)} sliders")
    a = attrs(named[0])
    return named[0], force[0], float(a.get("start", 0.05)), float(a.get("end", 30.0))


# ---------------------------------------------------------------- one session


@dataclass
class Stats:
    """What a session's moves gave while recorded: each answered move's latency (s), the
    moves sent, the ticks skipped (`late`), the server's messages while a move was in
    flight and the errors by kind."""

    latencies: list[float] = field(default_factory=list)  # seconds
    sent: int = 0
    late: int = 0
    messages: int = 0  # PATCH-DOC messages received while a change was in flight
    errors: dict[str, int] = field(default_factory=dict)

    def error(self, kind: str) -> None:
        self.errors[kind] = self.errors.get(kind, 0) + 1


class Session:
    """One simulated browser tab."""

    def __init__(self, url: str, http: AsyncHTTPClient, timeout: float, slider: str | None,
                 source: str | None = None):
        self.url, self.http, self.timeout, self.slider_name = url, http, timeout, slider
        #: the local address its connections are made from (None: the system's choice;
        #: on loopback any 127.x.y.z, so that a server sees another client address)
        self.source = source
        self.cookies: dict[str, str] = {}
        self.conn = None
        self.pending: tuple[str, float] | None = None  # (msgid, sent at)
        self.stats: Stats | None = None  # where results go (None: not recorded)
        self.alive = False
        self._n = 0
        self._reader: asyncio.Task | None = None
        #: messages received by type (after `open`)
        self.received: dict[str, int] = {}
        #: the PATCH-DOC contents received, while a list (None: not kept)
        self.patches: list[str] | None = None

    async def open(self, targets: bool = True) -> None:
        """Load the page as a browser does: its HTML, then `load`."""
        r = await self.http.fetch(self.url, request_timeout=60, follow_redirects=True,
                                  raise_error=False, network_interface=self.source)
        if r.code == 429:  # (past the address's page loads: `app.page.gate`)
            raise LookupError(f"no explorer: page load refused (HTTP 429, {r.effective_url})")
        if r.code != 200:
            raise ConnectionError(f"page load answered HTTP {r.code}")
        for value in r.headers.get_list("Set-Cookie"):
            for k, morsel in SimpleCookie(value).items():
                self.cookies[k] = morsel.value
        m = TOKEN.search(r.body.decode())
        if not m:
            raise LookupError("no session token in the page")
        await self.load(m.group(1), targets)

    async def load(self, token: str, targets: bool = True) -> None:
        """Do what BokehJS does with the page's session `token`: pull the document (the
        page's shell, a column), send ``document_ready`` once it is shown (Panel then
        runs the session's on-load callbacks, which build the explorer into the shell:
        `app.page.guard.serve_page`), and wait for what fills the shell.  With
        `targets`, find the ψ slider and the plots' source in it: LookupError if they
        are not there (naming the server's refusal or failure note if that came)."""
        content = await self.pull(token)
        pulled = json.loads(content)
        shells = [r["id"] for r in pulled["doc"]["roots"] if r.get("name", "").endswith("Column")]
        await self.send("PATCH-DOC", {"events": [DOCUMENT_READY]})
        self.doc = {"pulled": pulled, "filled": []}
        try:  # a revision whose page's HTML holds the explorer (--revs)
            find_targets(pulled, self.slider_name)
            shells = []
        except LookupError:
            pass
        while shells:
            header, content = await asyncio.wait_for(self.read(), 120)
            if header.get("msgtype") != "PATCH-DOC":
                continue
            patch = json.loads(content)
            self.doc["filled"].append(patch)
            if any(e.get("attr") == "children" and e.get("model", {}).get("id") in shells
                   for e in patch.get("events", [])):
                break
        if targets:
            try:
                self.slider, self.force, self.start, self.end = find_targets(
                    self.doc, self.slider_name)
            except LookupError as err:
                text = json.dumps(self.doc["filled"])
                notes = [n for n in (REFUSED, FAILED) if n in text]
                raise LookupError(f"no explorer: {notes[0] if notes else err}") from None
            self.force_ref = f'"model":{{"id":"{self.force}"}}'
        self.value = None
        self.alive = True
        self._reader = asyncio.create_task(self._read_loop())

    async def connect(self, token: str) -> None:
        """Open the websocket of the session `token` names and wait for the server's ACK
        (ConnectionError if the server closes it instead)."""
        parts = urlsplit(self.url)
        headers = {"Origin": f"{parts.scheme}://{parts.netloc}",
                   "Sec-WebSocket-Protocol": f"bokeh, {token}"}
        if self.cookies:
            headers["Cookie"] = "; ".join(f"{k}={v}" for k, v in self.cookies.items())
        ws = "wss" if parts.scheme == "https" else "ws"
        req = HTTPRequest(f"{ws}://{parts.netloc}{parts.path.rstrip('/')}/ws", headers=headers,
                          request_timeout=60, connect_timeout=30,
                          network_interface=self.source)
        self.conn = await websocket_connect(req, max_message_size=64 << 20)
        header, _ = await asyncio.wait_for(self.read(), 60)
        if header.get("msgtype") != "ACK":
            raise ConnectionError(f"expected ACK, got {header.get('msgtype')}")

    async def pull(self, token: str) -> str:
        """Open the websocket of the session `token` names (from the page, or made up: the
        server then builds the session for the websocket alone) and pull its document:
        the PULL-DOC-REPLY's content."""
        await self.connect(token)
        await self.send("PULL-DOC-REQ", {})
        for _ in range(100):  # the server may send patches (e.g. the URL) before the reply
            header, content = await asyncio.wait_for(self.read(), 60)
            if header.get("msgtype") == "PULL-DOC-REPLY":
                return content
        raise ConnectionError("no PULL-DOC-REPLY")

    async def read(self) -> tuple[dict, str]:
        """One whole message: (header, content text); buffers are read and dropped."""
        frames = []
        for _ in range(3):
            f = await self.conn.read_message()
            if f is None:
                raise ConnectionError("websocket closed")
            frames.append(f)
        header = json.loads(frames[0])
        for _ in range(2 * int(header.get("num_buffers", 0))):
            if await self.conn.read_message() is None:
                raise ConnectionError("websocket closed")
        return header, frames[2]

    async def send(self, msgtype: str, content: dict) -> str:
        """Send one message of `msgtype` with `content` (no buffers); its msgid."""
        self._n += 1
        msgid = f"lt{self._n}"
        for frame in ({"msgid": msgid, "msgtype": msgtype}, {}, content):
            await self.conn.write_message(json.dumps(frame))
        return msgid

    async def _read_loop(self) -> None:
        try:
            while True:
                header, content = await self.read()
                kind = header.get("msgtype")
                self.received[kind] = self.received.get(kind, 0) + 1
                if kind == "PATCH-DOC" and self.patches is not None:
                    self.patches.append(content)
                if kind == "PATCH-DOC" and self.pending and self.stats is not None:
                    self.stats.messages += 1
                if kind == "PATCH-DOC" and self.pending and self.force_ref in content:
                    if self.stats is not None:
                        self.stats.latencies.append(time.perf_counter() - self.pending[1])
                    self.pending = None
                elif kind == "ERROR":
                    if self.stats is not None:
                        self.stats.error("server ERROR reply")
                    if self.pending and header.get("reqid") == self.pending[0]:
                        self.pending = None
        except (ConnectionError, WebSocketClosedError, asyncio.CancelledError):
            pass
        except Exception:  # a malformed message: this session is lost
            pass
        finally:
            self.alive = False

    async def move(self) -> None:
        """One tick: send a new ψ unless the previous one is still unanswered."""
        if not self.alive:
            if self.stats is not None:
                self.stats.error("connection lost")
            return
        now = time.perf_counter()
        if self.pending:
            if now - self.pending[1] < self.timeout:
                if self.stats is not None:
                    self.stats.late += 1
                return
            if self.stats is not None:
                self.stats.error(f"no update within {self.timeout:g} s")
            self.pending = None
        lo, hi = max(self.start, 0.2), min(self.end, 20.0)
        v = round(random.uniform(lo, hi), 6)
        while v == self.value:
            v = round(random.uniform(lo, hi), 6)
        self.value = v
        event = {"kind": "ModelChanged", "model": {"id": self.slider}, "attr": "value", "new": v}
        try:
            msgid = f"lt{self._n + 1}"
            self.pending = (msgid, time.perf_counter())
            await self.send("PATCH-DOC", {"events": [event]})
            if self.stats is not None:
                self.stats.sent += 1
        except WebSocketClosedError:
            self.pending = None
            self.alive = False
            if self.stats is not None:
                self.stats.error("connection lost")

    def close(self) -> None:
        if self._reader:
            self._reader.cancel()
        if self.conn is not None:
            self.conn.close()
