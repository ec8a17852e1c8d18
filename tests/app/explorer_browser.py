"""Helpers shared by the browser tests and the latency benchmark.

Starts the explorer with `python -m app.serve` (unless EXPLORER_URL names a running one) and
launches Debian's Chromium through Playwright.  No browser is ever downloaded.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
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


def free_port() -> int:
    """A TCP port nobody listens on right now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_until(condition, timeout: float = 20.0, interval: float = 0.05, what: str = ""):
    """Call `condition()` every `interval` s until it returns something true, and return
    that; TimeoutError if it has not after `timeout` s (`what`: what was waited for)."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() > deadline:
            raise TimeoutError(f"waited {timeout} s for {what or condition}")
        time.sleep(interval)


def steady(read, quiet: float = 0.5, timeout: float = 20.0, interval: float = 0.1):
    """`read()` once it has returned the same value for `quiet` s (what the browser
    shows has settled); TimeoutError if it still changes after `timeout` s."""
    last = {"value": read(), "since": time.monotonic()}

    def unchanged() -> bool:
        now = read()
        if now != last["value"]:
            last.update(value=now, since=time.monotonic())
        return time.monotonic() - last["since"] >= quiet

    wait_until(unchanged, timeout, interval, what=f"{read} to stay the same for {quiet} s")
    return last["value"]


def wait_for_http(url: str, timeout: float = 60.0) -> None:
    """Poll `url` until it answers 200; TimeoutError otherwise."""
    def answers() -> bool:
        try:
            with urllib.request.urlopen(url, timeout=5) as r:
                return r.status == 200
        except OSError:
            return False

    wait_until(answers, timeout, interval=0.3, what=f"{url} to answer 200")


@contextlib.contextmanager
def explorer_server(root: Path | None = None, timeout: float = 60.0) -> Iterator[str]:
    """Yield the explorer's URL: EXPLORER_URL if set, else a fresh `python -m app.serve`
    of the checkout at `root` (default: this one), which must answer within `timeout` s
    (a fresh checkout compiles the kernels first)."""
    url = os.environ.get("EXPLORER_URL")
    if url and root is None:
        yield url.rstrip("/")
        return
    port = free_port()
    log = tempfile.TemporaryFile("w+")
    cmd = [sys.executable, "-m", "app.serve", "--port", str(port)]
    proc = subprocess.Popen(cmd, cwd=root or ROOT, stdout=log, stderr=subprocess.STDOUT)
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


#: JavaScript: defines window.__col(name, col), a data column of the named model;
#: window.__views(keep), every BokehJS view of the page that `keep` accepts;
#: window.__slider(name), the values (value, start, end, step) of ExactSlider `name`'s
#: slider: its `SliderModel`, tagged NAME-value (window.__psi(): psi's value);
#: window.__renderers(), every glyph renderer view; and window.__renderer(source,
#: glyph type), the first glyph renderer view of the named source drawing that glyph.
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
  window.__slider = (name) => [...window.Bokeh.documents[0].all_models].find(
    (m) => m.tags != null && m.tags.includes(name + "-value"));
  window.__psi = () => window.__slider("psi").value;
  window.__renderers = () => window.__views(
    (v) => v.model != null && v.model.type === "GlyphRenderer");
  window.__renderer = (source, type) => window.__renderers().find(
    (v) => v.model.data_source.name === source && v.model.glyph.type === type);
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


def column(page, name: str, col: str) -> list[float] | None:
    """Read a data column of the named ColumnDataSource in the browser."""
    return page.evaluate("([n, c]) => window.__col(n, c)", [name, col])


def open_explorer(browser, url: str, width: int = 1600, height: int = 1400):
    """A page showing the explorer at `url` (after its data arrived) and its console log."""
    return load(browser.new_page(viewport={"width": width, "height": height}), url)


def load(page, url: str):
    """`page` showing the explorer at `url` (after its data arrived), and its console log
    from then on."""
    console: list[str] = []
    page.on("console", lambda m: console.append(f"{m.type}: {m.text}"))
    page.on("pageerror", lambda e: console.append(f"pageerror: {e}"))
    page.goto(url)
    page.wait_for_function(JS_READY, timeout=60_000)
    page.evaluate(JS_HELPERS)
    return page, console
