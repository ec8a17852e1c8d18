"""Methods scene: numerical methods of `core.numerics` against the closed form.

T(tau) of the chosen methods is overlaid on core's T(tau), each with its live error.
The scene is a collapsed card: its plots and charts are built when it is first opened,
and nothing is computed while it is closed.

Solving runs on one worker thread shared by every session of the server process (a
method may take a few hundred ms), with a progress bar, so sliders never wait for it.
Work is bounded: a session has at most one request waiting (a newer one replaces it),
at most `MAX_QUEUED` requests wait in the whole process (beyond that the scene says the
server is busy), and a session's requests are dropped when it ends.  The speed-accuracy
chart and the stability map come from `benchmarks/results/*.csv`, read once per process.
If `core.numerics` (or a method) is missing the scene shows a note instead.
"""

from __future__ import annotations

import csv
import math
import threading
from concurrent.futures import Future, ThreadPoolExecutor
from functools import cache, partial
from pathlib import Path

import numpy as np
import panel as pn
from bokeh.models import ColorBar, ColumnDataSource, LogColorMapper, LogTicker, Range1d
from bokeh.palettes import Viridis256
from panel.io import hold

from app.scenes import CURVE_POINTS, TOOLS, fit_range, new_figure, style_figure
from app.widgets import LabelledCheckbox
from core import Contact

try:
    from core import numerics
except ImportError:  # the app works without the numerics package
    numerics = None

RESULTS = Path(__file__).resolve().parent.parent / "benchmarks" / "results"
DEFAULT_METHODS = ("mdr", "lammps_mindlin")
PALETTE = ("#D55E00", "#0072B2", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#F0E442",
           "#000000", "#999999", "#882255")


#: Requests waiting for the shared worker, over all sessions of this process.
MAX_QUEUED = 16


class SharedWorker:
    """One worker thread for the Methods runs of every session, with a bounded queue."""

    def __init__(self, max_queued: int = MAX_QUEUED) -> None:
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="methods")
        self._slots = threading.BoundedSemaphore(max_queued)

    def submit(self, job) -> Future | None:
        """Run `job` on the worker; None (nothing queued) when the queue is full."""
        if not self._slots.acquire(blocking=False):
            return None
        future = self._pool.submit(job)
        future.add_done_callback(lambda _: self._slots.release())
        return future


WORKER = SharedWorker()


def available_methods() -> dict[str, str]:
    """Method name -> description of the methods `core.numerics` offers (may be empty)."""
    if numerics is None or not hasattr(numerics, "solve"):
        return {}
    return dict(getattr(numerics, "METHODS", {}))


@cache
def read_csv(path: Path) -> dict[str, np.ndarray] | None:
    """Columns of a CSV file (numeric where possible), or None if it is absent.

    Read once per process (the files ship with the app); callers must not modify the
    arrays."""
    if not path.exists():
        return None
    with path.open(newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return None
    out: dict[str, np.ndarray] = {}
    for key in rows[0]:
        col = [r[key] for r in rows]
        try:
            out[key] = np.array([float(x) for x in col])
        except ValueError:
            out[key] = np.array(col)
    return out


class MethodsScene:
    """Live comparison of numerical methods with the closed form, plus benchmark charts."""

    def __init__(self) -> None:
        self.methods = available_methods()
        self.source = ColumnDataSource({"xs": [], "ys": [], "label": [], "color": []},
                                       name="methods")
        self.exact = ColumnDataSource({"tau": [], "T": []}, name="methods_exact")
        self._generation = 0
        self._lock = threading.Lock()
        self._pending: Future | None = None
        self._doc = None
        self._built = False
        self._contact: Contact | None = None
        self.results: list = []
        # collapsed by default; while collapsed nothing here is built, computed or sent
        # (a hidden plot whose data changes also makes the browser lay out the page
        # again): the controls and the plot are built when the card is first opened
        self.card = pn.Card(title="Methods: numerical schemes against the closed form",
                            collapsed=True, sizing_mode="stretch_width", margin=6)
        self.card.param.watch(self._on_collapsed, "collapsed")

    def _build(self) -> None:
        """The controls and the overlay plot (on the card's first opening)."""
        self.choice = pn.widgets.MultiChoice(
            label="Methods", options=list(self.methods),
            value=[m for m in DEFAULT_METHODS if m in self.methods], sizing_mode="stretch_width")
        self.live = LabelledCheckbox(label="Recompute live on every change", value=False)
        self.run_button = pn.widgets.Button(label="Run methods", color="primary", width=140)
        self.progress = pn.indicators.Progress(active=False, visible=False, width=200)
        self.status = pn.pane.Markdown("", sizing_mode="stretch_width")
        self.table = pn.pane.Markdown("", sizing_mode="stretch_width")
        self.run_button.on_click(lambda _: self.run())
        self.choice.param.watch(lambda _: self.run(), "value")

        fig = new_figure("T / T₀: methods against the closed form", "τ = ωt (rad)", "T / T₀")
        fig.line("tau", "T", source=self.exact, color="black", line_width=4, alpha=0.35,
                 legend_label="closed form")
        fig.multi_line("xs", "ys", source=self.source, color="color", line_width=2,
                       legend_field="label")
        fig.legend.location = "bottom_left"
        style_figure(fig)
        self.figure = fig
        self._built = True
        self.card.objects = self._body()

    @property
    def shown(self) -> bool:
        """Whether the scene is expanded (the closed form and live runs follow the
        parameters only then)."""
        return not self.card.collapsed

    def _on_collapsed(self, event) -> None:
        if event.new:
            return
        if not self._built:
            self._build()
        if self._contact is not None:
            with hold():
                self.update_contact(self._contact)

    def close(self) -> None:
        """The session ended: drop its waiting request and make a running one stale."""
        with self._lock:
            self._generation += 1
            if self._pending is not None:
                self._pending.cancel()

    # ------------------------------------------------------------- live runs

    def update_contact(self, c: Contact) -> None:
        """New parameters: redraw the closed form; rerun the methods if live (only
        while the scene is shown; expanding it catches up)."""
        self._contact = c
        if self._doc is None:
            self._doc = pn.state.curdoc
        if not self.shown:
            return
        tau = c.tau_grid(CURVE_POINTS)
        line = c.at(tau)
        T, P = line.tangential_force, line.normal_force
        self.exact.data = {"tau": tau, "T": T}
        fit_range(self.figure.x_range, tau, pad=0.02)
        fit_range(self.figure.y_range, T, -P, P)
        if self.live.value:
            self.run()

    def update_tau(self, c: Contact, tau: float) -> None:
        """Nothing here depends on tau."""

    def run(self) -> None:
        """Solve the chosen methods for the current contact, in a worker thread when
        served (synchronously without a server session, e.g. in a notebook)."""
        if not self.methods or self._contact is None:
            return
        with self._lock:
            self._generation += 1
            generation = self._generation
        names = list(self.choice.value)
        self.progress.param.update(active=True, visible=True)
        self.status.object = f"computing {', '.join(names) or 'nothing'}…"
        job = partial(self._solve_all, generation, self._contact, names)
        if self._doc is None or self._doc.session_context is None:
            job()
            return
        with self._lock:
            if self._pending is not None:
                self._pending.cancel()  # replaced by this newer request
            self._pending = WORKER.submit(job)
        if self._pending is None:
            self._show(generation, self._contact, [],
                       ["the server is busy with other sessions' runs: try again shortly"])

    def _solve_all(self, generation: int, c: Contact, names: list[str]) -> None:
        results, errors = [], []
        for name in names:
            if generation != self._generation:
                return  # a newer request supersedes this one
            try:
                res = numerics.solve(name, c, numerics.INTERACTIVE_RESOLUTION.get(name, 200))
            except Exception as err:  # a method may be missing or reject parameters
                errors.append(f"{name}: {err}")
                continue
            results.append(res)
        apply = partial(self._show, generation, c, results, errors)
        if self._doc is not None and self._doc.session_context is not None:
            self._doc.add_next_tick_callback(apply)
        else:
            apply()

    def _show(self, generation: int, c: Contact, results: list, errors: list[str]) -> None:
        if generation != self._generation:
            return
        self.results = results
        rows = []
        for res in results:
            tau = np.asarray(res.tau, float)
            err_T = float(np.max(np.abs(np.asarray(res.T) - c.tangential_force(tau))))
            err_imp = abs(res.impulse_ratio - c.impulse_ratio)
            rows.append(f"| {res.method} | {res.resolution} | {err_T:.2e} | {err_imp:.2e} | "
                        f"{res.wall_time * 1e3:.0f} ms |")
        self.source.data = {
            "xs": [np.asarray(r.tau, float) for r in results],
            "ys": [np.asarray(r.T, float) for r in results],
            "label": [r.method for r in results],
            "color": [PALETTE[list(self.methods).index(r.method) % len(PALETTE)]
                      for r in results],
        }
        self.table.object = ("| method | resolution | max abs(T − T_exact) / T₀ | "
                             "impulse-ratio error | time |\n|---|---|---|---|---|\n"
                             + "\n".join(rows)) if rows else ""
        self.status.object = "\n".join(f"- ⚠ {e}" for e in errors)
        self.progress.param.update(active=False, visible=False)

    # ---------------------------------------------------------- benchmarks

    def speed_accuracy_figure(self):
        """Wall time against error per method, from speed_accuracy.csv (None if absent)."""
        data = read_csv(RESULTS / "speed_accuracy.csv")
        if data is None or "err" not in data or "wall_time" not in data:
            return None
        fig = new_figure("Speed against accuracy (benchmarks/results)", "wall time (s)",
                         "max error of T / T₀", x_axis_type="log", y_axis_type="log",
                         x_range=Range1d(1e-7, 10), y_range=Range1d(1e-17, 10))
        methods = list(dict.fromkeys(data["method"].tolist()))
        for i, name in enumerate(methods):
            sel = (data["method"] == name) & (data["err"] > 0) & (data["wall_time"] > 0)
            if sel.any():
                fig.scatter(data["wall_time"][sel], np.maximum(data["err"][sel], 1e-17),
                            color=PALETTE[i % len(PALETTE)], size=7, alpha=0.6,
                            legend_label=name)
        fig.legend.location = "bottom_left"
        fig.legend.label_text_font_size = "10pt"
        style_figure(fig)
        fig.height = 420
        return fig

    def stability_figure(self):
        """Error over (psi, tau0) for every method, from stability_map.csv (None if absent)."""
        data = read_csv(RESULTS / "stability_map.csv")
        if data is None or "err" not in data:
            return None
        methods = list(dict.fromkeys(data["method"].tolist()))
        psis = np.unique(data["psi"])
        tau0s = np.unique(data["tau0"])
        src = ColumnDataSource({
            "x": [math.log10(p) for p in data["psi"]],
            "y": [tau0s.tolist().index(t) for t in data["tau0"]],
            "method": [methods.index(m) for m in data["method"]],
            "err": np.maximum(data["err"], 1e-17),
        }, name="stability")
        # one row of tiles per method: y = method index + tau0 row / rows
        rows = len(tau0s)
        src.data["y"] = [m + (y + 0.5) / rows for m, y in
                         zip(src.data["method"], src.data["y"], strict=True)]
        mapper = LogColorMapper(palette=Viridis256, low=1e-16, high=1.0)
        dx = float(np.min(np.diff(np.log10(psis)))) if psis.size > 1 else 1.0
        fig = new_figure("Stability map: error over ψ (x) and τ₀ (rows) per method", "log₁₀ ψ",
                         "method", x_range=Range1d(math.log10(psis[0]) - dx,
                                                  math.log10(psis[-1]) + dx),
                         y_range=Range1d(0, len(methods)), height=60 + 34 * len(methods),
                         tools=TOOLS + ",hover", tooltips=[("error", "@err{0.0e}")])
        fig.rect("x", "y", width=dx, height=1 / rows, source=src,
                 fill_color={"field": "err", "transform": mapper}, line_color=None)
        fig.yaxis.ticker = [i + 0.5 for i in range(len(methods))]
        fig.yaxis.major_label_overrides = {i + 0.5: m for i, m in enumerate(methods)}
        fig.add_layout(ColorBar(color_mapper=mapper, ticker=LogTicker(), width=12,
                                title="error"), "right")
        style_figure(fig)
        return fig

    def view(self) -> pn.Card:
        """The scene: a collapsed card, filled (`_build`, `_body`) when first opened."""
        return self.card

    def _body(self) -> list:
        """Controls, the overlay and its error table, and the benchmark charts."""
        if not self.methods:
            body = [pn.pane.Alert("The numerical methods (`core.numerics`) are not available "
                                  "in this installation; the closed-form scenes above are "
                                  "unaffected.", alert_type="info")]
        else:
            body = [pn.Row(self.choice, self.run_button, self.progress),
                    self.live, self.status, pn.pane.Bokeh(self.figure), self.table,
                    pn.pane.Markdown("Methods: " + "; ".join(
                        f"**{k}**: {v}" for k, v in self.methods.items()))]
        charts = [f for f in (self.speed_accuracy_figure(), self.stability_figure())
                  if f is not None]
        if charts:
            body += [pn.pane.Bokeh(f, sizing_mode="stretch_width") for f in charts]
        else:
            body.append(pn.pane.Markdown("_No benchmark results in benchmarks/results._"))
        return body
