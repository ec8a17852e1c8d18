"""Replicas behind nginx on loopback, without Docker: the replica smoke test.

    python docker/replicas.py smoke        # `make replica-smoke`; exit 0 = PASS
    python docker/replicas.py serve        # start the stack, print its URL, wait for Ctrl-C

`Stack` starts N `python -m app.serve` processes on free 127.0.0.1 ports and Debian's
nginx with the shipped docker/nginx.conf, its template filled in as the official nginx
image does (${LISTEN}, ${UPSTREAM_SERVERS}), on another free loopback port.  The
replicas allow the websocket origin of the balancer (127.0.0.1:PORT, localhost:PORT),
which is what a browser sends through it.

`smoke` checks, through the balancer, speaking Bokeh's protocol as a browser does
(docker/browser_client.py's Session: GET /main with its cookies, then the websocket,
then a ψ move answered by the plots' update):

1. sessions opened (at least 6) until both replicas hold some (at most 24), each moving the slider
   once and getting its update;
2. sticky: in nginx's access log, every session's GET /main and its websocket
   /main/ws went to the same replica (the log names the upstream of each request);
3. a websocket from a foreign Origin through the balancer is refused (403);
4. one replica is killed (SIGKILL): its sessions' websockets close, the other
   replica's sessions still answer, and new sessions (fresh ones, and ones whose cookie
   pointed at the dead replica) all work.

Needs nginx on PATH (`make nginx` installs Debian's); everything listens on 127.0.0.1
and stops at the end, also on failure.  Takes about a minute on 2 cores.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CONF = ROOT / "docker" / "nginx.conf"

#: Seconds a replica may take to answer /liveness: a first start compiles the closed
#: form's kernels (15-30 s on 2 idle cores, minutes on busy ones).
START_TIMEOUT = 240.0

TOP = """\
daemon off;
worker_processes 1;
pid {d}/nginx.pid;
error_log {d}/error.log notice;
events {{ worker_connections 1024; }}
http {{
    access_log {d}/access.log;
    client_body_temp_path {d}/tmp/body;
    proxy_temp_path {d}/tmp/proxy;
    fastcgi_temp_path {d}/tmp/fastcgi;
    uwsgi_temp_path {d}/tmp/uwsgi;
    scgi_temp_path {d}/tmp/scgi;
    include {d}/explorer.conf;
}}
"""


def nginx_exe() -> str | None:
    for cand in (shutil.which("nginx"), "/usr/sbin/nginx"):
        if cand and os.access(cand, os.X_OK):
            return cand
    return None


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def render(template: str, **values: str) -> str:
    """envsubst as the nginx image runs it: only the named variables are replaced."""
    out = template
    for k, v in values.items():
        out = out.replace("${" + k + "}", v)
    left = [m for m in re.findall(r"\$\{(\w+)\}", out)]
    if left:
        raise KeyError(f"template variables not given: {left}")
    return out


def wait_http(url: str, timeout: float = 90.0, proc: subprocess.Popen | None = None) -> None:
    end = time.monotonic() + timeout
    while True:
        try:
            with urllib.request.urlopen(url, timeout=5) as r:
                if r.status == 200:
                    return
        except (OSError, urllib.error.URLError):
            pass
        if proc is not None and proc.poll() is not None:
            raise RuntimeError(f"process {proc.args} exited with {proc.returncode}")
        if time.monotonic() > end:
            raise TimeoutError(f"{url} did not answer within {timeout:g} s")
        time.sleep(0.25)


@dataclass
class Replica:
    port: int
    proc: subprocess.Popen

    @property
    def addr(self) -> str:
        return f"127.0.0.1:{self.port}"


class Stack:
    """N app.serve replicas and nginx with docker/nginx.conf, all on 127.0.0.1."""

    def __init__(self, n: int = 2, procs: int = 1, workdir: str | None = None,
                 python: str = sys.executable, class_size: int | None = None) -> None:
        """`class_size`: the replicas' ``--class-size`` (default theirs); nginx's limits
        are docker/nginx.conf's whatever it is."""
        self.n, self.procs, self.python = n, procs, python
        self.class_size = class_size
        self.dir = Path(workdir or tempfile.mkdtemp(prefix="explorer-replicas-"))
        self.replicas: list[Replica] = []
        self.nginx: subprocess.Popen | None = None
        self.port = 0
        self.nginx_version = ""

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def start(self) -> Stack:
        exe = nginx_exe()
        if exe is None:
            raise FileNotFoundError("nginx is not installed (make nginx)")
        self.nginx_version = subprocess.run([exe, "-v"], capture_output=True, text=True,
                                            check=False).stderr.strip().split("/")[-1]
        try:
            self.port = free_port()
            origins = [f"127.0.0.1:{self.port}", f"localhost:{self.port}"]
            for i in range(self.n):
                port = free_port()
                log = open(self.dir / f"replica{i + 1}.log", "wb")
                cmd = [self.python, "-m", "app.serve", "--address", "127.0.0.1",
                       "--port", str(port), "--num-procs", str(self.procs),
                       "--behind-proxy"]
                if self.class_size:
                    cmd += ["--class-size", str(self.class_size)]
                for o in origins:
                    cmd += ["--allow-websocket-origin", o]
                proc = subprocess.Popen(cmd, cwd=ROOT, stdout=log, stderr=subprocess.STDOUT,
                                        start_new_session=True)
                self.replicas.append(Replica(port, proc))
            for r in self.replicas:
                wait_http(f"http://{r.addr}/liveness", START_TIMEOUT, proc=r.proc)
            servers = " ".join(f"server {r.addr};" for r in self.replicas)
            conf = render(CONF.read_text(), LISTEN=f"127.0.0.1:{self.port}",
                          UPSTREAM_SERVERS=servers)
            (self.dir / "explorer.conf").write_text(conf)
            (self.dir / "tmp").mkdir(exist_ok=True)
            os.chmod(self.dir, 0o755)
            os.chmod(self.dir / "tmp", 0o777)
            (self.dir / "nginx.conf").write_text(TOP.format(d=self.dir))
            test = subprocess.run([exe, "-t", "-c", str(self.dir / "nginx.conf")],
                                  capture_output=True, text=True, check=False)
            if test.returncode != 0:
                raise RuntimeError(f"nginx -t failed:\n{test.stderr}")
            out = open(self.dir / "nginx.out", "wb")
            self.nginx = subprocess.Popen([exe, "-c", str(self.dir / "nginx.conf")],
                                          stdout=out, stderr=subprocess.STDOUT,
                                          start_new_session=True)
            wait_http(f"{self.url}/liveness", 30, proc=self.nginx)
        except BaseException:
            self.stop()
            raise
        return self

    def kill(self, i: int) -> None:
        """SIGKILL replica i and all its processes."""
        r = self.replicas[i]
        if r.proc.poll() is None:
            os.killpg(r.proc.pid, signal.SIGKILL)
            r.proc.wait(10)

    def stop(self) -> None:
        procs = [r.proc for r in self.replicas]
        if self.nginx is not None:
            procs.insert(0, self.nginx)
        for p in procs:
            if p.poll() is None:
                try:
                    os.killpg(p.pid, signal.SIGTERM)
                except ProcessLookupError:
                    pass
        for p in procs:
            try:
                p.wait(15)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait(5)

    def access_log(self) -> list[dict[str, str]]:
        """nginx's access log (the `explorer` format): status, request, route, upstream."""
        pat = re.compile(r'^\S+ (?P<status>\d+) "(?P<request>[^"]*)" route=(?P<route>\S*) '
                         r"upstream=(?P<upstream>\S*)")
        out = []
        for path in (self.dir / "nginx.out",):
            if path.exists():
                for line in path.read_text(errors="replace").splitlines():
                    m = pat.match(line)
                    if m:
                        out.append(m.groupdict())
        return out


# ---------------------------------------------------------------- the smoke test


def _client():
    """The browser's side of Bokeh's protocol (docker/browser_client.py)."""
    if str(ROOT) not in sys.path:  # (run as `python docker/replicas.py`)
        sys.path.insert(0, str(ROOT))
    from docker import browser_client

    return browser_client


def log(msg: str) -> None:
    print(f"[replicas] {msg}", file=sys.stderr, flush=True)


async def _session(url: str, http, cookie: str | None = None):
    bc = _client()
    s = bc.Session(url, http, timeout=10.0, slider=None)
    if cookie:
        s.cookies["explorer_route"] = cookie
    await s.open()
    return s


async def _moved(s, timeout: float = 15.0) -> float:
    """Move ψ once; seconds until the plots' update, or raise."""
    bc = _client()
    s.stats = bc.Stats()
    await s.move()
    end = time.monotonic() + timeout
    while s.pending and s.alive and time.monotonic() < end:
        await asyncio.sleep(0.02)
    stats, s.stats = s.stats, None
    if not stats.latencies:
        raise AssertionError(f"no update after a move (alive={s.alive}, errors={stats.errors})")
    return stats.latencies[0]


def _ws_status(base: str, origin: str) -> int:
    """HTTP status of a websocket handshake on /main/ws from `origin`, through `base`."""
    import http.client

    with urllib.request.urlopen(base + "/main", timeout=60) as r:
        page = r.read().decode()
        cookie = (r.headers.get("Set-Cookie") or "").split(";")[0]
    token = _client().TOKEN.search(page).group(1)
    host, port = base.split("//")[1].split(":")
    conn = http.client.HTTPConnection(host, int(port), timeout=10)
    conn.request("GET", "/main/ws", headers={
        "Connection": "Upgrade", "Upgrade": "websocket", "Sec-WebSocket-Version": "13",
        "Sec-WebSocket-Key": "x3JJHMbDL1EzLkh9GBhXDw==", "Origin": origin,
        "Sec-WebSocket-Protocol": f"bokeh, {token}", "Cookie": cookie})
    status = conn.getresponse().status
    conn.close()
    return status


async def smoke_async(stack: Stack) -> dict:
    from tornado.httpclient import AsyncHTTPClient

    url = stack.url + "/main"
    http = AsyncHTTPClient()
    upstreams = {r.addr for r in stack.replicas}
    sessions = []
    result: dict = {}
    try:
        # 1. sessions until every replica holds some
        route_of: dict[str, str] = {}
        for _ in range(24):
            s = await _session(url, http)
            await _moved(s)
            sessions.append(s)
            route_of.clear()
            for e in stack.access_log():
                if e["request"].startswith("GET /main "):
                    route_of[e["route"]] = e["upstream"]
            held = {route_of.get(x.cookies.get("explorer_route")) for x in sessions}
            if len(sessions) >= 6 and upstreams <= held:
                break
        per_replica = {a: sum(route_of.get(x.cookies.get("explorer_route")) == a
                              for x in sessions) for a in sorted(upstreams)}
        log(f"{len(sessions)} sessions through {stack.url}, per replica: {per_replica}")
        if not all(per_replica.values()):
            raise AssertionError(f"a replica got no session: {per_replica}")
        result["sessions_per_replica"] = per_replica

        # 3. foreign origin refused through the balancer, own origin accepted
        bad = _ws_status(stack.url, "http://evil.example")
        own = _ws_status(stack.url, stack.url)
        if (bad, own) != (403, 101):
            raise AssertionError(f"websocket through nginx: foreign origin {bad}, own {own}")
        log("through nginx: foreign websocket origin 403, own origin 101")

        # 4. kill the replica of the first session
        victim_addr = route_of[sessions[0].cookies["explorer_route"]]
        victim = next(i for i, r in enumerate(stack.replicas) if r.addr == victim_addr)
        on_victim = [s for s in sessions if route_of[s.cookies["explorer_route"]] == victim_addr]
        others = [s for s in sessions if s not in on_victim]
        stack.kill(victim)
        log(f"killed replica {victim + 1} ({victim_addr}, {len(on_victim)} sessions)")
        end = time.monotonic() + 10
        while any(s.alive for s in on_victim) and time.monotonic() < end:
            await asyncio.sleep(0.1)
        if any(s.alive for s in on_victim):
            raise AssertionError("sessions of the killed replica still look connected")
        for s in others:
            await _moved(s)
        log(f"{len(others)} sessions of the surviving replica still answer")
        fresh = []
        for i in range(6):
            cookie = on_victim[0].cookies["explorer_route"] if i < 2 else None
            s = await _session(url, http, cookie)
            await _moved(s)
            fresh.append(s)
        sessions += fresh
        log("6 new sessions (2 with the dead replica's cookie) opened and answered")
        result["after_kill"] = {"killed": victim_addr, "new_sessions_ok": len(fresh),
                                "surviving_sessions_ok": len(others)}
    finally:
        for s in sessions:
            s.close()
        http.close()
    await asyncio.sleep(1.0)  # websockets are logged when they close

    # 2. sticky: each route's page and websocket went to one replica
    by_route: dict[str, set[str]] = {}
    kinds: dict[str, set[str]] = {}
    for e in stack.access_log():
        path = e["request"].split(" ")[1] if " " in e["request"] else ""
        if path in ("/main", "/main/ws"):
            # a request retried after the kill lists two upstreams ("a, b"): the last served
            up = e["upstream"].split(",")[-1].strip()
            by_route.setdefault(e["route"], set()).add(up)
            kinds.setdefault(e["route"], set()).add(path)
    before = [x.cookies["explorer_route"] for x in sessions[: len(sessions) - 6]]
    for route in before:
        if kinds.get(route) != {"/main", "/main/ws"}:
            raise AssertionError(f"route {route}: requests seen {kinds.get(route)}")
        if len(by_route[route]) != 1:
            raise AssertionError(f"route {route} went to several replicas: {by_route[route]}")
    log(f"sticky: for each of {len(before)} sessions, GET /main and /main/ws hit one replica")
    result["sticky_sessions_checked"] = len(before)
    return result


def smoke(n: int = 2) -> dict:
    stack = Stack(n=n).start()
    log(f"nginx {stack.nginx_version} on {stack.url}, replicas "
        f"{', '.join(r.addr for r in stack.replicas)} (files in {stack.dir})")
    try:
        return asyncio.run(smoke_async(stack))
    finally:
        stack.stop()


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("command", choices=["smoke", "serve"])
    p.add_argument("--replicas", type=int, default=2)
    p.add_argument("--procs", type=int, default=1, help="--num-procs of each replica")
    args = p.parse_args(argv)
    if nginx_exe() is None:
        log("nginx is not installed: `make nginx` (Debian's package)")
        return 2
    t = time.monotonic()
    if args.command == "smoke":
        smoke(args.replicas)
        log(f"PASS in {time.monotonic() - t:.0f} s")
        return 0
    stack = Stack(n=args.replicas, procs=args.procs).start()
    print(f"{stack.url}/main  (replicas {', '.join(r.addr for r in stack.replicas)}, "
          f"pids {', '.join(str(r.proc.pid) for r in stack.replicas)}; Ctrl-C stops)",
          flush=True)
    try:
        signal.sigwait({signal.SIGINT, signal.SIGTERM})
    finally:
        stack.stop()
    return 0


if __name__ == "__main__":
    sys.exit(main())
