"""How evenly the shipped docker/nginx.conf spreads new visitors over the replicas.

Debian's nginx runs docker/nginx.conf on loopback in front of two, then three stand-in
upstreams that answer every request with their own name.  Requests without the route
cookie are new visitors (each gets a fresh random route, nginx's $request_id); every
upstream must get 1/N of them, within 3.5 standard deviations of the binomial count,
whatever the upstreams are called.  A request that sends its cookie back goes to the
same upstream every time (page and websocket meet in one replica).
"""

from __future__ import annotations

import http.client
import math
import socketserver
import subprocess
import sys
import threading
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "docker"))
import replicas  # noqa: E402  (docker/replicas.py)

CONF = ROOT / "docker" / "nginx.conf"
VISITORS = 12_000


class _Named(socketserver.ThreadingTCPServer):
    """An HTTP/1.1 upstream (keep-alive) that answers every GET with its own port."""

    daemon_threads = True
    allow_reuse_address = True

    def __init__(self) -> None:
        super().__init__(("127.0.0.1", 0), _Handler)

    @property
    def port(self) -> int:
        return self.server_address[1]


class _Handler(socketserver.StreamRequestHandler):
    def handle(self) -> None:
        body = str(self.server.server_address[1]).encode()
        while self.rfile.readline():
            while self.rfile.readline() not in (b"\r\n", b"\n", b""):
                pass
            self.wfile.write(b"HTTP/1.1 200 OK\r\nContent-Type: text/plain\r\n"
                             b"Content-Length: %d\r\n\r\n%s" % (len(body), body))
            self.wfile.flush()


def _balancer(exe: str, d: Path, upstreams: list[_Named]) -> tuple[subprocess.Popen, int]:
    """nginx with docker/nginx.conf in `d`, in front of `upstreams`: (process, port)."""
    (d / "tmp").mkdir()
    d.chmod(0o755)
    (d / "tmp").chmod(0o777)
    port = replicas.free_port()
    servers = " ".join(f"server 127.0.0.1:{u.port};" for u in upstreams)
    (d / "explorer.conf").write_text(replicas.render(
        CONF.read_text(), LISTEN=f"127.0.0.1:{port}", UPSTREAM_SERVERS=servers))
    (d / "nginx.conf").write_text(replicas.TOP.format(d=d))
    proc = subprocess.Popen([exe, "-c", str(d / "nginx.conf")], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, start_new_session=True)
    replicas.wait_http(f"http://127.0.0.1:{port}/static/probe.js", 30, proc=proc)
    return proc, port


def _counts(port: int, n: int, cookie: str | None = None) -> dict[str, int]:
    """n GETs of /static/x.js on one keep-alive connection: answers per upstream."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    counts: dict[str, int] = {}
    headers = {"Cookie": f"explorer_route={cookie}"} if cookie else {}
    try:
        for _ in range(n):
            conn.request("GET", "/static/x.js", headers=headers)
            who = conn.getresponse().read().decode()
            counts[who] = counts.get(who, 0) + 1
    finally:
        conn.close()
    return counts


@pytest.fixture(scope="module")
def nginx() -> str:
    exe = replicas.nginx_exe()
    if exe is None:
        pytest.skip("nginx is not installed (make nginx)")
    return exe


@pytest.mark.parametrize("n_upstreams", [2, 3])
def test_new_visitors_spread_evenly_and_each_stays(nginx, tmp_path, n_upstreams):
    upstreams = [_Named() for _ in range(n_upstreams)]
    for u in upstreams:
        threading.Thread(target=u.serve_forever, daemon=True).start()
    proc, port = _balancer(nginx, tmp_path, upstreams)
    try:
        counts = _counts(port, VISITORS)
        assert set(counts) == {str(u.port) for u in upstreams}, counts
        share = 1 / n_upstreams
        sd = math.sqrt(VISITORS * share * (1 - share))
        worst = max(abs(c - VISITORS * share) for c in counts.values())
        assert worst <= 3.5 * sd, (counts, f"{worst / sd:.1f} standard deviations")
        for route in ("a", "visitor-2", "0123456789abcdef0123456789abcdef"):
            assert len(_counts(port, 20, cookie=route)) == 1  # sticky
    finally:
        proc.terminate()
        proc.wait(15)
        for u in upstreams:
            u.shutdown()
            u.server_close()
