"""Client-side animation: one contact's frames computed here, played by the browser.

Pressing Play sends the frames of the whole contact once (a few hundred kB); a small
script then paints them at the browser's own frame rate, copying each frame into the
plotted arrays in place, so no message crosses the websocket per frame (a server-paced
animation tops out near 10 frames/s on a modest machine; this one runs at the display's
rate). Every number still comes from `core`, computed on the server by the scenes'
own vectorised methods; the script only copies them. The server follows the same clock
(progress = start + speed * elapsed / CONTACT_SECONDS) for the scrubber, the formulas and
the tau a pause lands on.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from bokeh.models import ColumnDataSource, CustomJS, Label
from bokeh.plotting import figure as Figure

from app.phases import style
from app.scenes import CurveScene, DiscScene, TractionScene
from core import Contact

FRAMES_PER_CONTACT = 240  # one contact at speed 1 in CONTACT_SECONDS: 60 frames/s at 4 s

_PLAY_JS = """
const st = window.__zharii_player || (window.__zharii_player = {raf: null});
if (st.raf !== null) { cancelAnimationFrame(st.raf); st.raf = null; }
const get = (src) => (src.data instanceof Map ? Object.fromEntries(src.data) : src.data);
const F = get(frames);
const K = F.tau ? F.tau.length : 0;
if (K === 0) { return; }                       // stopped by the server
const P = get(profiles);
const L = P.r.length / K;
const names = ["r", "traction", "upper", "lower", "stick_lo", "stick_hi"];
const seconds = F.seconds[0], speed = F.speed[0], start = F.start[0];
const t0 = performance.now();
let last = -1, phase = -1, texted = -1e9;
function draw(k) {
  const T = get(traction);
  for (const n of names) { const dst = T[n], src = P[n];
    for (let i = 0; i < L; i++) { dst[i] = src[k * L + i]; } }
  traction.change.emit();
  const D = get(disc);
  D.inner[1] = F.b[k]; D.outer[0] = F.b[k]; D.outer[1] = F.a[k];
  D.color[1] = F.disc_color[k]; D.label[1] = F.disc_label[k];
  disc.change.emit();
  for (let j = 0; j < markers.length; j++) {
    const M = get(markers[j]), cols = marker_columns[j];
    for (let i = 0; i < cols.length; i++) { M.x[i] = F.tau[k]; M.y[i] = F[cols[i]][k]; }
    markers[j].change.emit();
  }
  if (F.phase[k] !== phase) {                  // a few times per contact
    phase = F.phase[k];
    phase_label.text = F.phase_name[k];
    phase_label.text_color = F.phase_color[k];
  }
}
function tick(now) {
  // a frame's timestamp may precede t0 by a little: keep progress in [0, 1)
  const p = (start + speed * Math.max(0, now - t0) / 1000 / seconds) % 1;
  const k = Math.max(0, Math.min(K - 1, Math.floor(p * K)));
  if (k !== last) { draw(k); last = k; }
  if (now - texted > 250) { caption.text = F.caption[k]; texted = now; }
  st.raf = requestAnimationFrame(tick);
}
st.raf = requestAnimationFrame(tick);
"""


def frame_taus(c: Contact, n: int = FRAMES_PER_CONTACT) -> np.ndarray:
    """The n times of the frames, tau0 to pi - tau0 inclusive."""
    return np.linspace(c.tau0, c.tau_end, n)


def frame_index(progress: float, n: int = FRAMES_PER_CONTACT) -> int:
    """The frame shown at `progress` in [0, 1) through the contact (as the script does)."""
    return min(n - 1, math.floor((progress % 1.0) * n))


class Player:
    """The frame store and the script that plays it in the browser."""

    def __init__(self, traction: TractionScene, disc: DiscScene, curves: list[CurveScene],
                 caption: Label, phase_label: Label, host: Figure,
                 captions: Callable[[Contact, np.ndarray], list[str]]) -> None:
        """``captions(c, taus)`` gives the caption text of each frame; `host` is a figure
        of the page that keeps the frame sources in the document."""
        self.traction, self.disc, self.curves = traction, disc, curves
        self.captions = captions
        self.frames = ColumnDataSource(data={}, name="frames")
        self.profiles = ColumnDataSource(data={}, name="frame_profiles")
        # referenced from a figure, so that both sources are part of the document
        host.tags = [*host.tags, self.frames, self.profiles]
        self.frames.js_on_change("data", CustomJS(args={
            "frames": self.frames, "profiles": self.profiles, "traction": traction.source,
            "disc": disc.source, "markers": [s.marker for s in curves],
            "marker_columns": [[f"{s.name}:{col}" for col, *_ in s.curves] for s in curves],
            "caption": caption, "phase_label": phase_label,
        }, code=_PLAY_JS))

    def play(self, c: Contact, start: float, speed: float, seconds: float) -> None:
        """Send the frames of contact `c` and start the browser's player at progress
        `start` in [0, 1) (profiles first: the script starts on the frames' arrival)."""
        taus = frame_taus(c)
        self.profiles.data = {k: v.ravel() for k, v in self.traction.profiles(c, taus).items()}
        line = c.at(taus)
        phases = line.phase
        looks = [style(p) for p in phases]
        data = {
            "tau": taus, "a": line.contact_radius, "b": line.stick_radius,
            "phase": phases,
            "disc_color": [look.ring_color for look in looks],
            "disc_label": [look.ring for look in looks],
            "caption": self.captions(c, taus),
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
