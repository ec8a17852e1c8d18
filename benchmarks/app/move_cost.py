"""What one psi move costs the explorer server: CPU per move as closed-form contacts.

Serves the working tree (or, with ``--revs A B``, the git revisions A and B, each a
worktree in a temporary directory) as one process each, opens one session on each
(the load test's simulated browser tab, `docker.browser_client.Session`) and moves its psi slider
``--moves`` times, one move every ``--interval`` s (so that a page's debounced writes,
such as a URL written 0.4 s after a burst, land between moves as they do for a
visitor), alternating between the arms move by move: both see the same machine load.

Reported per arm: the server process's CPU time per move (its CPU over the moves, less
its idle CPU over as long, measured before over ``--idle`` s: the kernel counts CPU time
in ticks of 10 ms, one tick in a 5 s window is 2 ms per s, 1.6 ms per move over a run of
150 moves; the CPU without that correction is reported too), as a multiple of one
closed-form contact (``core.numerics.metrics.closed_form_time(Contact, 0.4, pi/6)``, the
yardstick of `benchmarks.app.common.yardstick_us`, measured before and after
the run); the websocket messages (PATCH-DOC) the client got per move and their bytes; the
median time from sending a move to the traction data's arrival.  With ``--rounds N`` the
run is made N times, each with fresh server processes (one process's speed differs from
another's by a few per cent), and the median of the N paired ratios is reported.

    .venv/bin/python -m benchmarks.app.move_cost
    .venv/bin/python -m benchmarks.app.move_cost --revs 1c3d2f1 HEAD --moves 150
    .venv/bin/python -m benchmarks.app.move_cost --revs 1c3d2f1 HEAD --moves 100 --rounds 3

Loopback only; every request has a timeout.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import statistics
import time
from pathlib import Path

from tornado.httpclient import AsyncHTTPClient

from benchmarks.app.common import cpu_s, explorer_server, server_pid, worktree, yardstick_us
from docker.browser_client import Session, Stats


class Arm:
    """One served revision, its session and its counts."""

    def __init__(self, name: str, url: str) -> None:
        self.name, self.url, self.pid = name, url, server_pid(url)
        self.stats = Stats()
        self.bytes = 0
        self.cpu = self.raw_cpu = 0.0
        self.idle_cpu_per_s = 0.0

    async def open(self, http: AsyncHTTPClient) -> None:
        self.session = Session(self.url, http, 10.0, None)
        await self.session.open()
        self.session.patches = []

    async def move(self) -> None:
        """One move, waiting (at most 10 s) for the traction data to come back."""
        s = self.session
        s.stats = self.stats
        await s.move()
        deadline = time.perf_counter() + 10
        while s.pending and time.perf_counter() < deadline:
            await asyncio.sleep(0.002)


def tree_cpu_s(pid: int) -> float:
    """CPU seconds so far of process `pid` and its children (a fresh server compiles
    kernels in a child process, then loads them)."""
    import psutil

    p = psutil.Process(pid)
    total = 0.0
    for q in [p, *p.children(recursive=True)]:
        try:
            t = q.cpu_times()
            total += t.user + t.system
        except psutil.NoSuchProcess:
            pass
    return total


async def settle(pid: int, busy: float = 0.03, quiet: int = 3, timeout: float = 900.0) -> None:
    """Wait until process `pid` and its children have used less than `busy` of a CPU in
    each of `quiet` seconds in a row (a fresh server loads or compiles kernels)."""
    deadline, calm = time.perf_counter() + timeout, 0
    while calm < quiet and time.perf_counter() < deadline:
        c0 = tree_cpu_s(pid)
        await asyncio.sleep(1.0)
        calm = calm + 1 if tree_cpu_s(pid) - c0 < busy else 0


async def run(arms: list[Arm], moves: int, interval: float, warmup: int,
              idle: float) -> None:
    for a in arms:
        await settle(a.pid)
    http = AsyncHTTPClient()
    for a in arms:
        await a.open(http)
    await asyncio.sleep(2.0)
    for _ in range(warmup):  # numba, caches, the first patches
        for a in arms:
            await a.move()
            await asyncio.sleep(interval)
    for a in arms:
        await settle(a.pid)
    c0 = {a.name: cpu_s(a.pid) for a in arms}
    await asyncio.sleep(idle)
    for a in arms:
        a.idle_cpu_per_s = (cpu_s(a.pid) - c0[a.name]) / idle
        a.stats = Stats()
        a.session.patches = []
    t0 = time.perf_counter()
    c0 = {a.name: cpu_s(a.pid) for a in arms}
    for i in range(moves):
        for a in arms if i % 2 == 0 else reversed(arms):
            await a.move()
            await asyncio.sleep(interval / len(arms))
    await asyncio.sleep(1.0)  # the last move's deferred writes
    wall = time.perf_counter() - t0
    for a in arms:
        a.raw_cpu = cpu_s(a.pid) - c0[a.name]
        a.cpu = a.raw_cpu - a.idle_cpu_per_s * wall
        a.bytes = sum(len(p) for p in a.session.patches)
        a.messages = len(a.session.patches)
        a.session.close()


def report(arms: list[Arm], moves: int, unit: float) -> dict:
    """Each arm's figures (printed, and returned by arm name)."""
    rows = {}
    for a in arms:
        per_move = a.cpu / moves
        lat = statistics.median(a.stats.latencies) * 1e3 if a.stats.latencies else float("nan")
        row = {"cpu_ms_per_move": round(per_move * 1e3, 2),
               "raw_cpu_ms_per_move": round(a.raw_cpu / moves * 1e3, 2),
               "closed_form_contacts_per_move": round(per_move * 1e6 / unit),
               "messages_per_move": round(a.messages / moves, 2),
               "bytes_per_move": round(a.bytes / moves),
               "median_reply_ms": round(lat, 1), "errors": a.stats.errors,
               "idle_cpu_ms_per_s": round(a.idle_cpu_per_s * 1e3, 2)}
        rows[a.name] = row
        print(f"  {a.name}: {row['cpu_ms_per_move']} ms CPU per move = "
              f"{row['closed_form_contacts_per_move']} closed-form contacts "
              f"({row['raw_cpu_ms_per_move']} ms without the idle correction); "
              f"{row['messages_per_move']} messages, {row['bytes_per_move']} bytes per move; "
              f"reply median {row['median_reply_ms']} ms; errors {row['errors']}; "
              f"idle {row['idle_cpu_ms_per_s']} ms of CPU per s")
    if len(arms) == 2:
        (a, ra), (b, rb) = ((rows[x.name]["cpu_ms_per_move"], rows[x.name]["raw_cpu_ms_per_move"])
                            for x in arms)
        print(f"  {arms[1].name} / {arms[0].name}: {b / a:.2f} of the CPU per move "
              f"({rb / ra:.2f} without the idle correction)")
    return rows


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--moves", type=int, default=100)
    ap.add_argument("--interval", type=float, default=0.4, help="s between one arm's moves")
    ap.add_argument("--warmup", type=int, default=10)
    ap.add_argument("--idle", type=float, default=20.0,
                    help="s of idle CPU measured per arm before the moves")
    ap.add_argument("--revs", nargs=2, metavar=("A", "B"))
    ap.add_argument("--rounds", type=int, default=1,
                    help="runs, each with fresh server processes (a process's own speed "
                         "varies by a few per cent); with two arms the ratios' median too")
    ap.add_argument("--json", type=Path, help="also write the figures here")
    args = ap.parse_args()
    before = yardstick_us()
    out = {"yardstick_us": [round(before, 2)], "moves": args.moves, "rounds": []}
    with contextlib.ExitStack() as trees:
        roots = ({rev: trees.enter_context(worktree(rev)) for rev in args.revs} if args.revs
                 else {"working tree": None})
        for k in range(args.rounds):
            with contextlib.ExitStack() as servers:
                arms = [Arm(name, servers.enter_context(explorer_server(root, timeout=900)))
                        for name, root in roots.items()]
                asyncio.run(run(arms, args.moves, args.interval, args.warmup, args.idle))
            after = yardstick_us()
            print(f"{'' if args.rounds == 1 else f'round {k + 1}: '}{args.moves} psi moves per "
                  f"arm, one every {args.interval:g} s, arms alternating; yardstick (one "
                  f"closed-form contact) {before:.1f} us before, {after:.1f} us after")
            out["rounds"].append(report(arms, args.moves, statistics.mean((before, after))))
            out["yardstick_us"].append(round(after, 2))
            before = after
    if args.rounds > 1 and len(roots) == 2:
        a, b = roots
        ratios = [r[b]["cpu_ms_per_move"] / r[a]["cpu_ms_per_move"] for r in out["rounds"]]
        out["ratios"] = [round(x, 3) for x in ratios]
        print(f"{b} / {a} over {args.rounds} rounds: median {statistics.median(ratios):.2f} "
              f"(each: {', '.join(f'{x:.2f}' for x in ratios)})")
    if args.json:
        args.json.write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
