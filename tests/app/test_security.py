"""What reaches the explorer from outside is shown as text and bounded (app/serve.py).

In the browser: markup and script payloads in every query parameter run nothing,
inject no element and are shown literally.  Over HTTP and the websocket: every page
carries a nonce-based Content-Security-Policy, a foreign Origin's websocket upgrade
gets 403, oversized or malformed websocket messages close only their connection, a
client that stops half-way through a frame is disconnected within a bound while an
idle one that answers pings stays, and Bokeh's autoload script (which would echo its
parameter into JavaScript) answers 404.  The basic-auth password is read from the
environment and never appears on the server's command line.
"""

from __future__ import annotations

import asyncio
import json
import os
import re
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from concurrent.futures import ThreadPoolExecutor
from urllib.parse import urlencode, urlsplit

import pytest
from explorer_browser import JS_READY, ROOT, free_port, wait_for_http
from tornado.httpclient import HTTPClientError, HTTPRequest
from tornado.websocket import WebSocketClosedError, websocket_connect

from app.contact.query import parse_query
from app.contact.state import QUERY_KEYS
from app.serve import SESSION

#: One payload per query parameter, each marked so that an injected element is found.
PAYLOADS = {
    "psi": "<img src=x id=xss-psi onerror=alert('psi')>",
    "tau0": "<script id=xss-tau0>alert('tau0')</script>",
    "mu": "\"><svg id=xss-mu onload=alert('mu')>",
    "nu": "<b id=xss-nu>nu</b>",
    "tau": "<iframe id=xss-tau src=javascript:alert('tau')></iframe>",
    "log_psi": "<details id=xss-log open ontoggle=alert('log')>",
    "period": "<video id=xss-period src=x onerror=alert('period')>",
    "preset": "[click](javascript:alert('preset')) <a id=xss-preset href=x>a</a>",
    "physical": "<img src=x id=xss-physical onerror=alert('physical')>",
    "material": "<script id=xss-material>alert('material')</script>",
    "R": "<b id=xss-R>R</b>",
    "G": "<svg id=xss-G onload=alert('G')>",
    "H": "<img src=x id=xss-H onerror=alert('H')>",
    "u0": "<i id=xss-u0>u0</i>",
    "h": "<u id=xss-h>h</u>",
    "omega": "<s id=xss-omega>omega</s>",
    "drive": "<marquee id=xss-drive>drive</marquee>",
    "theta": "<img src=x id=xss-theta onerror=alert('theta')>",
    "<img src=x id=xss-key onerror=alert('key')>": "1",
}

#: JavaScript: elements anywhere in the page (shadow roots included) matching a selector.
JS_FIND = """(selector) => {
  const found = [];
  const walk = (root) => {
    root.querySelectorAll(selector).forEach((e) => found.push(e.outerHTML.slice(0, 80)));
    root.querySelectorAll('*').forEach((e) => { if (e.shadowRoot) walk(e.shadowRoot); });
  };
  walk(document);
  return found;
}"""

#: JavaScript: the text of the named Panel pane's element (its shadow root's text).
JS_TEXT_OF_MESSAGE = """() => {
  const texts = [];
  const walk = (root) => {
    root.querySelectorAll('*').forEach((e) => {
      if (e.shadowRoot) {
        const t = e.shadowRoot.textContent || '';
        if (t.includes('is not a number') || t.includes('unknown parameter')) texts.push(t);
        walk(e.shadowRoot);
      }
    });
  };
  walk(document);
  return texts.sort((a, b) => a.length - b.length)[0] || '';
}"""


@pytest.mark.browser
def test_query_payloads_run_nothing_and_show_as_text(browser, url) -> None:
    assert set(QUERY_KEYS) <= set(PAYLOADS), "a query parameter has no payload"
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    dialogs: list[str] = []
    page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
    page.goto(f"{url}?{urlencode(PAYLOADS)}")
    page.wait_for_function(JS_READY, timeout=60_000)
    page.wait_for_timeout(1500)  # time let pass on purpose: any injected handler fires
    assert dialogs == []
    assert page.evaluate(JS_FIND, "[id^='xss'], a[href^='javascript'], iframe") == []
    shown = page.evaluate(JS_TEXT_OF_MESSAGE)
    _, messages = parse_query(PAYLOADS)
    assert len(messages) == len(PAYLOADS)
    for message in messages:  # each shown as the text it is, markup and all
        assert message in shown, (message, shown)
    page.close()


def test_pages_carry_a_nonce_content_security_policy(url) -> None:
    with urllib.request.urlopen(url) as r:
        csp = r.headers["Content-Security-Policy"]
        body = r.read().decode()
        assert r.headers["X-Content-Type-Options"] == "nosniff"
    nonce = re.search(r"'nonce-([^']+)'", csp).group(1)
    assert "'unsafe-inline'" not in csp.split("script-src")[1].split(";")[0]
    tags = re.findall(r"<script\b[^>]*>", body)
    assert tags and all(f'nonce="{nonce}"' in t for t in tags)
    with urllib.request.urlopen(url) as r:  # a fresh nonce per response
        assert nonce not in r.headers["Content-Security-Policy"]


def _session_token(url: str) -> str:
    with urllib.request.urlopen(url) as r:
        page = r.read().decode()
    return re.search(r'\\?"token\\?":\s*\\?"([^"\\]+)', page).group(1)


def run(coro) -> object:
    """Run a coroutine on a loop of its own (Playwright's sync API owns this thread's)."""
    with ThreadPoolExecutor(1) as pool:
        return pool.submit(asyncio.run, coro).result(timeout=60)


def _ws(url: str, origin: str, token: str):
    parts = urlsplit(url)
    req = HTTPRequest(f"ws://{parts.netloc}{parts.path}/ws",
                      headers={"Origin": origin, "Sec-WebSocket-Protocol": f"bokeh, {token}"})
    return websocket_connect(req, max_message_size=64 << 20)


def test_websocket_from_a_foreign_origin_is_refused(url) -> None:
    own = "http://" + urlsplit(url).netloc

    async def connect(origin: str) -> int:
        try:
            conn = await _ws(url, origin, _session_token(url))
        except HTTPClientError as err:
            return err.code
        conn.close()
        return 101

    assert run(connect("http://evil.example")) == 403
    assert run(connect(own)) == 101


async def _connect(url: str):
    """A Bokeh websocket connection from the page's own origin, past the server's ACK."""
    conn = await _ws(url, "http://" + urlsplit(url).netloc, _session_token(url))
    for _ in range(3):  # the ACK: header, metadata, content
        await conn.read_message()
    return conn


async def _server_info(conn) -> str:
    """Ask for the server's info over a Bokeh connection; the reply's msgtype."""
    for frame in ({"msgid": "info-1", "msgtype": "SERVER-INFO-REQ"}, {}, {}):
        await conn.write_message(json.dumps(frame))
    while True:
        header = json.loads(await asyncio.wait_for(conn.read_message(), 10))
        if header.get("reqid") == "info-1":
            return header["msgtype"]


async def _closed(conn) -> int | None:
    """Wait until the server closes `conn`; its close code."""
    while await asyncio.wait_for(conn.read_message(), 10) is not None:
        pass
    return conn.close_code


#: Messages (Bokeh's: header, metadata, content frames) that must close their connection,
#: with Bokeh's close code 10000, "failed to parse a message".
BAD_MESSAGES = {
    "garbage": ["not json at all", "{}", "{}"],
    "no-msgid": [json.dumps({"msgtype": "PATCH-DOC"}), "{}", "{}"],
}


@pytest.mark.parametrize("name", BAD_MESSAGES)
def test_bad_websocket_messages_close_only_their_connection(url, name) -> None:
    async def send() -> tuple[int | None, str]:
        conn = await _connect(url)
        assert await _server_info(conn) == "SERVER-INFO-REPLY"
        for frame in BAD_MESSAGES[name]:
            await conn.write_message(frame)
        code = await _closed(conn)
        other = await _connect(url)  # the server goes on serving other connections
        reply = await _server_info(other)
        other.close()
        return code, reply

    assert run(send()) == (10000, "SERVER-INFO-REPLY")


async def _ask_padded(url: str, size: int) -> tuple[str, int | None]:
    """A valid SERVER-INFO-REQ whose header frame is padded with blanks to `size` bytes:
    ("SERVER-INFO-REPLY", None) if the server answers it, else ("closed", close code).

    The server closes a connection whose frame is over the cap as soon as it has read the
    frame's length, without reading the rest: the client may then fail while still
    writing, and may or may not get the close frame (1009) before the reset, so only
    its absence of a reply is certain."""
    conn = await _connect(url)
    header = json.dumps({"msgid": "padded", "msgtype": "SERVER-INFO-REQ"})
    try:
        for frame in (header + " " * (size - len(header)), "{}", "{}"):
            await conn.write_message(frame)
        while (message := await asyncio.wait_for(conn.read_message(), 10)) is not None:
            frame = json.loads(message)
            if isinstance(frame, dict) and frame.get("reqid") == "padded":
                return frame["msgtype"], None
    except WebSocketClosedError:
        pass
    finally:
        conn.close()
    return "closed", conn.close_code


def test_a_message_over_the_size_cap_closes_only_its_connection(url) -> None:
    """A frame of exactly the cap is answered; one byte more closes its connection (code
    1009 when the close frame arrives), and the server goes on serving others."""
    cap = SESSION["websocket_max_message_size"]

    async def send() -> tuple[tuple, tuple, str]:
        at_cap = await _ask_padded(url, cap)
        over = await _ask_padded(url, cap + 1)
        other = await _connect(url)
        reply = await _server_info(other)
        other.close()
        return at_cap, over, reply

    at_cap, (over, code), reply = run(send())
    assert at_cap == ("SERVER-INFO-REPLY", None)
    assert over == "closed" and code in (1009, None), (over, code)
    assert reply == "SERVER-INFO-REPLY"


#: A marker that must never come back from the server, in the autoload parameter.
AUTOLOAD_PROBE = "x'</script><script>alert('autoload-probe')</script>"


@pytest.mark.parametrize("path", ["/autoload.js", "/autoload_js"])
def test_the_autoload_script_is_not_served(url, path) -> None:
    """Bokeh's autoload endpoint writes its bokeh-autoload-element parameter, unescaped,
    into JavaScript served from the app's origin; the app never uses it and answers 404
    with an empty body (also for "autoload_js": Bokeh's route is a regex with an
    unescaped dot)."""
    query = urlencode({"bokeh-autoload-element": AUTOLOAD_PROBE, "bokeh-app-path": "/main"})
    try:
        with urllib.request.urlopen(f"{url}{path}?{query}", timeout=60) as r:
            status, body = r.status, r.read()
    except urllib.error.HTTPError as err:
        status, body = err.code, err.read()
    assert status == 404, (status, body[:200])
    assert b"autoload-probe" not in body and body == b""


def _bound() -> float:
    """Seconds within which a client that answers no ping is dropped: Tornado pings after
    an interval, closes after a timeout without the pong, aborts 5 s after its close."""
    return SESSION["websocket_ping_interval"] + SESSION["websocket_ping_timeout"] + 5


async def _raw_websocket(url: str) -> tuple[asyncio.StreamReader, asyncio.StreamWriter]:
    """A websocket to the page's own session opened by hand (no ping answered, ever)."""
    parts = urlsplit(url)
    reader, writer = await asyncio.open_connection(parts.hostname, parts.port)
    token = _session_token(url)
    writer.write((f"GET {parts.path}/ws HTTP/1.1\r\nHost: {parts.netloc}\r\n"
                  "Connection: Upgrade\r\nUpgrade: websocket\r\nSec-WebSocket-Version: 13\r\n"
                  "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                  f"Origin: http://{parts.netloc}\r\n"
                  f"Sec-WebSocket-Protocol: bokeh, {token}\r\n\r\n").encode())
    await writer.drain()
    head = await asyncio.wait_for(reader.readuntil(b"\r\n\r\n"), 30)
    assert head.startswith(b"HTTP/1.1 101"), head[:100]
    return reader, writer


def test_a_half_sent_frame_is_disconnected_within_the_bound(url) -> None:
    """A client that sends the first 10 bytes of a 100-byte frame and stops can answer no
    ping: the server closes its connection within the bound (<= 30 s).  A client idle as
    long that answers pings (Tornado's, reading what it is sent, like a browser) is still
    served afterwards."""
    bound = _bound()
    assert bound <= 30

    async def drain(conn) -> None:
        # Tornado's client answers pings only while its messages are read
        while await conn.read_message() is not None:
            pass

    async def scenario() -> tuple[float, str]:
        idle = await _connect(url)
        reading = asyncio.ensure_future(drain(idle))
        reader, writer = await _raw_websocket(url)
        mask = b"\x01\x02\x03\x04"
        writer.write(bytes([0x81, 0x80 | 100]) + mask + b"x" * 10)  # FIN text, masked, len 100
        await writer.drain()
        t0 = time.monotonic()
        deadline, closed = t0 + bound + 15, False
        while not closed and time.monotonic() < deadline:
            try:  # the session's messages and the server's pings, until the end
                data = await asyncio.wait_for(reader.read(65536), deadline - time.monotonic())
            except TimeoutError:
                break
            except ConnectionError:
                data = b""
            closed = not data
        elapsed = time.monotonic() - t0
        writer.close()
        assert closed, f"the half-sent frame's connection is still open after {elapsed:.1f} s"
        reading.cancel()
        reply = await _server_info(idle)  # the idle client that answers pings: still served
        idle.close()
        return elapsed, reply

    elapsed, reply = run(scenario())
    assert elapsed <= bound + 2, f"closed after {elapsed:.1f} s, bound {bound} s"
    assert reply == "SERVER-INFO-REPLY"


def test_the_password_is_read_from_the_environment_never_from_argv(tmp_path) -> None:
    """BASIC_AUTH (a password with blanks) reaches the server through its environment:
    the pages ask for the login, the password logs in, and no process's command line
    (what ps shows every user) holds it.  --basic-auth on a command line is refused."""
    password = "correct horse battery staple"
    port = free_port()
    env = {**os.environ, "BASIC_AUTH": password}
    log = tempfile.TemporaryFile("w+")
    proc = subprocess.Popen([sys.executable, "-m", "app.serve", "--port", str(port), "--admin"],
                            cwd=ROOT, env=env, stdout=log, stderr=subprocess.STDOUT)
    base = f"http://127.0.0.1:{port}"
    try:
        wait_for_http(f"{base}/liveness", 90)
        cmdline = open(f"/proc/{proc.pid}/cmdline", "rb").read().decode()
        assert "--port" in cmdline and "horse" not in cmdline, cmdline

        class NoRedirect(urllib.request.HTTPRedirectHandler):
            def redirect_request(self, *args, **kwargs):
                return None

        opener = urllib.request.build_opener(NoRedirect)
        with pytest.raises(urllib.error.HTTPError) as anonymous:
            opener.open(f"{base}/main", timeout=60)
        assert anonymous.value.code == 302
        assert "login" in anonymous.value.headers["Location"]

        def login(pw: str) -> str:
            """The session cookie the login sets for `pw` ("" if refused)."""
            data = urlencode({"username": "teacher", "password": pw}).encode()
            try:
                opener.open(f"{base}/login", data=data, timeout=60)
            except urllib.error.HTTPError as err:
                cookies = err.headers.get_all("Set-Cookie") or []
                return "; ".join(c.split(";")[0] for c in cookies if c.startswith("user="))
            return ""

        assert login("correct") == ""
        cookie = login(password)
        assert cookie
        req = urllib.request.Request(f"{base}/main", headers={"Cookie": cookie})
        with opener.open(req, timeout=60) as r:
            assert r.status == 200 and b"Bokeh" in r.read()
    finally:
        proc.terminate()
        proc.wait(30)
        log.close()
    refused = subprocess.run([sys.executable, "-m", "app.serve", "--basic-auth", password],
                             cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert refused.returncode == 2 and "BASIC_AUTH" in refused.stderr
    assert "horse" not in refused.stderr
