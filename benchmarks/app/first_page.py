"""A newcomer's first page: from `python -m app.serve` to the plots drawn in Chromium.

Serves the working tree with an empty numba cache (as on a fresh machine after `make
serve`: every kernel is compiled) and measures
  (a) start -> address printed: what the server takes before it offers the page (it
      compiles the closed form first; the Methods and Motor kernels compile meanwhile in
      another process);
  (b) address printed -> first page's plots drawn: the page opened in headless Chromium
      the moment the address is printed, until its T(tau) source holds data and every
      glyph renderer of the page has been painted (two animation frames later).
Target: (b) <= 3 s on the project's 2-core machine.  For scale, (c) a second page on
the same server, from its opening to its plots drawn.  `--warm` keeps numba's cache of
this checkout (a second start).

    .venv/bin/python -m benchmarks.app.first_page [--warm] [--runs 1]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time

from benchmarks.app.common import CHROMIUM_ARGS, JS_READY, ROOT, chromium_path, free_port

#: JavaScript: resolves once the page has painted twice after its data arrived.
JS_PAINTED = "() => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))"


def first_page(warm: bool) -> tuple[float, float, float]:
    """(start -> address printed, address printed -> plots drawn, a second page's plots
    drawn on the same server, from its opening), in s."""
    from playwright.sync_api import sync_playwright

    env = dict(os.environ)
    cache = None if warm else tempfile.TemporaryDirectory()
    if cache is not None:
        env["NUMBA_CACHE_DIR"] = cache.name
    port = free_port()
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium_path(), args=CHROMIUM_ARGS)
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        started = time.perf_counter()
        proc = subprocess.Popen([sys.executable, "-m", "app.serve", "--port", str(port)],
                                cwd=ROOT, env=env, stderr=subprocess.PIPE, text=True)
        try:
            for line in proc.stderr:
                if "explorer at http" in line:
                    break
            else:
                raise RuntimeError("the server ended before it printed its address")
            address = time.perf_counter()
            page.goto(f"http://127.0.0.1:{port}/main")
            page.wait_for_function(JS_READY, timeout=120_000)
            page.evaluate(JS_PAINTED)
            drawn = time.perf_counter()
            second = browser.new_page(viewport={"width": 1280, "height": 800})
            opened = time.perf_counter()
            second.goto(f"http://127.0.0.1:{port}/main")
            second.wait_for_function(JS_READY, timeout=120_000)
            second.evaluate(JS_PAINTED)
            again = time.perf_counter() - opened
        finally:
            proc.terminate()
            proc.wait(timeout=20)
            browser.close()
            if cache is not None:
                cache.cleanup()
    return address - started, drawn - address, again


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--warm", action="store_true", help="keep numba's cache (a second start)")
    ap.add_argument("--runs", type=int, default=1)
    args = ap.parse_args()
    for run in range(args.runs):
        ready, drawn, again = first_page(args.warm)
        verdict = "met" if drawn <= 3.0 else "NOT met"
        print(f"run {run + 1} ({'warm' if args.warm else 'cold'} cache): address printed "
              f"{ready:.1f} s after start; first page's plots drawn {drawn:.2f} s after the "
              f"address (target <= 3 s: {verdict}); a second page {again:.2f} s", flush=True)


if __name__ == "__main__":
    main()
