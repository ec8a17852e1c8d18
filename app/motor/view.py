"""The Motor card (`MotorScene`): the rod of Fig. 1 driving a rotor, from the contact
point to thrust, speed, load, start-up and wear.

A self-contained Panel viewable (mount it anywhere): the inputs (`app.motor.fields`, as
`MotorState`), the figures (`app.motor.figures`) updated in place, the CSV downloads
(`app.motor.downloads`).  The rod and the values at x0 are closed form, drawn at once;
what costs more (`app.motor.data.compute`: the thrust-speed curve at x0, the operating
point and start-up under the load, the wear along the rod) runs on the process's job
runner (`app.kit.jobs.RUNNER`), with a progress bar that every outcome clears; only the
newest request's result is shown.  A refused input says why under its box, in its unit,
and the last good state stays.  `contact` is the (psi, tau0) of x0 (None where the
contact never opens) for the explorer's scenes to follow; `query()` / `apply_query()`
read and write the URL (keys `motor_*`); `close()` drops the session's waiting job.
"""

from __future__ import annotations

import html
import io
from collections.abc import Callable, Mapping
from functools import partial
from typing import Any

import numpy as np
import panel as pn
import param
from bokeh.events import Tap

import app.motor.data as data
import app.motor.downloads as downloads
import app.motor.plots as plots
from app.contact import export
from app.kit.a11y import expandable_card
from app.kit.batch import held
from app.kit.figures import fit_range
from app.kit.jobs import RUNNER
from app.kit.progress import JobProgress
from app.kit.sliders import ExactSlider
from app.kit.widgets import ERROR_STYLE, LabelledCheckbox, show_later, text_html
from app.kit.wire import inline
from app.motor.fields import (
    FIELDS,
    LOAD_FIELDS,
    ROD_FIELDS,
    ROD_MATERIALS,
    ROD_PRESETS,
    ROTOR_FIELDS,
    ROTOR_PRESETS,
    WEAR_FIELDS,
    check,
    joint,
    softer_hardness,
)
from app.motor.figures import MotorFigures
from app.motor.map_view import MapCard
from app.motor.state import URL_PARAMS, MotorState, decode

#: Inputs whose change needs only the job (not the closed-form drawing).
JOB_ONLY = frozenset((*WEAR_FIELDS, *LOAD_FIELDS))


class MotorScene(pn.viewable.Viewer):
    """The motor of Fig. 1: rod, stall thrust, thrust-speed and efficiency, load,
    start-up and wear.  Follow `contact` (`on_contact`), read/write the URL with
    `query()` / `apply_query()`, and call `close()` when the session ends."""

    contact = param.Parameter(default=None, doc=(
        "(psi, tau0 in rad) at x0, or None where the contact never opens"))

    def __init__(self, state: MotorState | None = None) -> None:
        super().__init__()
        self.state = state or MotorState()
        self.figures = MotorFigures()
        self.motor, self.x0 = self.state.motor()
        self.profile: data.MotorProfile | None = None  # along the rod
        self.at_x0: data.MotorProfile | None = None
        #: the job's results on screen (None until the first arrives)
        self.results: data.Results | None = None
        self._requests = 0
        self._closed = False
        self._widgets()
        self.design_map = MapCard(self.state)  # the design map, built when opened
        self.figures.rod_figure.on_event(Tap, self._on_tap)
        self.state.param.watch(self._on_state, [p for p in URL_PARAMS if "preset" not in p])
        self.state.param.watch(self._on_presets, ["rod_preset", "rotor_preset"])
        self.refresh()

    # -------------------------------------------------------------- widgets

    def _widgets(self) -> None:
        s = self.state
        self.inputs: dict[str, ExactSlider] = {}
        for name, field in FIELDS.items():
            widget = ExactSlider(label=field.title(), value=getattr(s, name),
                                 start=field.start, end=field.end, step=field.step,
                                 parse=partial(self.parse, name), name=f"motor_{name}")
            widget.param.watch(partial(self._on_input, name), "value")
            self.inputs[name] = widget

        def select(label: str, options: Mapping[str, str], value: str) -> pn.widgets.Select:
            return pn.widgets.Select(label=label, options=dict(options), value=value,
                                     sizing_mode="stretch_width")

        self.rod_select = select("Rod", {"(custom)": "", **{
            p.label: k for k, p in ROD_PRESETS.items()}}, s.rod_preset)
        self.rotor_select = select("Rotor", {"(custom)": "", **{
            p.label: k for k, p in ROTOR_PRESETS.items()}}, s.rotor_preset)
        self.material_select = select("The rod's contact layer", {
            label: k for k, label in ROD_MATERIALS.items()}, s.rod_material)
        self.flat_box = LabelledCheckbox(label="Flat rod face (else a sphere of the "
                                         "rotor's radius)", value=s.flat)
        self.rod_select.param.watch(lambda e: self.apply_preset("rod", e.new), "value")
        self.rotor_select.param.watch(lambda e: self.apply_preset("rotor", e.new), "value")
        self.material_select.param.watch(lambda e: self.choose(rod_material=e.new), "value")
        self.flat_box.param.watch(lambda e: self.choose(flat=e.new), "value")
        self.progress = JobProgress(width=180)

        def pane(name: str, **kw: Any) -> pn.pane.HTML:
            return pn.pane.HTML("", sizing_mode="stretch_width", name=name, **kw)

        self.status = pane("motor_status")
        self.message = pane("motor_message", visible=False, styles=ERROR_STYLE)
        self.beta = pane("motor_beta")
        self.operating_text = pane("motor_operating_text")
        self.wear_text = pane("motor_wear_text")
        self.downloads = {
            key: pn.widgets.FileDownload(callback=partial(self.csv_file, key),
                                         filename=f"zharii_motor_{key}.csv", label=label,
                                         color="primary", width=190)
            for key, label in (("thrust", "CSV: thrust along rod"),
                               ("speed", "CSV: thrust-speed curve"))}

    def __panel__(self) -> pn.viewable.Viewable:
        """Controls beside the six plots."""
        def card(title: str, *objects: Any) -> pn.Card:
            return expandable_card(*objects, title=title, collapsed=True,
                                   sizing_mode="stretch_width")

        rod = card("Rod", self.rod_select, *(self.inputs[k] for k in ROD_FIELDS),
                   self.material_select, self.flat_box)
        rotor = card("Rotor", self.rotor_select, *(self.inputs[k] for k in ROTOR_FIELDS))
        load = card("Load and start-up", *(self.inputs[k] for k in LOAD_FIELDS))
        wear = card("Wear (Archard)", *(self.inputs[k] for k in WEAR_FIELDS))
        controls = pn.Column(self.inputs["x0"], rod, rotor, load, wear, self.message,
                             self.beta, pn.Row(self.progress), self.status,
                             self.operating_text, self.wear_text,
                             *self.downloads.values(),
                             styles={"flex": "0 0 320px"})
        plots = [pn.pane.Bokeh(fig, sizing_mode="stretch_width",
                               styles={"flex": "1 1 480px", "min-width": "0"})
                 for fig in self.figures.figures]
        return pn.FlexBox(controls, *plots, self.design_map.card, sizing_mode="stretch_width")

    # -------------------------------------------------------------- inputs

    def parse(self, name: str, text: str) -> float:
        """The value typed `text` gives field `name`, checked with the rest of the state
        (`app.motor.fields.check`); ValueError with the message to show."""
        return check(name, text, self.state.values())

    def _on_input(self, name: str, event: param.parameterized.Event) -> None:
        if event.new == getattr(self.state, name):
            return
        widget = self.inputs[name]
        try:
            check(name, event.new, self.state.values())
        except ValueError as err:  # a slider move core refuses (e.g. L below |x0|)
            widget.error = str(err)
            show_later(widget, getattr(self.state, name))
            return
        widget.error = ""
        setattr(self.state, name, event.new)

    def _on_tap(self, event: Tap) -> None:
        """A tap on the rod drawing puts the rotor there (x in mm, to 1 µm)."""
        if event.x is None:
            return
        try:
            x = check("x0", round(float(event.x), 3), self.state.values())
        except ValueError as err:
            self.inputs["x0"].error = str(err)
            return
        self.inputs["x0"].error = ""
        self.state.x0 = x

    def apply_preset(self, part: str, name: str) -> None:
        """Load rod (`part` 'rod') or rotor ('rotor') preset `name`; '' does nothing. A
        rotor preset also sets the hardness to the softer body's. A preset that does not
        fit the rest of the state is refused with a message."""
        presets = ROD_PRESETS if part == "rod" else ROTOR_PRESETS
        if name not in presets:
            return
        values = dict(presets[name].values)
        if part == "rotor":
            values["hardness"] = softer_hardness(name, self.state.rod_material)
        if self._refused(presets[name].label, values):
            return
        self.state.param.update(**values, **{f"{part}_preset": name})

    def choose(self, **choice: Any) -> None:
        """Set the rod's contact layer (`rod_material`) or face (`flat`); a material
        also sets the hardness to the softer body's."""
        if all(getattr(self.state, k) == v for k, v in choice.items()):
            return
        if "rod_material" in choice:
            hard = softer_hardness(self.state.rotor_preset, choice["rod_material"])
            choice.update({} if hard is None else {"hardness": hard})
        what = ("the rod's contact layer" if "rod_material" in choice
                else "the flat rod face")
        if not self._refused(what, choice):
            self.state.param.update(**choice)

    def _refused(self, what: str, values: Mapping[str, Any]) -> bool:
        """Whether `values` are refused with the rest of the state; if so, says why and
        puts the menus back."""
        try:
            joint({**self.state.values(), **values})
        except ValueError as err:
            self.show_message(f"{what} refused: {err}")
            show_later(self.rod_select, self.state.rod_preset)
            show_later(self.rotor_select, self.state.rotor_preset)
            show_later(self.material_select, self.state.rod_material)
            show_later(self.flat_box, self.state.flat)
            return True
        self.show_message("")
        return False

    def show_message(self, text: str) -> None:
        """Show `text` (as text, never markup) above the status; '' hides it."""
        self.message.param.update(object=html.escape(text), visible=bool(text))

    def _on_presets(self, *events: param.parameterized.Event) -> None:
        self.rod_select.value = self.state.rod_preset
        self.rotor_select.value = self.state.rotor_preset

    def _on_state(self, *events: param.parameterized.Event) -> None:
        names = {e.name for e in events}
        for name in names & set(FIELDS):  # the widgets follow the state (presets, URL)
            self.inputs[name].value = getattr(self.state, name)
        self.material_select.value = self.state.rod_material
        self.flat_box.value = self.state.flat
        self.refresh(rod=not names <= {"x0", *JOB_ONLY}, x0=not names <= JOB_ONLY)

    # -------------------------------------------------------------- closed form

    def refresh(self, rod: bool = True, x0: bool = True) -> None:
        """Show the state: the whole rod (`rod`), the values at x0 (`x0`), and ask the
        runner for the rest."""
        self.motor, self.x0 = self.state.motor()
        with held():
            if rod:
                self._show_rod()
            if x0:
                self._show_x0()
        self.request()

    def _show_rod(self) -> None:
        m, f = self.motor, self.figures
        L = m.rod.half_length
        p = self.profile = m.profile(data.rod_grid(L))
        k_u, k_H = data.magnifications(m)
        f.rod.data = inline(data.rod_columns(m, p))
        R_mm, delta_mm = m.R * 1e3, m.rod.thickness * 1e3
        f.frame.data = {"x": [-L * 1e3 - R_mm, L * 1e3 + R_mm],
                        "y": [-0.5 * delta_mm - 0.5 * R_mm, 0.5 * delta_mm + 2.6 * R_mm]}
        f.readout.y = f.frame.data["y"][1]
        f.rod_figure.title.text = (f"Rod and rotor (to scale; amplitudes magnified: "
                                   f"u₀ ×{k_u:.3g}, H ×{k_H:.3g})")
        thrust_mN = p.stall_thrust * 1e3
        f.thrust.data = inline({"x": p.x0, "x_mm": p.x0 * 1e3, "psi": p.psi, "tau0": p.tau0,
                                "stall_thrust": p.stall_thrust, "thrust_mN": thrust_mN})
        left, right = ([v * 1e3 for v in run] for run in data.invalid_runs(p.x0, p.opens, L))
        f.invalid.data = {"left": left, "right": right}
        f.ends.data = data.end_notes(left, right)
        best = [int(np.nanargmin(thrust_mN)), int(np.nanargmax(thrust_mN))] if p.opens.any() \
            else []
        f.optimum.data = {"x_mm": (p.x0[best] * 1e3).tolist(),
                          "thrust_mN": thrust_mN[best].tolist()}
        for fig in (f.thrust_figure, f.wear_figure):
            fig.x_range.start, fig.x_range.end = -L * 1e3, L * 1e3
        limit = m.mu * m.preload * 1e3
        fit_range(f.thrust_figure.y_range, [-limit, limit], pad=0.08)
        end = L * 1e3 * (1.0 - 1e-3)  # the x0 slider spans the rod, ends excluded
        self.inputs["x0"].set_range(-end, end, self.state.x0)
        warning = m.beta_warning
        self.beta.object = text_html(
            f"Dundurs' β = {m.beta:.3g} (0 for the paper's identical bodies)"
            + (f". ⚠ {warning}." if warning else ""))

    def _show_x0(self) -> None:
        m, f = self.motor, self.figures
        p = self.at_x0 = m.profile(self.x0)
        thrust = float(p.stall_thrust)
        x, y = data.rotor_centre(m, self.x0)
        label = ("never opens" if not p.opens else "↺" if thrust > 0 else "↻" if thrust < 0
                 else "no thrust")
        f.rotor.data = {"x": [x], "y": [y], "radius": [m.R * 1e3], "label": [label]}
        f.x0.data = {"x_mm": [x], "thrust_mN": [thrust * 1e3]}
        if p.opens:
            f.readout.text = (f"x₀ = {x:.4g} mm  ψ = {float(p.psi):.4g}  "
                              f"τ₀ = {float(p.tau0):.4f} rad  "
                              f"stall thrust = {thrust * 1e3:.4g} mN")
            self.contact = (float(p.psi), float(p.tau0))
        else:
            f.readout.text = (f"x₀ = {x:.4g} mm: the contact never opens here "
                              f"(Φ = {float(p.load_factor):.3g} ≥ 8): the model does "
                              "not apply")
            self.contact = None

    def on_contact(self, callback: Callable[[tuple[float, float] | None], None]) -> None:
        """Call `callback(contact)` whenever `contact` changes ((psi, tau0) or None)."""
        self.param.watch(lambda e: callback(e.new), "contact")

    # -------------------------------------------------------------- the job

    def request(self) -> None:
        """Ask the runner for the curve, the load's results and the wear (a newer
        request replaces a waiting one; only the newest result is shown)."""
        if self._closed:
            return
        self._requests += 1
        s = self.state
        si = {k: FIELDS[k].si(getattr(s, k)) for k in (*WEAR_FIELDS, *LOAD_FIELDS)}
        job = partial(data.compute, data.Request(
            self.motor, self.x0, si["load"], si["mass"], si["k"], si["hardness"]))
        self.progress.busy = True
        self.status.object = "computing the thrust-speed curve, the load and the wear…"
        RUNNER.submit(self, job, partial(self._done, self._requests))

    def _done(self, request: int, outcome: data.Results | Exception) -> None:
        if request != self._requests:
            return  # a newer request is on its way
        with held():
            self.progress.busy = False
            if isinstance(outcome, Exception):
                self.status.object = text_html(f"⚠ could not compute: {outcome}")
                return
            self.results = outcome
            at, f = outcome.at_x0, self.figures
            self.status.object = plots.curve(f, self.motor, self.x0, at)
            self.operating_text.object = plots.load(f, at)
            plots.wear(f, outcome.wear)
            self.wear_text.object = text_html(plots.deepest(outcome.wear))

    def close(self) -> None:
        """The session ended: drop the waiting job; ask for nothing more."""
        self._closed = True
        RUNNER.cancel(self)
        self.design_map.close()

    # -------------------------------------------------------------- URL and CSV

    def query(self) -> dict[str, str]:
        """The card's state as URL values (keys `motor_*`)."""
        return self.state.query()

    def apply_query(self, query: Mapping[str, str | bytes | list]) -> list[str]:
        """Apply the `motor_*` values of a URL query (other keys are ignored); returns one
        message per refused value (in its box's unit), whose last good value is kept."""
        updates, messages = decode(query, self.state)
        self.state.param.update(**updates)
        return messages

    def csv_text(self, key: str) -> str:
        """CSV 'thrust' (the rod) or 'speed' (the curve at x0, the job's: cached) in the
        explorer's style."""
        s = self.state
        at = data.at_x0(self.motor, self.x0, FIELDS["load"].si(s.load), FIELDS["mass"].si(s.mass))
        if key == "thrust":
            table = downloads.thrust_table(self.profile)
        elif key == "speed":
            table = downloads.speed_table(self.motor, self.x0, at)
        else:
            raise KeyError(key)
        return export.csv_text(table, downloads.header(key, self.motor, self.x0, at))

    def csv_filename(self, key: str) -> str:
        """The CSV's file name: what it holds and the inputs in display units."""
        return downloads.filename(key, self.state)

    def csv_file(self, key: str) -> io.StringIO:
        """The CSV as a file object for `pn.widgets.FileDownload` (named on the click)."""
        self.downloads[key].filename = self.csv_filename(key)
        return io.StringIO(self.csv_text(key))

