"""Play / Pause on the server: a pause adopts the frame the browser reports showing at the
press, checked as any value from a browser (issue 23)."""

from __future__ import annotations

import math

import pytest

import app.contact.animation
from app.contact.play_button import PAUSE_LABEL, PLAY_LABEL
from app.contact.player import frame_index, frame_taus
from app.contact.view import ContactView


def press(view: ContactView, shown: object) -> None:
    """What a press in the browser sends: the tau of the frame shown, then the click."""
    button = view.controls.play_button
    button.frame_tau = shown
    button.clicks += 1


@pytest.fixture
def playing(monkeypatch) -> tuple[ContactView, list[float]]:
    """A contact view playing from tau0, on a clock the test moves (monotonic s)."""
    view = ContactView()
    now = [100.0]
    monkeypatch.setattr(app.contact.animation.time, "monotonic", lambda: now[0])
    view.state.tau = view.state.current.tau0
    press(view, None)
    assert view.state.playing and view.controls.play_button.label == PAUSE_LABEL
    now[0] += 1.53  # the server's clock: 91.8 frames into the contact
    return view, now


def test_a_pause_lands_on_the_frame_the_browser_showed(playing) -> None:
    view, _ = playing
    taus = frame_taus(view.state.current)
    shown = float(taus[57])  # (behind the server's clock: frame 91)
    press(view, shown)
    assert not view.state.playing and view.controls.play_button.label == PLAY_LABEL
    assert view.state.tau == shown and view.controls.tau_slider.value == shown
    assert len(view.player.frames.data) == 0


@pytest.mark.parametrize("shown", [None, math.nan, math.inf, -math.inf, True, "1.2",
                                   [1.2], 1e300, -1.0, 0.5235987755982988 - 1e-9,
                                   2.6179938779914944 + 1e-9])
def test_a_report_no_page_sends_falls_back_on_the_clock(playing, shown) -> None:
    """Not a finite number within the contact (tau0 = pi/6 to 5 pi/6): refused, and the
    pause lands on the frame of the server's clock."""
    view, now = playing
    clock = float(frame_taus(view.state.current)[frame_index(1.53 / 4.0)])
    assert view.animation.clock_tau(now[0]) == clock
    press(view, shown)
    assert not view.state.playing and view.state.tau == clock


def test_the_ends_of_the_contact_are_frames(playing) -> None:
    view, _ = playing
    c = view.state.current
    press(view, c.tau_end)
    assert view.state.tau == c.tau_end
    press(view, None)  # plays again: the report of a press that plays is not used
    assert view.state.playing
    press(view, c.tau0)
    assert not view.state.playing and view.state.tau == c.tau0


def test_the_whole_period_plays_the_spheres_apart_and_the_contact_in_cores_phases() -> None:
    """`period`: the frames run from -pi/2 to 3 pi/2 (as many as for the contact: the
    player's budget), the spheres apart outside the contact (the gap h - H sin tau > 0,
    no force) and the contact's frames in core's phases; a pause may land in the gap,
    and Step wraps at the period's end."""
    from app.contact.spheres import drawing
    from app.contact.state import ExplorerState

    view = ContactView(ExplorerState(period=True))
    c = view.state.current
    taus = frame_taus(c, period=True)
    assert taus[0] == -math.pi / 2 and taus[-1] == 3 * math.pi / 2
    assert taus.size == frame_taus(c).size
    inside = (taus >= c.tau0) & (taus <= c.tau_end)
    assert inside.any() and (~inside).any()
    d = drawing(c, taus)
    lower, upper = d["spheres_lower"]["y"], d["spheres_upper"]["y"]
    apart = lower.max(axis=1) < upper.min(axis=1)
    assert apart[~inside].all() and not apart[inside].any()
    assert (d["spheres_forces"]["label"][~inside] == "").all()
    assert (c.phase(taus[inside]) > 0).all() and (c.phase(taus[~inside]) == 0).all()
    view.state.playing = True
    assert len(view.player.frames.data["tau"]) == taus.size
    assert view.player.frames.data["tau"][0] == -math.pi / 2
    gap = float(taus[10])  # (before the contact: the spheres approaching)
    press(view, gap)
    assert not view.state.playing and view.state.tau == gap  # not clamped into the contact
    assert view.controls.tau_slider.start == -math.pi / 2
    view.state.tau = 3 * math.pi / 2
    assert view.animation.step() == -math.pi / 2
    view.state.period = False  # the contact alone again: tau back inside it
    assert c.tau0 <= view.state.tau <= c.tau_end and view.controls.tau_slider.start == c.tau0
