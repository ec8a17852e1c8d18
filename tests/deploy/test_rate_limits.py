"""The rate limits of the shipped docker/nginx.conf, against a stand-in upstream.

Debian's nginx runs docker/nginx.conf on loopback in front of a small HTTP server that
answers every page at once and accepts every websocket upgrade (101) and holds it, so
that only nginx's limits decide: a class of 60 loading the page at once from one address
passes, a burst beyond the configured one gets 429 and the static files are not limited;
an address holds at most the configured number of websockets, and one more gets 429
until one of them closes.  The numbers are read from the configuration itself.
"""

from __future__ import annotations

import http.client
import re
import socket
import socketserver
import subprocess
import sys
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "docker"))
import replicas  # noqa: E402  (docker/replicas.py)

CONF = ROOT / "docker" / "nginx.conf"
TLS_CONF = ROOT / "docker" / "nginx-tls.conf"


def _limits(text: str) -> dict[str, float]:
    """The page-load rate (per second) and burst, and the websocket cap, of a config."""
    rate = re.search(r"limit_req_zone \$binary_remote_addr zone=explorer_pages:\S+ "
                     r"rate=(\d+)r/([sm]);", text)
    burst = re.search(r"location ~ \^/main/\?\$ \{\s*limit_req zone=explorer_pages "
                      r"burst=(\d+) nodelay;", text)
    conns = re.search(r"location = /main/ws \{\s*limit_conn explorer_ws (\d+);", text)
    assert rate and burst and conns, "the page and websocket limits are not where expected"
    per_s = int(rate.group(1)) / (60 if rate.group(2) == "m" else 1)
    return {"rate": per_s, "burst": int(burst.group(1)), "websockets": int(conns.group(1))}


def test_both_configurations_set_the_same_limits():
    plain, tls = _limits(CONF.read_text()), _limits(TLS_CONF.read_text())
    assert plain == tls
    # a class of 60 behind one NAT: every student's page load and a reload each, and
    # two tabs each with the teacher's
    assert plain["burst"] >= 120 and plain["websockets"] >= 121
    for text in (CONF.read_text(), TLS_CONF.read_text()):
        assert "limit_req_status 429;" in text and "limit_conn_status 429;" in text


class _Upstream(socketserver.ThreadingTCPServer):
    """Answers any GET with a small page, and a websocket upgrade with 101, holding it."""

    daemon_threads = True
    allow_reuse_address = True

    def __init__(self) -> None:
        super().__init__(("127.0.0.1", 0), _Handler)
        self.held: list[socket.socket] = []

    @property
    def port(self) -> int:
        return self.server_address[1]


class _Handler(socketserver.StreamRequestHandler):
    def handle(self) -> None:
        while True:
            line = self.rfile.readline()
            if not line:
                return
            headers = {}
            while (h := self.rfile.readline()) not in (b"\r\n", b"\n", b""):
                k, _, v = h.decode().partition(":")
                headers[k.strip().lower()] = v.strip()
            if headers.get("upgrade", "").lower() == "websocket":
                self.wfile.write(b"HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\n"
                                 b"Connection: Upgrade\r\n"
                                 b"Sec-WebSocket-Accept: s3pPLMBiTxaQ9kYGzzhZRbK+xOo=\r\n\r\n")
                self.wfile.flush()
                self.rfile.read()  # held until the other side closes
                return
            self.wfile.write(b"HTTP/1.1 200 OK\r\nContent-Type: text/html\r\n"
                             b"Content-Length: 4\r\n\r\npage")
            self.wfile.flush()


@pytest.fixture(scope="module")
def balancer(tmp_path_factory):
    """nginx with docker/nginx.conf on a loopback port, in front of the stand-in upstream."""
    exe = replicas.nginx_exe()
    if exe is None:
        pytest.skip("nginx is not installed (make nginx)")
    upstream = _Upstream()
    threading.Thread(target=upstream.serve_forever, daemon=True).start()
    d = tmp_path_factory.mktemp("nginx")
    (d / "tmp").mkdir()
    d.chmod(0o755)
    (d / "tmp").chmod(0o777)
    port = replicas.free_port()
    (d / "explorer.conf").write_text(replicas.render(
        CONF.read_text(), LISTEN=f"127.0.0.1:{port}",
        UPSTREAM_SERVERS=f"server 127.0.0.1:{upstream.port};"))
    (d / "nginx.conf").write_text(replicas.TOP.format(d=d))
    test = subprocess.run([exe, "-t", "-c", str(d / "nginx.conf")], capture_output=True,
                          text=True, timeout=30, check=False)
    assert test.returncode == 0, test.stderr
    proc = subprocess.Popen([exe, "-c", str(d / "nginx.conf")], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, start_new_session=True)
    try:
        replicas.wait_http(f"http://127.0.0.1:{port}/static/probe.js", 30, proc=proc)
        yield port
    finally:
        proc.terminate()
        proc.wait(15)
        upstream.shutdown()
        upstream.server_close()


def _get(port: int, path: str) -> int:
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    try:
        conn.request("GET", path)
        return conn.getresponse().status
    finally:
        conn.close()


def _burst(port: int, path: str, n: int) -> list[int]:
    """n GETs of path, all sent at once (one connection each): their statuses."""
    with ThreadPoolExecutor(n) as pool:
        return list(pool.map(lambda _: _get(port, path), range(n)))


def test_a_class_loads_at_once_and_a_bigger_burst_is_refused(balancer):
    limits = _limits(CONF.read_text())
    t0 = time.monotonic()
    first = _burst(balancer, "/main?view=present", 60)
    assert first == [200] * 60, first  # a class of 60 behind one address
    assert _burst(balancer, "/static/js/bokeh.min.js", 150) == [200] * 150  # not limited
    second = _burst(balancer, "/main/", 150)
    elapsed = time.monotonic() - t0
    passed = first.count(200) + second.count(200)
    assert set(second) <= {200, 429}, second
    # nginx lets burst + 1 through at once, then one per 1 / rate seconds
    allowed = limits["burst"] + 1 + limits["rate"] * elapsed
    assert limits["burst"] + 1 <= passed <= allowed + 1, (passed, allowed, elapsed)
    assert second.count(429) >= 210 - allowed - 1 > 0


def _upgrade(port: int) -> tuple[int, socket.socket]:
    """A websocket handshake on /main/ws through the balancer: its status and socket."""
    s = socket.create_connection(("127.0.0.1", port), timeout=30)
    s.sendall(b"GET /main/ws HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: Upgrade\r\n"
              b"Upgrade: websocket\r\nSec-WebSocket-Version: 13\r\n"
              b"Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n")
    head = b""
    while b"\r\n\r\n" not in head:
        chunk = s.recv(4096)
        if not chunk:
            break
        head += chunk
    status = int(head.split(b" ", 2)[1]) if head.startswith(b"HTTP/1.1 ") else 0
    return status, s


def test_one_address_holds_at_most_the_websocket_cap(balancer):
    cap = int(_limits(CONF.read_text())["websockets"])
    held: list[socket.socket] = []
    try:
        for _ in range(cap):
            status, s = _upgrade(balancer)
            held.append(s)
            assert status == 101, f"websocket {len(held)} of {cap} got {status}"
        status, s = _upgrade(balancer)
        s.close()
        assert status == 429
        held.pop().close()  # one closes: a new one is let in once nginx has seen it go
        deadline = time.monotonic() + 10
        while True:
            status, s = _upgrade(balancer)
            if status == 101:
                held.append(s)
                break
            s.close()
            assert status == 429 and time.monotonic() < deadline, status
            time.sleep(0.05)
    finally:
        for s in held:
            s.close()
