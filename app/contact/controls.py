"""The contact's controls: widgets made from the state's parameters.

Sliders with exact entry for psi, tau0, mu and nu (`ExactSlider`), the way the drive
is set (by psi, or by its angle theta with its own slider) and the note on what mu and
nu change, the tau scrubber (it writes the state's tau; while playing, the browser's
player moves it), Play/Pause, Step, Speed, the log-psi box, the preset menu and its
note, Reset, the SI inputs (`app.contact.physical_inputs`), the formula card and the CSV
downloads.  `app.contact.view.connect` connects them to the state (every value a widget
takes from the browser reaches the state there, refused when the state's domain refuses
it) and to the view.
"""

from __future__ import annotations

import html
import io
import math
from collections.abc import Callable
from functools import partial
from typing import Protocol

import panel as pn

from app.contact.formulas import FORMULAS_TAG
from app.contact.notes import NOTES
from app.contact.physical_inputs import PhysicalInputs
from app.contact.play_button import PlayButton
from app.contact.state import PRESETS, ExplorerState, parse_tau, parse_value
from app.kit.a11y import RadioGroup
from app.kit.sliders import ExactSlider, LabelledSlider
from app.kit.style import FORMULA_CSS, NOTE_STYLE
from app.kit.widgets import LabelledCheckbox

#: The sliders of the contact's four numbers: (name, label, start, end, step); their
#: boxes take any value of core's domain, the slider widening to show it.
SLIDERS = (("psi", "ψ = tan θ / tan θ₀", 0.05, 30.0, 0.01),
           ("tau0", "τ₀ (rad): contact starts", -1.5, 1.5, 0.005),
           ("mu", "μ friction", 0.01, 1.0, 0.01),
           ("nu", "ν Poisson ratio", 0.0, 0.49, 0.01))

#: The drive modes' names on their buttons (`ExplorerState.drive`).
DRIVE_OPTIONS = {"ψ": "psi", "angle θ": "angle"}

#: Under the mu and nu sliders: what they change, per way of setting the drive.
DRIVE_NOTES = {
    "psi": "With ψ held, μ and ν leave every plot unchanged: they enter only through "
           "ψ = tan θ / tan θ₀ and the scales (T₀, a*, p*); they turn θ₀, θ and the "
           "drive line. Set the drive by its angle θ to see friction change the phases.",
    "angle": "The drive's angle θ is held: ψ = tan θ / tan θ₀ follows from θ, μ and ν "
             "(eq 23), so more friction (a larger θ₀) means a smaller ψ and longer stick.",
    "physical": "ψ and τ₀ follow from the physical inputs (θ = arctan(u₀/H)), μ and ν.",
}

#: The tau slider's step (rad): one degree of the period a key press (Page Up / Down
#: five), about 120 steps over a contact of tau0 = pi/6, where 0.002 rad moved nothing
#: one could see.
TAU_STEP = math.pi / 180

#: The note of a preset left: in its place, faded.
LEFT_NOTE_STYLE = {**NOTE_STYLE, "opacity": "0.45"}

#: The CSV downloads: key -> what it holds (`ContactView.csv_text`).
DOWNLOADS = ("curves", "traction", "impulse")


class ControlledView(Protocol):
    """What the controls read of the view (`app.contact.view.ContactView`): the CSV
    files."""

    def csv_file(self, key: str) -> io.StringIO: ...


class Controls:
    """The contact's widgets, showing `state`'s values; `view` makes the CSV files.  They
    are connected to the state and the view by `app.contact.view.connect`."""

    def __init__(self, state: ExplorerState, view: ControlledView) -> None:
        for name, label, start, end, step in SLIDERS:
            widget = ExactSlider(label=label, value=getattr(state, name), start=start,
                                 end=end, step=step, parse=partial(parse_value, name),
                                 name=name)
            setattr(self, f"{name}_slider", widget)
        self.drive_select = RadioGroup(  # (a radio group: aria-checked)
            label="Set the drive by", options=DRIVE_OPTIONS, value=state.drive,
            sizing_mode="stretch_width", margin=(5, 10))
        self.drive_control = pn.Column(
            pn.pane.HTML("Set the drive by", margin=(0, 10)), self.drive_select,
            sizing_mode="stretch_width", margin=0)
        self.theta_slider = ExactSlider(
            label="θ (°): drive angle, tan θ = u₀/H", value=state.theta, start=0.0, end=89.5,
            step=0.1, parse=partial(parse_value, "theta"), name="theta")
        self.drive_note = pn.pane.HTML("", sizing_mode="stretch_width", styles=NOTE_STYLE,
                                       name="drive_note")
        c = state.contact()
        self.tau_slider = ExactSlider(
            label="τ = ωt (rad): time", value=state.tau, start=c.tau0, end=c.tau_end,
            step=TAU_STEP, parse=lambda text: parse_tau(text, state.current, state.period),
            name="tau")
        self.play_button = PlayButton(width=110)  # (the keyboard stays on it)
        self.step_button = pn.widgets.Button(label="Step", width=100)
        self.speed_slider = LabelledSlider(label="Speed", value=state.speed, start=0.1,
                                           end=5.0, step=0.1, show_title=True,
                                           sizing_mode="stretch_width", margin=(5, 10))
        self.log_box = LabelledCheckbox(label="log ψ axis (to 10⁶)", value=state.log_psi)
        self.period_box = LabelledCheckbox(
            label="Play the whole period: approach, contact, parting", value=state.period)
        options = {"(custom)": "", **{p.label: k for k, p in PRESETS.items()}}
        self.preset_select = pn.widgets.Select(label="Preset: the paper's figures",
                                               options=options, value=state.preset)
        self.note = pn.pane.HTML("", sizing_mode="stretch_width", styles=NOTE_STYLE)
        self.show_preset(state.preset, NOTES.get(state.preset, ""))
        self.reset_button = pn.widgets.Button(label="Reset", width=100)

        self.physical_inputs = PhysicalInputs(state)  # R in mm, G in GPa, ...
        self.physical_box = self.physical_inputs.physical_box
        self.material_select = self.physical_inputs.material_select
        self.physical_card = self.physical_inputs.card
        self._drive_shown: tuple[bool, str] | None = None
        self.show_drive(state)
        self.formulas = pn.pane.LaTeX(  # (scaled down to fit a narrow card; else scroll)
            "", renderer="katex", sizing_mode="stretch_width", styles={"overflow-x": "auto"},
            stylesheets=[FORMULA_CSS], tags=[FORMULAS_TAG])
        self.downloads = {key: self._download(key, view.csv_file) for key in DOWNLOADS}

    @staticmethod
    def _download(key: str, make: Callable[[str], io.StringIO]) -> pn.widgets.FileDownload:
        return pn.widgets.FileDownload(callback=partial(make, key), filename=f"{key}.csv",
                                       label=f"CSV: {key}", color="primary", width=150)

    def show_preset(self, name: str, note: str) -> None:
        """The menu on preset `name` ('' once left) and its note.  A preset left keeps its
        note's box, faded (`LEFT_NOTE_STYLE`): the controls below it stay where they are
        (a drag that leaves a preset keeps its slider under the pointer)."""
        self.preset_select.value = name
        if name:
            self.note.param.update(object=html.escape(note), visible=bool(note),
                                   styles=NOTE_STYLE)
        else:
            self.note.styles = LEFT_NOTE_STYLE

    def show_drive(self, state: ExplorerState) -> None:
        """The sliders of what follows from other inputs disabled (psi with the drive's
        angle or SI inputs, theta with psi or SI inputs, tau0 with SI inputs;
        `ExplorerState._follow_inputs` derives them) and the note on mu and nu; nothing when
        they show this state's already (every move of a slider calls this)."""
        shown = (state.physical, state.drive)
        if shown == self._drive_shown:
            return
        self._drive_shown = shown
        angle = state.drive == "angle"
        self.psi_slider.disabled = state.physical or angle
        self.tau0_slider.disabled = state.physical
        self.theta_slider.disabled = state.physical or not angle
        self.drive_note.object = html.escape(
            DRIVE_NOTES["physical" if state.physical else state.drive])

    def show_playing(self, playing: bool) -> None:
        """Play/Pause's label and colour."""
        self.play_button.show(playing)

    def clear_refusals(self) -> None:
        """No box says why a value was refused any more (after Reset, or a switch of the
        physical inputs: the value they quote is no longer on screen)."""
        for slider in self.sliders().values():
            slider.error = ""

    def sliders(self) -> dict[str, ExactSlider]:
        """The sliders with exact entry, by the name of the state's parameter each sets."""
        return {"psi": self.psi_slider, "theta": self.theta_slider,
                "tau0": self.tau0_slider, "mu": self.mu_slider, "nu": self.nu_slider,
                "tau": self.tau_slider}
