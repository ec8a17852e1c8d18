"""The "How exact is the model?" card: `BemCard`, a collapsed card built when it is first
opened, over the 3D boundary-element referee of `core.bem` (docs/bem.md).

Inside: at the explorer's contact and time, the referee's traction in the contact plane
(|p_t| as an image with its direction as segments, the stuck elements, p_y) beside the
closed form's (`Contact.traction` on the same elements, the stick disc), T(tau) of both
over the contact, and the closed form's error mapped over nu and beta with the current
contact marked (`app/results/bem_error_map.csv`).  Nothing is computed until "Compute"
is pressed: the run goes to the process's job runner (`app.kit.jobs.RUNNER`) with a
progress bar, at a resolution of bounded cost (`app.bem.data.RESOLUTIONS`; a finer one is
refused with the command line that runs it); the card keeps its last few runs
(`app.bem.data.RunCache`), so a contact met again is shown without running.  After the
contact changes, the result shown says that it is of the previous contact until the
current one is computed.  Named sources: ``bem_referee``, ``bem_closed``, ``bem_stuck``,
``bem_arrows``, ``bem_closed_arrows``, ``bem_circles``, ``bem_T``, ``bem_T_closed``,
``bem_map_nu``, ``bem_map_sweep``, ``bem_map_pairs``, ``bem_map_current``.
"""

from __future__ import annotations

from functools import cache, partial

import numpy as np
import panel as pn
from bokeh.models import (
    ColorBar,
    ColumnDataSource,
    HoverTool,
    Label,
    LinearColorMapper,
    PrintfTickFormatter,
    Span,
)
from bokeh.palettes import RdBu11, Viridis256

from app.bem import data
from app.kit.batch import held
from app.kit.figures import fit_range, new_figure, place_legend, style_figure
from app.kit.jobs import RUNNER
from app.kit.lazy_card import LazyCard
from app.kit.progress import JobProgress
from app.kit.widgets import ERROR_STYLE, text_html
from core import Contact
from core.bem.error_map import SWEEP_NU, MapRow

TITLE = "How exact is the model? The closed form against 3D elasticity (boundary elements)"
INTRO = (
    "The closed form is exact to float64 *within the paper's model*, which neglects the "
    "transverse traction p_y that Poisson's ratio creates (Cattaneo-Mindlin: exact at "
    "ν = 0) and, for dissimilar bodies, the coupling of the normal and tangential problems "
    "(Goodman: exact at Dundurs' β = 0). `core.bem` solves the same loading as a 3D "
    "boundary-element problem without either (docs/bem.md). Press **Compute** to solve "
    "the contact shown above on it (identical spheres: β = 0); the fields follow the "
    "time τ of the explorer.")
MAP_NOTE = (
    "The map: worst |T − T_closed| / T₀ over a contact of the paper's loading ψ = 1 + √2, "
    "τ₀ = π/6, μ = 0.2, on 32 elements across with the grid estimate |32 − 16| as "
    "whiskers (written by `python -m core.bem map --grids 16 32 --steps 200 --csv "
    "benchmarks/results/bem_error_map.csv`); the open markers are the referee's change "
    "from its own run at ν = β = 0 (the model's error with most of the discretisation "
    "error cancelled). The dashed line is 1 % of T₀; the grey line marks the contact "
    "shown (its ν; β = 0 for identical spheres).")
#: Colours: the referee, the closed form, the stick zone.
REFEREE, CLOSED, STICK = "#D55E00", "#000000", "#ffffff"
FIELD_SIZE = 280  # px, each field figure's height (its width: and a colour bar; a phone's 390 px)


@cache
def error_map() -> tuple[MapRow, ...]:
    """The error map's rows, read once per process."""
    return tuple(data.read_map())


def contact_text(c: Contact | data.RunKey) -> str:
    return f"ψ = {c.psi:.4g}, τ₀ = {c.tau0:.4g}, μ = {c.mu:.4g}, ν = {c.nu:.4g}"


class BemCard(pn.viewable.Viewer):
    """The card, showing contact `contact` at time `tau` (`update` follows the page)."""

    def __init__(self, contact: Contact, tau: float, **params) -> None:
        super().__init__(**params)
        self.contact, self.tau = contact, tau
        self.cache = data.RunCache()
        self.result: data.Referee | None = None  # the run shown
        self._requests = 0  # a result is shown only if it is the newest request's
        self._closed = False
        self._shown_step: tuple[data.RunKey, int] | None = None
        self.sources = {name: ColumnDataSource(columns, name=f"bem_{name}") for name, columns in {
            "referee": {"pt": [], "py": [], "x": [], "y": [], "dw": []},
            "closed": {"pt": [], "x": [], "y": [], "dw": []},
            "stuck": {"x": [], "y": [], "h": []},
            "arrows": {"x0": [], "y0": [], "x1": [], "y1": []},
            "closed_arrows": {"x0": [], "y0": [], "x1": [], "y1": []},
            "circles": {"x": [], "y": [], "r": []},
            "T": {"tau": [], "T": [], "dT": []},
            "T_closed": {"tau": [], "T": []},
            "map_nu": {}, "map_sweep": {}, "map_pairs": {},
            "map_current": {"nu": [], "err": []},
        }.items()}
        self.lazy = LazyCard(TITLE, self._build, self._on_opened)
        self.card = self.lazy.card

    def __panel__(self) -> pn.Card:
        return self.card

    @property
    def built(self) -> bool:
        """Whether the card's content exists (it has been opened)."""
        return self.lazy.built

    def _on_opened(self, first: bool) -> None:
        if first:
            self._show_map_mark()
            self._show_status()

    def close(self) -> None:
        """The session ended: drop the waiting run; ask for nothing more."""
        self._closed = True
        RUNNER.cancel(self)

    # ------------------------------------------------------------------ build

    def _build(self) -> list:
        options = {f"{r.label} (a few seconds)": r for r in data.RESOLUTIONS}
        big = data.COMMAND_LINE_ONLY
        options[f"{big.label} (command line only)"] = big
        self.resolution = pn.widgets.Select(label="Resolution", options=options,
                                            value=data.RESOLUTIONS[0], width=380)
        self.compute_button = pn.widgets.Button(label="Compute", color="primary",
                                                width=120)
        self.compute_button.on_click(lambda _: self.compute())
        self.resolution.param.watch(lambda _: self._show_status(), "value")
        self.progress = JobProgress(width=200)
        self.status = pn.pane.HTML("", sizing_mode="stretch_width", name="bem_status")
        self.message = pn.pane.HTML("", sizing_mode="stretch_width", styles=ERROR_STYLE,
                                    name="bem_message")
        self.readout = pn.pane.HTML("", sizing_mode="stretch_width", name="bem_readout")
        self.pt_mapper = LinearColorMapper(palette=Viridis256, low=0.0, high=1.0)
        self.py_mapper = LinearColorMapper(palette=tuple(reversed(RdBu11)), low=-0.05,
                                           high=0.05)
        self.fields = [self._field_figure("referee", "Referee: |p_t| / (μp*), stick zone",
                                          "pt", self.pt_mapper, "arrows", stuck=True),
                       self._field_figure("closed", "Closed form: |p_t| / (μp*), stick disc",
                                          "pt", self.pt_mapper, "closed_arrows"),
                       self._field_figure("referee", "Referee: p_y / (μp*) (closed form: 0)",
                                          "py", self.py_mapper, None)]
        self.force_figure = self._force_figure()
        self.map_figures = self._map_figures()
        return [
            pn.pane.Markdown(INTRO, sizing_mode="stretch_width"),
            pn.Row(self.resolution, self.compute_button, self.progress),
            self.message, self.status, self.readout,
            pn.FlexBox(*(pn.pane.Bokeh(f) for f in self.fields), sizing_mode="stretch_width"),
            pn.pane.Bokeh(self.force_figure, sizing_mode="stretch_width"),
            pn.pane.Bokeh(self.diff_figure, sizing_mode="stretch_width"),
            pn.FlexBox(*(pn.pane.Bokeh(f) for f in self.map_figures),
                       sizing_mode="stretch_width"),
            pn.pane.Markdown(MAP_NOTE, sizing_mode="stretch_width",
                             styles={"font-size": "0.9em"}),
        ]

    def _field_figure(self, source: str, title: str, column: str,
                      mapper: LinearColorMapper, arrows: str | None, stuck: bool = False):
        fig = new_figure(title, "x / a* (along the drive)", "y / a*", sizing_mode="fixed",
                         width=FIELD_SIZE + 90, height=FIELD_SIZE, min_width=None,
                         match_aspect=True)
        fit_range(fig.x_range, [-1.1, 1.1], pad=0.0)
        fit_range(fig.y_range, [-1.1, 1.1], pad=0.0)
        fig.image(image=column, x="x", y="y", dw="dw", dh="dw", color_mapper=mapper,
                  source=self.sources[source])
        if arrows is not None:
            fig.segment("x0", "y0", "x1", "y1", source=self.sources[arrows],
                        color=STICK, line_width=1.2, alpha=0.8)
        if stuck:
            fig.rect("x", "y", width="h", height="h", source=self.sources["stuck"],
                     fill_alpha=0.0, line_color=STICK, line_width=1.5)
        fig.circle("x", "y", radius="r", source=self.sources["circles"], fill_alpha=0.0,
                   line_color=STICK if not stuck else "#dddddd", line_dash="dashed",
                   line_width=1.5)
        fig.add_layout(ColorBar(color_mapper=mapper, width=12), "right")
        style_figure(fig)
        fig.title.text_font_size = "11pt"
        return fig

    def _force_figure(self):
        fig = new_figure("T / T₀ over the contact: referee and closed form", "τ = ωt (rad)",
                         "T / T₀", height=300)
        fig.line("tau", "T", source=self.sources["T_closed"], color=CLOSED, line_width=4,
                 alpha=0.35, legend_label="closed form")
        fig.scatter("tau", "T", source=self.sources["T"], color=REFEREE, size=4,
                    legend_label="referee (boundary elements)")
        self.tau_mark = Span(location=self.tau, dimension="height", line_color="#777777",
                             line_dash="dotted", line_width=1.5)
        fig.add_layout(self.tau_mark)
        fig.legend.location = "bottom_left"
        style_figure(fig)
        diff = new_figure("The referee's T minus the closed form's", "τ = ωt (rad)",
                          "(T − T_closed) / T₀", height=220, x_range=fig.x_range)
        diff.line("tau", "dT", source=self.sources["T"], color=REFEREE, line_width=1.5)
        diff.scatter("tau", "dT", source=self.sources["T"], color=REFEREE, size=3)
        self.diff_mark = Span(location=self.tau, dimension="height", line_color="#777777",
                              line_dash="dotted", line_width=1.5)
        diff.add_layout(self.diff_mark)
        diff.yaxis.formatter = PrintfTickFormatter(format="%.1e")
        style_figure(diff)
        diff.title.text_font_size = "12pt"
        self.diff_figure = diff
        return fig

    def _map_figures(self) -> list:
        columns = data.map_columns(list(error_map()))
        for name in ("nu", "sweep", "pairs"):
            self.sources[f"map_{name}"].data = columns[name]
        figs = []
        for title, x_label, parts in (
                ("Identical bodies: the error over ν", "ν", (("nu", "identical bodies"),)),
                ("Dissimilar bodies: the error over β", "Dundurs' β",
                 (("sweep", f"β sweep (ν = {SWEEP_NU:g})"),
                  ("pairs", "core.MOTOR_MATERIALS pairs")))):
            fig = new_figure(title, x_label, "worst |T − T_closed| / T₀", y_axis_type="log",
                             height=340, tools="pan,wheel_zoom,reset,save")
            xs = np.concatenate([columns[p]["x"] for p, _ in parts])
            fit_range(fig.x_range, xs, [0.0])
            fit_range(fig.y_range, [1e-6, 0.03], pad=0.0)
            markers = []
            for (part, label), colour, marker in zip(parts, ("#0072B2", "#009E73"),
                                                     ("circle", "square"), strict=False):
                src = self.sources[f"map_{part}"]
                fig.segment("x", "lo", "x", "hi", source=src, color=colour, line_width=1.5)
                markers.append(fig.scatter("x", "err", source=src, color=colour, size=8,
                                           marker=marker, legend_label=label))
                short = label.split(" (")[0]
                fig.scatter("x", "model", source=src, line_color=colour, fill_color=None,
                            size=8, marker=marker, legend_label=f"{short}: vs ν = β = 0")
            fig.add_tools(HoverTool(renderers=markers, tooltips=[
                ("pair", "@label"), ("error", "@err{0.0e} T₀"), ("vs ν = β = 0",
                                                                 "@model{0.0e} T₀")]))
            fig.add_layout(Span(location=data.LEVEL, dimension="width", line_color="#a4161a",
                                line_dash="dashed", line_width=1.5))
            fig.add_layout(Label(x=float(xs.min()), y=data.LEVEL, text="1 % of T₀",
                                 text_color="#a4161a", text_font_size="10pt", y_offset=3))
            mark = Span(location=0.0, dimension="height", line_color="#777777",
                        line_width=2, line_alpha=0.7)
            fig.add_layout(mark)
            figs.append(fig)
            if x_label == "ν":
                self.nu_mark = mark
                fig.scatter("nu", "err", source=self.sources["map_current"], marker="star",
                            size=16, color="#777777", legend_label="the contact shown")
        for fig in figs:
            style_figure(fig)
            place_legend(fig, fig.legend[0], "below")
            fig.legend.update(label_text_font_size="10pt", ncols=2)
        return figs

    # ----------------------------------------------------------------- follow

    def update(self, contact: Contact, tau: float) -> None:
        """The page shows `contact` at `tau`: the card follows (while it is built), a
        contact met before is shown from the cache, nothing is computed."""
        self.contact, self.tau = contact, tau
        if not self.built:
            return
        with held():
            result = self.result
            if result is None or not result.key.same_contact(contact):
                cached = self._cached()
                if cached is not None:
                    self._show(cached)
                    return
            self._show_map_mark()
            if result is not None and result.key.same_contact(contact):
                self._show_fields(result)
            self._show_status()

    def _cached(self) -> data.Referee | None:
        try:
            return self.cache.get(data.request(self.contact, self.resolution.value))
        except ValueError:
            return None

    # ---------------------------------------------------------------- compute

    def compute(self) -> None:
        """Compute the contact shown at the chosen resolution on the job runner (shown
        at once if the card has it); a refused request says why."""
        if self._closed:
            return
        try:
            key = data.request(self.contact, self.resolution.value)
        except ValueError as err:
            self.message.object = text_html(f"⚠ {err}")
            return
        self.message.object = ""
        self._requests += 1
        cached = self.cache.get(key)
        if cached is not None:
            self.progress.busy = False
            self._show(cached)
            return
        self.progress.busy = True
        self.status.object = text_html(f"computing the referee on {self.resolution.value.label}"
                                       f" ({contact_text(key)})…")
        RUNNER.submit(self, partial(data.compute, key), partial(self._done, self._requests))

    def _done(self, request: int, outcome: data.Referee | Exception) -> None:
        """A run's outcome (on the session's loop): kept, and shown if it is the newest
        request's; the progress bar ends then, whatever the outcome."""
        if not isinstance(outcome, Exception):
            self.cache.put(outcome)
        if request != self._requests:
            return
        with held():
            self.progress.busy = False
            if isinstance(outcome, Exception):
                self.message.object = text_html(f"⚠ the referee could not run: {outcome}")
                self._show_status()
                return
            self._show(outcome)

    # ------------------------------------------------------------------- show

    def _show(self, run: data.Referee) -> None:
        """Show `run`: its fields at the page's tau, T(tau), the status."""
        self.result = run
        with held():
            forces = data.force_columns(run)
            self.sources["T"].data = forces["referee"]
            self.sources["T_closed"].data = forces["closed"]
            fig = self.force_figure
            fit_range(fig.x_range, forces["closed"]["tau"], pad=0.02)
            fit_range(fig.y_range, forces["closed"]["T"], forces["referee"]["T"])
            fit_range(self.diff_figure.y_range, forces["referee"]["dT"])
            self._shown_step = None
            self._show_fields(run)
            self._show_map_mark()
            self._show_status()

    def _show_fields(self, run: data.Referee) -> None:
        """The fields of `run` at its step nearest the page's tau (once per step)."""
        k = data.step_at(run, self.tau)
        if self._shown_step == (run.key, k):
            return
        self._shown_step = (run.key, k)
        f = data.field_columns(run, self.tau)
        with held():
            for name in ("referee", "closed", "stuck", "circles"):
                self.sources[name].data = f[name]
            self.sources["arrows"].data = f["referee_arrows"]
            self.sources["closed_arrows"].data = f["closed_arrows"]
            high = max(float(np.max(f["referee"]["pt"][0])),
                       float(np.max(f["closed"]["pt"][0])), 1e-12)
            self.pt_mapper.high = high
            py = max(float(np.abs(f["referee"]["py"][0]).max()), 1e-6)
            self.py_mapper.update(low=-py, high=py)
            self.tau_mark.location = self.diff_mark.location = f["readout"]["tau"]
            self.readout.object = readout_html(f["readout"])

    def _show_map_mark(self) -> None:
        """The contact's nu on the map (sent only when it changes)."""
        nu = self.contact.nu
        if self.nu_mark.location == nu and self.sources["map_current"].data["nu"]:
            return
        inside = data.NU_RANGE.contains(nu)
        self.nu_mark.location = nu
        self.sources["map_current"].data = {
            "nu": [nu] if inside else [],
            "err": [data.map_at(list(error_map()), nu)] if inside else []}

    def _show_status(self) -> None:
        """What the result shown is: none yet, of the previous contact, or this one's
        (while a run is on its way, the status says so until it arrives)."""
        run, c = self.result, self.contact
        if self.progress.busy:
            return
        if run is None:
            text = (f"Nothing computed yet: press Compute to solve the contact shown "
                    f"({contact_text(c)}) on the referee.")
        elif not run.key.same_contact(c):
            text = (f"⚠ This result is of the previous contact ({contact_text(run.key)}), "
                    f"not of the one shown ({contact_text(c)}): press Compute for it.")
        else:
            text = (f"The referee on {run.key.grid} elements across and {run.key.steps} time "
                    f"steps ({run.seconds:.1f} s): worst |T − T_closed| over the contact "
                    f"{run.worst_T_error:.2g} T₀ (the model's error and the referee's "
                    f"discretisation error together; docs/bem.md).")
        self.status.object = text_html(text)


def readout_html(r: dict) -> str:
    """The numbers at the time shown (`app.bem.data.field_columns`' readout)."""
    return text_html(
        f"At τ = {r['tau']:.4f} rad (the run's time step nearest the explorer's τ): "
        f"T / T₀ = {r['T']:.5f} (referee), {r['T_closed']:.5f} (closed form); transverse "
        f"T_y / T₀ = {r['Ty']:.2e}; stick radius (equal area) {r['stick']:.3f} a* "
        f"(referee), {r['stick_closed']:.3f} a* (closed form).")
