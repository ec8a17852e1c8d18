"""What a page load costs the explorer server: sequential page loads on an idle server.

Starts ``python -m app.serve`` (one process) on a free loopback port, waits until it is
idle, loads the page once (the first load of a process imports and compiles what the
app needs: reported apart), then times ``--loads`` (20) sequential page loads of
``/main`` as a browser loads it (`load`), each from the request sent to the explorer
received: the server creating the session and its page's shell, rendering the page's
HTML, answering the websocket's pull, building the explorer into the page once the
client says the page is shown, and sending it.  Reported: median, min,
p90 and max in ms, the server process's CPU time per load, and the median as a multiple
of one closed-form contact (``core.numerics.metrics.closed_form_time(Contact, 0.4,
pi/6)``, the machine yardstick `benchmarks.app.common.yardstick_us`, measured before and after
the run).  Target: median <= 0.5 s.

``--profile FILE`` then records the server with py-spy (``.venv/bin/py-spy``) during
another ``--loads`` page loads (collapsed stacks in FILE) and prints where the time goes:
the functions of app/, Panel, Bokeh and param holding the most samples (inclusive) and
the most samples on their own (self).  The timing run is not profiled.

    .venv/bin/python -m benchmarks.app.page_load
    .venv/bin/python -m benchmarks.app.page_load --loads 20 --profile /tmp/page.txt --json out.json
    .venv/bin/python -m benchmarks.app.page_load --revs 6269e5a HEAD --loads 15

``--revs A B`` serves two git revisions side by side and alternates their loads (the
CPU of each counted over the load and the 0.5 s after it, where a session's first
messages are answered).

``--gc PAGES`` instead builds PAGES sessions' pages in this process, keeping them as
the server keeps its sessions, and prints the models of each page's document, the time
of each and of CPython's full garbage collections during it, with the collector's
thresholds the server sets (``--python-thresholds``: Python's own).

The server runs as the image runs it, with BOKEH_VALIDATE_DOC=false (Bokeh's checks of
each new document, which only log; `make serve` and the tests keep them on);
``--validate-doc`` measures it with them.

Loopback only; every request has a timeout.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

from benchmarks.app.common import (
    AUDIENCE,
    cpu_s,
    explorer_server,
    loopback_only,
    serve,
    server_pid,
    stop,
    worktree,
    yardstick_us,
)
from docker.browser_client import Session

#: Target: median server time of a page load, in seconds.
TARGET_S = 0.5

#: Frames of these packages are summarised by --profile (py-spy names files relative to
#: their entry of sys.path: "app/main.py", "bokeh/document/document.py").
OURS = re.compile(r"\((?:/[^()]*/)?(app|core|panel|bokeh|param)/")
#: The line number of a frame, dropped to merge a function's lines.
LINE = re.compile(r":\d+\)$")


def load(url: str) -> float:
    """Seconds from sending GET `url` to having the explorer, loaded as a browser loads
    it (`docker.browser_client.Session.open`: the page's HTML, its websocket, the document (the
    page's shell), ``document_ready``, and the explorer built into the page, received).
    The browser's own work (scripts, rendering) is not in it."""
    from tornado.httpclient import AsyncHTTPClient

    async def go() -> float:
        session = Session(url, AsyncHTTPClient(), 10.0, None)
        t0 = time.perf_counter()
        try:
            await session.open()
            return time.perf_counter() - t0
        finally:
            session.close()

    return asyncio.run(go())


def timed_loads(url: str, pid: int, loads: int) -> dict:
    """`loads` sequential page loads of `url`: their times, and the server's CPU time
    per load."""
    c0 = cpu_s(pid)
    times = [load(url) for _ in range(loads)]
    return summary(times, cpu_s(pid) - c0)


def summary(times: list[float], cpu: float) -> dict:
    """Page loads that took `times` (s) and `cpu` s of the server's CPU in all: their
    count, times (ms, sorted), median, min, p90 and max, and the CPU per load (ms)."""
    ms = sorted(1e3 * t for t in times)
    return {"loads": len(ms), "ms": [round(x, 1) for x in ms],
            "median_ms": round(statistics.median(ms), 1), "min_ms": round(ms[0], 1),
            "p90_ms": round(ms[int(0.9 * (len(ms) - 1))], 1), "max_ms": round(ms[-1], 1),
            "server_cpu_ms_per_load": round(1e3 * cpu / len(ms), 1)}


def paired(revs: list[str], loads: int, idle: float) -> dict:
    """Revisions `revs` served side by side (a worktree each), their loads alternated:
    per revision, the loads' `summary`, as `timed_loads`."""
    import contextlib

    with contextlib.ExitStack() as stack:
        urls = {rev: stack.enter_context(explorer_server(stack.enter_context(worktree(rev)),
                                                         timeout=900)) for rev in revs}
        pids = {rev: server_pid(url) for rev, url in urls.items()}
        time.sleep(idle)
        for url in urls.values():
            load(url)  # (the first load of a process, apart)
        time.sleep(idle)
        times: dict[str, list[float]] = {rev: [] for rev in revs}
        cpu = dict.fromkeys(revs, 0.0)
        for _ in range(loads):
            for rev, url in urls.items():
                c0 = cpu_s(pids[rev])
                times[rev].append(load(url))
                time.sleep(0.5)  # (what the load leaves to do: the session's first messages)
                cpu[rev] += cpu_s(pids[rev]) - c0
    return {rev: summary(times[rev], cpu[rev]) for rev in revs}


def py_spy() -> str:
    """The py-spy executable beside this Python, else on PATH."""
    here = Path(sys.executable).with_name("py-spy")
    found = str(here) if here.exists() else shutil.which("py-spy")
    if not found:
        raise SystemExit("py-spy not found (pip install py-spy)")
    return found


def profile(url: str, pid: int, loads: int, out: Path) -> dict:
    """Record the server with py-spy during `loads` page loads; collapsed stacks go to
    `out`."""
    rec = subprocess.Popen([py_spy(), "record", "--pid", str(pid), "--rate", "250",
                            "--format", "raw", "--output", str(out), "--nonblocking"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(2.0)  # py-spy attaches
    try:
        for _ in range(loads):
            load(url)
    finally:
        rec.send_signal(signal.SIGINT)
        try:
            _, err = rec.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            rec.kill()
            _, err = rec.communicate()
    if not out.exists():
        raise SystemExit(f"py-spy wrote no profile: {err.strip()[-500:]}")
    return summarize(out)


def summarize(path: Path, top: int = 25) -> dict:
    """Shares of the samples in a py-spy collapsed-stack file: per function (its lines
    merged), inclusive for the app's own code (app/, core/) and for Panel, Bokeh and
    param, and self (the innermost frame) for any code."""
    inclusive: dict[str, Counter[str]] = {"app": Counter(), "libraries": Counter()}
    own: Counter[str] = Counter()
    total = 0
    for line in path.read_text().splitlines():
        stack, _, count = line.rpartition(" ")
        if not stack or not count.isdigit():
            continue
        n = int(count)
        total += n
        frames = [LINE.sub(")", f) for f in stack.split(";") if f]
        for f in set(frames):
            m = OURS.search(f)
            if m:
                inclusive["app" if m.group(1) in ("app", "core") else "libraries"][f] += n
        if frames:
            own[frames[-1]] += n

    def share(c: Counter[str]) -> list[list]:
        return [[f, round(100 * n / total, 1)] for f, n in c.most_common(top)] if total else []

    return {"samples": total, "inclusive_app_pct": share(inclusive["app"]),
            "inclusive_libraries_pct": share(inclusive["libraries"]), "self_pct": share(own)}


def gc_pauses(pages: int, python_thresholds: bool = False) -> list[tuple[float, float, int]]:
    """Build `pages` sessions' documents in this process, keeping each (as the server
    keeps its sessions), with the collector as the server runs it (its modules' objects
    frozen after a first page, `app.page.memory.THRESHOLDS`, `SessionMemory` told of each
    build), or with Python's own thresholds: per page, (ms to build it, ms of CPython's
    full garbage collections during the build, models in its document)."""
    import gc

    os.environ.setdefault("BOKEH_VALIDATE_DOC", "false")
    import panel as pn
    from bokeh.document import Document
    from panel.io.state import set_curdoc

    from app.page.explorer import Explorer
    from app.page.memory import THRESHOLDS, SessionMemory

    pn.extension("katex", notifications=False)
    Explorer().view().get_root(Document())  # (what app.serve does before it serves)
    gc.freeze()
    if not python_thresholds:
        gc.set_threshold(*THRESHOLDS)
    memory = SessionMemory()

    full = {"start": 0.0, "total": 0.0}

    def watch(phase: str, info: dict) -> None:
        if info["generation"] == 2:
            if phase == "start":
                full["start"] = time.perf_counter()
            else:
                full["total"] += time.perf_counter() - full["start"]

    gc.callbacks.append(watch)
    kept, out = [], []
    try:
        for _ in range(pages):
            doc, full["total"] = Document(), 0.0
            t0 = time.perf_counter()
            with set_curdoc(doc):
                explorer = Explorer(query={})
                explorer.view().server_doc(doc)
            out.append((1e3 * (time.perf_counter() - t0), 1e3 * full["total"],
                        len(list(doc.models))))
            kept.append((doc, explorer))
            memory.built()
    finally:
        gc.callbacks.remove(watch)
        memory.stop()
    return out


def main(argv: list[str] | None = None) -> int:
    """Parse the command line, start the server, time the loads, print the report."""
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--loads", type=int, default=20, help="sequential timed page loads")
    p.add_argument("--idle", type=float, default=3.0,
                   help="seconds to let the server settle before the first load")
    p.add_argument("--profile", type=Path, help="profile another --loads loads with py-spy, "
                   "collapsed stacks written here")
    p.add_argument("--json", type=Path, help="write the results here")
    p.add_argument("--validate-doc", action="store_true",
                   help="let Bokeh validate each document (the image sets "
                        "BOKEH_VALIDATE_DOC=false; `make serve` validates)")
    p.add_argument("--gc", type=int, metavar="PAGES",
                   help="instead: build PAGES pages in this process, keeping each, and "
                        "print each one's build time and full garbage collections")
    p.add_argument("--python-thresholds", action="store_true",
                   help="with --gc: the collector's thresholds as Python sets them, not as "
                        "the server does (app.page.memory.THRESHOLDS)")
    p.add_argument("--revs", nargs=2, metavar=("A", "B"),
                   help="instead: serve git revisions A and B side by side and alternate "
                        "their loads (each load, then 0.5 s for what it leaves to do)")
    args = p.parse_args(argv)
    if args.revs:
        os.environ["BOKEH_VALIDATE_DOC"] = "true" if args.validate_doc else "false"
        res = paired(args.revs, args.loads, args.idle)
        print(f"{args.loads} page loads per revision, alternated; "
              f"BOKEH_VALIDATE_DOC={os.environ['BOKEH_VALIDATE_DOC']}")
        for rev, r in res.items():
            print(f"  {rev}: median {r['median_ms']:.0f} ms (min {r['min_ms']:.0f}, p90 "
                  f"{r['p90_ms']:.0f}); server CPU {r['server_cpu_ms_per_load']:.0f} ms per load")
        if args.json:
            args.json.write_text(json.dumps(res, indent=2) + "\n")
        return 0
    if args.gc:
        for i, (ms, gc_ms, models) in enumerate(gc_pauses(args.gc, args.python_thresholds), 1):
            print(f"page {i:3d} ({models} models): {ms:5.0f} ms, of which full garbage "
                  f"collection {gc_ms:4.0f} ms")
        return 0
    if args.loads < 1:
        p.error("--loads must be >= 1")

    res: dict = {"yardstick_before_us": round(yardstick_us(), 1)}
    validate = "true" if args.validate_doc else "false"
    os.environ["BOKEH_VALIDATE_DOC"] = validate  # (the server started below inherits it)
    proc, url = serve(1, class_size=AUDIENCE)
    loopback_only(url)
    res["setup"] = (f"BOKEH_VALIDATE_DOC={validate} python -m app.serve --num-procs 1 "
                    f"({url}); {os.cpu_count()} CPUs")
    try:
        time.sleep(args.idle)
        res["first_load_ms"] = round(1e3 * load(url), 1)
        time.sleep(args.idle)
        res.update(timed_loads(url, proc.pid, args.loads))
        if args.profile:
            res["profile"] = profile(url, proc.pid, args.loads, args.profile)
    finally:
        stop(proc)
    res["yardstick_after_us"] = round(yardstick_us(), 1)
    med_us = 1e3 * res["median_ms"]
    res["median_in_contacts"] = [round(med_us / res["yardstick_before_us"]),
                                 round(med_us / res["yardstick_after_us"])]
    res["met"] = res["median_ms"] <= 1e3 * TARGET_S
    print(f"setup: {res['setup']}")
    print(f"first load of the process: {res['first_load_ms']:.0f} ms")
    print(f"{res['loads']} sequential page loads of /main: median {res['median_ms']:.0f} ms "
          f"(min {res['min_ms']:.0f}, p90 {res['p90_ms']:.0f}, max {res['max_ms']:.0f}); "
          f"server CPU {res['server_cpu_ms_per_load']:.0f} ms per load")
    print(f"median = {res['median_in_contacts'][0]}-{res['median_in_contacts'][1]} closed-form "
          f"contacts; target <= {1e3 * TARGET_S:.0f} ms: {'met' if res['met'] else 'NOT met'}")
    print(f"machine yardstick (one closed-form contact): {res['yardstick_before_us']:.0f} us "
          f"before, {res['yardstick_after_us']:.0f} us after the run")
    if "profile" in res:
        pr = res["profile"]
        print(f"profile ({pr['samples']} samples, {args.profile}): inclusive % of samples, "
              "the app's code")
        for f, s in pr["inclusive_app_pct"]:
            print(f"  {s:5.1f}  {f}")
        print("inclusive % of samples, Panel, Bokeh, param")
        for f, s in pr["inclusive_libraries_pct"]:
            print(f"  {s:5.1f}  {f}")
        print("self % of samples")
        for f, s in pr["self_pct"][:15]:
            print(f"  {s:5.1f}  {f}")
    if args.json:
        args.json.write_text(json.dumps(res, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
