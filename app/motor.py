"""Motor scene: the rod of Fig. 1 driving a rotor, from the contact point to thrust and speed.

`MotorScene` is a self-contained Panel viewable (mount it anywhere). It shows

1. the rod drawn to scale with the amplitudes of its standing wave (longitudinal u0(x),
   normal H(x), magnified) and the rotor resting on it at the contact point x0 (set by
   the slider, the exact box, or a tap on the drawing);
2. the stall thrust along the rod (`core.motor.Motor.stall_thrust`), its optimum of the
   plotted points marked, the region where the contact never opens (core's nan) shaded;
3. the thrust-speed and efficiency curves at x0 (`core.motor.thrust_speed_curve`,
   `no_load_speed`, `best_efficiency`), computed on the shared worker thread of
   `app.methods` with a progress bar, so a slider never waits for them, and cached
   (bounded `lru_cache` on the rounded contact);
4. CSV downloads of both curves, in the explorer's style (`app.contact.export`): a header block
   with the source, the app's version and the inputs in SI, columns named with their
   units, file names carrying the inputs.

The state is a `MotorState` in the units people think in (mm, um, kHz, GPa, N); the
scene converts to SI at the boundary and every number shown comes from `core.motor`.
A refused input shows core's ValueError text under its box and keeps the last good
state. `contact` is the (psi, tau0) of x0, or None where the model does not apply, for
the Fig. 6-9 scenes to follow; `query()` / `apply_query()` read and write the state as
URL values (keys `motor_*`), and `close()` drops the session's background work.
"""

from __future__ import annotations

import contextlib
import html
import io
import math
import threading
import time
from collections.abc import Callable, Iterator, Mapping
from concurrent.futures import Future
from dataclasses import dataclass
from functools import lru_cache, partial
from typing import Any

import numpy as np
import panel as pn
import param
from bokeh.events import Tap
from bokeh.models import ColumnDataSource, DataRange1d, Label, Range1d
from panel.io import hold

from app.contact import export
from app.kit.figures import FRAME_LEVEL, fit_range, new_figure, style_figure
from app.kit.widgets import ERROR_STYLE, ExactSlider
from app.kit.wire import inline
from app.methods import WORKER, SharedWorker
from core.motor import (
    BestEfficiency,
    Motor,
    MotorProfile,
    MovingRotor,
    Rod,
    best_efficiency,
    no_load_speed,
    thrust_speed_curve,
)

#: Points along the rod for the drawing and the stall-thrust curve.
ROD_POINTS = 1001
#: Clustering of those points towards the centre, where the thrust peaks (psi = 1 lies
#: within ~1 % of L of the centre): x = L sinh(c t) / sinh(c), t uniform in (-1, 1);
#: spacing ~6e-5 L at the centre, ~0.012 L at the ends.
ROD_CLUSTER = 6.0
#: Speeds on a thrust-speed curve (stall to full counter-slip).
SPEED_POINTS = 40
#: Significant digits of psi, tau0, mu, nu in the cache key of a thrust-speed curve
#: (the curve is computed at the rounded values: 1e-12 relative, far below its 1e-4).
KEY_DIGITS = 12
#: Thrust-speed curves kept (per process; a few kB each).
CACHE_SIZE = 256
#: Prefix of this scene's URL query keys.
PREFIX = "motor_"

#: Colours (Okabe-Ito) and the shading of the never-opening region.
THRUST_COLOR, EFFICIENCY_COLOR, ROTOR_COLOR = "#0072B2", "#009E73", "#D55E00"
INVALID_COLOR = "#999999"


# ------------------------------------------------------------------ inputs and units

@dataclass(frozen=True)
class Field:
    """One input: its core name, label, display unit, SI factor (SI = value * factor,
    or value / divisor for the decimal submultiples, so that e.g. 20 mm is exactly the
    double nearest 0.02 m) and the slider's teaching range in display units."""

    core: str
    label: str
    unit: str
    factor: float
    divisor: float
    start: float
    end: float
    step: float

    def si(self, value: float) -> float:
        """`value` (display unit) in SI."""
        return value / self.divisor * self.factor

    def title(self) -> str:
        """The label with its unit, e.g. 'L, rod half-length (mm)'."""
        return f"{self.label} ({self.unit})" if self.unit else self.label


#: Inputs in display units: rod (L, delta, nu_rod, A, f), rotor (R, G, nu, mu, N), x0.
FIELDS: dict[str, Field] = {
    "L": Field("half_length", "L, rod half-length", "mm", 1.0, 1e3, 5.0, 50.0, 0.5),
    "delta": Field("thickness", "δ, rod thickness", "mm", 1.0, 1e3, 0.5, 10.0, 0.1),
    "nu_rod": Field("nu_rod", "ν_rod, Poisson ratio of the rod", "", 1.0, 1.0, 0.0, 0.5, 0.01),
    "A": Field("amplitude", "A, amplitude at the rod's end", "µm", 1.0, 1e6, 0.5, 30.0, 0.5),
    "f": Field("frequency", "f, frequency", "kHz", 1e3, 1.0, 10.0, 100.0, 0.5),
    "R": Field("R", "R, rotor radius", "mm", 1.0, 1e3, 0.5, 20.0, 0.1),
    "G": Field("G", "G, shear modulus", "GPa", 1e9, 1.0, 5.0, 200.0, 1.0),
    "nu": Field("nu", "ν, Poisson ratio", "", 1.0, 1.0, 0.0, 0.5, 0.01),
    "mu": Field("mu", "μ, friction coefficient", "", 1.0, 1.0, 0.05, 1.0, 0.01),
    "N": Field("preload", "N, preload", "N", 1.0, 1.0, 0.01, 5.0, 0.01),
    "x0": Field("x0", "x₀, contact point", "mm", 1.0, 1e3, -20.0, 20.0, 0.01),
}
ROD_FIELDS = ("L", "delta", "nu_rod", "A", "f")
ROTOR_FIELDS = ("R", "G", "nu", "mu", "N")
#: The SI unit of each display unit (core's).
SI_UNITS = {"mm": "m", "µm": "m", "kHz": "Hz", "GPa": "Pa", "N": "N", "": ""}


@dataclass(frozen=True)
class Preset:
    """Values of some fields (display units) under a label."""

    label: str
    values: dict[str, float]


#: A piezoceramic (PZT) rod in its first longitudinal mode near 40 kHz.
ROD_PRESETS: dict[str, Preset] = {
    "pzt40": Preset("PZT rod, 2L = 40 mm, δ = 4 mm, A = 10 µm, 40 kHz",
                    {"L": 20.0, "delta": 4.0, "nu_rod": 0.31, "A": 10.0, "f": 40.0}),
    "pzt60": Preset("PZT rod, 2L = 26 mm, δ = 3 mm, A = 6 µm, 60 kHz",
                    {"L": 13.0, "delta": 3.0, "nu_rod": 0.31, "A": 6.0, "f": 60.0}),
}
#: Rotors: handbook values of G, nu and a dry friction coefficient; R = 5 mm, N = 0.5 N.
ROTOR_PRESETS: dict[str, Preset] = {
    "steel": Preset("steel rotor, R = 5 mm, N = 0.5 N",
                    {"R": 5.0, "G": 79.3, "nu": 0.29, "mu": 0.2, "N": 0.5}),
    "alumina": Preset("alumina rotor, R = 5 mm, N = 0.5 N",
                      {"R": 5.0, "G": 152.0, "nu": 0.22, "mu": 0.3, "N": 0.5}),
}
DEFAULT_ROD, DEFAULT_ROTOR, DEFAULT_X0 = "pzt40", "steel", -5.0

#: URL keys of the scene, in order.
QUERY_KEYS = tuple(PREFIX + k for k in ("rod", "rotor", *FIELDS))


def _number(raw: str) -> float | str:
    """The float a text stands for, or the text itself (core then names what is wrong)."""
    try:
        return float(raw)
    except ValueError:
        return raw


def build_motor(values: Mapping[str, Any]) -> tuple[Motor, float]:
    """The core `Motor` and x0 (m) of display-unit `values` (every key of FIELDS);
    ValueError with core's message (prefixed by the input it concerns) if core refuses
    them. A value may be a text: core then says why it is not a number."""
    si: dict[str, Any] = {}
    for name, field in FIELDS.items():
        value = values[name]
        si[name] = field.si(value) if isinstance(value, float | int) else value
    with _named("rod"):
        rod = Rod(**{FIELDS[k].core: si[k] for k in ROD_FIELDS})
    with _named("rotor"):
        motor = Motor(rod, **{FIELDS[k].core: si[k] for k in ROTOR_FIELDS})
    x0 = si["x0"]
    rod.check_x0(x0)  # its message names x0 already
    return motor, float(x0)


@contextlib.contextmanager
def _named(part: str) -> Iterator[None]:
    """Re-raise core's ValueError with the part of the input it concerns."""
    try:
        yield
    except ValueError as err:
        raise ValueError(f"{part}: {err}") from err


class MotorState(param.Parameterized):
    """What the user set, in display units (mm, µm, kHz, GPa, N); never a refused value."""

    rod_preset = param.String(default=DEFAULT_ROD, doc="rod preset key, '' once edited")
    rotor_preset = param.String(default=DEFAULT_ROTOR, doc="rotor preset key, '' once edited")
    L = param.Number(default=20.0, doc="rod half-length (mm)")
    delta = param.Number(default=4.0, doc="rod thickness (mm)")
    nu_rod = param.Number(default=0.31, doc="Poisson ratio of the rod")
    A = param.Number(default=10.0, doc="longitudinal amplitude at x = L (µm)")
    f = param.Number(default=40.0, doc="frequency (kHz)")
    R = param.Number(default=5.0, doc="rotor radius (mm)")
    G = param.Number(default=79.3, doc="shear modulus (GPa)")
    nu = param.Number(default=0.29, doc="Poisson ratio")
    mu = param.Number(default=0.2, doc="friction coefficient")
    N = param.Number(default=0.5, doc="preload (N)")
    x0 = param.Number(default=DEFAULT_X0, doc="contact point (mm)")

    def values(self) -> dict[str, float]:
        """Every field's value (display units)."""
        return {k: getattr(self, k) for k in FIELDS}

    def motor(self) -> tuple[Motor, float]:
        """The core `Motor` of the state and x0 in m."""
        return build_motor(self.values())

    def matches(self, presets: Mapping[str, Preset], name: str) -> bool:
        """Whether the fields of preset `name` hold its values."""
        return name in presets and all(
            getattr(self, k) == v for k, v in presets[name].values.items())

    @param.depends(*ROD_FIELDS, *ROTOR_FIELDS, watch=True)
    def _leave_presets(self) -> None:
        """A preset names what is on screen: any other value of its fields leaves it."""
        if self.rod_preset and not self.matches(ROD_PRESETS, self.rod_preset):
            self.rod_preset = ""
        if self.rotor_preset and not self.matches(ROTOR_PRESETS, self.rotor_preset):
            self.rotor_preset = ""

    def query(self) -> dict[str, str]:
        """The state as URL values: preset keys (their fields only where they differ),
        other fields as the shortest text that reads back as the same float."""
        q: dict[str, str] = {}
        for key, names in (("rod", ROD_FIELDS), ("rotor", ROTOR_FIELDS)):
            name = getattr(self, f"{key}_preset")
            if name:
                q[PREFIX + key] = name
            else:
                q.update({PREFIX + k: repr(float(getattr(self, k))) for k in names})
        q[PREFIX + "x0"] = repr(float(self.x0))
        return q


# ------------------------------------------------------------------ background work

@dataclass(frozen=True)
class SpeedCurve:
    """The thrust-speed curve of one contact (dimensionless, from core) with its no-load
    speed v0 and point of best efficiency, and the wall time (s) it took."""

    curve: MovingRotor
    no_load: float
    best: BestEfficiency
    seconds: float


def contact_key(psi: float, tau0: float, mu: float, nu: float) -> tuple[float, ...]:
    """(psi, tau0, mu, nu) rounded to KEY_DIGITS significant digits: the cache key, and
    the values the curve is computed at."""
    return tuple(float(f"{x:.{KEY_DIGITS}g}") for x in (psi, tau0, mu, nu))


@lru_cache(maxsize=CACHE_SIZE)
def speed_curve(psi: float, tau0: float, mu: float, nu: float) -> SpeedCurve:
    """`thrust_speed_curve` (SPEED_POINTS speeds), `no_load_speed` and `best_efficiency`
    of core at (psi, tau0, mu, nu) (pass a `contact_key`); cached, bounded."""
    start = time.perf_counter()
    curve = thrust_speed_curve(psi, tau0, SPEED_POINTS, mu=mu, nu=nu)
    v0 = no_load_speed(psi, tau0, mu=mu, nu=nu)
    best = best_efficiency(psi, tau0, mu=mu, nu=nu)
    return SpeedCurve(curve, v0, best, time.perf_counter() - start)


def rod_grid(half_length: float) -> np.ndarray:
    """ROD_POINTS points x (m) inside (-L, L), clustered towards the centre."""
    t = np.linspace(-1.0, 1.0, ROD_POINTS + 2)[1:-1]
    return half_length * (np.sinh(ROD_CLUSTER * t) / math.sinh(ROD_CLUSTER))


def invalid_runs(x: np.ndarray, opens: np.ndarray, half_length: float
                 ) -> tuple[list[float], list[float]]:
    """(left, right) of each run of points of x (sorted) where the contact never opens,
    a run that reaches the first or last point extended to the rod's end."""
    left: list[float] = []
    right: list[float] = []
    closed = np.concatenate([[False], ~opens, [False]])
    edges = np.flatnonzero(np.diff(closed.astype(np.int8)))
    for i, j in zip(edges[::2], edges[1::2] - 1, strict=True):
        left.append(-half_length if i == 0 else float(x[i]))
        right.append(half_length if j == x.size - 1 else float(x[j]))
    return left, right


# ------------------------------------------------------------------ the scene

class MotorScene(pn.viewable.Viewer):
    """The motor of Fig. 1: rod, stall thrust along it, thrust-speed and efficiency.

    Mount with `pn.panel(scene)` (or put `scene` in any layout); follow `contact`
    (`on_contact(callback)`), read/write the URL with `query()` / `apply_query()`, and
    call `close()` when the session ends.
    """

    contact = param.Parameter(default=None, doc=(
        "(psi, tau0 in rad) at x0, or None where the contact never opens"))

    def __init__(self, state: MotorState | None = None,
                 worker: SharedWorker = WORKER) -> None:
        super().__init__()
        self.state = state or MotorState()
        self.worker = worker
        self.motor, self.x0 = self.state.motor()
        self.profile: MotorProfile | None = None
        self.at_x0: MotorProfile | None = None
        #: the running or waiting thrust-speed request (a `Future`), None if none
        self.pending: Future | None = None
        #: the (psi, tau0, mu, nu) of the thrust-speed curve on screen, None if none
        self.shown_key: tuple[float, ...] | None = None
        self.shown: SpeedCurve | None = None
        self._generation = 0
        self._closed = False
        self._lock = threading.Lock()

        self._sources()
        self._figures()
        self._widgets()
        self.state.param.watch(self._on_state, list(FIELDS))
        self.state.param.watch(self._on_presets, ["rod_preset", "rotor_preset"])
        self.refresh()

    # -------------------------------------------------------------- build

    def _sources(self) -> None:
        self.rod_source = ColumnDataSource(
            {k: [] for k in ("x", "x_mm", "u0_um", "H_um", "top", "bottom", "wave")},
            name="motor_rod")
        self.rotor_source = ColumnDataSource({"x": [], "y": [], "radius": [], "label": []},
                                             name="motor_rotor")
        self.frame_source = ColumnDataSource({"x": [], "y": []}, name="motor_frame")
        self.thrust_source = ColumnDataSource(
            {k: [] for k in ("x", "x_mm", "psi", "tau0", "stall_thrust", "thrust_mN")},
            name="motor_thrust")
        self.invalid_source = ColumnDataSource({"left": [], "right": []}, name="motor_invalid")
        self.optimum_source = ColumnDataSource({"x_mm": [], "thrust_mN": []},
                                               name="motor_optimum")
        self.x0_source = ColumnDataSource({"x_mm": [], "thrust_mN": []}, name="motor_x0")
        self.speed_source = ColumnDataSource(
            {k: [] for k in ("v", "thrust_ratio", "efficiency", "V_mm_s", "thrust_mN",
                             "efficiency_pct")}, name="motor_speed")
        self.marks_source = ColumnDataSource(
            {k: [] for k in ("V_mm_s", "thrust_mN", "efficiency_pct", "label")},
            name="motor_speed_marks")

    def _figures(self) -> None:
        # the rod, to scale (x and y in mm); the range follows an invisible frame only,
        # so that moving the rotor leaves it as it is
        fig = new_figure("Rod and rotor", "x (mm)", "y (mm)", match_aspect=True,
                         x_range=DataRange1d(), y_range=DataRange1d(), width=900, height=300,
                         sizing_mode="scale_width")
        frame = fig.scatter("x", "y", source=self.frame_source, alpha=0.0, size=1)
        fig.x_range.renderers = fig.y_range.renderers = [frame]
        fig.vstrip("left", "right", source=self.invalid_source, fill_color=INVALID_COLOR,
                   fill_alpha=0.3, line_color=None)
        fig.varea("x_mm", "bottom", "top", source=self.rod_source, fill_color="#E69F00",
                  fill_alpha=0.5, legend_label="rod, top face at its peak (H magnified)")
        fig.line("x_mm", "wave", source=self.rod_source, color="black", line_width=2,
                 line_dash="dashed", legend_label="u₀(x) magnified (+: along +x)")
        fig.circle("x", "y", radius="radius", source=self.rotor_source,
                   fill_color=ROTOR_COLOR, fill_alpha=0.35, line_color="black",
                   level=FRAME_LEVEL)
        fig.text("x", "y", text="label", source=self.rotor_source, text_align="center",
                 text_baseline="middle", text_font_size="12pt", level=FRAME_LEVEL)
        fig.legend.location = "top_right"
        fig.on_event(Tap, self._on_tap)
        # at the top left of the frame (its y is set with the frame, in mm)
        self.readout = Label(x=8, y=0, x_units="screen", text="", text_baseline="top",
                             text_font_size="12pt", background_fill_color="white",
                             background_fill_alpha=0.8, level=FRAME_LEVEL,
                             name="motor_readout")
        fig.add_layout(self.readout)
        style_figure(fig)
        self.rod_figure = fig

        fig = new_figure("Stall thrust along the rod (rotor held)", "x₀ (mm)",
                         "stall thrust (mN, + along +x)")
        fig.vstrip("left", "right", source=self.invalid_source, fill_color=INVALID_COLOR,
                   fill_alpha=0.3, line_color=None, legend_label="contact never opens")
        fig.line("x_mm", "thrust_mN", source=self.thrust_source, color=THRUST_COLOR,
                 line_width=3, legend_label="stall thrust")
        fig.scatter("x_mm", "thrust_mN", source=self.optimum_source, marker="star", size=18,
                    color="#F0E442", line_color="black", legend_label="optimum")
        fig.vspan("x_mm", source=self.x0_source, line_color=ROTOR_COLOR, line_width=2,
                  line_dash="dotted", level=FRAME_LEVEL)
        fig.scatter("x_mm", "thrust_mN", source=self.x0_source, size=12, color=ROTOR_COLOR,
                    line_color="black", level=FRAME_LEVEL)
        fig.legend.location = "top_right"
        style_figure(fig)
        self.thrust_figure = fig

        speed_range = Range1d(0, 1)
        fig = new_figure("Thrust against rotor speed at x₀", "rotor speed V (mm/s)",
                         "thrust (mN, along the drive)", x_range=speed_range)
        fig.line("V_mm_s", "thrust_mN", source=self.speed_source, color=THRUST_COLOR,
                 line_width=3)
        fig.scatter("V_mm_s", "thrust_mN", source=self.marks_source, size=12,
                    marker="diamond", color="label", line_color="black")
        style_figure(fig)
        self.speed_figure = fig
        fig = new_figure("Efficiency against rotor speed at x₀", "rotor speed V (mm/s)",
                         "efficiency (%)", x_range=speed_range)
        fig.line("V_mm_s", "efficiency_pct", source=self.speed_source,
                 color=EFFICIENCY_COLOR, line_width=3)
        fig.scatter("V_mm_s", "efficiency_pct", source=self.marks_source, size=12,
                    marker="diamond", color="label", line_color="black")
        style_figure(fig)
        self.efficiency_figure = fig

    def _widgets(self) -> None:
        s = self.state
        self.inputs: dict[str, ExactSlider] = {}
        for name, field in FIELDS.items():
            widget = ExactSlider(label=field.title(), value=getattr(s, name),
                                 start=field.start, end=field.end, step=field.step,
                                 parse=partial(self.parse, name), name=f"motor_{name}")
            widget.param.watch(partial(self._on_input, name), "value")
            self.inputs[name] = widget
        self._x0_range()
        self.rod_select = pn.widgets.Select(
            label="Rod", options={"(custom)": "", **{p.label: k for k, p in ROD_PRESETS.items()}},
            value=s.rod_preset, sizing_mode="stretch_width")
        self.rotor_select = pn.widgets.Select(
            label="Rotor",
            options={"(custom)": "", **{p.label: k for k, p in ROTOR_PRESETS.items()}},
            value=s.rotor_preset, sizing_mode="stretch_width")
        self.rod_select.param.watch(lambda e: self.apply_preset("rod", e.new), "value")
        self.rotor_select.param.watch(lambda e: self.apply_preset("rotor", e.new), "value")
        self.progress = pn.indicators.Progress(active=False, visible=False, width=180)
        self.status = pn.pane.HTML("", sizing_mode="stretch_width", name="motor_status")
        self.message = pn.pane.HTML("", visible=False, styles=ERROR_STYLE,
                                    sizing_mode="stretch_width", name="motor_message")
        self.downloads = {
            key: pn.widgets.FileDownload(callback=partial(self.csv_file, key),
                                         filename=f"zharii_motor_{key}.csv", label=label,
                                         color="primary", width=190)
            for key, label in (("thrust", "CSV: thrust along rod"),
                               ("speed", "CSV: thrust-speed curve"))
        }

    def __panel__(self) -> pn.viewable.Viewable:
        """Controls beside the four plots."""
        rod = pn.Card(self.rod_select, *(self.inputs[k] for k in ROD_FIELDS),
                      title="Rod", collapsed=True, sizing_mode="stretch_width")
        rotor = pn.Card(self.rotor_select, *(self.inputs[k] for k in ROTOR_FIELDS),
                        title="Rotor", collapsed=True, sizing_mode="stretch_width")
        controls = pn.Column(self.inputs["x0"], rod, rotor, self.message,
                             pn.Row(self.progress), self.status, *self.downloads.values(),
                             styles={"flex": "0 0 320px"})

        def plot(fig: Any) -> pn.pane.Bokeh:
            return pn.pane.Bokeh(fig, sizing_mode="stretch_width",
                                 styles={"flex": "1 1 480px", "min-width": "0"})

        return pn.FlexBox(controls, plot(self.rod_figure), plot(self.thrust_figure),
                          plot(self.speed_figure), plot(self.efficiency_figure),
                          sizing_mode="stretch_width")

    # -------------------------------------------------------------- inputs

    def parse(self, name: str, text: str) -> float:
        """The value typed text gives field `name`, checked by core together with the
        rest of the state; ValueError with the message to show."""
        value = _number(text.strip())
        self.check(name, value)
        return float(value)

    def check(self, name: str, value: float | str) -> None:
        """ValueError (core's text, naming the input in display units) if field `name`
        = `value` is refused with the other fields as they are."""
        field = FIELDS[name]
        unit = f" {field.unit}" if field.unit and isinstance(value, float) else ""
        try:
            build_motor({**self.state.values(), name: value})
        except ValueError as err:
            raise ValueError(f"{name} = {value!s}{unit} refused: {err}") from err

    def _on_input(self, name: str, event: param.parameterized.Event) -> None:
        if event.new == getattr(self.state, name):
            return
        try:
            self.check(name, event.new)
        except ValueError as err:  # a slider move core refuses (e.g. L below |x0|)
            widget = self.inputs[name]
            widget.error = str(err)
            self._later(partial(setattr, widget, "value", getattr(self.state, name)))
            return
        self.inputs[name].error = ""
        setattr(self.state, name, event.new)

    def _on_tap(self, event: Tap) -> None:
        """A tap on the rod drawing puts the rotor there (x in mm, to 1 µm)."""
        if event.x is None:
            return
        x = round(float(event.x), 3)
        try:
            self.check("x0", x)
        except ValueError as err:
            self.inputs["x0"].error = str(err)
            return
        self.inputs["x0"].error = ""
        self.state.x0 = x

    def apply_preset(self, part: str, name: str) -> None:
        """Load rod (`part` 'rod') or rotor ('rotor') preset `name`; '' does nothing.
        A preset that does not fit the rest of the state is refused with a message."""
        presets = ROD_PRESETS if part == "rod" else ROTOR_PRESETS
        if not name or name not in presets:
            return
        values = presets[name].values
        try:
            build_motor({**self.state.values(), **values})
        except ValueError as err:
            self.show_message(f"{presets[name].label} refused: {err}")
            self._later(self._show_presets)
            return
        self.show_message("")
        self.state.param.update(**values, **{f"{part}_preset": name})

    def show_message(self, text: str) -> None:
        """Show `text` (as text, never markup) above the status; '' hides it."""
        self.message.param.update(object=html.escape(text), visible=bool(text))

    def _on_presets(self, *events: param.parameterized.Event) -> None:
        self._show_presets()

    def _show_presets(self) -> None:
        self.rod_select.value = self.state.rod_preset
        self.rotor_select.value = self.state.rotor_preset

    def _later(self, fn: Callable[[], None]) -> None:
        """Run `fn` after the browser's current change is handled (when served: Panel
        sends no change of a property back while handling the browser's change of it)."""
        doc = pn.state.curdoc
        if doc is not None and doc.session_context is not None:
            doc.add_next_tick_callback(fn)
        else:
            fn()

    def _on_state(self, *events: param.parameterized.Event) -> None:
        names = {e.name for e in events}
        for name in names:  # the widgets follow the state (presets, URL)
            self.inputs[name].value = getattr(self.state, name)
        self.refresh(x0_only=names == {"x0"})

    def _x0_range(self) -> None:
        """The x0 slider spans the rod, ends excluded."""
        L = self.state.L
        end = L * (1.0 - 1e-3)
        self.inputs["x0"].param.update(start=-end, end=end)

    # -------------------------------------------------------------- closed form

    def refresh(self, x0_only: bool = False) -> None:
        """Recompute for the state: the whole rod (unless only x0 changed), the values at
        x0, `contact`, and request the thrust-speed curve."""
        self.motor, self.x0 = self.state.motor()
        with hold():
            if not x0_only:
                self._show_rod()
            self._show_x0()
        self.request_curve()

    def _show_rod(self) -> None:
        m = self.motor
        rod = m.rod
        L = rod.half_length
        x = rod_grid(L)
        p = m.profile(x)
        self.profile = p
        delta_mm = rod.thickness * 1e3
        # magnifications for the drawing: the largest H to 0.3 delta, A to 0.35 delta
        k_H = 0.3 * rod.thickness / max(abs(rod.vertical_amplitude), 1e-300)
        k_u = 0.35 * rod.thickness / rod.amplitude
        x_mm = x * 1e3
        self.rod_source.data = inline({
            "x": x, "x_mm": x_mm, "u0_um": p.u0 * 1e6, "H_um": p.H * 1e6,
            "top": 0.5 * delta_mm + k_H * p.H * 1e3, "bottom": -0.5 * delta_mm - k_H * p.H * 1e3,
            "wave": k_u * p.u0 * 1e3})
        R_mm = m.R * 1e3
        self.frame_source.data = {"x": [-L * 1e3 - R_mm, L * 1e3 + R_mm],
                                  "y": [-0.5 * delta_mm - 0.5 * R_mm,
                                        0.5 * delta_mm + 2.4 * R_mm]}
        self.readout.y = self.frame_source.data["y"][1]
        self.rod_figure.title.text = (f"Rod and rotor (to scale; amplitudes magnified: "
                                      f"u₀ ×{k_u:.3g}, H ×{k_H:.3g})")
        thrust_mN = p.stall_thrust * 1e3
        self.thrust_source.data = inline({"x": x, "x_mm": x_mm, "psi": p.psi, "tau0": p.tau0,
                                          "stall_thrust": p.stall_thrust,
                                          "thrust_mN": thrust_mN})
        left, right = invalid_runs(x, p.opens, L)
        self.invalid_source.data = {"left": [v * 1e3 for v in left],
                                    "right": [v * 1e3 for v in right]}
        if p.opens.any():
            best = [int(np.nanargmin(thrust_mN)), int(np.nanargmax(thrust_mN))]
            self.optimum_source.data = {"x_mm": x_mm[best].tolist(),
                                        "thrust_mN": thrust_mN[best].tolist()}
        else:
            self.optimum_source.data = {"x_mm": [], "thrust_mN": []}
        self.thrust_figure.x_range.start, self.thrust_figure.x_range.end = -L * 1e3, L * 1e3
        limit = m.mu * m.preload * 1e3
        fit_range(self.thrust_figure.y_range, [-limit, limit], pad=0.08)
        self._x0_range()

    def _show_x0(self) -> None:
        m = self.motor
        p = m.profile(self.x0)
        self.at_x0 = p
        thrust = float(p.stall_thrust)
        x_mm, R_mm = self.x0 * 1e3, m.R * 1e3
        top = 0.5 * m.rod.thickness * 1e3
        if not p.opens:
            label = "never opens"
        elif thrust > 0:
            label = "↺"
        elif thrust < 0:
            label = "↻"
        else:
            label = "no thrust"
        self.rotor_source.data = {"x": [x_mm], "y": [top + R_mm], "radius": [R_mm],
                                  "label": [label]}
        self.x0_source.data = {"x_mm": [x_mm], "thrust_mN": [thrust * 1e3]}
        if p.opens:
            self.readout.text = (f"x₀ = {x_mm:.4g} mm  ψ = {float(p.psi):.4g}  "
                                 f"τ₀ = {float(p.tau0):.4f} rad  "
                                 f"stall thrust = {thrust * 1e3:.4g} mN")
            self.contact = (float(p.psi), float(p.tau0))
        else:
            self.readout.text = (f"x₀ = {x_mm:.4g} mm: the contact never opens here "
                                 f"(Φ = {float(p.load_factor):.3g} ≥ 8): the model does "
                                 "not apply")
            self.contact = None

    def on_contact(self, callback: Callable[[tuple[float, float] | None], None]) -> None:
        """Call `callback(contact)` whenever `contact` changes ((psi, tau0) or None)."""
        self.param.watch(lambda e: callback(e.new), "contact")

    # -------------------------------------------------------------- thrust-speed

    def curve_key(self) -> tuple[float, ...] | None:
        """The cache key of the thrust-speed curve the state asks for (None: no curve,
        the contact never opens at x0)."""
        if self.contact is None:
            return None
        return contact_key(*self.contact, self.motor.mu, self.motor.nu)

    def request_curve(self) -> None:
        """Ask the shared worker for the thrust-speed curve at x0 (a newer request
        replaces a waiting one; a stale result is dropped)."""
        with self._lock:
            if self._closed:
                return
            self._generation += 1
            generation = self._generation
            if self.pending is not None:
                self.pending.cancel()
                self.pending = None
        key = self.curve_key()
        if key is None:
            self._show_curve(generation, None, None,
                             "The contact never opens at x₀: no thrust-speed curve.")
            return
        scales = self._scales()
        doc = pn.state.curdoc
        self.progress.param.update(active=True, visible=True)
        self.status.object = "computing the thrust-speed curve…"
        future = self.worker.submit(partial(self._compute, generation, key, scales, doc))
        with self._lock:
            self.pending = future
        if future is None:
            self._show_curve(generation, None, None,
                             "The server is busy with other sessions' runs: change x₀ "
                             "again shortly.")

    def _scales(self) -> tuple[float, float, float]:
        """(m/s per unit of v, N per unit of r, W per unit of power) at x0: omega |u0|,
        mu N and mu N omega |u0| (core's scales of `MovingRotor`)."""
        m = self.motor
        speed = m.rod.omega * abs(float(m.rod.u0(self.x0)))
        force = m.mu * m.preload
        return speed, force, force * speed

    def _compute(self, generation: int, key: tuple[float, ...],
                 scales: tuple[float, float, float], doc: Any) -> None:
        """On the worker: the curve (cached), then shown on the session's next tick."""
        if generation != self._generation:
            return
        try:
            result, error = speed_curve(*key), ""
        except ValueError as err:  # e.g. x0 = 0: no tangential drive
            result, error = None, f"No thrust-speed curve at x₀: {err}"
        apply = partial(self._show_curve, generation, key, result, error, scales)
        if doc is not None and doc.session_context is not None:
            doc.add_next_tick_callback(apply)
        else:
            apply()

    def _show_curve(self, generation: int, key: tuple[float, ...] | None,
                    result: SpeedCurve | None, note: str,
                    scales: tuple[float, float, float] | None = None) -> None:
        if generation != self._generation:
            return
        self.shown_key, self.shown = key, result
        with hold():
            self.progress.param.update(active=False, visible=False)
            if result is None or scales is None:
                self.speed_source.data = {k: [] for k in self.speed_source.data}
                self.marks_source.data = {k: [] for k in self.marks_source.data}
                self.status.object = html.escape(note)
                return
            speed, force, _ = scales
            c = result.curve
            V = c.v * speed * 1e3
            thrust = c.thrust_ratio * force * 1e3
            eta = c.efficiency * 100.0
            self.speed_source.data = inline({"v": c.v, "thrust_ratio": c.thrust_ratio,
                                             "efficiency": c.efficiency, "V_mm_s": V,
                                             "thrust_mN": thrust, "efficiency_pct": eta})
            b = result.best
            self.marks_source.data = {
                "V_mm_s": [result.no_load * speed * 1e3, b.v * speed * 1e3],
                "thrust_mN": [0.0, b.thrust_ratio * force * 1e3],
                "efficiency_pct": [math.nan, b.efficiency * 100.0],
                "label": ["#CC79A7", "#F0E442"],
            }
            self.speed_figure.x_range.start, self.speed_figure.x_range.end = 0.0, float(V[-1])
            fit_range(self.speed_figure.y_range, thrust, pad=0.05)
            fit_range(self.efficiency_figure.y_range, [0.0], eta, pad=0.05)
            self.status.object = (
                f"ψ = {key[0]:.6g}, τ₀ = {key[1]:.4f} rad: no-load speed "
                f"<b>{result.no_load * speed * 1e3:.4g} mm/s</b> (pink); best efficiency "
                f"<b>{b.efficiency * 100:.3g} %</b> at {b.v * speed * 1e3:.4g} mm/s, "
                f"{b.thrust_ratio * force * 1e3:.4g} mN (yellow). "
                f"{SPEED_POINTS} speeds by MDR in {result.seconds * 1e3:.0f} ms.")

    def close(self) -> None:
        """The session ended: drop the waiting request, make a running one stale, and
        take no new ones."""
        with self._lock:
            self._closed = True
            self._generation += 1
            if self.pending is not None:
                self.pending.cancel()

    # -------------------------------------------------------------- URL

    def query(self) -> dict[str, str]:
        """The scene's state as URL values (keys `motor_*`)."""
        return self.state.query()

    def apply_query(self, query: Mapping[str, str | bytes | list]) -> list[str]:
        """Apply the `motor_*` values of a URL query (other keys are ignored); returns one
        message per refused value, whose last good value is kept. Presets first, then the
        fields, each checked by core with those accepted before it, x0 last."""
        flat: dict[str, str] = {}
        for key, raw in query.items():
            if not key.startswith(PREFIX):
                continue
            if isinstance(raw, list):
                raw = raw[-1] if raw else ""
            if isinstance(raw, bytes):
                raw = raw.decode("utf-8", "replace")
            flat[key.removeprefix(PREFIX)] = str(raw).strip()
        messages = [f"unknown parameter {PREFIX + k!r} ignored "
                    f"(known: {', '.join(QUERY_KEYS)})"
                    for k in flat if PREFIX + k not in QUERY_KEYS]
        values = self.state.values()
        presets: dict[str, str] = {}
        for part, table in (("rod", ROD_PRESETS), ("rotor", ROTOR_PRESETS)):
            if part in flat:
                name = flat[part]
                if name in table:
                    values.update(table[name].values)
                    presets[f"{part}_preset"] = name
                else:
                    messages.append(f"{PREFIX}{part} = {name!r} is unknown "
                                    f"(known: {', '.join(table)})")
        try:
            build_motor(values)
        except ValueError as err:  # presets that do not fit the current x0
            messages.append(f"presets refused: {err}")
            values, presets = self.state.values(), {}
        for name in FIELDS:
            if name not in flat:
                continue
            value = _number(flat[name])
            try:
                build_motor({**values, name: value})
            except ValueError as err:
                messages.append(f"{PREFIX}{name} = {flat[name]!r} refused: {err}")
                continue
            values[name] = float(value)
        self.state.param.update(**values, **presets)
        return messages

    # -------------------------------------------------------------- CSV

    def csv_table(self, key: str) -> dict[str, np.ndarray]:
        """The columns of CSV 'thrust' (the rod, on the points of the stall-thrust plot:
        x0, drive, psi, Phi, tau0, stall thrust) or 'speed' (the thrust-speed curve at x0,
        dimensionless then SI; no rows where there is none), named as `app.contact.export.COLUMNS`
        names them."""
        if key == "thrust":
            p = self.profile
            assert p is not None
            return {"x0 (m)": p.x0, "u0 (m)": p.u0, "H (m)": p.H, "psi": p.psi,
                    "Phi": p.load_factor, "opens": p.opens.astype(float),
                    "tau0 (rad)": p.tau0, "F_x/(mu N)": p.thrust_ratio,
                    "F_x (N)": p.stall_thrust}
        if key != "speed":
            raise KeyError(key)
        names = ("V/(omega u0)", "F/(mu N)", "eta", "P_out/(mu N omega u0)",
                 "P_in/(mu N omega u0)", "P_loss/(mu N omega u0)", "V (m/s)", "F (N)",
                 "P_out (W)", "P_in (W)", "P_loss (W)")
        result = self._speed_result()
        if result is None:
            return {name: np.empty(0) for name in names}
        speed, force, power = self._scales()
        c = result.curve
        return dict(zip(names, (c.v, c.thrust_ratio, c.efficiency, c.output_power,
                                c.input_power, c.friction_loss, c.v * speed,
                                c.thrust_ratio * force, c.output_power * power,
                                c.input_power * power, c.friction_loss * power),
                        strict=True))

    def _speed_result(self) -> SpeedCurve | None:
        """The thrust-speed curve at x0 (the cache's), or None where there is none."""
        ckey = self.curve_key()
        try:
            return speed_curve(*ckey) if ckey is not None else None
        except ValueError:  # e.g. x0 = 0: no tangential drive
            return None

    def csv_header(self, key: str) -> list[str]:
        """The comment lines of CSV `key` (`app.contact.export.comments`): the rod's and the
        rotor's inputs in SI (the floats core computed with), and for 'speed' x0 and the
        contact there."""
        m = self.motor
        names = (*ROD_FIELDS, *ROTOR_FIELDS, *(("x0",) if key == "speed" else ()))
        lines: list[export.Line] = [
            "inputs in SI (the rod: L half-length, delta thickness, nu_rod Poisson ratio,"
            " A amplitude at x = L, f frequency; the rotor: R radius, G shear modulus,"
            " nu Poisson ratio, mu friction coefficient, N preload"
            f"{'; x0 the contact point' if key == 'speed' else ''}):"]
        lines += [(n, SI_UNITS[FIELDS[n].unit],
                   self.x0 if n == "x0" else getattr(m.rod if n in ROD_FIELDS else m,
                                                     FIELDS[n].core))
                  for n in names]
        if key == "speed":
            ckey = self.curve_key()
            if ckey is None or self._speed_result() is None:
                lines.append("no curve: " + ("the contact never opens at x0" if ckey is None
                                             else "no tangential drive at x0"))
            else:
                lines.append("the contact at x0 (the curve is computed at these values,"
                             f" rounded to {KEY_DIGITS} significant digits):")
                lines += [(n, u, v) for (n, u), v in zip(export.PARAMETERS, ckey,
                                                         strict=True)]
        return export.comments(f"motor_{key}", lines)

    def csv_text(self, key: str) -> str:
        """CSV of 'thrust' or 'speed' (`csv_table`) in the explorer's style
        (`app.contact.export.csv_text`): the header block, the column names with units, the rows
        to 10 significant digits."""
        return export.csv_text(self.csv_table(key), self.csv_header(key))

    def csv_filename(self, key: str) -> str:
        """The CSV's file name (`app.contact.export.named`): what it holds and the inputs in
        display units (to 6 significant digits), x0 for the curve at x0."""
        names = (*ROD_FIELDS, *ROTOR_FIELDS, *(("x0",) if key == "speed" else ()))
        return export.named(f"motor_{key}", [
            (n, getattr(self.state, n), "g", FIELDS[n].unit.replace("µ", "u"))
            for n in names])

    def csv_file(self, key: str) -> io.StringIO:
        """The CSV as a file object for `pn.widgets.FileDownload` (named on the click)."""
        self.downloads[key].filename = self.csv_filename(key)
        return io.StringIO(self.csv_text(key))
