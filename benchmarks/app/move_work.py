"""What a psi move costs the explorer's own code: CPU per move without a server.

`benchmarks.app.move_cost` times a served process; this times, in a process of its
own per arm, only what the explorer does for a move: the psi slider set as the
browser's move sets it (`ExactSlider.value`, inside `panel.io.hold`), the state's
watchers and the scenes, and Bokeh's `PATCH-DOC` message of the changes with its JSON.
No websocket, no event loop, no Bokeh worker thread: a profile of this is the app's
part alone.  The arms (the working tree, or with ``--revs A B`` the git revisions A and
B) each build one page, then run ``--rounds`` rounds of the same ``--moves`` random psi
moves (uniform in [0.2, 20], the load test's), in alternation (the order swapped every
round); with ``--gap`` s of sleep before each move, CPU time only counted (a served
move comes after such a pause: the processor's caches have moved on).  Reported per
arm: the median and the lowest CPU ms per move over the rounds, the message's bytes;
with two arms the median of the paired round ratios.

    .venv/bin/python -m benchmarks.app.move_work
    .venv/bin/python -m benchmarks.app.move_work --revs b842cbc HEAD --rounds 20
    .venv/bin/python -m benchmarks.app.move_work --gap 0.3 --moves 30 --rounds 6
"""

from __future__ import annotations

import argparse
import contextlib
import statistics
import subprocess
import sys

from benchmarks.app.common import ROOT, worktree

#: The arm's process, run in the tree it measures (``python -c`` imports from there):
#: builds the page, then answers each line of its standard input (a round) with
#: "ms-per-move bytes-per-move".
WORKER = r"""
import random, sys, time
moves, gap = int(sys.argv[1]), float(sys.argv[2])
import panel as pn
from bokeh.document import Document
from bokeh.document.events import DocumentPatchedEvent
from bokeh.protocol import Protocol
from panel.io import hold
from panel.io.state import set_curdoc
pn.extension("katex", notifications=False)
from app.page.explorer import Explorer
doc = Document()
with set_curdoc(doc):  # (as a server builds a page: in its document)
    explorer = Explorer()
    doc.add_root(explorer.view().get_root(doc))
doc.to_json()
events = []
doc.on_change(lambda e: events.append(e) if isinstance(e, DocumentPatchedEvent) else None)
slider, protocol = explorer.contact.controls.psi_slider, Protocol()
rng = random.Random(1)
psis = [round(rng.uniform(0.2, 20.0), 6) for _ in range(moves)]

def one_round():
    cpu, size = 0.0, 0
    with set_curdoc(doc):
        for psi in psis:
            events.clear()
            if gap:
                time.sleep(gap)
            t = time.process_time()
            with hold(doc):
                slider.value = psi
            size += len(protocol.create("PATCH-DOC", list(events)).content_json)
            cpu += time.process_time() - t
    return cpu / moves * 1e3, size / moves

one_round()
print("ready", flush=True)
for _ in sys.stdin:
    ms, size = one_round()
    print(f"{ms:.4f} {size:.0f}", flush=True)
"""


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--moves", type=int, default=60, help="psi moves per round")
    ap.add_argument("--rounds", type=int, default=20)
    ap.add_argument("--gap", type=float, default=0.0, help="s of sleep before each move")
    ap.add_argument("--revs", nargs=2, metavar=("A", "B"))
    args = ap.parse_args()
    with contextlib.ExitStack() as stack:
        roots = ({rev: stack.enter_context(worktree(rev)) for rev in args.revs} if args.revs
                 else {"working tree": ROOT})
        procs = {name: subprocess.Popen(
            [sys.executable, "-c", WORKER, str(args.moves), str(args.gap)],
            cwd=root, stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
            for name, root in roots.items()}
        for p in procs.values():
            for line in p.stdout:
                if line.strip() == "ready":
                    break
            else:
                raise RuntimeError("an arm's worker ended before its page was built")
        ms: dict[str, list[float]] = {name: [] for name in procs}
        size: dict[str, float] = {}
        for r in range(args.rounds):
            order = list(procs.items()) if r % 2 == 0 else list(procs.items())[::-1]
            for name, p in order:
                p.stdin.write("go\n")
                p.stdin.flush()
                t, s = p.stdout.readline().split()
                ms[name].append(float(t))
                size[name] = float(s)
        for p in procs.values():
            p.stdin.close()
            p.wait(timeout=60)
    print(f"{args.moves} psi moves per round, {args.rounds} rounds, {args.gap:g} s before "
          f"each move; arms alternating")
    for name, times in ms.items():
        print(f"  {name}: median {statistics.median(times):.2f} ms of CPU per move, lowest "
              f"{min(times):.2f}; {size[name]:.0f} bytes per message")
    if len(ms) == 2:
        (a, ta), (b, tb) = ms.items()
        ratio = statistics.median(y / x for x, y in zip(ta, tb, strict=True))
        print(f"  {b} / {a}: {ratio:.3f} (median of the paired rounds)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
