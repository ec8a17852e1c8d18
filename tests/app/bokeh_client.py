"""A browser tab without a browser, for the tests: Bokeh's websocket protocol as BokehJS
speaks it to the served explorer.

`Tab.open` loads the page (its HTML, whose session token it reads), opens the websocket
with the page's ``Origin`` and the token, pulls the document (``PULL-DOC-REQ``), sends
the ``document_ready`` event BokehJS sends once it has rendered the page (Panel then
builds the explorer into the page's shell: `app.page.guard.serve_page`) and waits for
the explorer, whose ψ slider (`slider_values`) and plots' source (the
``ColumnDataSource`` named ``force``) it finds.  `Tab.move` sends a ψ value as a
browser's slider does (a ``PATCH-DOC`` of the slider's ``value``).

(The benchmarks and the replica smoke check have their own, docker/browser_client.py,
which also finds the slider in older revisions' pages: tests and benchmarks do not import
each other.)
"""

from __future__ import annotations

import asyncio
import json
import random
import re
import time
from urllib.parse import urlsplit

from tornado.httpclient import AsyncHTTPClient, HTTPRequest
from tornado.websocket import WebSocketClientConnection, websocket_connect

#: The event BokehJS sends when the page's document is rendered (a PATCH-DOC event).
DOCUMENT_READY = {"kind": "MessageSent", "msg_type": "bokeh_event",
                  "msg_data": {"type": "event", "name": "document_ready",
                               "values": {"type": "map"}}}
#: The session token in the page's HTML.
TOKEN = re.compile(r'\\?"token\\?":\s*\\?"([^"\\]+)')
#: The notes a page shows in place of the explorer (`app.page.guard`).
REFUSED = "Too many pages were opened from your network"
FAILED = "This page could not be shown"


def models(doc_json) -> dict[str, dict]:
    """Every model representation in a serialized document (or patch), by id."""
    found: dict[str, dict] = {}

    def walk(obj) -> None:
        if isinstance(obj, dict):
            if obj.get("type") == "object" and "id" in obj:
                if "attributes" in obj or obj["id"] not in found:
                    found[obj["id"]] = obj
            for v in obj.values():
                walk(v)
        elif isinstance(obj, list):
            for v in obj:
                walk(v)

    walk(doc_json)
    return found


def named(doc_json, name: str) -> list[str]:
    """The ids of the models whose ``name`` attribute is `name`."""
    return [i for i, m in models(doc_json).items()
            if m.get("attributes", {}).get("name") == name]


def slider_values(doc_json, name: str) -> list[str]:
    """The ids of the value models of the app's slider `name` (its `SliderModel`, tagged
    ``NAME-value``, whose ``value`` the browser's moves change)."""
    return [i for i, m in models(doc_json).items()
            if f"{name}-value" in (m.get("attributes", {}).get("tags") or [])]


class Tab:
    """One browser tab on the explorer at `url` (see the module docstring)."""

    def __init__(self, url: str, http: AsyncHTTPClient | None = None,
                 timeout: float = 10.0) -> None:
        self.url, self.http, self.timeout = url, http or AsyncHTTPClient(), timeout
        self.conn: WebSocketClientConnection | None = None
        self.doc: dict = {}  # {"pulled": the document, "filled": the patches that built it}
        self.psi: str | None = None  # the ψ slider's model id
        self.force_ref: str | None = None  # how a patch names the plots' source
        self.value: float | None = None  # the last ψ sent
        self.token: str | None = None  # the session's token, from the page
        self._n = 0

    async def open(self, targets: bool = True) -> None:
        """Load the page as a browser does: its HTML, then `load`."""
        r = await self.http.fetch(self.url, request_timeout=60, raise_error=False)
        if r.code != 200:
            raise ConnectionError(f"page load answered HTTP {r.code}")
        m = TOKEN.search(r.body.decode())
        if not m:
            raise LookupError("no session token in the page")
        self.token = m.group(1)
        await self.load(self.token, targets)

    async def connect(self, token: str) -> None:
        """Open the websocket of the session `token` names and wait for the server's
        ACK (ConnectionError if the server closes it instead)."""
        parts = urlsplit(self.url)
        req = HTTPRequest(f"ws://{parts.netloc}{parts.path.rstrip('/')}/ws",
                          headers={"Origin": f"{parts.scheme}://{parts.netloc}",
                                   "Sec-WebSocket-Protocol": f"bokeh, {token}"},
                          request_timeout=60, connect_timeout=30)
        self.conn = await websocket_connect(req, max_message_size=64 << 20)
        header, _ = await self.read()
        if header.get("msgtype") != "ACK":
            raise ConnectionError(f"expected ACK, got {header.get('msgtype')}")

    async def pull(self, token: str) -> str:
        """`connect`, then pull the document: the PULL-DOC-REPLY's content."""
        await self.connect(token)
        await self.send("PULL-DOC-REQ", {})
        for _ in range(100):  # (the server may send patches before the reply)
            header, content = await self.read()
            if header.get("msgtype") == "PULL-DOC-REPLY":
                return content
        raise ConnectionError("no PULL-DOC-REPLY")

    async def load(self, token: str, targets: bool = True) -> None:
        """Do what BokehJS does with the page's session `token`: pull the document (the
        page's shell), send ``document_ready``, and read the patches until the shell
        holds what was built into it.  With `targets`, find the ψ slider and the plots'
        source there: LookupError if they are not (naming the page's refusal or
        failure note if that came instead)."""
        pulled = json.loads(await self.pull(token))
        shells = {r["id"] for r in pulled["doc"]["roots"] if r.get("name", "").endswith("Column")}
        await self.send("PATCH-DOC", {"events": [DOCUMENT_READY]})
        self.doc = {"pulled": pulled, "filled": []}
        while True:
            header, content = await self.read(120)
            if header.get("msgtype") != "PATCH-DOC":
                continue
            patch = json.loads(content)
            self.doc["filled"].append(patch)
            if any(e.get("attr") == "children" and e.get("model", {}).get("id") in shells
                   for e in patch.get("events", [])):
                break
        if targets:
            psi, force = slider_values(self.doc, "psi"), named(self.doc, "force")
            if len(psi) != 1 or len(force) != 1:
                text = json.dumps(self.doc["filled"])
                notes = [n for n in (REFUSED, FAILED) if n in text]
                raise LookupError(f"no explorer: {notes[0] if notes else 'no psi or force'}")
            self.psi, self.force_ref = psi[0], f'"model":{{"id":"{force[0]}"}}'

    async def read(self, timeout: float | None = None) -> tuple[dict, str]:
        """The server's next whole message: (header, content text); its buffers are
        read and dropped.  ConnectionError once the websocket is closed."""
        async def frame():
            f = await self.conn.read_message()
            if f is None:
                raise ConnectionError("websocket closed")
            return f

        async def message() -> tuple[dict, str]:
            header, _, content = [await frame() for _ in range(3)]
            header = json.loads(header)
            for _ in range(2 * int(header.get("num_buffers", 0))):
                await frame()
            return header, content

        return await asyncio.wait_for(message(), timeout or self.timeout)

    async def send(self, msgtype: str, content: dict) -> str:
        """Send one message of `msgtype` with `content` (no buffers); its msgid."""
        self._n += 1
        msgid = f"t{self._n}"
        for part in ({"msgid": msgid, "msgtype": msgtype}, {}, content):
            await self.conn.write_message(json.dumps(part))
        return msgid

    async def move(self, psi: float | None = None) -> float:
        """Send a ψ move as the browser's slider does (`psi`, else a new random value in
        [0.2, 20]); the value sent."""
        while psi is None or psi == self.value:
            psi = round(random.uniform(0.2, 20.0), 6)
        self.value = psi
        await self.send("PATCH-DOC", {"events": [{"kind": "ModelChanged",
                                                  "model": {"id": self.psi},
                                                  "attr": "value", "new": psi}]})
        return psi

    async def moved(self, psi: float | None = None) -> tuple[list[str], float]:
        """`move`, then read until the plots' new data: the PATCH-DOC contents up to and
        with it, and the value sent."""
        psi = await self.move(psi)
        patches: list[str] = []
        deadline = time.monotonic() + self.timeout
        while not any(self.force_ref in p for p in patches):
            header, content = await self.read(max(0.1, deadline - time.monotonic()))
            if header["msgtype"] == "PATCH-DOC":
                patches.append(content)
        return patches, psi

    async def quiet(self, seconds: float = 0.5) -> list[tuple[dict, str]]:
        """The messages read until none came for `seconds` s."""
        got = []
        while True:
            try:
                got.append(await self.read(seconds))
            except TimeoutError:
                return got

    def close(self) -> None:
        if self.conn is not None:
            self.conn.close()
