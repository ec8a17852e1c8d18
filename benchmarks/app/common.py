"""What the app's benchmarks share: servers started and stopped, git revisions checked
out, the server's processes measured, a percentile, the machine's yardstick and the
browser (Debian's Chromium through Playwright, never downloaded).

Every benchmark serves the explorer with ``python -m app.serve`` (`serve`, or
`explorer_server` for one or more git revisions, unless EXPLORER_URL names a running
server); nothing here is imported from the tests (tests/app/explorer_browser.py is the
browser tests' own).
"""

from __future__ import annotations

import contextlib
import ipaddress
import math
import os
import shutil
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from urllib.parse import urlsplit

#: The repository's root (the benchmarks run from there: ``python -m benchmarks.app.NAME``).
ROOT = Path(__file__).resolve().parents[2]

#: The ``--class-size`` of a server started to measure capacity, memory or page loads:
#: every simulated visitor comes from 127.0.0.1, one address, whose page loads and
#: builds the server would otherwise limit as a class's (`app.page.bucket.CLASS_SIZE`).
#: The abuse mode keeps the default: those limits are what it tests.
AUDIENCE = 100_000

# ---------------------------------------------------------------- servers


def free_port() -> int:
    """A TCP port nobody listens on right now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for_http(url: str, timeout: float = 60.0) -> None:
    """Poll `url` until it answers 200; TimeoutError after `timeout` s."""
    deadline = time.monotonic() + timeout
    while True:
        try:
            with urllib.request.urlopen(url, timeout=5) as r:
                if r.status == 200:
                    return
        except OSError:
            pass
        if time.monotonic() > deadline:
            raise TimeoutError(f"waited {timeout} s for {url} to answer 200")
        time.sleep(0.3)


def serve(procs: int, log: Path | None = None,
          class_size: int | None = None) -> tuple[subprocess.Popen, str]:
    """Start `python -m app.serve --num-procs procs` on a free loopback port (its output
    to the file `log`, if given; with `--class-size class_size`, if given); the process
    (its own process group: `stop`) and the explorer's URL."""
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
    wait_for_http(f"http://127.0.0.1:{port}/liveness")
    return proc, f"http://127.0.0.1:{port}/main"


def stop(proc: subprocess.Popen) -> None:
    """Stop a server `serve` started (SIGTERM to its process group, SIGKILL after 15 s)."""
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(15)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(5)


@contextlib.contextmanager
def explorer_server(root: Path | None = None, timeout: float = 60.0) -> Iterator[str]:
    """Yield the explorer's URL: EXPLORER_URL if set (and `root` not given), else a fresh
    `python -m app.serve` of the checkout at `root` (default: this one), which must
    answer within `timeout` s (a fresh checkout compiles the kernels first)."""
    url = os.environ.get("EXPLORER_URL")
    if url and root is None:
        yield url.rstrip("/")
        return
    port = free_port()
    log = tempfile.TemporaryFile("w+")
    proc = subprocess.Popen([sys.executable, "-m", "app.serve", "--port", str(port)],
                            cwd=root or ROOT, stdout=log, stderr=subprocess.STDOUT)
    try:
        try:
            wait_for_http(f"http://127.0.0.1:{port}/liveness", timeout)
        except TimeoutError as err:
            log.seek(0)
            raise TimeoutError(f"{err}; the server said:\n{log.read()[-3000:]}") from err
        yield f"http://127.0.0.1:{port}/main"
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
        log.close()


@contextlib.contextmanager
def worktree(rev: str) -> Iterator[Path]:
    """A checkout of git revision `rev` in a temporary directory (removed afterwards)."""
    with tempfile.TemporaryDirectory(prefix="ab-") as tmp:
        path = Path(tmp) / "tree"
        subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach", str(path), rev],
                       check=True, capture_output=True)
        try:
            yield path
        finally:
            subprocess.run(["git", "-C", str(ROOT), "worktree", "remove", "--force", str(path)],
                           check=False, capture_output=True)


def loopback_only(url: str) -> None:
    """SystemExit unless `url`'s host is a loopback address (the load tests load nothing
    else)."""
    host = urlsplit(url).hostname or ""
    try:
        ok = host == "localhost" or ipaddress.ip_address(host).is_loopback
    except ValueError:
        ok = False
    if not ok:
        raise SystemExit(f"refusing to load {host!r}: this test targets loopback addresses only")


# ---------------------------------------------------------------- processes


def server_pid(url: str) -> int:
    """The pid of the process listening on `url`'s port."""
    import psutil

    port = urlsplit(url).port
    for c in psutil.net_connections("tcp"):
        if c.laddr and c.laddr.port == port and c.status == "LISTEN" and c.pid:
            return c.pid
    raise LookupError(f"no process listens on port {port}")


def cpu_s(pid: int) -> float:
    """CPU seconds (user + system) of process `pid` so far."""
    import psutil

    t = psutil.Process(pid).cpu_times()
    return t.user + t.system


def process_tree(pids: list[int]) -> list:
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


# ---------------------------------------------------------------- figures


def pct(values: list[float], q: float) -> float:
    """The `q`-th percentile of `values` (NaN for none; inclusive method)."""
    if not values:
        return float("nan")
    if len(values) == 1:
        return values[0]
    return statistics.quantiles(values, n=100, method="inclusive")[round(q) - 1]


def yardstick_us() -> float:
    """Microseconds of one closed-form contact (``closed_form_time(Contact, 0.4, pi/6)``,
    best of 5): the machine's speed at the time, printed before and after a run so that
    a slow run can be told from a slow machine."""
    from core import Contact
    from core.numerics.metrics import closed_form_time

    return 1e6 * min(closed_form_time(Contact, 0.4, math.pi / 6) for _ in range(5))


# ---------------------------------------------------------------- the browser

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu",
                 "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--no-first-run"]


def chromium_path() -> str | None:
    """Path of Debian's Chromium, installing it with apt-get if missing and possible."""
    if Path(CHROMIUM).exists():
        return CHROMIUM
    if shutil.which("apt-get") and os.geteuid() == 0:
        with contextlib.suppress(subprocess.SubprocessError, OSError):
            subprocess.run(["apt-get", "update", "-qq"], check=True, timeout=300,
                           capture_output=True)
            subprocess.run(["apt-get", "install", "-y", "-qq", "chromium"], check=True,
                           timeout=900, capture_output=True)
    return CHROMIUM if Path(CHROMIUM).exists() else None


#: JavaScript: defines window.__col(name, col), a data column of the named model;
#: window.__views(keep), every BokehJS view of the page that `keep` accepts;
#: window.__renderers(), every glyph renderer view.
JS_HELPERS = """() => {
  window.__col = (name, col) => {
    const m = window.Bokeh.documents[0].get_model_by_name(name);
    if (!m) return null;
    const v = m.data instanceof Map ? m.data.get(col) : m.data[col];
    return v == null ? null : Array.from(v);
  };
  window.__views = (keep) => {
    const views = [];
    const walk = (v) => {
      if (keep(v)) views.push(v);
      for (const c of v.children()) walk(c);
    };
    Object.values(window.Bokeh.index).forEach(walk);
    return views;
  };
  window.__renderers = () => window.__views(
    (v) => v.model != null && v.model.type === "GlyphRenderer");
}"""

#: JavaScript: true once the explorer's sources exist and hold data.
JS_READY = """() => {
  const d = window.Bokeh && window.Bokeh.documents && window.Bokeh.documents[0];
  if (!d) return false;
  const m = d.get_model_by_name('force');
  if (!m) return false;
  const t = m.data instanceof Map ? m.data.get('T') : m.data['T'];
  return t && t.length > 0;
}"""


def open_explorer(browser, url: str, width: int = 1600, height: int = 1400):
    """A page of `browser` (Playwright's) showing the explorer at `url` once its data
    arrived, with `JS_HELPERS` defined, and its console log from then on."""
    page = browser.new_page(viewport={"width": width, "height": height})
    console: list[str] = []
    page.on("console", lambda m: console.append(f"{m.type}: {m.text}"))
    page.on("pageerror", lambda e: console.append(f"pageerror: {e}"))
    page.goto(url)
    page.wait_for_function(JS_READY, timeout=60_000)
    page.evaluate(JS_HELPERS)
    return page, console
