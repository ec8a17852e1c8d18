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
`benchmarks.app.common.yardstick_us`, read after each level), and the machine's load average.
At the end: the sizing rule, the most sessions per serving process (one core each)
whose p95 stays within 200 ms.

Bounded: at most ``--max-sessions`` (200) sessions, every level ends after its
duration, every wait has a timeout, and the target must be a loopback address.

    # a server started here (python -m app.serve, 2 processes = one per core):
    python -m benchmarks.app.load_test --serve 2
    # any running server or balancer on this machine, its processes found by port:
    python -m benchmarks.app.load_test --url http://127.0.0.1:8080/main --pids 1234,1240
    # two replicas behind nginx (docker/replicas.py), everything started and stopped here
    # (make load-test):
    python -m benchmarks.app.load_test --replicas 2

Abuse (``--abuse [KIND ...]``, `benchmarks.app.abuse`): one probe session moving ψ every
``--interval`` s; per kind a ``--window`` alone, then one beside a single abusive client
of that kind (`ABUSE_KINDS`: a page-load loop, websockets with invented session ids,
PULL-DOC spam, the Methods card at 16x with live recompute, NaN as ψ), ``--rounds`` pairs
interleaved in one run against one server (``--serve 1`` unless given).  Per kind: the
probe's p50/p95 alone and beside (pooled over the rounds), their p95 ratio against the
kind's target and each round's ratio, moves answered, the server's CPU and the lines it
logged (its output goes to a file):

    python -m benchmarks.app.load_test --abuse --window 20
    python -m benchmarks.app.load_test --abuse pull-doc page-load-loop --window 20 --rounds 4

Results: a table on stdout, and ``--json FILE`` for the raw figures.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import random
import signal
import sys
import tempfile
import time
from pathlib import Path
from urllib.parse import urlsplit

from tornado.httpclient import AsyncHTTPClient

from benchmarks.app import abuse, load_figures
from benchmarks.app.common import (
    AUDIENCE,
    loopback_only,
    pct,
    serve,
    stop,
    usage,
    yardstick_us,
)
from docker.browser_client import Session, Stats

# ---------------------------------------------------------------- a run


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
                "yardstick_us": round(yardstick_us(), 1),
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


# ---------------------------------------------------------------- the report


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
    p.add_argument("--rounds", type=int, default=abuse.ROUNDS,
                   help="with --abuse: pairs of windows (alone, beside) per kind")
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
        from docker import replicas  # (docker/replicas.py)

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
            rows = asyncio.run(abuse.run_abuse(url, kinds, args.window, args.warmup,
                                               args.interval, args.timeout, pids, log,
                                               args.rounds))
        finally:
            if started is not None:
                stop(started)
        print(f"setup: {setup}; {os.cpu_count()} CPUs; one probe session moving ψ every "
              f"{args.interval:g} s; per kind {args.rounds} rounds of {args.window:g} s alone "
              f"and {args.window:g} s beside one abusive client (in turn first)")
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
