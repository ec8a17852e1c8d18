"""The Methods card: numerical methods of `core.numerics` against the closed form.

T(tau) of the chosen methods is overlaid on core's T(tau), each with its live error
(`app.methods.data`).  The card is collapsed: its plots and charts are built when it is
first opened, and nothing is computed while it is closed.  Solving runs on the process's
job runner (`app.kit.jobs.RUNNER`: one waiting job per card, cards served in turn), with
a progress bar that every outcome clears; only the newest request's result is shown, and
a closed card (its session ended) asks for nothing more.  The speed-accuracy chart and
the stability map come from the app's `results/*.csv`, read once per process; their
downloads carry the explorer's header block (`app.methods.results`).
"""

from __future__ import annotations

import io
from functools import cache, partial

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource

import app.methods.data as data
from app.kit.batch import held
from app.kit.figures import CURVE_POINTS, fit_range, new_figure, style_figure
from app.kit.jobs import RUNNER
from app.kit.lazy_card import LazyCard
from app.kit.progress import JobProgress
from app.kit.widgets import LabelledCheckbox, text_html
from app.methods.results import RESULTS, download_text, read_rows
from app.methods.speed_chart import STYLE, SpeedAccuracyData, speed_accuracy_chart
from app.methods.speed_chart import speed_accuracy_data as speed_views
from app.methods.stability_chart import (
    STABILITY_FIELDS,
    STABILITY_NOTE,
    StabilityData,
    colour_bar,
    error_mapper,
    map_cells,
    stability_data,
    stability_figure,
)
from core import Contact

#: The colour of a method the charts have no style for.
OTHER_COLOR = "#882255"


@cache
def speed_accuracy() -> SpeedAccuracyData | None:
    """The views of speed_accuracy.csv, once per process (None if the file is absent)."""
    path = RESULTS / "speed_accuracy.csv"
    return speed_views(read_rows(path)) if path.is_file() else None


@cache
def stability() -> StabilityData | None:
    """The cells of stability_map.csv, once per process (None if the file is absent)."""
    path = RESULTS / "stability_map.csv"
    return stability_data(read_rows(path)) if path.is_file() else None


def results_download(name: str, label: str) -> pn.widgets.FileDownload:
    """A button that downloads results file `name` with its header block."""
    return pn.widgets.FileDownload(
        callback=lambda: io.BytesIO(download_text(name).encode("utf-8")),
        filename=name, label=label, width=260)


def heading(title: str, script: str) -> pn.pane.HTML:
    """A chart's heading naming the benchmark script that wrote its data (as code, not
    as a link: the script is in the repository, not on this server)."""
    return pn.pane.HTML(f"<h3>{title} (written by <code>{script}</code>)</h3>",
                        sizing_mode="stretch_width")


class MethodsScene:
    """Live comparison of numerical methods with the closed form, plus benchmark charts."""

    def __init__(self) -> None:
        self.methods = data.available_methods()
        self.source = ColumnDataSource({"xs": [], "ys": [], "label": [], "color": []},
                                       name="methods")
        self.exact = ColumnDataSource({"tau": [], "T": []}, name="methods_exact")
        self._closed = False
        #: how many runs were asked for: a result is shown only if it is the newest's
        self._requests = 0
        self._contact: Contact | None = None
        self.results: list = []
        # collapsed by default; while collapsed nothing here is built, computed or sent
        # (a hidden plot whose data changes also makes the browser lay out the page
        # again): the controls and the plot are built when the card is first opened
        self.lazy = LazyCard("Methods: numerical schemes against the closed form",
                             self._build, self._on_opened)
        self.card = self.lazy.card

    def _build(self) -> list:
        """The controls and the overlay plot (on the card's first opening): the card's
        objects."""
        self.choice = pn.widgets.MultiChoice(
            label="Methods", options=list(self.methods),
            value=[m for m in data.DEFAULT_METHODS if m in self.methods],
            # (the placeholder names the search box: without one, BokehJS's Choices
            # gives it aria-label="null")
            placeholder="Add a method", sizing_mode="stretch_width")
        self.live = LabelledCheckbox(label="Recompute live on every change", value=False)
        self.resolution = pn.widgets.Select(
            label="Resolution", options=data.RESOLUTION_FACTORS, value=1.0, width=200)
        self.run_button = pn.widgets.Button(label="Run methods", color="primary", width=140)
        self.progress = JobProgress(width=200)
        self.status = pn.pane.HTML("", sizing_mode="stretch_width", name="methods_status")
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
        return self._body()

    @property
    def opened(self) -> bool:
        """Whether the scene is expanded (the closed form and live runs follow the
        parameters only then)."""
        return self.lazy.opened

    def _on_opened(self, first: bool) -> None:
        """Catch up with the parameters; on the first opening, run the methods chosen
        by default (drawn once)."""
        if self._contact is not None:
            self.update_contact(self._contact)
            if first:
                self.run()

    def close(self) -> None:
        """The session ended: drop the waiting run; ask for nothing more."""
        self._closed = True
        RUNNER.cancel(self)

    # ------------------------------------------------------------- live runs

    def update_contact(self, c: Contact) -> None:
        """New parameters: redraw the closed form; rerun the methods if live (only
        while the scene is shown; expanding it catches up)."""
        self._contact = c
        if not self.opened:
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
        """Solve the chosen methods for the current contact on the job runner (a newer
        run replaces a waiting one); the result is shown when it arrives."""
        if not self.methods or self._contact is None or self._closed:
            return
        self._requests += 1
        names = list(self.choice.value)
        self.progress.busy = True
        self.status.object = text_html(f"computing {', '.join(names) or 'nothing'}…")
        resolutions = {name: data.resolution(name, self.resolution.value) for name in names}
        RUNNER.submit(self, partial(data.solve_all, self._contact, resolutions),
                      partial(self._done, self._requests))

    def _done(self, request: int, outcome: data.Run | Exception) -> None:
        """A run's outcome (on the session's loop): shown if it is the newest request's;
        the progress bar and status end then, whatever the outcome."""
        if request != self._requests:
            return  # a newer run is on its way
        with held():
            self.progress.busy = False
            if isinstance(outcome, Exception):
                self.status.object = text_html(f"⚠ the methods could not run: {outcome}")
                return
            self.results = list(outcome.results)
            self.source.data = {
                "xs": [np.asarray(r.tau, float) for r in outcome.results],
                "ys": [np.asarray(r.T, float) for r in outcome.results],
                "label": [r.method for r in outcome.results],
                "color": [STYLE.get(r.method, (OTHER_COLOR,))[0] for r in outcome.results],
            }
            self.table.object = data.table(outcome)
            self.status.object = "<br>".join(text_html(f"⚠ {e}") for e in outcome.errors)

    # ---------------------------------------------------------- benchmarks

    def speed_accuracy_chart(self) -> list:
        """Time per contact against error (benchmarks/core/methods.py's chart), one view
        at a time: a selector (all cases, a regime or a case; relative or absolute
        error), the compiled peers with the closed form, the quadrature check, and the
        numbers behind them (speed_accuracy.csv). Empty without the results file."""
        views = speed_accuracy()
        if views is None:
            return []
        chart = speed_accuracy_chart(views, sizing_mode="stretch_width", min_width=300,
                                     peers_height=560, checks_height=320)
        for fig in (chart.peers, chart.checks):
            style_figure(fig)
            fig.legend.label_text_font_size = "11pt"
        view = pn.widgets.Select(label="View (time: median over the cases shown; error: "
                                 "worst)", options=views.keys, value=views.keys[0],
                                 sizing_mode="stretch_width")
        view.param.watch(lambda event: chart.show(event.new), "value")
        self.speed_view, self.speed_chart = view, chart
        return [heading("Speed against accuracy", "benchmarks/core/methods.py"),
                view, pn.pane.Bokeh(chart.peers, sizing_mode="stretch_width"),
                pn.pane.Bokeh(chart.checks, sizing_mode="stretch_width"),
                results_download("speed_accuracy.csv", "CSV: speed against accuracy")]

    def stability_map(self) -> list:
        """The stability map (benchmarks/core/stability_map.py's) of one method at a
        time, with selectors for the method and the quantity, and the numbers behind it
        (stability_map.csv). Empty without the results file."""
        cells = stability()
        if cells is None:
            return []
        mapper = error_mapper(cells)
        method = pn.widgets.Select(
            label="Method (at its fixed resolution)", sizing_mode="stretch_width",
            options={f"{m} (resolution {cells.resolution[m]})": m for m in cells.methods},
            value="mdr" if "mdr" in cells.methods else cells.methods[0])
        quantity = pn.widgets.Select(label="Quantity", options=STABILITY_FIELDS,
                                     sizing_mode="stretch_width")
        fig, source = stability_figure(cells, method.value, mapper, quantity.value,
                                       sizing_mode="stretch_width", min_width=300,
                                       height=480, tools="pan,wheel_zoom,reset,save")
        fig.title.text = "Stability map: error over (ψ, τ₀)"
        fig.add_layout(colour_bar(mapper), "right")
        style_figure(fig)

        def redraw(_) -> None:
            source.data = map_cells(cells, method.value, quantity.value)

        method.param.watch(redraw, "value")
        quantity.param.watch(redraw, "value")
        self.stability_controls, self.stability_source = (method, quantity), source
        self.stability_plot = fig
        return [heading("Stability map", "benchmarks/core/stability_map.py"),
                pn.Row(method, quantity, sizing_mode="stretch_width"),
                pn.pane.Bokeh(fig, sizing_mode="stretch_width"),
                pn.pane.HTML(STABILITY_NOTE.format(high=cells.high),
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
