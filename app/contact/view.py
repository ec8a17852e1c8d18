"""The contact feature: the state of one contact shown in every scene, and its controls.

`ContactView` shows an `ExplorerState` (what the user set) in the scenes (what is shown);
`connect` makes every subscription of the feature, in one place.  The path from a slider
to a plot (docs/app.md, "How data flows"; `tests/app/test_slider_path.py` traces it):

    SliderModel.value --ExactSlider.take_move, feed--> ExplorerState.set_input (psi and
      what follows: theta, tau, `current`) --watch--> Scene.follow
      -> TractionScene.update_tau -> source.data (core's numbers)

The state derives its own contact (`ExplorerState.current`) and corrections; each scene
follows the state's `current` and `tau` by its own watcher (`Scene.follow`: a hidden
scene computes nothing and catches up when shown), and the view follows them for what
is its own (`show_state`: the readout, the formulas, the caption, the tau slider, the
T(tau) family, the animation).  All changes of one step reach the browser as one
message (`app.kit.batch.held`, entered where a move enters the app).  The curve scenes
share one card of tabs: only the open tab is computed, the others catch up when opened.

The animation is played by the browser (`app.contact.animation`); the page around this
view (URL, cards of other features, messages) is `app.page.explorer`'s.
"""

from __future__ import annotations

import io
from functools import partial

import panel as pn
import param

from app.contact import export
from app.contact.animation import Animation
from app.contact.controls import Controls
from app.contact.curves import ForceScene, MotionScene
from app.contact.data import caption, captions, readout_rows
from app.contact.formulas import FORMULAS_TAG, formulas
from app.contact.impulse import ImpulseScene
from app.contact.multiples import SmallMultiples
from app.contact.notes import NOTES
from app.contact.player import Player, played
from app.contact.radii import RadiiScene
from app.contact.readout import Readout
from app.contact.spheres import SpheresScene
from app.contact.state import PRESETS, ExplorerState
from app.contact.traction import DiscScene, TractionScene
from app.kit.a11y import expandable_card
from app.kit.batch import held
from app.kit.scene import Scene
from app.kit.style import TAB_ROW_CSS
from app.kit.texts import PaneText
from app.kit.widgets import sync
from core import Contact

#: The curve tabs' titles, in the order of `ContactView.tabbed`.
TAB_TITLES = ("T(τ) (Fig. 7)", "Impulse (Fig. 8)", "Radii (Fig. 4b)", "Centre motion (Fig. 9)")


class ContactView(param.Parameterized):
    """One session's contact: its state, scenes, controls and animation."""

    state = param.ClassSelector(class_=ExplorerState, constant=True,
                                doc="what the user set; every scene shows it")

    def __init__(self, state: ExplorerState | None = None) -> None:
        state = state or ExplorerState()
        super().__init__(state=state)
        #: the phase whose formulas the card holds (-1: none yet)
        self._formula_phase = -1
        self.traction, self.disc = TractionScene(), DiscScene()
        self.force, self.impulse = ForceScene(), ImpulseScene()
        self.radii, self.motion = RadiiScene(), MotionScene()
        self.spheres = SpheresScene()
        self.scenes: list[Scene] = [self.spheres, self.traction, self.disc, self.force,
                                    self.impulse, self.radii, self.motion]
        self.readout = Readout()
        self.controls = Controls(state, self)
        self._formulas = PaneText(self.controls.formulas, FORMULAS_TAG)
        self.player = Player(self.traction, self.disc, [self.force, self.radii, self.motion],
                             self.traction.caption, self.traction.phase_label,
                             self.traction.figure, captions,
                             lambda taus: [self.controls.tau_slider.text(t) for t in taus],
                             sprites=[self.spheres])
        self.animation = Animation(self)
        self.impulse.set_log(state.log_psi)
        #: the curve scenes share one card, one tab each; a scene's figure is built when
        #: its tab is first opened
        self.tabbed: list[Scene] = [self.force, self.impulse, self.radii, self.motion]
        self.panes = [pn.pane.Bokeh(sizing_mode="stretch_width") for _ in self.tabbed]
        self.tabs = pn.Tabs(*zip(TAB_TITLES, self.panes, strict=True), dynamic=True,
                            sizing_mode="stretch_width", stylesheets=[TAB_ROW_CSS])
        for scene in self.tabbed[1:]:
            scene.hidden = True
        self._show_figure(0)
        self._open_preset_tab()  # (a link to Fig. 8 shows Fig. 8)
        self.fig6_card = expandable_card(
            title="Fig. 6 in full: the six traction profiles (ψ = 2.414, τ₀ = π/6)",
            collapsed=True, sizing_mode="stretch_width", margin=6)
        connect(self)
        self.draw_all()

    # ------------------------------------------------------------------ state

    def show_state(self, *events: param.parameterized.Event) -> None:
        """Show what is the view's of the state's contact (`current`) and tau: after a new
        contact the T(tau) family, the tau slider's range and the readout; the formulas
        and the caption at tau; the tau slider's value (a tau set elsewhere: a step, a
        typed value); while playing, the browser's player (re)started at the state's
        place instead (the scenes draw nothing then: `Scene.follow`)."""
        s = self.state
        c, tau = s.current, s.tau
        new = any(e.name == "current" for e in events)
        with held():
            if new:
                self._show_family()
                self.controls.tau_slider.set_range(*played(c, s.period), tau)
                self.readout.show(readout_rows(c))
            if s.playing:
                self.animation.start(self.animation.clock_progress() if new
                                     else self.animation.progress_of(tau))
                if not new:
                    return
            self._show_time(c, tau)

    def _show_time(self, c: Contact, tau: float) -> None:
        """The formulas, the caption and the tau slider at time `tau` of contact `c`."""
        self._show_formulas(c, tau)
        self.traction.caption.text = caption(c, tau)
        self.controls.tau_slider.value = tau  # (nothing when it holds tau: its own move)

    def settle(self) -> None:
        """After a pause: each scene shown draws the state's tau if it drew another
        (while playing, the browser played the frames and the scrubber moved tau
        without them), and the view's texts follow."""
        s = self.state
        with held():
            for scene in self.scenes:
                if not scene.hidden and scene.drawn_tau != s.tau:
                    scene.update_tau(s.current, s.tau)
                    scene.drawn_tau = s.tau
            self._show_time(s.current, s.tau)

    def show_tab(self, event: param.parameterized.Event) -> None:
        """Tab `event.new` opened: the other tabs' scenes hidden, its scene caught up
        and its figure in its pane."""
        if event.new not in range(len(self.tabbed)):  # (from a script: no such tab)
            return
        for i, scene in enumerate(self.tabbed):
            scene.hidden = i != event.new
        with held():
            self.catch_up([self.tabbed[event.new]])
            self._show_figure(event.new)

    def _show_figure(self, tab: int) -> None:
        """Put tab `tab`'s figure in its pane (built on first use)."""
        figure = self.tabbed[tab].figure
        if self.panes[tab].object is not figure:
            self.panes[tab].object = figure

    def catch_up(self, scenes: list[Scene]) -> None:
        """Draw those of `scenes` that missed changes while hidden (`Scene.stale`)."""
        with held():
            for scene in scenes:
                if scene.stale:
                    self._draw(scene)

    def _draw(self, scene: Scene) -> None:
        """Draw `scene` in full for the state's contact and tau."""
        s = self.state
        scene.stale = False
        scene.update_contact(s.current)
        scene.update_tau(s.current, s.tau)
        scene.drawn_tau = s.tau

    def draw_all(self) -> None:
        """Draw every scene shown and what is the view's (the others are marked to catch
        up when shown): a new view."""
        with held():
            for scene in self.scenes:
                if scene.hidden:
                    scene.stale = True
                else:
                    self._draw(scene)
            c = self.state.current
            self._show_family()
            self.controls.tau_slider.set_range(*played(c, self.state.period), self.state.tau)
            self.readout.show(readout_rows(c))
            self._show_time(c, self.state.tau)

    def _show_formulas(self, c: Contact, tau: float) -> None:
        phase = int(c.phase(tau))  # a 0-d array for one tau
        if phase != self._formula_phase:
            self._formula_phase = phase
            self._formulas.write(formulas(phase))

    # ---------------------------------------------------------------- presets

    def show_preset(self, *events: param.parameterized.Event) -> None:
        """The selector, its note and the T(tau) family follow the state's preset ('' once
        left); a preset opens the tab of its figure (Figs. 4, 8, 9)."""
        self.controls.show_preset(self.state.preset, NOTES.get(self.state.preset, ""))
        with held():
            self._show_family()
            self._open_preset_tab()

    def _open_preset_tab(self) -> None:
        preset = PRESETS.get(self.state.preset)
        if preset is not None:
            self.tabs.active = [s.name for s in self.tabbed].index(preset.tab)

    def _show_family(self) -> None:
        """Overlay the T(tau) curves of the preset's psi family (Fig. 7), or none."""
        c = self.state.current
        preset = PRESETS.get(self.state.preset)
        family = preset.family if preset else ()
        self.force.set_family([Contact(p, c.tau0, mu=c.mu, nu=c.nu) for p in family])

    def show_log(self, *events: param.parameterized.Event) -> None:
        """The impulse curve on the log psi axis, or not (the state's `log_psi`)."""
        self.impulse.set_log(self.state.log_psi)
        self.impulse.stale = True
        if not self.impulse.hidden:
            with held():
                self.catch_up([self.impulse])
                self._show_figure(self.tabbed.index(self.impulse))

    def show_fig6(self, event: param.parameterized.Event) -> None:
        """Build the six Fig. 6 plots when their card is first opened."""
        if not event.new and not self.fig6_card.objects:
            self.fig6_card.objects = [pn.pane.Bokeh(SmallMultiples().figure,
                                                    sizing_mode="stretch_width")]

    # ---------------------------------------------------------------- outputs

    def csv_text(self, key: str, tau: float | None = None) -> str:
        """CSV of the data shown (`app.contact.export`): 'curves' (T, radii, motion on the
        tau grid), 'traction' (the profile at time tau, rad: by default the state's) or
        'impulse' (the impulse curve), after comment lines naming the parameters."""
        self.catch_up(self.tabbed)  # a hidden tab's data too, as it is now
        c = self.state.current
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
        return export.file_name(key, self.state.current, tau if key == "traction" else None)

    def csv_file(self, key: str) -> io.StringIO:
        """The CSV as a file object, for `pn.widgets.FileDownload` (called on a click).

        A traction profile is taken at the tau shown: while playing, the browser's frame
        (`Animation.clock_tau`), named in the file and its name alike.  The download is
        named here, when it is made, not on every parameter change: renaming the
        buttons' files would re-render them in the browser per slider move.
        """
        tau = self.animation.clock_tau() if self.state.playing else self.state.tau
        self.controls.downloads[key].filename = self.csv_filename(key, tau)
        return io.StringIO(self.csv_text(key, tau))


def choose_preset(state: ExplorerState, event: param.parameterized.Event) -> None:
    """A preset chosen in the menu: loaded into the state ('(custom)' changes nothing)."""
    if event.new and event.new != state.preset:
        state.apply_preset(event.new)


def connect(view: ContactView) -> None:
    """Every subscription of the contact feature, in the order they run for a change.

    A value the user sets goes to the state (the widgets' own feeds and watchers); the
    state derives what follows from it first (its own watchers, registered when it was
    made: `ExplorerState._follow_inputs`, which sets its contact `current` and its
    corrections, `_leave_preset`, `_leave_material`); then each scene draws the state's
    contact and tau (`Scene.follow`), and the view shows what is its own; then the
    widgets show the state's values (a slider's own move comes back as the value it
    holds: nothing is sent).  The path of a slider move is docs/app.md's "How data
    flows"."""
    s, ui = view.state, view.controls
    # the state's contact and time drawn by each scene (a hidden one computes nothing)
    for scene in view.scenes:
        s.param.watch(scene.follow, ["current", "tau"])
    # the view's own: readout, formulas, caption, tau slider, T(tau) family, animation
    s.param.watch(view.show_state, ["current", "tau"])
    s.param.watch(view.show_preset, "preset")
    s.param.watch(view.show_log, "log_psi")
    s.param.watch(lambda e: ui.tau_slider.set_range(*played(s.current, e.new), s.tau),
                  "period")
    s.param.watch(lambda _: ui.show_drive(s), ["physical", "drive"])
    # the user's values into the state (`ExplorerState.set_input`: the value and what
    # follows from it in one batch; a value the state refuses changes nothing)
    for name, slider in ui.sliders().items():
        slider.feed(partial(s.set_input, name))
    sync(ui.drive_select, s.param.drive)
    sync(ui.speed_slider, s.param.speed)
    sync(ui.log_box, s.param.log_psi)
    sync(ui.period_box, s.param.period)
    ui.preset_select.param.watch(partial(choose_preset, s), "value")
    ui.reset_button.on_click(lambda _: (s.reset(), ui.clear_refusals()))
    ui.play_button.param.watch(lambda _: view.animation.press(ui.play_button.frame_tau),
                               "clicks")
    ui.step_button.on_click(lambda _: view.animation.step())
    # the state's values into the sliders
    for name, slider in ui.sliders().items():
        s.param.watch(partial(show_value, slider), name)
    # (the boxes the SI inputs replace say nothing of a value refused before)
    s.param.watch(lambda _: ui.clear_refusals(), "physical")
    # the view's own widgets
    view.tabs.param.watch(view.show_tab, "active")
    view.fig6_card.param.watch(view.show_fig6, "collapsed")


def show_value(widget: param.Parameterized, event: param.parameterized.Event) -> None:
    """`widget.value` set to the state's new value (nothing when it holds it already)."""
    widget.value = event.new
