"""The Motor card's design map (`MapCard`, a sub-card built when first opened): a Bokeh
image of a figure of merit over two of the card's inputs around its current design, a
hover with every merit of the design under the pointer, the current design marked, the
Pareto front of two merits beside it, and a click that loads a design into the card.

The map's data are `app.motor.map_data`'s: computed on the process's job runner
(`app.kit.jobs.RUNNER`, one job per block of a few rows, submitted in turn, so that the
runner's turns between sessions come between a map's blocks; a newer map replaces the
block waiting), kept in
the card's `MapCache` so that a map already computed (e.g. after a click loaded one of
its designs) is shown at once. Sizes beyond `map_data.SIZE_MAX` are refused with a
message naming the design study's command line. A click goes through the card's own
validation (`app.motor.fields.check`): a refused design says why and changes nothing.
"""

from __future__ import annotations

import html
from functools import partial
from typing import Any

import numpy as np
import panel as pn
import param
from bokeh.events import Tap
from bokeh.models import ColorBar, ColumnDataSource, HoverTool, LinearColorMapper
from bokeh.palettes import Viridis256

import app.motor.map_data as md
from app.kit.a11y import expandable_card
from app.kit.batch import held
from app.kit.figures import fit_range, new_figure, style_figure
from app.kit.jobs import RUNNER
from app.kit.progress import CSS, HIDDEN, SHOWN
from app.kit.widgets import ERROR_STYLE, text_html
from app.motor.fields import FIELDS, check
from app.motor.state import MotorState

#: The state's inputs a map depends on.
INPUTS = (*FIELDS, "rod_material", "flat")
#: The front's merits at first (the trade-off of a standing-wave motor).
FRONT_DEFAULT = ("stall_thrust", "best_efficiency")
#: Columns of the map's image source beside the merits: each pixel's design (axes).
AX, AY = "ax", "ay"


class MapProgressBar(pn.viewable.Viewer):
    """The map's progress bar: the designs done of the map's designs, shown while
    `busy` and hidden by its host's style otherwise (as `app.kit.progress.JobProgress`,
    so that nothing around it moves)."""

    busy = param.Boolean(default=False, doc="a map's blocks are being computed")
    done = param.Integer(default=0, bounds=(0, None), doc="designs done")
    total = param.Integer(default=1, bounds=(1, None), doc="designs of the map")

    def __init__(self, width: int = 180) -> None:
        super().__init__()
        self._bar = pn.indicators.Progress(value=0, max=1, active=False, width=width,
                                           css_classes=["motor-map-progress"],
                                           styles=HIDDEN, stylesheets=[CSS])

    def __panel__(self) -> pn.indicators.Progress:
        return self._bar

    def show(self, progress: md.MapProgress) -> None:
        """Show how far the map is (`map_data.MapProgress`)."""
        self.param.update(busy=True, total=progress.designs, done=progress.designs_done)

    @param.depends("busy", "done", "total", watch=True)
    def _draw(self) -> None:
        self._bar.param.update(max=self.total, value=self.done,
                               styles=SHOWN if self.busy else HIDDEN)


def merit_label(name: str) -> str:
    """'stall thrust (mN)'."""
    label, unit, _ = md.SHOWN[name]
    return f"{label} ({unit})"


def tooltips(x: str, y: str) -> list[tuple[str, str]]:
    """The hover's lines: the design's two axes, then every merit."""
    return [(FIELDS[x].title(), f"@{AX}{{%.5g}}"), (FIELDS[y].title(), f"@{AY}{{%.5g}}"),
            *((merit_label(n), f"@{n}{{%.4g}}") for n in md.SHOWN)]


class DesignMap(pn.viewable.Viewer):
    """The map of `state`'s neighbourhood: choose the axes, the merit shown, the size and
    the front's merits; a click on the map loads that design into `state`. Call
    `close()` when the session ends."""

    active = param.Boolean(default=True, doc="the map is on screen: it follows the state")

    def __init__(self, state: MotorState, cache: md.MapCache | None = None) -> None:
        super().__init__()
        self.state = state
        self.cache = cache or md.MapCache()
        #: the map requested last (None: refused) and the map on screen
        self.request: md.MapRequest | None = None
        self.data: md.MapData | None = None
        #: the map whose blocks are being computed, and its chain's token (None: none)
        self._computing: tuple[md.MapRequest, object] | None = None
        self._closed = False
        self._widgets()
        self._figures()
        self.state.param.watch(self._on_state, list(INPUTS))
        self.refresh()

    # -------------------------------------------------------------- widgets

    def _widgets(self) -> None:
        axes = {FIELDS[n].title(): n for n in md.AXES}
        merits = {merit_label(n): n for n in md.SHOWN}

        def select(label: str, options: dict[str, str], value: str) -> pn.widgets.Select:
            w = pn.widgets.Select(label=label, options=options, value=value, width=230)
            return w

        self.x_select = select("Map's x axis", axes, "x0")
        self.y_select = select("Map's y axis", axes, "N")
        self.merit_select = select("Colour: figure of merit", merits, "stall_thrust")
        self.front_x = select("Front's x merit", merits, FRONT_DEFAULT[0])
        self.front_y = select("Front's y merit", merits, FRONT_DEFAULT[1])
        self.size_input = pn.widgets.TextInput(
            label=f"Points per axis (at most {md.SIZE_MAX})", value=str(md.SIZE_DEFAULT),
            width=230, css_classes=["motor-map-size"])
        for w in (self.x_select, self.y_select, self.size_input):
            w.param.watch(lambda e: self.refresh(), "value")
        self.merit_select.param.watch(lambda e: self.show(), "value")
        for w in (self.front_x, self.front_y):
            w.param.watch(lambda e: self.show_front(), "value")
        self.progress = MapProgressBar(width=180)
        self.status = pn.pane.HTML("", name="motor_map_status", sizing_mode="stretch_width")
        self.message = pn.pane.HTML("", name="motor_map_message", visible=False,
                                    styles=ERROR_STYLE, sizing_mode="stretch_width")

    def _figures(self) -> None:
        self.source = ColumnDataSource(name="motor_map", data={
            "image": [], "x": [], "y": [], "dw": [], "dh": [], AX: [], AY: [],
            **{n: [] for n in md.SHOWN}})
        self.mark = ColumnDataSource(name="motor_map_mark", data={"x": [], "y": []})
        self.mapper = LinearColorMapper(palette=Viridis256, nan_color="#d9d9d9")
        fig = self.figure = new_figure("Design map", "", "", height=420,
                                       tools="pan,wheel_zoom,reset,save")
        image = fig.image(image="image", x="x", y="y", dw="dw", dh="dh", source=self.source,
                          color_mapper=self.mapper)
        self.hover = HoverTool(renderers=[image], tooltips=[], formatters={
            f"@{n}": "printf" for n in (AX, AY, *md.SHOWN)})
        fig.add_tools(self.hover)
        fig.scatter("x", "y", source=self.mark, marker="circle_cross", size=16,
                    fill_alpha=0.0, line_color="#e41a1c", line_width=3)
        self.colorbar = ColorBar(color_mapper=self.mapper, title="", width=14)
        fig.add_layout(self.colorbar, "right")
        fig.on_event(Tap, self._on_tap)
        self.designs = ColumnDataSource(name="motor_map_designs", data={"a": [], "b": []})
        self.front = ColumnDataSource(name="motor_map_front", data={
            "a": [], "b": [], AX: [], AY: []})
        pf = self.front_figure = new_figure("Pareto front of the map's designs", "", "",
                                            height=420)
        pf.scatter("a", "b", source=self.designs, size=4, color="#9e9e9e", alpha=0.6)
        pf.line("a", "b", source=self.front, color="#e41a1c", line_width=2)
        dots = pf.scatter("a", "b", source=self.front, size=8, color="#e41a1c")
        self.front_hover = HoverTool(renderers=[dots], tooltips=[])
        pf.add_tools(self.front_hover)
        for f in (fig, pf):
            style_figure(f)

    def __panel__(self) -> pn.viewable.Viewable:
        controls = pn.Column(self.x_select, self.y_select, self.size_input, self.merit_select,
                             self.front_x, self.front_y, pn.Row(self.progress), self.status,
                             self.message, styles={"flex": "0 0 250px"})
        plots = [pn.pane.Bokeh(f, sizing_mode="stretch_width",
                               styles={"flex": "1 1 420px", "min-width": "0"})
                 for f in (self.figure, self.front_figure)]
        return pn.FlexBox(controls, *plots, sizing_mode="stretch_width")

    # -------------------------------------------------------------- requests

    def show_message(self, text: str) -> None:
        """Show `text` (as text, never markup); '' hides it."""
        self.message.param.update(object=html.escape(text), visible=bool(text))

    def _on_state(self, *events: param.parameterized.Event) -> None:
        self._show_mark()
        self.refresh()

    @param.depends("active", watch=True)
    def _on_active(self) -> None:
        if self.active:
            self.refresh()

    def refresh(self) -> None:
        """Show the map of the state and the widgets' choices: at once if computed, else
        ask the runner for it (a newer request replaces a waiting one)."""
        if self._closed or not self.active:
            return
        try:
            request = md.MapRequest.of(self.state.values(), self.x_select.value,
                                       self.y_select.value, self.size_input.value)
        except ValueError as err:
            self.show_message(str(err))
            return
        self.show_message("")
        self.request = request
        data = self.cache.get(request)
        if data is not None:
            if self._computing is not None:  # another map's blocks end here
                self._computing = None
                RUNNER.cancel(self)
            self.progress.busy = False
            self.show(data)
            return
        if self._computing is not None and self._computing[0] == request:
            return  # its blocks are on their way
        self._computing = (request, object())
        self._submit(self._computing, md.blocks(request), [])

    def _submit(self, chain: tuple[md.MapRequest, object], todo: list[md.MapBlock],
                parts: list[md.MapData]) -> None:
        """Ask the runner for the next block of the map (one job; a newer map's first
        block replaces it while it waits), saying how far the map is (the bar: designs
        done; the status: the block running)."""
        progress = md.MapProgress.of(chain[0], todo)
        self.progress.show(progress)
        self.status.object = text_html(progress.status())
        RUNNER.submit(self, partial(md.compute, todo[0]),
                      partial(self._done, chain, todo, parts))

    def _done(self, chain: tuple[md.MapRequest, object], todo: list[md.MapBlock],
              parts: list[md.MapData], outcome: md.MapData | Exception) -> None:
        if chain is not self._computing or self._closed:
            return  # a newer map is on its way, or the session ended: no more blocks
        if isinstance(outcome, Exception):
            self._computing = None
            self.progress.busy = False
            self.status.object = text_html(f"⚠ could not compute the map: {outcome}")
            return
        parts = [*parts, outcome]
        if len(todo) > 1:
            self._submit(chain, todo[1:], parts)
            return
        self._computing = None
        data = md.assemble(chain[0], parts)
        self.cache.put(data)
        self.progress.busy = False
        self.show(data)

    def close(self) -> None:
        """The session ended: drop the waiting map; ask for nothing more."""
        self._closed = True
        self._computing = None
        RUNNER.cancel(self)

    # -------------------------------------------------------------- drawing

    def show(self, data: md.MapData | None = None) -> None:
        """Draw map `data` (default: the one on screen) coloured by the chosen merit."""
        data = data or self.data
        if data is None:
            return
        self.data = data
        x, y, merit = data.request.x, data.request.y, self.merit_select.value
        X, Y = np.meshgrid(data.x, data.y)
        dx, dy = np.ptp(data.x) / (data.x.size - 1), np.ptp(data.y) / (data.y.size - 1)
        left, bottom = data.x[0] - 0.5 * dx, data.y[0] - 0.5 * dy
        image = data.image(merit)
        finite = image[np.isfinite(image)]
        with held():
            self.source.data = {
                "image": [image], "x": [left], "y": [bottom], "dw": [dx * data.x.size],
                "dh": [dy * data.y.size], AX: [X], AY: [Y],
                **{n: [data.image(n)] for n in md.SHOWN}}
            lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (0, 1)
            self.mapper.update(low=lo, high=hi if hi > lo else lo + 1.0)
            self.colorbar.title = merit_label(merit)
            f = self.figure
            f.x_range.start, f.x_range.end = left, left + dx * data.x.size
            f.y_range.start, f.y_range.end = bottom, bottom + dy * data.y.size
            f.xaxis.axis_label, f.yaxis.axis_label = FIELDS[x].title(), FIELDS[y].title()
            f.title.text = f"Design map: {md.SHOWN[merit][0]}"
            self.hover.tooltips = tooltips(x, y)
            self._show_mark()
            self.show_front()
        n, ok = image.size, int(np.isfinite(data.merits["stall_thrust"]).sum())
        self.status.object = text_html(
            f"{data.x.size} × {data.y.size} map: {ok} of {n} designs in the model's range "
            "(grey: the contact never opens or the card refuses the design). Click a "
            "design to load it into the card.")

    def _show_mark(self) -> None:
        d = self.data
        if d is None:
            return
        self.mark.data = {"x": [getattr(self.state, d.request.x)],
                          "y": [getattr(self.state, d.request.y)]}

    def show_front(self) -> None:
        """The Pareto front of the two chosen merits over the map's designs."""
        d = self.data
        if d is None:
            return
        a_name, b_name = self.front_x.value, self.front_y.value
        a, b = d.image(a_name), d.image(b_name)
        if a_name == b_name:
            self.show_message("the Pareto front needs two different merits")
            index: list[tuple[int, int]] = []
        else:
            index = md.pareto_front(d, a_name, b_name)
        rows = [j for j, _ in index]
        cols = [i for _, i in index]
        ok = np.isfinite(a) & np.isfinite(b)
        with held():
            self.designs.data = {"a": a[ok], "b": b[ok]}
            self.front.data = {"a": a[rows, cols], "b": b[rows, cols],
                               AX: d.x[cols], AY: d.y[rows]}
            pf = self.front_figure
            pf.xaxis.axis_label, pf.yaxis.axis_label = merit_label(a_name), merit_label(b_name)
            fit_range(pf.x_range, a[ok] if ok.any() else [0, 1])
            fit_range(pf.y_range, b[ok] if ok.any() else [0, 1])
            x, y = d.request.x, d.request.y
            self.front_hover.tooltips = [
                (FIELDS[x].title(), f"@{AX}{{0.[0000]}}"),
                (FIELDS[y].title(), f"@{AY}{{0.[0000]}}"),
                (merit_label(a_name), "@a{0.[000]}"), (merit_label(b_name), "@b{0.[000]}")]

    # -------------------------------------------------------------- the click

    def _on_tap(self, event: Tap) -> None:
        if event.x is None or event.y is None:
            return
        self.load(float(event.x), float(event.y))

    def load(self, x: float, y: float) -> bool:
        """Load the map's design nearest (x, y) (display units) into the card, through
        the card's validation; whether it was loaded (else the message says why)."""
        d = self.data
        if d is None:
            return False
        j, i = d.nearest(x, y)
        design = d.design(j, i)
        ax, ay = d.request.x, d.request.y
        values = self.state.values()
        try:
            vx = check(ax, design[ax], values)
            vy = check(ay, design[ay], {**values, ax: vx})
        except ValueError as err:
            self.show_message(f"this design is refused: {err}")
            return False
        self.show_message("")
        self.state.param.update(**{ax: vx, ay: vy})
        return True


class MapCard:
    """The "Design map" sub-card of the Motor card, collapsed; its map is built when the
    card is first opened and follows the state only while the card is open."""

    TITLE = "Design map: two inputs swept, every figure of merit"

    def __init__(self, state: MotorState) -> None:
        self.state = state
        self.map: DesignMap | None = None
        self.card = expandable_card(title=self.TITLE, collapsed=True, sizing_mode="stretch_width",
                            styles={"flex": "1 1 100%"})
        self.card.param.watch(self._on_card, "collapsed")

    def _on_card(self, event: Any) -> None:
        if self.map is None and not event.new:
            self.map = DesignMap(self.state)
            self.card.objects = [self.map]
        elif self.map is not None:
            self.map.active = not event.new

    def close(self) -> None:
        """The session ended."""
        if self.map is not None:
            self.map.close()
