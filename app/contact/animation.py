"""The animation of one contact: Play, Pause, Step and Speed over `ContactView`.

The browser plays the frames (`app.contact.player`).  Pause lands on the frame the
browser showed at the press, which the press reports (`app.contact.play_button`); the
server follows the same clock, progress = start + speed * elapsed / CONTACT_SECONDS, for
the tau a speed change, a parameter change or a pause without a report (Alt + K, Step,
Reset) lands on.  A contact lasts CONTACT_SECONDS at speed 1.
"""

from __future__ import annotations

import logging
import time
from typing import Any, Protocol

import param

from app.contact.player import Player, frame_index, frame_taus, played
from app.contact.state import ExplorerState
from app.kit.batch import held
from app.kit.widgets import finite

log = logging.getLogger(__name__)

CONTACT_SECONDS = 4.0  # one contact lasts this long at speed 1


class Animated(Protocol):
    """What an animation plays: a state, the contact on screen, the player of its frames,
    the controls showing Play/Pause (`app.contact.view.ContactView`)."""

    state: ExplorerState
    player: Player
    controls: Any

    def settle(self) -> None: ...


class Animation(param.Parameterized):
    """Plays the contact of `view` in the browser, following its state's `playing` and
    `speed`."""

    def __init__(self, view: Animated) -> None:
        super().__init__()
        self.view = view
        #: (progress, time.monotonic(), speed) when the player last (re)started
        self.started = (0.0, 0.0, 1.0)
        #: the tau (rad) the pause being made lands on; None: the clock's (`clock_tau`)
        self.stop_at: float | None = None
        view.state.param.watch(self._on_playing, "playing")
        view.state.param.watch(self._on_speed, "speed")
        view.state.param.watch(self._on_period, "period")

    def span(self) -> tuple[float, float]:
        """The times played (rad): the contact on screen, or the whole period
        (`app.contact.player.played`)."""
        return played(self.view.state.current, self.view.state.period)

    def step(self, seconds: float = 1 / 30) -> float:
        """Advance tau as `seconds` of animation at the current speed; wrap at the end.

        Returns the new tau.  The last frame of a contact (or of the period, `span`) lands
        exactly on its end; the next one starts again at its start.  Stepping pauses a
        running animation.
        """
        state = self.view.state
        lo, hi = self.span()
        state.playing = False
        if state.tau >= hi:
            new = lo
        else:
            dtau = state.speed * (hi - lo) * seconds / CONTACT_SECONDS
            new = min(state.tau + dtau, hi)
        state.tau = new
        return new

    def progress_of(self, tau: float) -> float:
        """Where tau lies in the times played (`span`), in [0, 1)."""
        lo, hi = self.span()
        return min(max((tau - lo) / (hi - lo), 0.0), 1.0) % 1.0

    def clock_progress(self, now: float | None = None) -> float:
        """Where the browser's player is in the contact at time `now` (monotonic s), in
        [0, 1)."""
        progress, started, speed = self.started
        now = time.monotonic() if now is None else now
        return (progress + speed * (now - started) / CONTACT_SECONDS) % 1.0

    def clock_tau(self, now: float | None = None) -> float:
        """The tau of the frame the browser's player shows at time `now` (monotonic s)."""
        return float(frame_taus(self.view.state.current, period=self.view.state.period)[
            frame_index(self.clock_progress(now))])

    def landing(self, frame_tau: object) -> float:
        """The tau (rad) a pause lands on: `frame_tau`, the tau of the frame the browser showed
        at the press, when it is a finite number within the contact on screen; else (a
        report no page of this app sends, or none) the tau of the server's clock."""
        lo, hi = self.span()
        if finite(frame_tau) and lo <= frame_tau <= hi:
            return float(frame_tau)
        if frame_tau is not None:
            log.debug("refused the frame's tau %.80r from the browser", frame_tau)
        return self.clock_tau()

    def press(self, frame_tau: object) -> None:
        """Play / Pause pressed: play, or pause on the frame the browser showed at the
        press, `frame_tau` (its tau in rad, checked by `landing`)."""
        state = self.view.state
        if not state.playing:
            state.playing = True
            return
        self.stop_at = self.landing(frame_tau)
        try:
            state.playing = False
        finally:
            self.stop_at = None

    def start(self, progress: float) -> None:
        """(Re)start the browser's player at `progress` with the current contact and speed.

        The frames are Bokeh model changes made from a widget callback, which Panel runs
        without the document lock: they must go through `held()` (without it, a change
        made while a message is being written raises in Bokeh and the player never
        starts)."""
        speed = self.view.state.speed
        self.started = (progress, time.monotonic(), speed)
        with held():
            self.view.player.play(self.view.state.current, progress, speed, CONTACT_SECONDS,
                                  period=self.view.state.period)

    def _on_period(self, event: param.parameterized.Event) -> None:
        if self.view.state.playing:  # the same time shown, over the new span
            self.start(self.progress_of(self.clock_tau() if event.new else
                                        self.view.state.tau))

    def _on_speed(self, event: param.parameterized.Event) -> None:
        if self.view.state.playing:  # keep the current frame, change the pace
            self.start(self.clock_progress())

    def _on_playing(self, event: param.parameterized.Event) -> None:
        """Start the browser's player at the state's tau; a pause puts the state's tau
        (which holds the tau the play last started from) on the player's frame: the
        one reported by the press (`stop_at`), else the clock's."""
        view, playing = self.view, event.new
        view.controls.show_playing(playing)
        if playing:
            self.start(self.progress_of(view.state.tau))
            return
        with held():  # one message: the player stops and the plots settle on its frame
            view.player.stop()
            view.state.tau = self.clock_tau() if self.stop_at is None else self.stop_at
            view.settle()  # (if the frame is the tau the play started from)
