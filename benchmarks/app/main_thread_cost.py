"""The browser's main-thread time per psi move and per played frame, paired A/B.

End-to-end latency (`app_latency.py`) moves with the machine's load; this counts the
time the page's main thread spent in tasks (Chrome DevTools protocol `Performance`
metrics: TaskDuration, ScriptDuration, LayoutDuration) over N psi slider steps and over
S seconds of animation, per move and per distinct frame painted.  With `--revs A B ...`
each revision is served from a worktree the caller made (`--trees`), the arms
alternating run by run.

    .venv/bin/python -m benchmarks.app.main_thread_cost --trees /tmp/a /tmp/b [--runs 2]
"""

from __future__ import annotations

import argparse
import contextlib
import re
import statistics
from pathlib import Path

from benchmarks.app import app_latency
from benchmarks.app.common import (
    CHROMIUM_ARGS,
    chromium_path,
    explorer_server,
    open_explorer,
)

METRICS = ("TaskDuration", "ScriptDuration", "LayoutDuration", "RecalcStyleDuration")


def metrics(cdp) -> dict[str, float]:
    """The page's cumulative main-thread times (s)."""
    got = {m["name"]: m["value"] for m in cdp.send("Performance.getMetrics")["metrics"]}
    return {k: got.get(k, 0.0) for k in METRICS}


def spent(before: dict, after: dict, count: float) -> dict[str, float]:
    """ms of each metric per counted event."""
    return {k: 1e3 * (after[k] - before[k]) / max(count, 1) for k in METRICS}


def measure(url: str, moves: int, seconds: float) -> dict:
    """Main-thread ms per psi move and per painted frame of the explorer at `url`."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium_path(), args=CHROMIUM_ARGS)
        page, _ = open_explorer(browser, url, width=1600, height=1400)
        cdp = page.context.new_cdp_session(page)
        cdp.send("Performance.enable")
        sources = app_latency.focus_psi(page)
        for i in range(2):
            app_latency.step_psi(page, sources, i)
        m0 = metrics(cdp)
        for i in range(moves):
            app_latency.step_psi(page, sources, i)
        per_move = spent(m0, metrics(cdp), moves)
        page.get_by_role("button", name=re.compile("Play")).first.click()
        page.wait_for_function("() => (__col('frames', 'tau') || []).length > 0",
                               timeout=15_000)
        page.wait_for_timeout(1000)
        m1 = metrics(cdp)
        fps = page.evaluate(app_latency.JS_FPS, seconds * 1000)
        per_frame = spent(m1, metrics(cdp), fps["changes"])
        browser.close()
    return {"move": per_move, "frame": per_frame, "fps": fps["changes"] / fps["seconds"]}


def main() -> None:
    """Command line entry: print the figures per arm and run."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trees", nargs="+", required=True, help="checkouts to serve")
    ap.add_argument("--moves", type=int, default=20)
    ap.add_argument("--seconds", type=float, default=5.0)
    ap.add_argument("--runs", type=int, default=2)
    args = ap.parse_args()
    with contextlib.ExitStack() as stack:
        urls = {t: stack.enter_context(explorer_server(Path(t))) for t in args.trees}
        rows: dict[str, list] = {t: [] for t in args.trees}
        for i in range(args.runs):
            for t in (args.trees if i % 2 == 0 else list(reversed(args.trees))):
                rows[t].append(measure(urls[t], args.moves, args.seconds))
    for t, runs in rows.items():
        for what in ("move", "frame"):
            cells = "; ".join(f"{k} {statistics.median(r[what][k] for r in runs):.2f}"
                              for k in METRICS)
            print(f"{t}: main thread ms per {what} (median of {len(runs)} runs): {cells}")
        print(f"{t}: frames/s per run: {' '.join(f'{r['fps']:.1f}' for r in runs)}")


if __name__ == "__main__":
    main()
