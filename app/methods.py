"""Methods scene: numerical methods of `core.numerics` against the closed form.

T(tau) of the chosen methods is overlaid on core's T(tau), each with its live error.
The scene is a collapsed card: its plots and charts are built when it is first opened,
and nothing is computed while it is closed.

Solving runs on one worker thread shared by every session of the server process (a
method may take a few hundred ms), with a progress bar, so sliders never wait for it.
Work is bounded: a session has at most one request waiting (a newer one replaces it),
at most `MAX_QUEUED` requests wait in the whole process (beyond that the scene says the
server is busy), and a session's requests are dropped when it ends.  The speed-accuracy
chart and the stability map come from the app's `results/*.csv`, read once per process.
If `core.numerics` (or a method) is missing the scene shows a note instead.
"""

from __future__ import annotations

import io
import threading
from concurrent.futures import Future, ThreadPoolExecutor
from functools import cache, partial

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource
from panel.io import hold

from app.benchmark_charts import (
    RESULTS,
    STABILITY_FIELDS,
    STABILITY_NOTE,
    STYLE,
    SpeedAccuracyData,
    StabilityData,
    colour_bar,
    error_mapper,
    map_cells,
    read_rows,
    speed_accuracy_chart,
    speed_accuracy_data,
    stability_data,
    stability_figure,
)
from app.kit.figures import CURVE_POINTS, fit_range, new_figure, style_figure
from app.kit.widgets import LabelledCheckbox
from core import Contact

try:
    from core import numerics
except ImportError:  # the app works without the numerics package
    numerics = None

DEFAULT_METHODS = ("mdr", "lammps_mindlin")
#: The colour of a method the charts have no style for.
OTHER_COLOR = "#882255"


#: The resolutions offered, as factors of each method's interactive default
#: (`core.numerics.INTERACTIVE_RESOLUTION`), and the most a method is given whose cost
#: grows faster than its resolution: a solve takes at most ~0.2 s (the annulus at 128
#: rings; MDR at 6400 springs ~25 ms), so a client's choice bounds the work.
RESOLUTION_FACTORS = {"¼ × default": 0.25, "½ × default": 0.5, "default": 1.0,
                      "2 × default": 2.0, "4 × default": 4.0, "8 × default": 8.0,
                      "16 × default": 16.0}
MAX_RESOLUTION = {"annulus": 128}


def resolution(name: str, factor: float) -> int:
    """The resolution of method `name` at `factor` times its interactive default (at
    most its `MAX_RESOLUTION`)."""
    n = max(2, round(numerics.INTERACTIVE_RESOLUTION.get(name, 200) * factor))
    return min(n, MAX_RESOLUTION.get(name, n))


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
def speed_accuracy() -> SpeedAccuracyData | None:
    """The views of speed_accuracy.csv, once per process (None if the file is absent)."""
    path = RESULTS / "speed_accuracy.csv"
    return speed_accuracy_data(read_rows(path)) if path.is_file() else None


@cache
def stability() -> StabilityData | None:
    """The cells of stability_map.csv, once per process (None if the file is absent)."""
    path = RESULTS / "stability_map.csv"
    return stability_data(read_rows(path)) if path.is_file() else None


def results_download(name: str, label: str) -> pn.widgets.FileDownload:
    """A button that downloads the results file `name` (read when clicked)."""
    return pn.widgets.FileDownload(callback=lambda: io.BytesIO((RESULTS / name).read_bytes()),
                                   filename=name, label=label, width=260)


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
        self.resolution = pn.widgets.Select(
            label="Resolution", options=RESOLUTION_FACTORS, value=1.0, width=200)
        self.run_button = pn.widgets.Button(label="Run methods", color="primary", width=140)
        self.progress = pn.indicators.Progress(active=False, visible=False, width=200)
        self.status = pn.pane.Markdown("", sizing_mode="stretch_width")
        self.table = pn.pane.Markdown("", sizing_mode="stretch_width")
        self.run_button.on_click(lambda _: self.run())
        self.choice.param.watch(lambda _: self.run(), "value")
        self.resolution.param.watch(lambda _: self.run(), "value")

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
        first = not self._built
        if first:
            self._build()
        if self._contact is not None:
            with hold():
                self.update_contact(self._contact)
            if first:
                self.run()  # the methods chosen by default, drawn once on opening

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
        job = partial(self._solve_all, generation, self._contact,
                      {name: resolution(name, self.resolution.value) for name in names})
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

    def _solve_all(self, generation: int, c: Contact, resolutions: dict[str, int]) -> None:
        results, errors = [], []
        for name, n in resolutions.items():
            if generation != self._generation:
                return  # a newer request supersedes this one
            try:
                res = numerics.solve(name, c, n)
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
            "color": [STYLE.get(r.method, (OTHER_COLOR,))[0] for r in results],
        }
        self.table.object = ("| method | resolution | max abs(T − T_exact) / T₀ | "
                             "impulse-ratio error | time |\n|---|---|---|---|---|\n"
                             + "\n".join(rows)) if rows else ""
        self.status.object = "\n".join(f"- ⚠ {e}" for e in errors)
        self.progress.param.update(active=False, visible=False)

    # ---------------------------------------------------------- benchmarks

    def speed_accuracy_chart(self) -> list:
        """Time per contact against error (benchmarks/methods.py's chart), one view at a
        time: a selector (all cases, a regime or a case; relative or absolute error),
        the compiled peers with the closed form, the quadrature check, and the numbers
        behind them (speed_accuracy.csv). Empty without the results file."""
        data = speed_accuracy()
        if data is None:
            return []
        chart = speed_accuracy_chart(data, sizing_mode="stretch_width", min_width=300,
                                     peers_height=560, checks_height=320)
        for fig in (chart.peers, chart.checks):
            style_figure(fig)
            fig.legend.label_text_font_size = "11pt"
        view = pn.widgets.Select(label="View (time: median over the cases shown; error: "
                                 "worst)", options=data.keys, value=data.keys[0],
                                 sizing_mode="stretch_width")
        view.param.watch(lambda event: chart.show(event.new), "value")
        self.speed_view, self.speed_chart = view, chart
        return [pn.pane.Markdown("### Speed against accuracy (`benchmarks/methods.py`)"),
                view, pn.pane.Bokeh(chart.peers, sizing_mode="stretch_width"),
                pn.pane.Bokeh(chart.checks, sizing_mode="stretch_width"),
                results_download("speed_accuracy.csv", "CSV: speed against accuracy")]

    def stability_map(self) -> list:
        """The stability map (benchmarks/stability_map.py's) of one method at a time,
        with selectors for the method and the quantity, and the numbers behind it
        (stability_map.csv). Empty without the results file."""
        data = stability()
        if data is None:
            return []
        mapper = error_mapper(data)
        method = pn.widgets.Select(
            label="Method (at its fixed resolution)", sizing_mode="stretch_width",
            options={f"{m} (resolution {data.resolution[m]})": m for m in data.methods},
            value="mdr" if "mdr" in data.methods else data.methods[0])
        quantity = pn.widgets.Select(label="Quantity", options=STABILITY_FIELDS,
                                     sizing_mode="stretch_width")
        fig, source = stability_figure(data, method.value, mapper, quantity.value,
                                       sizing_mode="stretch_width", min_width=300,
                                       height=480, tools="pan,wheel_zoom,reset,save")
        fig.title.text = "Stability map: error over (ψ, τ₀)"
        fig.add_layout(colour_bar(mapper), "right")
        style_figure(fig)

        def redraw(_) -> None:
            source.data = map_cells(data, method.value, quantity.value)

        method.param.watch(redraw, "value")
        quantity.param.watch(redraw, "value")
        self.stability_controls, self.stability_source = (method, quantity), source
        self.stability_plot = fig
        return [pn.pane.Markdown("### Stability map (`benchmarks/stability_map.py`)"),
                pn.Row(method, quantity, sizing_mode="stretch_width"),
                pn.pane.Bokeh(fig, sizing_mode="stretch_width"),
                pn.pane.HTML(STABILITY_NOTE.format(high=data.high),
                             sizing_mode="stretch_width"),
                results_download("stability_map.csv", "CSV: stability map")]

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
            body = [pn.Row(self.choice, self.resolution, self.run_button, self.progress),
                    self.live, self.status, pn.pane.Bokeh(self.figure), self.table,
                    pn.pane.Markdown("Methods: " + "; ".join(
                        f"**{k}**: {v}" for k, v in self.methods.items()))]
        charts = self.speed_accuracy_chart() + self.stability_map()
        return body + (charts or [pn.pane.Markdown(
            "_No benchmark results in app/results._")])
