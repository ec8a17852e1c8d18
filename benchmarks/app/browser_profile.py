"""Where a psi move's time goes in the browser.

A CPU profile (Chrome DevTools protocol, 100 us sampling) of 24 psi slider steps as
`app_latency.py` makes them, against an explorer served from this checkout with BokehJS
unminified (BOKEH_MINIFIED=false, so that its functions keep their names).  Prints the
moves' latencies and, per move, the functions with the most self and inclusive time.

    .venv/bin/python -m benchmarks.app.browser_profile [--moves 24] [--top 40]
"""

from __future__ import annotations

import argparse
import collections
import os
import statistics
from pathlib import Path

from benchmarks.app import app_latency
from benchmarks.app.common import (
    CHROMIUM_ARGS,
    chromium_path,
    explorer_server,
    open_explorer,
)


def profile(moves: int) -> tuple[list[float], dict]:
    """The latencies (ms) of `moves` psi steps and the CPU profile taken over them."""
    from playwright.sync_api import sync_playwright

    os.environ["BOKEH_MINIFIED"] = "false"  # (the server started below inherits it)
    with explorer_server() as url, sync_playwright() as p:
        browser = p.chromium.launch(executable_path=chromium_path(), args=CHROMIUM_ARGS)
        page, _ = open_explorer(browser, url, width=1600, height=1400)
        sources = app_latency.focus_psi(page)
        cdp = page.context.new_cdp_session(page)
        cdp.send("Profiler.enable")
        cdp.send("Profiler.setSamplingInterval", {"interval": 100})
        for i in range(4):  # warm-up
            app_latency.step_psi(page, sources, i)
        cdp.send("Profiler.start")
        times = [app_latency.step_psi(page, sources, i) for i in range(moves)]
        prof = cdp.send("Profiler.stop")["profile"]
        browser.close()
    return times, prof


def tables(prof: dict) -> tuple[collections.Counter, collections.Counter]:
    """Self and inclusive time (us) per function ('name file:line')."""
    nodes = {n["id"]: n for n in prof["nodes"]}
    parent = {c: n["id"] for n in prof["nodes"] for c in n.get("children", [])}

    def key(nid: int) -> str:
        cf = nodes[nid]["callFrame"]
        return f'{cf["functionName"] or "(anonymous)"} {Path(cf["url"]).name.split("?")[0]}' \
               f':{cf["lineNumber"]}'

    per_node: collections.Counter = collections.Counter()
    for sample, dt in zip(prof["samples"], prof["timeDeltas"], strict=True):
        per_node[sample] += dt
    own: collections.Counter = collections.Counter()
    inclusive: collections.Counter = collections.Counter()
    for nid, dt in per_node.items():
        own[key(nid)] += dt
        seen = set()
        while nid is not None:
            k = key(nid)
            if k not in seen:
                inclusive[k] += dt
                seen.add(k)
            nid = parent.get(nid)
    return own, inclusive


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--moves", type=int, default=24)
    ap.add_argument("--top", type=int, default=40)
    args = ap.parse_args(argv)
    times, prof = profile(args.moves)
    print(f"slider move -> plots in view updated: median {statistics.median(times):.0f} ms "
          f"(profiler on), range {min(times):.0f}-{max(times):.0f} ms")
    own, inclusive = tables(prof)
    for title, table in (("self time", own), ("inclusive time", inclusive)):
        print(f"--- {title}, ms per move")
        for k, us in table.most_common(args.top):
            print(f"{us / 1000 / args.moves:7.2f}  {k}")


if __name__ == "__main__":
    main()
