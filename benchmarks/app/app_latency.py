"""Explorer latency in a real browser (Debian's Chromium through Playwright).

Measures
  (a) slider move -> every plot in view updated: a psi slider step by keyboard until
      every named data source drawn in the viewport that a psi move changes has changed
      and the browser has painted (two animation frames later);
      median and p90 over N moves;
  (b) animation frame rate: distinct tau-marker positions painted per second while
      playing.
Serves the app itself with `python -m app.serve` unless EXPLORER_URL is set.

    .venv/bin/python -m benchmarks.app.app_latency [--moves 30] [--seconds 5]
                                               [--width 1600] [--height 1400]
                                               [--runs 1] [--revs REV [REV ...]]

`--revs A B` serves the git revisions A and B (each a worktree in a temporary
directory) instead of the working tree and measures them in alternation, `--runs` times
each (paired A/B: both arms see the same machine load).  The figures say how many plots
were in the page's view (a tall page, --height 3200, has all of them in view).

It also prints a yardstick of the machine's speed before and after the run (one
closed-form contact, in us), so that a slow run can be told from a slow machine.
"""

from __future__ import annotations

import argparse
import contextlib
import re
import statistics

from benchmarks.app.common import (
    CHROMIUM_ARGS,
    chromium_path,
    explorer_server,
    open_explorer,
    worktree,
    yardstick_us,
)

#: What a psi move changes (the impulse curve itself depends on tau0 only: its marker;
#: `readout` is the derived table's source in revisions that drew it on a canvas); the
#: benchmark waits for those of them drawn in a plot in the page's view.
PSI_SOURCES = ["traction", "disc", "force", "force_marker", "impulse_marker", "radii",
               "radii_marker", "motion", "motion_marker", "readout", "spheres_lower",
               "spheres_patch"]

#: The names among `names` of sources drawn by a plot in the viewport.
JS_VISIBLE_SOURCES = """(names) => {
  const seen = new Set();
  for (const v of __renderers()) {
    const r = v.parent.el.getBoundingClientRect();
    if (r.width > 0 && r.bottom > 0 && r.top < window.innerHeight) {
      seen.add(v.model.data_source.name);
    }
  }
  return names.filter((n) => seen.has(n));
}"""

#: Arms a one-shot measurement: t0 at the next keydown, done when every source changed
#: and two animation frames (a paint) have passed.
JS_ARM = """(names) => {
  const doc = window.Bokeh.documents[0];
  window.__result = new Promise((resolve) => {
    let t0 = null;
    const pending = new Set(names);
    const slots = [];
    const finish = () => {
      slots.forEach(([m, f]) => m.change.disconnect(f));
      requestAnimationFrame(() => requestAnimationFrame(() => resolve(performance.now() - t0)));
    };
    for (const n of names) {
      const m = doc.get_model_by_name(n);
      const f = () => { pending.delete(n); if (t0 !== null && pending.size === 0) finish(); };
      m.change.connect(f);
      slots.push([m, f]);
    }
    document.addEventListener("keydown", () => { t0 = performance.now(); },
                              {capture: true, once: true});
    setTimeout(() => resolve(NaN), 15000);
  });
}"""

#: Counts distinct tau-marker positions painted during `ms` milliseconds.
JS_FPS = """(ms) => new Promise((resolve) => {
  const doc = window.Bokeh.documents[0];
  const marker = doc.get_model_by_name("force_marker");
  const x = () => { const d = marker.data; return (d instanceof Map ? d.get("x") : d.x)[0]; };
  let last = x(), changes = 0, frames = 0;
  const t0 = performance.now();
  const tick = () => {
    frames += 1;
    const now = x();
    if (now !== last) { changes += 1; last = now; }
    if (performance.now() - t0 < ms) requestAnimationFrame(tick);
    else resolve({changes, frames, seconds: (performance.now() - t0) / 1000});
  };
  requestAnimationFrame(tick);
})"""


#: [plots in the viewport, plots on the page] (canvases of Bokeh plots, by their boxes).
JS_IN_VIEW = """() => {
  const plots = __views((v) => v.model != null && v.model.type === "Figure"
                                && v.el.getBoundingClientRect().width > 0);
  const inside = plots.filter((v) => {
    const r = v.el.getBoundingClientRect();
    return r.bottom > 0 && r.top < window.innerHeight && r.right > 0 && r.left < window.innerWidth;
  });
  return [inside.length, plots.length];
}"""


def focus_psi(page) -> list[str]:
    """Focus the psi slider of the explorer `page` (after 2 s of settling): its range
    input, or in revisions before 5174ea3 its noUiSlider handle; returns the names of
    the sources in view that a psi move changes."""
    page.wait_for_timeout(2000)
    page.locator(".slider-psi input[type=range], .slider-psi .noUi-handle").focus()
    return page.evaluate(JS_VISIBLE_SOURCES, PSI_SOURCES)


def step_psi(page, sources: list[str], i: int) -> float:
    """Step the focused psi slider by keyboard (right for even i, left for odd) and
    return the ms until every source of `sources` changed and was painted (nan after
    15 s); then wait 250 ms."""
    page.evaluate(JS_ARM, sources)
    page.keyboard.press("ArrowRight" if i % 2 == 0 else "ArrowLeft")
    ms = page.evaluate("window.__result")
    page.wait_for_timeout(250)
    return ms


def measure(url: str, moves: int, seconds: float, width: int = 1600,
            height: int = 1400) -> dict[str, float]:
    """Run both measurements against the explorer at `url` in a `width` x `height` page."""
    from playwright.sync_api import sync_playwright

    path = chromium_path()
    if path is None:
        raise SystemExit("no /usr/bin/chromium (apt-get install chromium)")
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=path, args=CHROMIUM_ARGS)
        page, _ = open_explorer(browser, url, width=width, height=height)
        sources = focus_psi(page)
        # (the first two moves warm up caches on both sides)
        times = [step_psi(page, sources, i) for i in range(moves + 2)][2:]
        in_view = page.evaluate(JS_IN_VIEW)
        page.get_by_role("button", name="▶ Play").click()
        # the player starts when the contact's frames arrive
        page.wait_for_function("() => (__col('frames', 'tau') || []).length > 0",
                               timeout=15_000)
        page.wait_for_timeout(1000)
        fps = page.evaluate(JS_FPS, seconds * 1000)
        page.get_by_role("button", name=re.compile("Pause")).click()
        browser.close()
    ok = sorted(t for t in times if t == t)
    if not ok:
        raise SystemExit(f"no slider move updated all of {sources} within 15 s")
    return {
        "moves": len(ok),
        "median_ms": statistics.median(ok),
        "p90_ms": ok[max(0, round(0.9 * len(ok)) - 1)],
        "fps": fps["changes"] / fps["seconds"],
        "paint_fps": fps["frames"] / fps["seconds"],
        "in_view": in_view,
        "sources": sources,
    }


def report(label: str, rows: list[dict[str, float]]) -> None:
    """Print one arm's runs: per-run medians and frame rates, and how many meet the targets
    (median <= 100 ms, >= 30 frames/s)."""
    med = [r["median_ms"] for r in rows]
    fps = [r["fps"] for r in rows]
    print(f"{label}: slider move median per run (ms): {' '.join(f'{m:.0f}' for m in med)}; "
          f"<= 100 ms in {sum(m <= 100 for m in med)} of {len(med)}")
    print(f"{label}: frames/s per run: {' '.join(f'{f:.1f}' for f in fps)}; "
          f">= 30 in {sum(f >= 30 for f in fps)} of {len(fps)}")
    p90 = " ".join(f"{r['p90_ms']:.0f}" for r in rows)
    print(f"{label}: median of medians {statistics.median(med):.0f} ms, p90 per run {p90} ms, "
          f"median {statistics.median(fps):.1f} frames/s")


def main() -> None:
    """Command line entry: print the figures."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--moves", type=int, default=30)
    ap.add_argument("--seconds", type=float, default=5.0)
    ap.add_argument("--width", type=int, default=1600)
    ap.add_argument("--height", type=int, default=1400)
    ap.add_argument("--runs", type=int, default=1, help="runs (per arm with --compare)")
    ap.add_argument("--revs", nargs="+", metavar="REV",
                    help="measure these git revisions (paired) instead of the working tree")
    args = ap.parse_args()
    before = yardstick_us()
    size = (args.moves, args.seconds, args.width, args.height)
    with contextlib.ExitStack() as stack:
        arms = ({rev: stack.enter_context(worktree(rev)) for rev in args.revs} if args.revs
                else {"working tree": None})
        urls = {k: stack.enter_context(explorer_server(root, timeout=900))
                for k, root in arms.items()}
        rows: dict[str, list] = {k: [] for k in arms}
        for i in range(args.runs):
            order = list(arms) if i % 2 == 0 else list(reversed(arms))
            for k in order:
                rows[k].append(measure(urls[k], *size))
    after = yardstick_us()
    shown, plots = next(iter(rows.values()))[0]["in_view"]
    print(f"page {args.width}x{args.height}: {shown} of {plots} plots in view; "
          f"{args.moves} psi moves and {args.seconds:g} s of animation per run")
    for k, r in rows.items():
        print(f"{k}: a move is timed until these sources in view changed: "
              f"{', '.join(r[0]['sources'])}")
    for k, r in rows.items():
        report(k, r)
    print(f"machine yardstick (one closed-form contact): {before:.0f} us before, "
          f"{after:.0f} us after the run")


if __name__ == "__main__":
    main()
