"""Load test of the explorer server: N browser-like sessions, each moving the ψ slider.

Each simulated user speaks Bokeh's websocket protocol, as BokehJS does in a browser:

1. ``GET /main`` (the server builds the session's document; cookies are kept, so a
   balancer's sticky cookie is honoured), the session token is read from the page;
2. the websocket ``/main/ws`` with that token and the page's own ``Origin``; after the
   server's ``ACK`` it sends ``PULL-DOC-REQ`` and finds, in the document it gets, the ψ
   slider's model and the ``ColumnDataSource`` named ``force``; then it sends the
   ``document_ready`` event, as BokehJS does once it has rendered the page (Panel treats
   a session as loaded from then on);
3. every ``--interval`` seconds (0.3 s; each session with its own random phase) it sends
   a ``PATCH-DOC`` that sets the slider's ``value`` to a new ψ, and times how long the
   server takes to send the ``PATCH-DOC`` that changes the ``force`` source's data.
   One change is in flight per session: a tick that finds the previous change still
   unanswered is skipped and counted (``late``), as a browser would merge the moves.
   A change unanswered after ``--timeout`` s, a server ``ERROR`` reply, a dropped
   connection or a failed page load counts as an error.

Levels (``--levels 10,25,50,100``) are run one after the other on the same growing set
of sessions (sessions are opened, a few at a time, before a level starts); each level
runs ``--warmup`` s unrecorded, then ``--duration`` s recorded.  Per level it reports
p50/p95/max latency, the changes answered, the messages per answered change (the
server's PATCH-DOCs while a change was in flight), late ticks, errors, the server's resident
memory (RSS, all its processes) and its CPU use (in % of one core, over the recorded
window), and the load client's own CPU (it shares the machine's cores with the server).
Per serving process (`load_figures`: each replica, or each forked ``--num-procs``
child) it reports the CPU over the window, the busiest over their mean (target 1.3x)
and its sessions (from the balancer's log, or the process's websockets); the server's
CPU per answered move in ms and in closed-form contacts (the yardstick of
benchmarks/app/page_load.py, read after each level), and the machine's load average.
At the end: the sizing rule, the most sessions per serving process (one core each)
whose p95 stays within 200 ms.

Bounded: at most ``--max-sessions`` (200) sessions, every level ends after its
duration, every wait has a timeout, and the target must be a loopback address.

    # a server started here (python -m app.serve, 2 processes = one per core):
    python benchmarks/app/load_test.py --serve 2
    # any running server or balancer on this machine, its processes found by port:
    python benchmarks/app/load_test.py --url http://127.0.0.1:8080/main --pids 1234,1240
    # two replicas behind nginx (docker/replicas.py), everything started and stopped here
    # (make load-test):
    python benchmarks/app/load_test.py --replicas 2

Abuse (``--abuse [KIND ...]``, issue 22; benchmarks/app/abuse.py): one probe session moving ψ every
``--interval`` s; per kind a ``--window`` alone, then one beside a single abusive client
of that kind (`ABUSE_KINDS`: a page-load loop, websockets with invented session ids,
PULL-DOC spam, the Methods card at 16x with live recompute, NaN as ψ), interleaved in one
run against one server (``--serve 1`` unless given).  Per kind: the probe's p50/p95 alone
and beside, their p95 ratio against the 1.5x target, moves answered, the server's CPU and
the lines it logged (its output goes to a file):

    python benchmarks/app/load_test.py --abuse --window 30
    python benchmarks/app/load_test.py --abuse pull-doc nan --window 20

Results: a table on stdout, and ``--json FILE`` for the raw figures.
"""

from __future__ import annotations

import argparse
import asyncio
import ipaddress
import json
import os
import random
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from http.cookies import SimpleCookie
from pathlib import Path
from urllib.parse import urlsplit

from tornado.httpclient import AsyncHTTPClient, HTTPRequest
from tornado.websocket import WebSocketClosedError, websocket_connect

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "app"))

from explorer_browser import free_port  # noqa: E402
from explorer_browser import wait_for_http as wait_http  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import load_figures  # noqa: E402

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


def _strings(obj) -> list[str]:
    if isinstance(obj, str):
        return [obj]
    if isinstance(obj, dict):
        return [s for v in obj.values() for s in _strings(v)]
    if isinstance(obj, list):
        return [s for v in obj for s in _strings(v)]
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
                texts = [s for j in inside if j != i for s in _strings(attrs(j))]
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
    latencies: list[float] = field(default_factory=list)  # seconds
    sent: int = 0
    late: int = 0
    messages: int = 0  # PATCH-DOC messages received while a change was in flight
    errors: dict[str, int] = field(default_factory=dict)

    def error(self, kind: str) -> None:
        self.errors[kind] = self.errors.get(kind, 0) + 1


class Session:
    """One simulated browser tab."""

    def __init__(self, url: str, http: AsyncHTTPClient, timeout: float, slider: str | None):
        self.url, self.http, self.timeout, self.slider_name = url, http, timeout, slider
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
                                  raise_error=False)
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
        await self._send("PATCH-DOC", {"events": [DOCUMENT_READY]})
        self.doc = {"pulled": pulled, "filled": []}
        try:  # a server that builds the explorer for the page's HTML (before 54858cc)
            find_targets(pulled, self.slider_name)
            shells = []
        except LookupError:
            pass
        while shells:
            header, content = await asyncio.wait_for(self._read(), 120)
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
                          request_timeout=60, connect_timeout=30)
        self.conn = await websocket_connect(req, max_message_size=64 << 20)
        header, _ = await asyncio.wait_for(self._read(), 60)
        if header.get("msgtype") != "ACK":
            raise ConnectionError(f"expected ACK, got {header.get('msgtype')}")

    async def pull(self, token: str) -> str:
        """Open the websocket of the session `token` names (from the page, or made up: the
        server then builds the session for the websocket alone) and pull its document:
        the PULL-DOC-REPLY's content."""
        await self.connect(token)
        await self._send("PULL-DOC-REQ", {})
        for _ in range(100):  # the server may send patches (e.g. the URL) before the reply
            header, content = await asyncio.wait_for(self._read(), 60)
            if header.get("msgtype") == "PULL-DOC-REPLY":
                return content
        raise ConnectionError("no PULL-DOC-REPLY")

    async def _read(self) -> tuple[dict, str]:
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

    async def _send(self, msgtype: str, content: dict) -> str:
        self._n += 1
        msgid = f"lt{self._n}"
        for frame in ({"msgid": msgid, "msgtype": msgtype}, {}, content):
            await self.conn.write_message(json.dumps(frame))
        return msgid

    async def _read_loop(self) -> None:
        try:
            while True:
                header, content = await self._read()
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
            await self._send("PATCH-DOC", {"events": [event]})
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


# ---------------------------------------------------------------- server metrics


def process_tree(pids: list[int]):
    """psutil processes of `pids` and all their descendants (e.g. --num-procs children)."""
    import psutil

    procs = {}
    for pid in pids:
        try:
            p = psutil.Process(pid)
        except psutil.NoSuchProcess:
            continue
        for q in [p, *p.children(recursive=True)]:
            procs[q.pid] = q
    return list(procs.values())


def usage(pids: list[int]) -> tuple[float, dict[int, float]]:
    """(RSS in MiB summed, {pid: CPU seconds user+system}) over the processes' trees."""
    import psutil

    rss, cpu = 0.0, {}
    for p in process_tree(pids):
        try:
            rss += p.memory_info().rss / 2**20
            t = p.cpu_times()
            cpu[p.pid] = t.user + t.system
        except psutil.NoSuchProcess:
            pass
    return rss, cpu


# ---------------------------------------------------------------- a run


def pct(values: list[float], q: float) -> float:
    if not values:
        return float("nan")
    if len(values) == 1:
        return values[0]
    return statistics.quantiles(values, n=100, method="inclusive")[round(q) - 1]


async def run_levels(url: str, levels: list[int], duration: float, warmup: float,
                     interval: float, timeout: float, pids: list[int], slider: str | None,
                     open_concurrency: int = 4, serving: list[int] | None = None,
                     placement=None) -> list[dict]:
    """The levels one after the other; a row of figures per level.  `serving`: the
    server processes whose CPU is compared (default: `load_figures.serving_pids`);
    `placement(live sessions, serving)`: sessions per serving process."""
    AsyncHTTPClient.configure(None, max_clients=max(levels) + 10)
    serving = serving or (load_figures.serving_pids(pids) if pids else [])
    http = AsyncHTTPClient()
    sessions: list[Session] = []
    results = []
    try:
        for n in levels:
            stats = Stats()
            t_open = time.perf_counter()
            sem = asyncio.Semaphore(open_concurrency)

            async def opened(s: Session, sem=sem, stats=stats) -> Session | None:
                async with sem:
                    try:
                        await asyncio.wait_for(s.open(), 120)
                        return s
                    except Exception as err:  # counted, reported
                        stats.error(f"session open failed: {type(err).__name__}: {err}"[:120])
                        s.close()
                        return None

            new = [Session(url, http, timeout, slider) for _ in range(n - len(sessions))]
            sessions += [s for s in await asyncio.gather(*map(opened, new)) if s]
            open_s = time.perf_counter() - t_open
            live = [s for s in sessions if s.alive]
            print(f"[load] {len(live)} sessions open ({len(new)} new in {open_s:.1f} s); "
                  f"warm-up {warmup:g} s, then {duration:g} s recorded", file=sys.stderr)

            async def ticker(s: Session, until: float) -> None:
                next_t = time.perf_counter() + random.uniform(0, interval)
                while next_t < until:
                    await asyncio.sleep(max(0.0, next_t - time.perf_counter()))
                    await s.move()
                    next_t += interval

            t0 = time.perf_counter()
            await asyncio.gather(*(ticker(s, t0 + warmup) for s in live))
            for s in live:
                s.stats = stats
            rss0, cpu0 = usage(pids)
            me0 = time.process_time()
            t1 = time.perf_counter()
            await asyncio.gather(*(ticker(s, t1 + duration) for s in live))
            # changes still in flight get their timeout to be answered
            end = time.perf_counter() + timeout
            while any(s.pending and s.alive for s in live) and time.perf_counter() < end:
                await asyncio.sleep(0.05)
            wall = max(time.perf_counter() - t1, 1e-3)
            rss1, cpu1 = usage(pids)
            me = time.process_time() - me0
            load = load_figures.load_average()
            placed = placement(live, serving) if placement and serving else None
            for s in live:
                if s.pending and s.alive:
                    stats.error(f"no update within {timeout:g} s")
                s.stats = None
                s.pending = None
            lat = sorted(x * 1e3 for x in stats.latencies)
            row = {
                "sessions": n, "open": len(live), "duration_s": round(wall, 1),
                "changes_sent": stats.sent, "updates": len(lat), "late_ticks": stats.late,
                "errors": sum(stats.errors.values()), "error_kinds": stats.errors,
                "p50_ms": round(pct(lat, 50), 1), "p95_ms": round(pct(lat, 95), 1),
                "max_ms": round(lat[-1], 1) if lat else float("nan"),
                "updates_per_s": round(len(lat) / wall, 1),
                # messages the server sent per answered change (1: all it changes in one)
                "messages_per_update": round(stats.messages / len(lat), 2) if lat else None,
                "server_rss_mib": round(rss1, 0), "server_rss_before_mib": round(rss0, 0),
                "server_cpu_pct": round(100 * (sum(cpu1.values()) - sum(cpu0.values())) / wall)
                if pids else None,
                # per process (a parent that only forks --num-procs children shows ~0)
                "server_cpu_pct_per_process": sorted(
                    (round(100 * (c - cpu0.get(pid, 0.0)) / wall) for pid, c in cpu1.items()),
                    reverse=True),
                "client_cpu_pct": round(100 * me / wall, 0),
                "session_open_s": round(open_s, 1),
                # each serving process's CPU % (in the order of `serving`), max / mean
                "cpu_spread": load_figures.cpu_spread(cpu0, cpu1, wall, serving),
                "sessions_per_process": placed,
                "load_average": load,
                "yardstick_us": round(load_figures.yardstick_us(), 1),
            }
            row.update(load_figures.per_move(sum(cpu1.values()) - sum(cpu0.values()),
                                             len(lat), row["yardstick_us"]) if pids else {})
            results.append(row)
            print(f"[load] {json.dumps(row)}", file=sys.stderr)
    finally:
        for s in sessions:
            s.close()
        http.close()
    return results


# ---------------------------------------------------------------- servers to test


#: The ``--class-size`` of a server started to measure capacity, memory or page loads:
#: every simulated visitor comes from 127.0.0.1, one address, whose page loads and
#: builds the server would otherwise limit as a class's (`app.page.bucket.CLASS_SIZE`).
#: The abuse mode keeps the default: those limits are what it tests.
AUDIENCE = 100_000


def serve(procs: int, log: Path | None = None,
          class_size: int | None = None) -> tuple[subprocess.Popen, str]:
    """Start `python -m app.serve --num-procs procs` on a free loopback port (its output
    to the file `log`, if given; with `--class-size class_size`, if given)."""
    port = free_port()
    out = open(log, "wb") if log else subprocess.DEVNULL
    sized = ["--class-size", str(class_size)] if class_size else []
    try:
        proc = subprocess.Popen(
            [sys.executable, "-m", "app.serve", "--port", str(port), "--num-procs", str(procs),
             *sized],
            cwd=ROOT, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
    finally:
        if log:
            out.close()
    wait_http(f"http://127.0.0.1:{port}/liveness")
    return proc, f"http://127.0.0.1:{port}/main"


def stop(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(15)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(5)


def loopback_only(url: str) -> None:
    host = urlsplit(url).hostname or ""
    try:
        ok = host == "localhost" or ipaddress.ip_address(host).is_loopback
    except ValueError:
        ok = False
    if not ok:
        raise SystemExit(f"refusing to load {host!r}: this test targets loopback addresses only")


def table(results: list[dict]) -> str:
    """The levels as a Markdown table (rows as `run_levels` gives them)."""
    head = ("| sessions | p50 ms | p95 ms | max ms | updates/s | messages/update "
            "| late ticks | errors | server RSS MiB | server CPU % | CPU % per process "
            "| max/mean | sessions per process | CPU ms per move | = contacts "
            "| client CPU % | load avg |")
    lines = [head, "|" + " --- |" * 17]
    for r in results:
        spread = r.get("cpu_spread") or {}
        placed = r.get("sessions_per_process")
        lines.append(
            f"| {r['sessions']} | {r['p50_ms']} | {r['p95_ms']} | {r['max_ms']} "
            f"| {r['updates_per_s']} | {r['messages_per_update']} "
            f"| {r['late_ticks']} | {r['errors']} "
            f"| {r['server_rss_mib']:.0f} | {r['server_cpu_pct']} "
            f"| {' / '.join(map(str, spread.get('cpu_pct', []))) or '-'} "
            f"| {spread.get('max_over_mean') or '-'} "
            f"| {' / '.join(map(str, placed)) if placed else '-'} "
            f"| {r.get('cpu_ms_per_move') or '-'} | {r.get('contacts_per_move') or '-'} "
            f"| {r['client_cpu_pct']} | {r.get('load_average', '-')} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    import abuse  # (benchmarks/app/abuse.py: the --abuse mode, which imports this module)

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    where = p.add_mutually_exclusive_group()
    where.add_argument("--url", help="the app's page on a running server or balancer "
                                     "(loopback), e.g. http://127.0.0.1:5006/main")
    where.add_argument("--serve", type=int, metavar="PROCS",
                       help="start python -m app.serve --num-procs PROCS here and test it")
    where.add_argument("--replicas", type=int, metavar="N",
                       help="start N replicas behind nginx (docker/replicas.py) and test "
                            "through the balancer")
    p.add_argument("--procs", type=int, default=1,
                   help="with --replicas: --num-procs of each replica (default 1)")
    p.add_argument("--pids", default="", help="comma-separated server pids (with --url) "
                   "whose process trees' RSS and CPU are reported")
    p.add_argument("--levels", default="10,25,50,100")
    p.add_argument("--duration", type=float, default=30.0, help="recorded seconds per level")
    p.add_argument("--warmup", type=float, default=5.0, help="unrecorded seconds per level")
    p.add_argument("--interval", type=float, default=0.3, help="seconds between moves")
    p.add_argument("--timeout", type=float, default=5.0, help="seconds before a change "
                   "without its update counts as an error")
    p.add_argument("--slider", default=None, help="name of the ψ Slider model (default: "
                   "the one named 'psi', else found by its 'ψ' label)")
    p.add_argument("--max-sessions", type=int, default=200)
    p.add_argument("--json", type=Path, help="write the results here")
    p.add_argument("--abuse", nargs="*", choices=abuse.ABUSE_KINDS, metavar="KIND",
                   help="instead of levels: one probe session moving ψ, per KIND (default "
                        f"all: {', '.join(abuse.ABUSE_KINDS)}) a window alone, then one beside an "
                        "abusive client of that kind (with --serve, default --serve 1)")
    p.add_argument("--window", type=float, default=20.0,
                   help="with --abuse: recorded seconds per window")
    args = p.parse_args(argv)
    if args.abuse is not None:
        if args.replicas is not None:
            p.error("--abuse runs against one server (--serve or --url)")
        if args.serve is None and args.url is None:
            args.serve = 1
        kinds = [k for k in abuse.ABUSE_KINDS if k in (args.abuse or abuse.ABUSE_KINDS)]
    levels = sorted({int(x) for x in args.levels.split(",") if x.strip()})
    if not levels or levels[0] < 1 or levels[-1] > args.max_sessions:
        p.error(f"levels must be between 1 and --max-sessions ({args.max_sessions})")

    # SIGTERM stops the run as Ctrl-C does: the servers started here are stopped too
    # (a background job of a non-interactive shell ignores SIGINT)
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    started = None
    stack = None
    serving = placement = None
    pids = [int(x) for x in args.pids.split(",") if x.strip()]
    log = None
    # (the servers started here: the abuse mode tests the default per-address limits)
    class_size = None if args.abuse is not None else AUDIENCE
    sized = f" --class-size {class_size}" if class_size else ""
    if args.serve is not None:
        if args.abuse is not None:  # its log lines are counted per window
            log = Path(tempfile.mkdtemp(prefix="load-test-")) / "server.log"
        started, url = serve(args.serve, log, class_size)
        pids = [started.pid]
        setup = f"python -m app.serve --num-procs {args.serve}{sized}"
    elif args.replicas is not None:
        sys.path.insert(0, str(ROOT / "docker"))
        import replicas  # docker/replicas.py

        stack = replicas.Stack(n=args.replicas, procs=args.procs,
                               class_size=class_size).start()
        url = stack.url + "/main"
        pids = [r.proc.pid for r in stack.replicas]
        if args.procs == 1:  # each replica is one serving process: sessions from the log
            serving = pids
            placement = load_figures.replica_placement(stack)
        setup = (f"{args.replicas} x python -m app.serve --num-procs {args.procs}{sized} "
                 f"behind nginx {stack.nginx_version} (docker/nginx.conf)")
    else:
        url = args.url or "http://127.0.0.1:5006/main"
        setup = f"{url} (pids {pids or 'not given'})"
    loopback_only(url)
    if args.abuse is not None:
        try:
            print(f"[abuse] {setup}; {os.cpu_count()} CPUs; kinds {kinds}; server log {log}",
                  file=sys.stderr)
            rows = asyncio.run(abuse.run_abuse(url, kinds, args.window, args.warmup, args.interval,
                                         args.timeout, pids, log))
        finally:
            if started is not None:
                stop(started)
        print(f"setup: {setup}; {os.cpu_count()} CPUs; one probe session moving ψ every "
              f"{args.interval:g} s; per kind {args.window:g} s alone, then {args.window:g} s "
              "beside one abusive client")
        print(abuse.abuse_table(rows))
        if args.json:
            args.json.write_text(json.dumps({"setup": setup, "cpus": os.cpu_count(),
                                             "rows": rows}, indent=2) + "\n")
        return 0
    if placement is None and pids:
        placement = load_figures.process_placement(urlsplit(url).port)
    try:
        print(f"[load] {setup}; {os.cpu_count()} CPUs; levels {levels}; load average "
              f"{load_figures.load_average()}", file=sys.stderr)
        results = asyncio.run(run_levels(url, levels, args.duration, args.warmup,
                                         args.interval, args.timeout, pids, args.slider,
                                         serving=serving, placement=placement))
    finally:
        if started is not None:
            stop(started)
        if stack is not None:
            stack.stop()
    print(f"setup: {setup}; {os.cpu_count()} CPUs; a move every {args.interval:g} s per "
          f"session; {args.duration:g} s recorded per level after {args.warmup:g} s")
    print(table(results))
    processes = max((len(r["cpu_spread"]["cpu_pct"]) for r in results), default=0)
    rule = load_figures.sizing(results, processes, args.interval) if processes else None
    if rule:
        print(load_figures.sizing_text(rule, args.interval))
    if args.json:
        args.json.write_text(json.dumps({"setup": setup, "cpus": os.cpu_count(),
                                         "args": {k: str(v) for k, v in vars(args).items()},
                                         "results": results, "sizing": rule}, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
