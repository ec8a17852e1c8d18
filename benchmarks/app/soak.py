"""Soak test of the explorer server's memory: many page loads, then many moves in one tab.

Starts ``python -m app.serve`` (one process) on a free loopback port and measures the
resident memory (RSS) of that process:

(a) **page loads**: after a warm-up (a few loads of each kind, then the server's
    session cleanup), ``--loads`` GETs of ``/main`` whose websocket never connects (a
    link preview, a crawler), the cleanup, then ``--loads`` page loads that do connect
    (the page, the websocket, the document pulled, one ψ move answered, the tab closed),
    the cleanup again.  The cleanup is waited for as the server's settings make it
    happen (``app.serve.SESSION``: an unused session is discarded after its lifetime,
    checked every few seconds; a session whose websocket closed is unused from then on),
    plus a margin; RSS is then read until it stops moving.  Reported: RSS at start,
    after the warm-up (the baseline), after each kind of load, and the growth per
    session against the target (within 0.5 MB per session of the baseline).
(b) **one long session**: ``--changes`` ψ moves in ONE session, each sent when the
    previous one's plot update has arrived, speaking Bokeh's websocket protocol with
    ``docker.browser_client.Session``.  The server's RSS
    is sampled every ``--every`` changes; a least-squares line through the samples gives
    the trend per 1000 changes with its 95 % confidence interval, over the whole run and
    over its second half (what remains once caches are warm).  The trend counts as beyond
    noise when its interval excludes zero *and* the fitted rise over the run exceeds twice
    the samples' scatter about the line.

Bounded: loopback only, one session at a time, every wait has a timeout, and the long
session stops at ``--budget`` seconds (default 900) whatever count it reached.  A move
takes 60-90 ms from change to update on the shared 2-core machine, so the default
counts take about 4-5 minutes for (a) and 12-15 minutes for (b); ``--changes 2000``
gives a 3-minute look at (b).

    .venv/bin/python -m benchmarks.app.soak                      # both parts, default counts
    .venv/bin/python -m benchmarks.app.soak --loads 50 --changes 2000 --json soak.json
    .venv/bin/python -m benchmarks.app.soak --skip-loads         # only the long session
    .venv/bin/python -m benchmarks.app.soak --skip-changes --malloc-trim   # see below

``--malloc-trim`` starts the server with glibc's ``malloc_trim(0)`` run every 5 s on
its event loop (a ``python -c`` wrapper around ``app.serve.main``): RSS that falls back
with it was free memory the allocator kept, not objects kept alive.

A yardstick of the machine's speed (one closed-form contact, in us) is printed before and
after the run.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import math
import statistics
import subprocess
import sys
import time
from pathlib import Path

from tornado.httpclient import AsyncHTTPClient

from app.serve import SESSION
from benchmarks.app.common import (
    AUDIENCE,
    ROOT,
    free_port,
    loopback_only,
    serve,
    stop,
    wait_for_http,
    yardstick_us,
)
from docker.browser_client import Session, Stats

#: ``python -c`` program for --malloc-trim: app.serve's main, plus glibc's malloc_trim(0)
#: every 5 s on the server's event loop (returns the allocator's free pages to the system).
TRIMMED_SERVER = """\
import ctypes, sys
from tornado.ioloop import PeriodicCallback
trim = ctypes.CDLL("libc.so.6").malloc_trim
PeriodicCallback(lambda: trim(0), 5000).start()
from app.serve import main
sys.exit(main())
"""

#: Target of part (a): RSS back within this many MB (MiB here) per session of the baseline.
TARGET_MB_PER_SESSION = 0.5


def rss_mib(pid: int) -> float:
    """Resident memory of process `pid` in MiB."""
    import psutil

    return psutil.Process(pid).memory_info().rss / 2**20


def serve_trimmed() -> tuple[subprocess.Popen, str]:
    """Like `benchmarks.app.common.serve` (1), with glibc's malloc_trim(0) run every 5 s in the
    server (a diagnosis: memory the allocator holds free vs memory still in use)."""
    port = free_port()
    proc = subprocess.Popen([sys.executable, "-c", TRIMMED_SERVER, "--port", str(port),
                             "--class-size", str(AUDIENCE)],
                            cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    wait_for_http(f"http://127.0.0.1:{port}/liveness")
    return proc, f"http://127.0.0.1:{port}/main"


def cleanup_wait_s(margin: float = 5.0) -> float:
    """Seconds after the last page load by which the server has discarded its sessions:
    the unused-session lifetime, one check interval and a margin."""
    return (SESSION["unused_session_lifetime_milliseconds"]
            + SESSION["check_unused_sessions_milliseconds"]) / 1e3 + margin


async def settled_rss(pid: int, wait: float, step: float = 2.0, limit: float = 30.0) -> float:
    """RSS (MiB) once the cleanup has run: wait `wait` s, then read every `step` s until two
    readings agree within 0.5 MiB (at most `limit` s more); the last reading."""
    await asyncio.sleep(wait)
    last = rss_mib(pid)
    end = time.monotonic() + limit
    while time.monotonic() < end:
        await asyncio.sleep(step)
        now = rss_mib(pid)
        if abs(now - last) <= 0.5:
            return now
        last = now
    return last


# ---------------------------------------------------------------- (a) page loads


async def page_only(url: str, http: AsyncHTTPClient) -> None:
    """One GET of the page whose websocket never connects."""
    await http.fetch(url, request_timeout=60, follow_redirects=True)


async def full_tab(url: str, http: AsyncHTTPClient, timeout: float) -> None:
    """One browser tab: page, websocket, document pulled, one ψ move answered, closed."""
    s = Session(url, http, timeout, None)
    try:
        await asyncio.wait_for(s.open(), 120)
        s.stats = Stats()
        await s.move()
        await answered(s, timeout)
        if s.stats.errors or not s.stats.latencies:
            raise RuntimeError(f"the move was not answered: {s.stats.errors}")
    finally:
        s.close()


async def answered(s: Session, timeout: float) -> None:
    """Wait until session `s` has no change in flight (answered, or `timeout` s passed)."""
    if s.pending is None:
        return
    end = s.pending[1] + timeout
    while s.pending is not None and s.alive and time.perf_counter() < end:
        await asyncio.sleep(0.001)


async def page_loads(url: str, pid: int, loads: int, warmup: int, timeout: float) -> dict:
    """Part (a): RSS before and after `loads` page loads of each kind, after the cleanup."""
    http = AsyncHTTPClient()
    wait = cleanup_wait_s()
    out: dict = {"rss_start_mib": round(rss_mib(pid), 1), "cleanup_wait_s": wait}
    print(f"[soak] RSS at start {out['rss_start_mib']} MiB; warm-up {warmup} loads of "
          f"each kind", file=sys.stderr)
    for _ in range(warmup):
        await page_only(url, http)
        await full_tab(url, http, timeout)
    base = await settled_rss(pid, wait)
    out["rss_baseline_mib"] = round(base, 1)
    print(f"[soak] baseline after warm-up and cleanup: {base:.1f} MiB", file=sys.stderr)
    prev = base
    for kind, one in (("page_only", lambda: page_only(url, http)),
                      ("with_websocket", lambda: full_tab(url, http, timeout))):
        t0 = time.perf_counter()
        failed = 0
        peak = prev
        for i in range(loads):
            try:
                await one()
            except Exception as err:  # counted, reported
                failed += 1
                print(f"[soak] {kind} load {i} failed: {type(err).__name__}: {err}"[:200],
                      file=sys.stderr)
            if i % 10 == 9:
                peak = max(peak, rss_mib(pid))
        took = time.perf_counter() - t0
        after = await settled_rss(pid, wait)
        row = {"loads": loads, "failed": failed, "seconds": round(took, 1),
               "rss_peak_mib": round(peak, 1), "rss_after_cleanup_mib": round(after, 1),
               "growth_mib_per_session": round((after - prev) / loads, 3)}
        out[kind] = row
        print(f"[soak] {kind}: {json.dumps(row)}", file=sys.stderr)
        prev = after
    total = 2 * loads
    out["rss_end_mib"] = round(prev, 1)
    out["growth_mib_per_session"] = round((prev - base) / total, 3)
    out["target_mib_per_session"] = TARGET_MB_PER_SESSION
    out["met"] = (prev - base) / total <= TARGET_MB_PER_SESSION
    http.close()
    return out


# ---------------------------------------------------------------- (b) one long session


def trend(xs: list[float], ys: list[float]) -> dict:
    """Least-squares line ys = a + b xs: slope b, its standard error and 95 % interval,
    the residuals' standard deviation, and the fitted rise over the span of xs."""
    from scipy import stats

    n = len(xs)
    if n < 3:
        return {"points": n}
    fit = stats.linregress(xs, ys)
    resid = [y - (fit.intercept + fit.slope * x) for x, y in zip(xs, ys, strict=True)]
    sd = math.sqrt(sum(r * r for r in resid) / (n - 2))
    half = stats.t.ppf(0.975, n - 2) * fit.stderr
    rise = fit.slope * (max(xs) - min(xs))
    beyond = (abs(fit.slope) > half) and abs(rise) > 2 * sd
    return {"points": n, "slope": round(fit.slope, 4), "stderr": round(fit.stderr, 4),
            "ci95": [round(fit.slope - half, 4), round(fit.slope + half, 4)],
            "residual_sd": round(sd, 3), "fitted_rise": round(rise, 3),
            "beyond_noise": bool(beyond)}


async def long_session(url: str, pid: int, changes: int, every: int, warmup: int,
                       timeout: float, budget: float) -> dict:
    """Part (b): `changes` ψ moves in one session, RSS sampled every `every` changes."""
    http = AsyncHTTPClient()
    s = Session(url, http, timeout, None)
    await asyncio.wait_for(s.open(), 120)
    try:
        s.stats = Stats()
        for _ in range(warmup):
            await s.move()
            await answered(s, timeout)
        s.stats = stats_ = Stats()
        samples: list[tuple[int, float]] = [(0, rss_mib(pid))]
        t0 = time.perf_counter()
        done = 0
        stopped = None
        while done < changes:
            if not s.alive:
                stopped = "connection lost"
                break
            if time.perf_counter() - t0 > budget:
                stopped = f"time budget of {budget:g} s reached"
                break
            await s.move()
            await answered(s, timeout)
            done += 1
            if done % every == 0:
                samples.append((done, rss_mib(pid)))
                print(f"[soak] {done} changes, RSS {samples[-1][1]:.1f} MiB, "
                      f"{time.perf_counter() - t0:.0f} s", file=sys.stderr)
        took = time.perf_counter() - t0
    finally:
        s.close()
        http.close()
    xs = [n / 1000 for n, _ in samples]
    ys = [r for _, r in samples]
    second = [(x, y) for x, y in zip(xs, ys, strict=True) if x >= xs[-1] / 2]
    lat = sorted(1e3 * v for v in stats_.latencies)
    return {
        "changes": done, "stopped": stopped, "seconds": round(took, 1), "every": every,
        "warmup_changes": warmup,
        "errors": sum(stats_.errors.values()), "error_kinds": stats_.errors,
        "latency_ms": {"p50": round(statistics.median(lat), 1) if lat else None,
                       "p95": round(lat[int(0.95 * (len(lat) - 1))], 1) if lat else None,
                       "max": round(lat[-1], 1) if lat else None},
        "rss_mib": [[n, round(r, 2)] for n, r in samples],
        "rss_first_mib": round(ys[0], 1), "rss_last_mib": round(ys[-1], 1),
        "rss_min_mib": round(min(ys), 1), "rss_max_mib": round(max(ys), 1),
        "trend_mib_per_1000": trend(xs, ys),
        "trend_second_half_mib_per_1000": trend([x for x, _ in second],
                                                [y for _, y in second]),
    }


# ---------------------------------------------------------------- report


def report(res: dict) -> str:
    """The results as the lines printed on stdout."""
    lines = []
    a = res.get("page_loads")
    if a:
        lines.append(f"(a) page loads: RSS at start {a['rss_start_mib']} MiB, baseline after "
                     f"warm-up and cleanup {a['rss_baseline_mib']} MiB")
        for kind in ("page_only", "with_websocket"):
            r = a[kind]
            lines.append(f"    {r['loads']} loads {kind.replace('_', ' ')} "
                         f"({r['failed']} failed, {r['seconds']} s): peak "
                         f"{r['rss_peak_mib']} MiB, after cleanup "
                         f"{r['rss_after_cleanup_mib']} MiB = "
                         f"{r['growth_mib_per_session']:+.3f} MiB per session")
        lines.append(f"    overall {a['rss_baseline_mib']} -> {a['rss_end_mib']} MiB = "
                     f"{a['growth_mib_per_session']:+.3f} MiB per session (target <= "
                     f"{a['target_mib_per_session']}): {'met' if a['met'] else 'NOT met'}")
    b = res.get("long_session")
    if b:
        t, t2 = b["trend_mib_per_1000"], b["trend_second_half_mib_per_1000"]
        lines.append(f"(b) one session, {b['changes']} changes in {b['seconds']} s "
                     f"({b['errors']} errors{'; stopped: ' + b['stopped'] if b['stopped'] else ''}"
                     f"), latency p50 {b['latency_ms']['p50']} ms p95 {b['latency_ms']['p95']} "
                     f"ms: RSS {b['rss_first_mib']} -> {b['rss_last_mib']} MiB "
                     f"(min {b['rss_min_mib']}, max {b['rss_max_mib']})")
        for label, tr in (("whole run", t), ("second half", t2)):
            if "slope" not in tr:
                lines.append(f"    {label}: too few samples ({tr['points']})")
                continue
            lines.append(f"    {label}: {tr['slope']:+.3f} MiB per 1000 changes (95 % "
                         f"interval {tr['ci95'][0]:+.3f} .. {tr['ci95'][1]:+.3f}; scatter "
                         f"{tr['residual_sd']:.2f} MiB; fitted rise {tr['fitted_rise']:+.2f} "
                         f"MiB over {tr['points']} samples): "
                         f"{'BEYOND noise' if tr['beyond_noise'] else 'within noise'}")
    lines.append(f"machine yardstick (one closed-form contact): {res['yardstick_before_us']:.0f}"
                 f" us before, {res['yardstick_after_us']:.0f} us after the run")
    return "\n".join(lines)


async def run(args: argparse.Namespace, url: str, pid: int) -> dict:
    """Both parts against the server at `url` (process `pid`)."""
    res: dict = {}
    if not args.skip_loads:
        res["page_loads"] = await page_loads(url, pid, args.loads, args.warmup_loads,
                                             args.timeout)
    if not args.skip_changes:
        res["long_session"] = await long_session(url, pid, args.changes, args.every,
                                                 args.warmup_changes, args.timeout,
                                                 args.budget)
    return res


def main(argv: list[str] | None = None) -> int:
    """Parse the command line, start the server, run the parts, print the report."""
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--loads", type=int, default=50, help="page loads of each kind (a)")
    p.add_argument("--warmup-loads", type=int, default=3,
                   help="loads of each kind before the baseline")
    p.add_argument("--changes", type=int, default=10_000, help="ψ moves in one session (b)")
    p.add_argument("--every", type=int, default=500, help="RSS sampled every this many moves")
    p.add_argument("--warmup-changes", type=int, default=100,
                   help="moves before the first sample")
    p.add_argument("--timeout", type=float, default=10.0,
                   help="seconds for a move's update before it counts as an error")
    p.add_argument("--budget", type=float, default=900.0,
                   help="seconds at most for the long session's moves")
    p.add_argument("--skip-loads", action="store_true", help="skip part (a)")
    p.add_argument("--skip-changes", action="store_true", help="skip part (b)")
    p.add_argument("--malloc-trim", action="store_true",
                   help="run glibc's malloc_trim(0) in the server every 5 s (tells memory "
                        "the allocator keeps from memory in use)")
    p.add_argument("--json", type=Path, help="write the results here")
    args = p.parse_args(argv)
    if args.loads < 1 or args.changes < 1 or args.every < 1:
        p.error("--loads, --changes and --every must be >= 1")

    res: dict = {"yardstick_before_us": round(yardstick_us(), 1)}
    proc, url = serve_trimmed() if args.malloc_trim else serve(1, class_size=AUDIENCE)
    loopback_only(url)
    res["setup"] = (f"python -m app.serve --num-procs 1 ({url})"
                    f"{' with malloc_trim(0) every 5 s' if args.malloc_trim else ''}; "
                    f"session settings {SESSION}")
    print(f"[soak] {res['setup']}", file=sys.stderr)
    try:
        res.update(asyncio.run(run(args, url, proc.pid)))
    finally:
        stop(proc)
    res["yardstick_after_us"] = round(yardstick_us(), 1)
    print(report(res))
    if args.json:
        args.json.write_text(json.dumps(res, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
