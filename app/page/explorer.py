"""The explorer: controls and scenes assembled into one page (`app.page.layout`).

`Explorer`, a `param.Parameterized` controller, shows an `ExplorerState` (what the user
set) in the scenes (what is shown).  One handler, `show_state`, depends on every input of
the contact and on tau: it compares the state with what is on screen, rebuilds the
`core.Contact` and refreshes every scene when the contact differs, refreshes only what
depends on tau when only tau differs, and does nothing when both are shown; a state it
must correct first (psi and tau0 derived from SI inputs, tau clamped into the contact)
it corrects and leaves the showing to the call that correction makes.  So no change is
ever hidden from it and none is shown twice.  All changes of one step are sent to the
browser in one message (`panel.io.hold`).  The animation is played by the browser from
frames computed here (`app.contact.player`), which moves the tau box, the slider and the
formulas with the plots; the server follows the player's clock.
"""

from __future__ import annotations

import html
import io
import math
import textwrap
import time
from functools import partial
from urllib.parse import urlencode

import numpy as np
import panel as pn
import param
from panel.io import hold
from panel.io.location import Location
from panel.io.resources import get_dist_path

from app.contact import export
from app.contact.curves import ForceScene, MotionScene, RadiiScene
from app.contact.formulas import formulas
from app.contact.impulse import ImpulseScene
from app.contact.multiples import SmallMultiples
from app.contact.notes import NOTES
from app.contact.physical_inputs import PhysicalInputs
from app.contact.player import Player, frame_index, frame_taus
from app.contact.readout import Readout
from app.contact.spheres import SpheresScene
from app.contact.state import (
    PRESETS,
    SI_KEYS,
    ExplorerState,
    parse_query,
    parse_tau,
    parse_value,
    query_value,
)
from app.contact.traction import DiscScene, TractionScene
from app.kit.figures import Scene
from app.kit.widgets import ExactSlider, LabelledCheckbox, LabelledSlider, bind, follow
from app.methods import MethodsScene
from app.motor import FIELDS as MOTOR_FIELDS
from app.motor import PREFIX as MOTOR_PREFIX
from app.motor import MotorScene
from app.page import layout, presentation
from core import Contact

CONTACT_SECONDS = 4.0  # one contact lasts this long at speed 1
MESSAGE_CHARS = 400  # a message longer than this (it quotes a long link) is cut
URL_DELAY_S = 0.4  # the URL follows the parameters this long after the last change (s)

#: the state's parameters that define the contact (`ExplorerState.contact`)
CONTACT_INPUTS = ("psi", "tau0", "mu", "nu", "physical", *SI_KEYS)


def apply_query(state: ExplorerState, query: dict) -> list[str]:
    """Apply a URL query's validated values to `state`; returns the messages to show.
    A combination core rejects falls back to the defaults of the values it gave."""
    values, messages = parse_query(query)
    defaults = {k: state.param[k].default for k in values}
    state.param.update(**values)
    try:
        state.contact()
    except ValueError as err:
        messages.append(f"these parameters are rejected ({err}); defaults used")
        state.param.update(**defaults)
    return messages


class Explorer(param.Parameterized):
    """One user's session: state, widgets, scenes and their wiring."""

    state = param.ClassSelector(class_=ExplorerState, constant=True,
                                doc="what the user set; everything on the page shows it")

    def __init__(self, state: ExplorerState | None = None,
                 query: dict | None = None, location: Location | None = None
                 ) -> None:
        state = state or ExplorerState()
        #: the page's URL (`app.page.guard.location_of`), None without a served page
        self.location = location
        query = dict(query or {})
        view = query_value(query.pop("view", ""))
        motor_query = {k: v for k, v in query.items() if k.startswith(MOTOR_PREFIX)}
        rest = {k: v for k, v in query.items() if k not in motor_query}
        messages = apply_query(state, rest) if rest else []
        super().__init__(state=state)  # (the handlers below watch the state from here)
        self.messages = messages
        #: the Motor scene's part of the URL (applied when the scene is built)
        self._motor_query = motor_query
        #: the page shown: '' (everything) or 'present' (one screen, `app.page.presentation`)
        self.view_name = view if view == presentation.VIEW else ""
        if view not in ("", presentation.VIEW):
            self.messages.append(f"view = {view!r} is unknown (known: {presentation.VIEW});"
                                 " the full page is shown")
        self.contact: Contact = self.state.contact()
        #: the time the scenes on the server show (the player's frames aside)
        self._shown_tau = self.state.tau
        #: the contact's inputs as last seen: a change of them retires the messages shown
        self._inputs = self._contact_inputs()
        self._shown_phase = -1
        self._url_pending = False
        self._url_due = 0.0

        self.traction = TractionScene()
        self.disc = DiscScene()
        self.force = ForceScene()
        self.impulse = ImpulseScene()
        self.radii = RadiiScene()
        self.motion = MotionScene()
        self.spheres = SpheresScene()
        self.scenes: list[Scene] = [self.spheres, self.traction, self.disc, self.force,
                                    self.impulse, self.radii, self.motion]
        self.readout = Readout()
        self.methods = MethodsScene()
        self.motor: MotorScene | None = None  # built when its card is first opened
        self.player = Player(self.traction, self.disc, [self.force, self.radii, self.motion],
                             self.traction.caption, self.traction.phase_label,
                             self.traction.figure, self._now_texts,
                             lambda taus: [self.tau_slider.text(t) for t in taus],
                             sprites=[self.spheres])
        #: (progress, time.monotonic(), speed) when the player last (re)started
        self._play_start = (0.0, 0.0, 1.0)

        self._build_widgets()
        self.impulse.set_log(self.state.log_psi)
        #: the curve scenes share one card, one tab each; only the open tab is drawn and
        #: computed (the others catch up when their tab is opened) and a scene's figure is
        #: built when its tab is first opened
        self.tabbed: list[Scene] = [self.force, self.impulse, self.radii, self.motion]
        self.panes = [pn.pane.Bokeh(sizing_mode="stretch_width") for _ in self.tabbed]
        self.tabs = pn.Tabs(*zip(("T(τ) (Fig. 7)", "Impulse (Fig. 8)", "Radii (Fig. 4b)",
                                  "Centre motion (Fig. 9)"), self.panes, strict=True),
                            dynamic=True, sizing_mode="stretch_width",
                            stylesheets=[layout.TAB_ROW_CSS])
        self._show_figure(0)
        self._stale: set[Scene] = set()
        self.tabs.param.watch(self._on_tab, ["active"])
        self.motor_card = pn.Card(title="Motor: the rod, its thrust and speed (Fig. 1)",
                                  collapsed=True, sizing_mode="stretch_width", margin=6)
        self.motor_card.param.watch(self._on_motor_card, "collapsed")
        self.fig6_card = pn.Card(title="Fig. 6 in full: the six traction profiles "
                                 "(ψ = 2.414, τ₀ = π/6)", collapsed=True,
                                 sizing_mode="stretch_width", margin=6)
        self.fig6_card.param.watch(self._on_fig6_card, "collapsed")
        self.refresh()
        if self._motor_query:  # a link to the motor opens it
            self.motor_card.collapsed = False

    # ------------------------------------------------------------------ state

    def _contact_inputs(self) -> tuple:
        return tuple(getattr(self.state, k) for k in CONTACT_INPUTS)

    @param.depends(*(f"state.{k}" for k in (*CONTACT_INPUTS, "tau")), watch=True)
    def show_state(self) -> None:
        """Show the state: refresh every scene if its contact is not the one shown, else
        what depends on tau if its tau is not the one shown, else nothing.

        A state that needs correcting first (with SI inputs psi and tau0 follow from
        them; tau is kept inside the contact) is corrected, and the change that makes
        calls this again to show it.  SI inputs that core refuses together are not
        applied (the physical inputs' card says why, under its boxes)."""
        s = self.state
        inputs = self._contact_inputs()
        if inputs != self._inputs:  # the user changed the contact: past messages are done
            self._inputs = inputs
            self.show_messages([])
        self.psi_slider.disabled = self.tau0_slider.disabled = s.physical
        try:
            c = s.contact()
        except ValueError:
            if s.physical:
                return
            raise
        fixes = {"psi": c.psi, "tau0": c.tau0} if s.physical else {}
        fixes["tau"] = min(max(s.tau, c.tau0), c.tau_end)
        fixes = {k: v for k, v in fixes.items() if getattr(s, k) != v}
        if fixes:
            s.param.update(**fixes)  # (which calls this again)
            return
        if (c, c.scales) != (self.contact, self.contact.scales):
            self.contact = c
            self.refresh()
        elif s.tau != self._shown_tau:
            if s.playing:  # the scrubber moved while playing: play on from there
                self._start_player(self._progress_of(s.tau))
            else:
                self.update_tau()
            self._write_url()

    def shown(self, scene: Scene) -> bool:
        """Whether `scene` is on the page now (the curve scenes: their tab is open)."""
        return scene not in self.tabbed or self.tabbed[self.tabs.active] is scene

    def _on_tab(self, event) -> None:
        if event.new not in range(len(self.tabbed)):  # (from a script: no such tab)
            return
        with hold():
            self.catch_up([self.tabbed[event.new]])
            self._show_figure(event.new)

    def _show_figure(self, tab: int) -> None:
        """Put tab `tab`'s figure in its pane (built on first use)."""
        figure = self.tabbed[tab].figure
        if self.panes[tab].object is not figure:
            self.panes[tab].object = figure

    def catch_up(self, scenes: list[Scene]) -> None:
        """Bring those of `scenes` that missed changes while hidden up to date."""
        c, tau = self.contact, self.state.tau
        with hold():
            for scene in scenes:
                if scene in self._stale:
                    self._stale.discard(scene)
                    scene.update_contact(c)
                    scene.update_tau(c, tau)

    def refresh(self) -> None:
        """Recompute every scene shown for the current state (after a parameter change);
        the others are marked to catch up when shown."""
        c = self.contact
        tau = self._shown_tau = self.state.tau
        with hold():
            for scene in self.scenes:
                if self.shown(scene):
                    scene.update_contact(c)
                    scene.update_tau(c, tau)
                else:
                    self._stale.add(scene)
            self._show_family()
            self.tau_slider.param.update(start=c.tau0, end=c.tau_end, value=tau)
            self.readout.show(self.readout_rows(c))
            self._show_formulas(c, tau)
            self.traction.caption.text = self._now_text(c, tau)
            self.methods.update_contact(c)
            if self.state.playing:  # the player goes on, at its place in the contact
                self._start_player(self._clock_progress())
        self._write_url()

    # ------------------------------------------------------------------ motor

    def _on_motor_card(self, event) -> None:
        """Build the Motor scene when its card is first opened."""
        if event.new or self.motor is not None:
            return
        self.motor = MotorScene()
        self.follow_motor = LabelledCheckbox(
            label="The plots above show the contact at the rotor's x₀", value=True)
        messages = self.motor.apply_query(self._motor_query)
        self.motor.on_contact(self._follow_motor)
        self.motor.state.param.watch(lambda *_: self._write_url(),
                                     [*MOTOR_FIELDS, "rod_preset", "rotor_preset"])
        self.follow_motor.param.watch(lambda e: self._follow_motor(self.motor.contact),
                                      "value")
        self.motor_card.objects = [self.follow_motor, self.motor]
        self._follow_motor(self.motor.contact)
        if messages:  # the link's refused motor values (after following, which clears)
            self.show_messages([*self.messages, *messages])

    def _on_fig6_card(self, event) -> None:
        """Build the six Fig. 6 plots when their card is first opened."""
        if not event.new and not self.fig6_card.objects:
            self.fig6_card.objects = [pn.pane.Bokeh(SmallMultiples().figure,
                                                    sizing_mode="stretch_width")]

    def _follow_motor(self, contact: tuple[float, float] | None) -> None:
        """The scenes above show the rotor's contact (psi, tau0 at x0; its mu, nu)."""
        if contact is None or not self.follow_motor.value:
            return
        psi, tau0 = contact
        m = self.motor.state
        try:
            Contact(psi, tau0, mu=m.mu, nu=m.nu)
        except ValueError as err:  # (e.g. a preload so light that tau0 rounds to pi/2)
            self.show_messages([*self.messages, f"The plots cannot follow the rotor's "
                                f"contact at x₀: {err}"])
            return
        self.state.param.update(physical=False, psi=psi, tau0=tau0, mu=m.mu, nu=m.nu)

    @param.depends("state.preset", watch=True)
    def _on_preset(self) -> None:
        """The selector, its note and the T(tau) family follow the state's preset ('' once
        left)."""
        self.preset_select.value = self.state.preset
        self._show_note()
        with hold():
            self._show_family()
        self._write_url()

    def _show_note(self) -> None:
        """What to notice in the preset on screen (hidden once it is left)."""
        note = NOTES.get(self.state.preset, "")
        self.note.param.update(object=html.escape(note), visible=bool(note))

    def _show_family(self) -> None:
        """Overlay the T(tau) curves of the preset's psi family (Fig. 7), or none."""
        c = self.contact
        preset = PRESETS.get(self.state.preset)
        family = preset.family if preset else ()
        self.force.set_family([Contact(p, c.tau0, mu=c.mu, nu=c.nu) for p in family])

    def update_tau(self) -> None:
        """Refresh what depends on tau only (a scrub, a step, the frame a pause lands on)."""
        c = self.contact
        tau = self._shown_tau = self.state.tau
        with hold():
            for scene in self.scenes:
                if scene in self._stale:
                    continue  # caught up in full when shown
                if self.shown(scene):
                    scene.update_tau(c, tau)
                else:
                    self._stale.add(scene)
            self.methods.update_tau(c, tau)
            self._show_formulas(c, tau)
            self.traction.caption.text = self._now_text(c, tau)
            self.tau_slider.value = tau  # (its watcher finds the state's tau unchanged)

    def _show_formulas(self, c: Contact, tau: float) -> None:
        phase = int(c.phase(tau))  # a 0-d array for one tau
        if phase != self._shown_phase:
            self._shown_phase = phase
            self.formulas.object = formulas(phase)

    @param.depends("state.log_psi", watch=True)
    def _on_log(self) -> None:
        self.impulse.set_log(self.state.log_psi)
        self._stale.add(self.impulse)
        if self.shown(self.impulse):
            with hold():
                self.catch_up([self.impulse])
                self._show_figure(self.tabbed.index(self.impulse))
        self._write_url()

    # -------------------------------------------------------------- animation

    def step(self, seconds: float = 1 / 30) -> float:
        """Advance tau as `seconds` of animation at the current speed; wrap at the end.

        Returns the new tau.  The last frame of a contact lands exactly on pi - tau0;
        the next one starts again at tau0.  Stepping pauses a running animation.
        """
        self.state.playing = False
        c = self.contact
        tau = self.state.tau
        if tau >= c.tau_end:
            new = c.tau0
        else:
            dtau = self.state.speed * (c.tau_end - c.tau0) * seconds / CONTACT_SECONDS
            new = min(tau + dtau, c.tau_end)
        self.state.tau = new
        return new

    def _progress_of(self, tau: float) -> float:
        """Where tau lies in the contact, in [0, 1)."""
        c = self.contact
        return min(max((tau - c.tau0) / (c.tau_end - c.tau0), 0.0), 1.0) % 1.0

    def _clock_progress(self, now: float | None = None) -> float:
        """Where the browser's player is in the contact at time `now` (monotonic s), in
        [0, 1)."""
        progress, started, speed = self._play_start
        now = time.monotonic() if now is None else now
        return (progress + speed * (now - started) / CONTACT_SECONDS) % 1.0

    def clock_tau(self, now: float | None = None) -> float:
        """The tau of the frame the browser's player shows at time `now` (monotonic s)."""
        return float(frame_taus(self.contact)[frame_index(self._clock_progress(now))])

    def _start_player(self, progress: float) -> None:
        """(Re)start the browser's player at `progress` with the current contact and speed.

        The frames are Bokeh model changes made from a widget callback, which Panel runs
        without the document lock: they must go through `hold()` (without it, a change
        made while a message is being written raises in Bokeh and the player never
        starts)."""
        c = self.contact
        self._play_start = (progress, time.monotonic(), self.state.speed)
        with hold():
            self.player.play(c, progress, self.state.speed, CONTACT_SECONDS)

    @param.depends("state.speed", watch=True)
    def _on_speed(self) -> None:
        if self.state.playing:  # keep the current frame, change the pace
            self._start_player(self._clock_progress())

    @param.depends("state.playing", watch=True)
    def _on_playing(self) -> None:
        """Start the browser's player at the state's tau; a pause puts the state's tau
        (which holds the tau the play last started from) on the player's frame."""
        playing = self.state.playing
        self.play_button.label = "‖ Pause" if playing else "▶ Play"
        self.play_button.color = "warning" if playing else "success"
        if playing:
            self._start_player(self._progress_of(self.state.tau))
            return
        with hold():  # one message: the player stops and the plots settle on its frame
            self.player.stop()
            self.state.tau = self.clock_tau()
            self.show_state()  # (if the frame is the tau the play started from)

    # ------------------------------------------------------------------- view

    def _build_widgets(self) -> None:
        s = self.state
        for name, label, start, end, step in (
                ("psi", "ψ = tan θ / tan θ₀", 0.05, 30.0, 0.01),
                ("tau0", "τ₀ (rad): contact starts", -1.5, 1.5, 0.005),
                ("mu", "μ friction", 0.01, 1.0, 0.01),
                ("nu", "ν Poisson ratio", 0.0, 0.49, 0.01)):
            widget = ExactSlider(label=label, value=getattr(s, name), start=start, end=end,
                                 step=step, parse=partial(parse_value, name), name=name)
            bind(widget, s.param[name])
            setattr(self, f"{name}_slider", widget)
        # not bound both ways: while playing, the browser's player moves it (the state
        # keeps the tau the play started from)
        self.tau_slider = ExactSlider(
            label="τ = ωt (rad): time", value=s.tau, start=self.contact.tau0,
            end=self.contact.tau_end, step=0.002,
            parse=lambda text: parse_tau(text, self.contact), name="tau")
        follow(self.tau_slider, s.param.tau)
        self.play_button = pn.widgets.Button(label="▶ Play", color="success", width=110)
        self.play_button.on_click(lambda _: setattr(s, "playing", not s.playing))
        self.step_button = pn.widgets.Button(label="Step", width=100)
        self.step_button.on_click(lambda _: self.step())
        self.speed_slider = LabelledSlider(label="Speed", value=s.speed, start=0.1, end=5.0,
                                           step=0.1, show_title=True,
                                           sizing_mode="stretch_width", margin=(5, 10))
        bind(self.speed_slider, s.param.speed)
        self.log_box = LabelledCheckbox.from_param(s.param.log_psi,
                                                   label="log ψ axis (to 10⁶)")
        options = {"(custom)": "", **{p.label: k for k, p in PRESETS.items()}}
        self.preset_select = pn.widgets.Select(label="Preset: the paper's figures",
                                               options=options, value=s.preset)
        self.preset_select.param.watch(self._on_preset_select, "value")
        self.note = pn.pane.HTML("", sizing_mode="stretch_width", styles=layout.NOTE_STYLE)
        self._show_note()
        self.reset_button = pn.widgets.Button(label="Reset", width=100)
        self.reset_button.on_click(lambda _: s.reset())

        self.physical_inputs = PhysicalInputs(s)  # R in mm, G in GPa, ... (its module)
        self.physical_box = self.physical_inputs.physical_box
        self.material_select = self.physical_inputs.material_select
        self.physical_card = self.physical_inputs.card
        # a link with physical inputs: psi and tau0 follow from them (as in `show_state`)
        self.psi_slider.disabled = self.tau0_slider.disabled = s.physical

        self.message = pn.pane.HTML("", visible=False, sizing_mode="stretch_width",
                                    name="query_message", styles=layout.MESSAGE_STYLE)
        self.show_messages(self.messages)
        self.formulas = pn.pane.LaTeX(  # (scaled down to fit a narrow card; else scroll)
            "", renderer="katex", sizing_mode="stretch_width", styles={"overflow-x": "auto"},
            stylesheets=[layout.FORMULA_CSS], tags=["formulas"])
        self.downloads = {
            key: pn.widgets.FileDownload(callback=lambda key=key: self.csv_file(key),
                                         filename=f"{key}.csv", label=f"CSV: {key}",
                                         color="primary", width=150)
            for key in ("curves", "traction", "impulse")
        }

    def _on_preset_select(self, event) -> None:
        if event.new and event.new != self.state.preset:
            self.state.apply_preset(event.new)

    def show_messages(self, messages: list[str]) -> None:
        """Show warnings (e.g. rejected URL values) above the plots; [] hides them.

        Messages quote what the user sent (the URL's values): they are shown as text,
        never as markup.  Unchanged messages are not sent again.
        """
        text = "<br>".join(html.escape(textwrap.shorten(m, MESSAGE_CHARS, placeholder=" …"))
                           for m in messages)
        if text != self.message.object or self.message.visible != bool(messages):
            self.message.param.update(object=text, visible=bool(messages))

    @staticmethod
    def readout_rows(c: Contact) -> list[tuple[str, str]]:
        """The derived quantities shown: (quantity, value) pairs."""
        rows = [
            ("θ (incidence angle)", f"{math.degrees(c.theta):.3f}°"),
            ("θ₀ (critical angle)", f"{math.degrees(c.theta0):.3f}°"),
            ("ψ", f"{c.psi:.6g}"),
            ("τ₀ … π − τ₀", f"{c.tau0:.4f} … {c.tau_end:.4f} rad"),
            ("τ₁ (stick disc vanishes)", "none (ψ ≤ 1)" if math.isnan(c.tau1)
             else f"{c.tau1:.4f} rad"),
            ("T_imp / (μ P_imp)", f"{c.impulse_ratio:.5f}"),
        ]
        sc = c.scales
        if sc is not None:
            rows += [
                ("T₀ (force scale)", f"{sc.T0:.4g} N"),
                ("P₀ = T₀/μ", f"{sc.P0:.4g} N"),
                ("a* (largest contact radius)", f"{sc.a_star * 1e6:.4g} µm"),
                ("p* (peak pressure)", f"{sc.p_star / 1e6:.4g} MPa"),
                ("normal impulse", f"{sc.normal_impulse:.4g} N·s"),
                ("tangential impulse", f"{sc.tangential_impulse:.4g} N·s"),
                ("period 2π/ω", f"{sc.period * 1e6:.4g} µs"),
            ]
        return rows

    def _now_text(self, c: Contact, tau: float) -> str:
        return self._now_texts(c, np.array([tau]))[0]

    @staticmethod
    def _now_texts(c: Contact, taus: np.ndarray) -> list[str]:
        """The caption of the traction plot at each of the times taus."""
        T, a, b = (f(taus) for f in (c.tangential_force, c.contact_radius, c.stick_radius))
        texts = [f"τ = {t:.4f} rad  T/T₀ = {x:+.4f}\na/a* = {y:.4f}  b/a* = {z:.4f}"
                 for t, x, y, z in zip(taus, T, a, b, strict=True)]
        sc = c.scales
        if sc is not None:
            texts = [text + (f"\nt = {t * sc.period / (2 * math.pi) * 1e6:.4g} µs"
                             f"  T = {x * sc.T0:.4g} N\n"
                             f"a = {y * sc.a_star * 1e6:.4g} µm  b = {z * sc.a_star * 1e6:.4g} µm")
                     for text, t, x, y, z in zip(texts, taus, T, a, b, strict=True)]
        return texts

    # ---------------------------------------------------------------- outputs

    def csv_text(self, key: str, tau: float | None = None) -> str:
        """CSV of the data shown (`app.contact.export`): 'curves' (T, radii, motion on the tau
        grid), 'traction' (the profile at time tau, rad: by default the state's) or
        'impulse' (the impulse curve), after comment lines naming the parameters."""
        self.catch_up(self.tabbed)  # a hidden tab's data too, as it is now
        c = self.contact
        tau = self.state.tau if tau is None else tau
        if key == "curves":
            table = export.curves_table(self.force, self.radii, self.motion, c)
        elif key == "traction":
            table = export.traction_table(self.traction, c, tau)
        elif key == "impulse":
            table = self.impulse.table()
        else:
            raise KeyError(key)
        return export.csv_text(table, export.header(key, c, tau if key == "traction" else None))

    def csv_filename(self, key: str, tau: float | None = None) -> str:
        """The CSV file's name, after the parameters it holds and, for 'traction', the
        time tau (rad; by default the state's)."""
        tau = self.state.tau if tau is None else tau
        return export.file_name(key, self.contact, tau if key == "traction" else None)

    def csv_file(self, key: str) -> io.StringIO:
        """The CSV as a file object, for `pn.widgets.FileDownload` (called on a click).

        A traction profile is taken at the tau shown: while playing, the browser's frame
        (`clock_tau`), named in the file and its name alike.  The download is named here,
        when it is made, not on every parameter change: renaming the buttons' files
        would re-render them in the browser per slider move.
        """
        tau = self.clock_tau() if self.state.playing else self.state.tau
        self.downloads[key].filename = self.csv_filename(key, tau)
        return io.StringIO(self.csv_text(key, tau))

    def _write_url(self) -> None:
        """Put the parameters in the page's URL, URL_DELAY_S after the last change.

        Every URL change is a round trip (the browser pushes the history entry and
        reports the new location back); during a slider drag it would compete with the
        plots for the browser, so a burst of changes writes the URL once, at its end.
        """
        loc, doc = self.location, pn.state.curdoc
        if loc is None or doc is None:
            return
        if doc.session_context is None:  # no server session (a notebook): no loop to wait on
            self._put_url(loc)
            return
        self._url_due = time.monotonic() + URL_DELAY_S
        if not self._url_pending:
            self._url_pending = True
            doc.add_timeout_callback(partial(self._flush_url, loc, doc),
                                     int(URL_DELAY_S * 1000))

    def _flush_url(self, loc, doc) -> None:
        wait = self._url_due - time.monotonic()
        if wait > 0.005:  # changed again meanwhile: wait for the end of the burst
            doc.add_timeout_callback(partial(self._flush_url, loc, doc), int(wait * 1000))
            return
        self._url_pending = False
        self._put_url(loc)

    def _put_url(self, loc) -> None:
        query = self.state.query()
        if self.motor is not None:
            query.update(self.motor.query())
        if self.view_name:
            query["view"] = self.view_name
        loc.search = "?" + urlencode(query)

    def view(self) -> pn.Column:
        """The page: `app.page.layout.page`, or the one-screen `app.page.presentation` view when
        the explorer was opened with view=present."""
        if self.view_name == presentation.VIEW:
            return presentation.presentation(self)
        return layout.page(self)

    def servable(self, page: pn.Column | None = None) -> pn.Column:
        """Mark the page servable (the application script `app/main.py` calls this).

        Panel points its components' stylesheets at its CDN until it renders the page's
        HTML, and then at the server's own copies.  With `--num-procs` above 1 a page's
        websocket may reach a process that did not serve the page, which builds the
        session's document for the websocket alone: its stylesheets would stay on the
        CDN, which the page's Content-Security-Policy refuses (and an offline classroom
        cannot reach).  So the document says where they are before it is built."""
        doc = pn.state.curdoc
        if doc is not None:
            doc.template_variables.setdefault("dist_url", get_dist_path(cdn=False))
        page = (page or self.view()).servable(title=layout.TITLE,
                                              location=self.location or True)
        if doc is not None:
            doc.template_variables["meta"] = layout.META
            pn.state.on_session_destroyed(self.close)
            for slider in (self.psi_slider, self.tau0_slider, self.mu_slider,
                           self.nu_slider, self.tau_slider):
                slider.follow_browser(doc)  # (its moves without Panel's 50 ms wait)
        return page

    def close(self, session_context) -> None:
        """The session ended: stop the Methods and Motor runs."""
        self.methods.close()
        if self.motor is not None:
            self.motor.close()


def build_explorer(query: dict | None = None,
                   location: Location | None = None) -> Explorer:
    """Build one session's explorer; `query` defaults to the page's URL query."""
    if query is None:
        query = dict(pn.state.session_args) if pn.state.curdoc is not None else {}
    return Explorer(query=query, location=location)
