"""Fig. 6 and the contact disc: the traction profile across the contact at the current
tau (`TractionScene`, source `traction`) and the disc seen from above, stick disc and
slip annulus coloured by phase (`DiscScene`, source `disc`)."""

from __future__ import annotations

import math

import numpy as np
from bokeh.core.property.validation import validate
from bokeh.models import (
    Annulus,
    Circle,
    Label,
    Line,
    VArea,
)

from app.contact.phases import STICK_COLOR, style
from app.kit.changes import changed, put, show
from app.kit.figures import (
    DATA_LEVEL,
    FRAME_LEVEL,
    PROFILE_POINTS,
    add_legend,
    draw,
    negated,
    new_figure,
    stamp,
    style_figure,
)
from app.kit.scene import Scene
from core import Contact

#: The traction profile's columns (`TractionScene.profiles`), as the browser's player
#: copies them frame by frame (`app/contact/player.js`).
PROFILE_COLUMNS = ("r", "traction", "upper", "stick_hi")
#: The caption's offset (px) under the top of the stamp's line (9 pt, line height 1.2).
CAPTION_BELOW_STAMP = -20


class TractionScene(Scene):
    """Fig. 6: tau_u(r) / (mu p*) across the diameter at the current tau."""

    name = "traction"

    def __init__(self) -> None:
        super().__init__({k: [] for k in PROFILE_COLUMNS})
        fig = new_figure("Traction profile", "r / a*", "traction  τᵤ / (μ p*)", height=390)
        # (the lower halves, -p and -stick_hi, the browser draws from the upper ones)
        stick = draw(fig, VArea, self.source, x="r", y1=negated("stick_hi"), y2="stick_hi",
                     fill_color=STICK_COLOR, fill_alpha=0.25, level=DATA_LEVEL)
        envelope = [draw(fig, Line, self.source, x="r", y=y, line_dash="dashed",
                         color="grey", line_width=2, level=DATA_LEVEL)
                    for y in ("upper", negated("upper"))]
        self.line = draw(fig, Line, self.source, x="r", y="traction", color="black",
                         line_width=3, level=DATA_LEVEL)
        # in one row above the frame (inside it, it covered the stick zone and the rim;
        # beside it, it left a phone too narrow a frame)
        add_legend(fig, [("stick zone", [stick]), ("±μ p", envelope), ("τᵤ", [self.line])],
                   place="above")
        # values at the current tau, drawn on the canvas: a text pane beside the plot
        # would make the browser lay out the whole page again on every frame
        self.caption = Label(x=0, y=0, text="", text_align="right", text_baseline="top",
                             text_font_size="13pt", background_fill_color="white",
                             background_fill_alpha=0.8, name="traction_caption",
                             level=FRAME_LEVEL)
        fig.add_layout(self.caption)
        # the phase, in its colour, drawn with the data: BokehJS does not always repaint a
        # changed Title (its new text showed only after a resize), a Label on the overlay
        # level is painted with every frame
        self.phase_label = Label(x=0, y=0, text="", text_baseline="bottom",
                                 text_align="center", text_font_size="17pt",
                                 text_font_style="bold",
                                 background_fill_color="white", background_fill_alpha=0.8,
                                 name="traction_phase", level=FRAME_LEVEL)
        fig.add_layout(self.phase_label)
        # psi, tau0 and tau, top right, the caption under it (placed with the ranges)
        self.stamp = stamp(fig, x_units="data", y_units="data", text_align="right",
                           text_baseline="top")
        style_figure(fig)
        self.figure = fig

    def update_contact(self, c: Contact) -> None:
        """The r grid and the plot's ranges and labels, after the largest contact radius
        a/a* and pressure p/p* (at pi/2: eqs 6, 7, which depend on tau0 alone)."""
        if self.note_tau0(c):
            self._a_max = float(c.contact_radius(math.pi / 2))
            self._p_max = float(c.pressure(0.0, math.pi / 2))
            self.r_grid = np.linspace(-1.05 * self._a_max, 1.05 * self._a_max,
                                      PROFILE_POINTS)
        a_max, p_max = self._a_max, self._p_max
        fig = self.figure
        put(fig.x_range, start=-1.1 * a_max, end=1.1 * a_max)
        # room above the largest pressure for the stamp's line and the caption's two
        # lines under it (each across the frame's width: side by side, they met on a
        # narrow plot), below it for the phase
        put(fig.y_range, start=-1.6 * p_max, end=2.9 * p_max)
        put(self.stamp, x=1.08 * a_max, y=2.87 * p_max)
        put(self.caption, x=1.08 * a_max, y=2.87 * p_max, y_offset=CAPTION_BELOW_STAMP)
        put(self.phase_label, x=0.0, y=-1.55 * p_max)  # bottom centre

    def profiles(self, c: Contact, taus: np.ndarray) -> dict[str, np.ndarray]:
        """The profile at each of the K times `taus`: columns of shape (K, L).

        Each row is the r grid with -a, a, -b, b inserted (sharp corners at the contact
        and stick edges), so every frame has the same length L and the browser's player
        can copy frames into the plotted arrays in place.  The columns (`PROFILE_COLUMNS`):
        r, the traction, the envelope p (the Coulomb bound mu p in units of mu p*) and
        p inside the stick disc (0 outside); the plots draw -p and the stick zone's
        lower edge negated, in the browser.
        """
        taus = np.atleast_1d(np.asarray(taus, float))
        line = c.at(taus)
        a, b = line.contact_radius, line.stick_radius
        n = self.r_grid.size
        r = np.empty((taus.size, n + 4))
        r[:, :n] = self.r_grid
        r[:, n:] = np.array([-a, a, -b, b]).T
        r.sort(axis=1)
        t = taus[:, None]
        p = c.pressure(r, t)
        stick = (np.abs(r) <= b[:, None]) & (b[:, None] > 0)
        return {"r": r, "traction": c.traction(r, t), "upper": p,
                "stick_hi": np.where(stick, p, 0.0)}

    def table(self, c: Contact, tau: float) -> dict[str, np.ndarray]:
        """The profile of contact `c` at time tau (rad), on the points `update_tau` plots,
        for the CSV download: r/a* (signed position along x through the centre), the
        traction tau_u/(mu p*) (eqs 18, 24, 33, 36), the pressure p/p* (eq 6; also the
        Coulomb bound mu p in units of mu p*) and stick (1 in the stick disc |r| <= b,
        0 in slip and outside contact)."""
        profile = {k: v[0] for k, v in self.profiles(c, np.array([tau])).items()}
        r, b = profile["r"], float(c.stick_radius(tau))
        return {"r/a*": r, "tau_u/(mu p*)": profile["traction"], "p/p*": profile["upper"],
                "stick": ((np.abs(r) <= b) & (b > 0)).astype(float)}

    def update_tau(self, c: Contact, tau: float) -> None:
        """The profile at time tau into the source `traction` (written here, only when a
        column differs: `app.kit.changes.changed`; Bokeh does not validate the columns),
        the phase under it."""
        profile = {k: v[0] for k, v in self.profiles(c, np.array([tau])).items()}
        new = changed(self.source, profile)
        if new is not None:
            with validate(False):
                self.source.data = new
        look = style(c.phase(tau))
        put(self.phase_label, text_color=look.color, text=look.name)


class DiscScene(Scene):
    """Top view of the contact disc: stick disc and slip annulus coloured by phase.

    The plot's ranges reach `RIM` times the largest contact radius around it and, below
    it, a band `BAND` times that radius high for the stamp (the corners outside the
    circle are smaller than the stamp's three lines)."""

    name = "disc"
    RIM, BAND = 1.15, 0.45

    def __init__(self) -> None:
        super().__init__({"x": [0.0, 0.0], "y": [0.0, 0.0], "inner": [0.0, 0.0],
                          "outer": [0.0, 0.0], "color": [STICK_COLOR, STICK_COLOR],
                          "label": ["stick", "slip"]})
        # no legend: a legend built from the data would repaint the whole plot per frame
        fig = new_figure("Contact disc (top view)", "x / a*", "y / a*", match_aspect=True,
                         sizing_mode="fixed", width=350, height=400)
        self.envelope = draw(fig, Circle, x=0, y=0, radius=1.0, fill_alpha=0,
                             line_dash="dotted", line_color="grey", line_width=2)
        draw(fig, Annulus, self.source, x="x", y="y", inner_radius="inner",
             outer_radius="outer", fill_color="color", line_color="black", line_width=1,
             level=DATA_LEVEL)
        fig.x_range.start, fig.x_range.end = -self.RIM, self.RIM
        fig.y_range.start, fig.y_range.end = -self.RIM - self.BAND, self.RIM
        stamp(fig, sep="\n")  # (in the band, bottom left)
        style_figure(fig)
        self.figure = fig

    def update_contact(self, c: Contact) -> None:
        """The envelope (the largest contact, a/a* at pi/2, eq 7) and the ranges around
        it, the stamp's band below."""
        a_max = float(c.contact_radius(math.pi / 2))
        put(self.envelope.glyph, radius=a_max)
        put(self.figure.x_range, start=-self.RIM * a_max, end=self.RIM * a_max)
        put(self.figure.y_range, start=-(self.RIM + self.BAND) * a_max, end=self.RIM * a_max)

    def update_tau(self, c: Contact, tau: float) -> None:
        line = c.at(tau)
        a, b, look = float(line.contact_radius), float(line.stick_radius), style(line.phase)
        show(self.source, {
            "x": [0.0, 0.0], "y": [0.0, 0.0], "inner": [0.0, b], "outer": [b, a],
            "color": [STICK_COLOR, look.ring_color], "label": ["stick", look.ring],
        })
