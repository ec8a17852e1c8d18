"""How long the garbage collector stops a server process full of sessions.

A class of ``--sessions`` students (40) joins one server process: that many explorer
pages are built, one after the other, as `app.page.guard.serve_page` builds them; then
one student leaves (their document is dropped) and the full collection Panel runs 5 s
after a session closes is timed.  Two arms, each in a fresh process, alternated
``--runs`` times in one run:

- ``python``: the collector as Python runs it (what the server did before
  `app.page.memory.SessionMemory`);
- ``sessions``: `SessionMemory` told of every build and of the close.

Per arm: the close's pause (ms: the interpreter held, no session served), and the full
collections Python ran by itself while the class joined (count and their total ms).

    .venv/bin/python -m benchmarks.app.gc_pause
    .venv/bin/python -m benchmarks.app.gc_pause --sessions 40 --runs 3
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time

from benchmarks.app.common import ROOT

ARMS = ("python", "sessions")


def arm(name: str, sessions: int) -> dict:
    """One arm in this process: build, close one, time the collection (see the module)."""
    import gc

    from bokeh.document import Document

    from app.page.explorer import Explorer
    from app.page.memory import SessionMemory
    from core.warm import warm

    warm()
    Explorer().view().get_root(Document())  # imports and caches, as the server's start
    gc.collect()
    gc.freeze()  # (the server's start freezes its modules' objects: app.serve)
    full: list[float] = []
    started: list[float] = []

    def timed(phase: str, info: dict) -> None:
        if info["generation"] == 2:
            if phase == "start":
                started.append(time.perf_counter())
            else:
                full.append(time.perf_counter() - started.pop())

    memory = SessionMemory() if name == "sessions" else None
    gc.callbacks.append(timed)
    docs = []
    for _ in range(sessions):
        doc = Document()
        Explorer().view().get_root(doc)
        docs.append(doc)
        if memory:
            memory.built()
    joined = list(full)
    docs.pop()
    if memory:
        memory.closed()
    t = time.perf_counter()
    gc.collect()  # Panel's, after the close
    close_ms = (time.perf_counter() - t) * 1e3
    return {"arm": name, "close_pause_ms": round(close_ms, 1),
            "full_while_joining": len(joined),
            "full_while_joining_ms": round(sum(joined) * 1e3, 1)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sessions", type=int, default=40)
    ap.add_argument("--runs", type=int, default=2)
    ap.add_argument("--arm", choices=ARMS, help=argparse.SUPPRESS)  # (one arm, here)
    args = ap.parse_args()
    if args.arm:
        print(json.dumps(arm(args.arm, args.sessions)))
        return
    rows = []
    for run in range(args.runs):
        for name in ARMS:
            out = subprocess.run([sys.executable, "-m", "benchmarks.app.gc_pause", "--arm", name,
                                  "--sessions", str(args.sessions)], cwd=ROOT, check=True,
                                 capture_output=True, text=True, timeout=900).stdout
            rows.append({"run": run + 1, **json.loads(out.splitlines()[-1])})
            print(json.dumps(rows[-1]), file=sys.stderr)
    print(f"{args.sessions} sessions built in one process, then one closed; "
          f"{args.runs} runs, arms alternated")
    print("| arm | close's pause ms (per run) | Python's full collections while joining "
          "(count / ms, per run) |\n| --- | --- | --- |")
    for name in ARMS:
        mine = [r for r in rows if r["arm"] == name]
        print(f"| {name} | {' / '.join(str(r['close_pause_ms']) for r in mine)} "
              f"(median {statistics.median(r['close_pause_ms'] for r in mine):.0f}) | "
              + " / ".join(f"{r['full_while_joining']} / {r['full_while_joining_ms']}"
                           for r in mine) + " |")


if __name__ == "__main__":
    main()
