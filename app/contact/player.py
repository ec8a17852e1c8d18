"""Client-side animation: one contact's frames computed here, played by the browser.

Pressing Play sends the frames of the whole contact once (a few hundred kB); a small
script then paints them at the browser's own frame rate, copying each frame into the
plotted arrays in place, so no message crosses the websocket per frame (a server-paced
animation tops out near 10 frames/s on a modest machine; this one runs at the display's
rate). Every number still comes from `core`, computed on the server by the scenes'
own vectorised methods; the script only copies them.

Everything that depends on tau moves in the same frame: the plots, the caption, the
phase label, the tau box and slider, and the formula card (at a phase change).  The
script writes those texts with BokehJS's public `setv(..., {sync: false})`: the
browser does not send 60 changes a second back to the server, which goes on holding
the values it last sent.  The script remembers those values, and a copy of every source
it writes frames into (also what the server sends while it plays), and puts them back
the moment the frames are emptied (before the rest of that message, which may set a
value to the very one on screen: BokehJS then sees no change), so that after a pause
the page shows exactly what the server holds, and
every later change of the server's is drawn (Bokeh sends no property set to the value
it holds, and the spheres scene sends no data its sources hold already: a phase badge
paused in the phase the play started in is not sent again).  The
script keeps the tau of the frame on screen (`window.__zharii_player.shown`), which
Play / Pause reports with a press (`app.contact.play_button`): a pause lands on that
frame.  The server follows the same clock (progress = start + speed * elapsed /
CONTACT_SECONDS) for the tau a speed change or a parameter change lands on.

While it plays, a plot out of the viewport (or in a closed tab) is not painted: the
script holds it (BokehJS's `hold_render`, set in the browser only) while an
IntersectionObserver sees it outside the viewport, so that it is painted, with the frame
of that moment, as it comes into view, and every plot is painted when the player stops.
Its sources still change with every frame.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Protocol

import numpy as np
from bokeh.models import ColumnDataSource, CustomJS, Label
from bokeh.plotting import figure as Figure

from app.contact.curves import CurveScene
from app.contact.formulas import FORMULAS_TAG, formulas
from app.contact.phases import style
from app.contact.traction import DiscScene, TractionScene
from app.kit.wire import column
from core import Contact, Phase

FRAMES_PER_CONTACT = 240  # one contact at speed 1 in CONTACT_SECONDS: 60 frames/s at 4 s

#: The script that plays the frames (the body of a `CustomJS`: its args are named in
#: `Player.__init__`).
_PLAY_JS = Path(__file__).with_name("player.js").read_text()

#: The tags by which the server finds the controls the script writes (`Player.play`).
CONTROL_TAGS = {"entry": "tau-entry", "slider": "tau-value", "formula": FORMULAS_TAG}


class Sprite(Protocol):
    """A scene the player animates by copying rows: its named sources, and what they
    hold at K times (per source, its columns as arrays of shape (K, n))."""

    sources: dict[str, ColumnDataSource]

    def drawing(self, c: Contact, taus: np.ndarray) -> dict[str, dict[str, np.ndarray]]:
        ...


#: One whole period of the drive (rad): the spheres apart, approaching, touching at
#: tau0, parting at pi - tau0 and apart again (eq 3).
PERIOD = (-math.pi / 2, 3 * math.pi / 2)


def played(c: Contact, period: bool = False) -> tuple[float, float]:
    """The times the animation plays (rad): the contact, tau0 to pi - tau0, or with
    `period` the whole period `PERIOD`."""
    return PERIOD if period else (c.tau0, c.tau_end)


def frame_taus(c: Contact, n: int = FRAMES_PER_CONTACT, period: bool = False) -> np.ndarray:
    """The n times of the frames over `played(c, period)`, both ends included (as many
    frames for the period as for the contact: the player's budget)."""
    return np.linspace(*played(c, period), n)


def frame_index(progress: float, n: int = FRAMES_PER_CONTACT) -> int:
    """The frame shown at `progress` in [0, 1) through the contact (as the script does)."""
    return min(n - 1, math.floor((progress % 1.0) * n))


class Player:
    """The frame store and the script that plays it in the browser."""

    def __init__(self, traction: TractionScene, disc: DiscScene, curves: list[CurveScene],
                 caption: Label, phase_label: Label, host: Figure,
                 captions: Callable[[Contact, np.ndarray], list[str]],
                 tau_texts: Callable[[np.ndarray], list[str]],
                 sprites: Sequence[Sprite] = ()) -> None:
        """``captions(c, taus)`` gives the caption text of each frame, ``tau_texts(taus)``
        the tau box's; `host` is a figure of the page that keeps the frame sources in the
        document; `sprites` are scenes animated row by row."""
        self.traction, self.disc, self.curves = traction, disc, curves
        self.captions, self.tau_texts = captions, tau_texts
        self.sprites = list(sprites)
        self.frames = ColumnDataSource(data={}, name="frames")
        self.profiles = ColumnDataSource(data={}, name="frame_profiles")
        #: the frames of each sprite source, flattened (K * n per column)
        self.sprite_frames = {name: ColumnDataSource(data={}, name=f"frames_{name}")
                              for sprite in self.sprites for name in sprite.sources}
        # referenced from a figure, so that the frame sources are part of the document
        host.tags = [*host.tags, self.frames, self.profiles, *self.sprite_frames.values()]
        self.script = CustomJS(args={
            "frames": self.frames, "profiles": self.profiles, "traction": traction.source,
            "disc": disc.source, "markers": [s.marker for s in curves],
            "marker_columns": [[f"{s.name}:{col}" for col, *_ in s.curves] for s in curves],
            "caption": caption, "phase_label": phase_label,
            "formulas": [formulas(p) for p in Phase],
            "sprites": [[source, self.sprite_frames[name], list(source.data)]
                        for sprite in self.sprites for name, source in sprite.sources.items()],
            **dict.fromkeys(CONTROL_TAGS),
        }, code=_PLAY_JS)
        self.frames.js_on_change("data", self.script)

    def _find_controls(self) -> None:
        """Give the script the page's tau box, tau slider and formula card (Panel builds
        their models per page: found in the frames' document by their tags)."""
        doc = self.frames.document
        if doc is None:
            return
        found = {name: doc.select_one({"tags": tag}) for name, tag in CONTROL_TAGS.items()}
        if any(self.script.args[name] is not model for name, model in found.items()):
            self.script.args = {**self.script.args, **found}

    def play(self, c: Contact, start: float, speed: float, seconds: float,
             period: bool = False) -> None:
        """Send the frames of contact `c` (over the contact, or with `period` the whole
        period) and start the browser's player at progress `start` in [0, 1) (profiles
        first: the script starts on the frames' arrival)."""
        self._find_controls()
        taus = frame_taus(c, period=period)
        self.profiles.data = {k: v.ravel() for k, v in self.traction.profiles(c, taus).items()}
        for sprite in self.sprites:
            for name, cols in sprite.drawing(c, taus).items():
                # (K, n) arrays as K * n values, frame after frame
                self.sprite_frames[name].data = {k: column(v) for k, v in cols.items()}
        line = c.at(taus)
        phases = line.phase
        looks = [style(p) for p in phases]
        data = {
            "tau": taus, "a": line.contact_radius, "b": line.stick_radius,
            "phase": phases,
            "disc_color": [look.ring_color for look in looks],
            "disc_label": [look.ring for look in looks],
            "caption": self.captions(c, taus),
            "tau_text": self.tau_texts(taus),
            "phase_name": [look.name for look in looks],
            "phase_color": [look.color for look in looks],
            **{f"{s.name}:{col}": v for s in self.curves for col, v in s.columns(c, taus).items()},
        }
        n = taus.size
        data.update(start=[start] * n, speed=[speed] * n, seconds=[seconds] * n)
        self.frames.data = data

    def stop(self) -> None:
        """Stop the browser's player (it stops when the frames are emptied)."""
        self.frames.data = {}
        self.profiles.data = {}
        for source in self.sprite_frames.values():
            source.data = {}
