"""The load test's figures beyond latency: how evenly the server processes share the
work, what a move costs in closed-form contacts, and the sizing rule.

Used by `benchmarks.app.load_test` (its levels); pure functions but for the ones that
read processes (psutil).
"""

from __future__ import annotations

import math
import os
import statistics

#: The latency a level must keep to count as holding (p95 of a move, ms).
P95_TARGET_MS = 200.0

#: The most a serving process may work above the mean of them all (max / mean CPU).
SPREAD_TARGET = 1.3


def serving_pids(pids: list[int]) -> list[int]:
    """The processes that serve sessions among `pids` and their descendants: every
    ``app.serve`` process without an ``app.serve`` child (with ``--num-procs N`` the
    parent only forks and waits; a replica of one process serves itself).  A helper
    process such as the kernels' warm-up (``core.warm``) is not one."""
    import psutil

    found: list[int] = []
    for pid in pids:
        try:
            root = psutil.Process(pid)
            tree = [root, *root.children(recursive=True)]
        except psutil.NoSuchProcess:
            continue
        for p in tree:
            try:
                if not _is_server(p):
                    continue
                if not any(_is_server(c) for c in p.children()):
                    found.append(p.pid)
            except psutil.NoSuchProcess:
                pass
    return sorted(set(found))


def _is_server(p) -> bool:
    return "app.serve" in " ".join(p.cmdline())


def cpu_spread(cpu0: dict[int, float], cpu1: dict[int, float], wall: float,
               serving: list[int]) -> dict:
    """Each serving process's CPU over a window, in % of one core (in the order of
    `serving`; 0 for one that is gone), and the highest over their mean (1.0: even).
    `cpu0`, `cpu1`: CPU seconds by pid at the window's start and end; `wall`: its s."""
    pct = [100 * (cpu1[p] - cpu0.get(p, 0.0)) / wall if p in cpu1 else 0.0 for p in serving]
    mean = statistics.fmean(pct) if pct else 0.0
    return {"cpu_pct": [round(x) for x in pct],
            "max_over_mean": round(max(pct) / mean, 2) if mean > 0 else None}


def sessions_by_replica(entries: list[dict[str, str]], routes: list[str],
                        addrs: list[str]) -> list[int]:
    """Sessions per replica (in the order of `addrs`, "host:port") from nginx's access
    log (`entries` as `docker/replicas.py`'s `Stack.access_log` gives them): the
    upstream that answered the last ``GET /main`` of each session's route cookie."""
    where: dict[str, str] = {}
    for e in entries:
        if e["request"].startswith("GET /main "):
            where[e["route"]] = e["upstream"].split(",")[-1].strip()
    return [sum(where.get(r) == a for r in routes) for a in addrs]


def sessions_by_process(serving: list[int], port: int) -> list[int]:
    """Established connections on `port` per serving process (in the order of
    `serving`): a session's websocket is one, held for as long as the session lives."""
    import psutil

    out = []
    for pid in serving:
        try:
            conns = psutil.Process(pid).net_connections(kind="tcp")
        except psutil.NoSuchProcess:
            out.append(0)
            continue
        out.append(sum(c.status == psutil.CONN_ESTABLISHED and c.laddr.port == port
                       for c in conns))
    return out


def replica_placement(stack):
    """`run_levels`'s placement for replicas of one process behind nginx: sessions per
    replica (in the stack's order) from the balancer's access log."""
    addrs = [r.addr for r in stack.replicas]

    def placed(live: list, serving: list[int]) -> list[int]:
        routes = [s.cookies.get("explorer_route", "") for s in live]
        return sessions_by_replica(stack.access_log(), routes, addrs)

    return placed


def process_placement(port: int):
    """`run_levels`'s placement for server processes listening on `port` themselves:
    sessions per process, counted as their established connections (websockets)."""
    def placed(live: list, serving: list[int]) -> list[int]:
        return sessions_by_process(serving, port)

    return placed


def per_move(cpu_s: float, moves: int, yardstick: float) -> dict:
    """Server CPU per answered move: ms, and in closed-form contacts (`yardstick` in us)."""
    if moves <= 0:
        return {"cpu_ms_per_move": None, "contacts_per_move": None}
    ms = 1e3 * cpu_s / moves
    return {"cpu_ms_per_move": round(ms, 2), "contacts_per_move": round(1e3 * ms / yardstick)}


def load_average() -> float:
    """The machine's 1-minute load average (uptime's first figure)."""
    return round(os.getloadavg()[0], 2)


def sizing(rows: list[dict], processes: int, interval: float) -> dict:
    """The sizing rule from a run's levels: the most sessions whose p95 stays within
    `P95_TARGET_MS` with no error, per serving process (one core each), and the students
    per core the CPU per move allows at one move every `interval` s with the core 100 %
    busy (the mean over the levels that hold)."""
    held = [r for r in rows if r["p95_ms"] <= P95_TARGET_MS and not r["errors"]]
    best = max(held, key=lambda r: r["sessions"]) if held else None
    costs = [r["cpu_ms_per_move"] for r in held if r.get("cpu_ms_per_move")]
    ms = statistics.fmean(costs) if costs else math.nan
    return {
        "sessions_held": best["sessions"] if best else 0,
        "processes": processes,
        "students_per_core": round(best["sessions"] / processes, 1) if best else 0.0,
        "spread_at_held": best.get("cpu_spread", {}).get("max_over_mean") if best else None,
        "cpu_ms_per_move": round(ms, 2),
        "students_per_core_by_cpu": round(1e3 * interval / ms, 1) if costs else None,
    }


def sizing_text(s: dict, interval: float) -> str:
    """The sizing rule in a sentence (`s` as `sizing` gives it)."""
    if not s["sessions_held"]:
        return f"no level kept p95 <= {P95_TARGET_MS:g} ms without errors"
    spread = (f"; CPU of the busiest process {s['spread_at_held']:.2f}x the mean "
              f"(target <= {SPREAD_TARGET:g}x)" if s["spread_at_held"] else "")
    return (f"p95 <= {P95_TARGET_MS:g} ms held up to {s['sessions_held']} sessions on "
            f"{s['processes']} server processes: {s['students_per_core']:g} students per "
            f"core moving a slider every {interval:g} s{spread}; at "
            f"{s['cpu_ms_per_move']:.1f} ms of CPU per move a fully busy core answers "
            f"{s['students_per_core_by_cpu']:g} such students")
