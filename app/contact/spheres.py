"""The physical scene: the two spheres in section (the paper's Fig. 2), synced to tau.

The upper sphere is held; the lower one is driven along its oblique line (eq 3: its
centre moves by u_x0 = u0 sin tau sideways and u_z0 = H sin tau upwards, at the angle
theta from the vertical).  While they touch, both are drawn flattened at the plane
midway between them, with the contact patch of radius a (eq 7) on it: the stick disc
b (eq 30) in the stick colour, the rest of the patch in the colour of what it does
(slip or counter-slip).  Arrows give the forces on the upper sphere: P / P0 up (eq 9)
and T along the drive (eqs 38, 39; T0 = mu P0), in one physical unit (`force_unit`: the
contact's largest P, or mu P if longer, drawn `ARROW` radii long), with the Coulomb bound
+-mu P that T stays within (slipping, T reaches it).  The badge names the phase
(`Contact.phase`).

Displacements are exaggerated: the normal amplitude H is drawn as `DRIVE` sphere radii
and u0 at the true angle theta up to `MAX_SIDE` radii (the scale is stated on the plot).
The contact patch is drawn with core's a / a* on that exaggerated scale.

Below them, a strip shows one whole period (tau from -pi/2 to 3 pi/2): the lower
sphere's height u_z0 / H = sin tau (eq 3), the contact (sin tau > sin tau0, eq 4)
shaded, the gaps before and after it marked "apart", and the current tau marked
(`drawing` at a tau in the gap draws the spheres apart: no patch, no force).  Under the
strip a row of small pictograms (`app.contact.pictograms`) shows the spheres at six
times of the period, each joined to its time on the strip: apart, closing, touching,
in contact, releasing, opening; the gap is open outside the contact.  The other plots
stay on the contact.

Every number comes from `core` through `drawing(c, taus)`, which gives each source's
columns at K times as arrays of shape (K, n): `update_tau` shows one time, the browser's
player (`app.contact.player`) copies the frames of a whole contact.

What a scene sends on a move, here and in the other scenes of the contact: `show` gives a
source data only when a column differs from what it holds (Bokeh sends every data set,
equal or not), `put` sets only the properties that differ, and what depends on tau0
alone (here the period strip, the pictograms and the sphere at rest) is drawn again only
when tau0 changes: a psi move computes and sends only what it changes.
"""

from __future__ import annotations

import math

import numpy as np
from bokeh.models import (
    ColumnDataSource,
    Label,
    Line,
    Patch,
    Patches,
    Range1d,
    SaveTool,
    Scatter,
    Segment,
    Text,
    VArea,
)
from bokeh.plotting import figure

from app.contact import pictograms
from app.contact.phases import STICK_COLOR, style
from app.kit.changes import put, show
from app.kit.figures import FRAME_LEVEL, draw, follow_clock, png_name, stamp, style_figure
from app.kit.scene import Scene
from app.kit.wire import column
from core import Contact
from core.clock import half_sines

DRIVE = 0.15  # the drawn normal amplitude H, in sphere radii
MAX_SIDE = 0.45  # the largest drawn tangential amplitude u0, in sphere radii
ARROW = 0.9  # the drawn length of the contact's largest P (at pi/2), in radii
OUTLINE_POINTS = 97  # points of each sphere's outline
HEAD_SIZE = 13  # arrow heads, screen pixels
BOUND_TICK = 0.05  # half the height of the ticks at the ends of the +-mu P bound, radii
#: What the ticked dashes about the arrows' foot are (under the drive line's note).
BOUND_WORDS = "ticks: T's Coulomb bound ±μP\n(P, T to one scale)"
#: The notes under the spheres: their top (scene units), type (pt) and how many lines
#: the first of them has (the rest, the drive line and `BOUND_WORDS`).
NOTES_TOP, NOTE_PT, NOTE_LINES = -1.2, 11, 4

_ANGLES = np.linspace(0.0, 2.0 * math.pi, OUTLINE_POINTS)
#: the unit circle's outline and the held upper sphere's (centre (0, 1)), radii
_COS, _SIN = np.cos(_ANGLES), np.sin(_ANGLES)
_UPPER_Y = 1.0 + _SIN
#: the force labels' drop below their arrows' tips (P's none, T's 0.14 radii)
_LABEL_DROP = np.array([0.0, 0.14])

#: The period strip: tau from PERIOD[0] to PERIOD[1] drawn across x in [-1.5, 1.5]
#: sphere radii, sin tau as STRIP_HEIGHT radii about y = STRIP_Y.
PERIOD = (-math.pi / 2, 3 * math.pi / 2)
STRIP_Y, STRIP_HEIGHT = -2.95, 0.22


#: The farthest from the strip's middle (sphere radii) a word over it is centred.
WORDS_REACH = 1.3


def strip_x(taus: np.ndarray) -> np.ndarray:
    """The x (sphere radii) of the times `taus` (rad) on the period strip."""
    return -1.5 + 3.0 * (np.asarray(taus, float) - PERIOD[0]) / (PERIOD[1] - PERIOD[0])


def strip_y(taus: np.ndarray) -> np.ndarray:
    """The y (sphere radii) of the lower sphere's height sin tau (eq 3) on the strip."""
    return STRIP_Y + STRIP_HEIGHT * np.sin(np.asarray(taus, float))


def drawn_amplitudes(c: Contact) -> tuple[float, float]:
    """The drawn amplitudes (H, u0) in sphere radii: H is `DRIVE`, u0 follows the angle
    of incidence (u0 / H = tan theta) up to `MAX_SIDE`."""
    return DRIVE, min(DRIVE * math.tan(c.theta), MAX_SIDE)


def one_minus_sin_tau0(c: Contact) -> float:
    """1 - sin tau0 = 2 sin^2(e/2), e = pi/2 - tau0, without the cancellation of the
    difference (it stays > 0 for tau0 within 1e-12 of pi/2, where sin tau0 rounds to 1)."""
    return 2.0 * half_sines(c.tau0)[0] ** 2


def scale_note(c: Contact) -> str:
    """What the drawing exaggerates, in words."""
    H, u0 = drawn_amplitudes(c)
    sc = c.scales
    if sc is not None:  # SI inputs: the true factor, drawn H / true H (both over R)
        # a* = sqrt(R (H - h) / 2), alpha* = H - h = H (1 - sin tau0)
        true_h = sc.alpha_star**2 / (2 * sc.a_star**2 * one_minus_sin_tau0(c))
        note = f"displacements drawn ×{H / true_h:.3g}"
    else:
        note = f"not to scale: H as {DRIVE:g} R"
    if u0 < DRIVE * math.tan(c.theta):  # (short: the plot may be 240 px wide)
        note += f", u₀ ≤ {MAX_SIDE:g} R"
    return note


def _rows(*columns: np.ndarray) -> np.ndarray:
    """The K-vectors `columns` side by side: shape (K, len(columns)) (`np.stack(...,
    axis=1)` without its checks; a view of a (len(columns), K) array)."""
    return np.array(columns).T


def force_unit(c: Contact) -> float:
    """The drawn length (sphere radii) of a force P0 on the upper sphere: both forces
    are drawn in this one physical unit, so that the contact's largest P, (1 - sin
    tau0)^(3/2) P0 at pi/2 (eq 9), or its largest mu P, whichever is longer, is `ARROW`
    long."""
    return ARROW / (one_minus_sin_tau0(c) ** 1.5 * max(1.0, c.mu))


def force_arrows(c: Contact, P: np.ndarray, T: np.ndarray, xc: np.ndarray,
                 y: np.ndarray) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """The arrows of the forces on the upper sphere at K times, from the contact's centre
    (`xc`, `y`, sphere radii): P / P0 up (eq 9) and T along the drive (eqs 38, 39), both
    in the unit `force_unit` (T / P0 = mu T / T0: slipping, T is as long as mu P, the
    Coulomb bound), with their labels (every one while the spheres touch, however short
    its arrow); and the bound itself, the segment of +-mu P (dashed, with its end
    ticks: `BOUND_WORDS`) that T stays within.  Columns of shape (K, 2)."""
    K = P.size
    unit = force_unit(c)
    uP, uT, uB = unit * P, unit * c.mu * T, unit * c.mu * P
    touching = P > 0
    head = _rows(uP, np.abs(uT)) > 0.01  # an arrow long enough for its head
    labels = np.array([[f"P = {p:.3g} P₀", f"T = {t:+.3g} T₀"]
                       for p, t in zip(P.tolist(), T.tolist(), strict=True)],
                      dtype=object).reshape(K, 2)
    tip_y = _rows(y + uP, y)
    forces = {
        "x0": _rows(xc, xc), "y0": _rows(y, y),
        "x1": _rows(xc, xc + uT), "y1": tip_y,
        # labels: P's beside its tip, T's below its arrow (beside the bound's ticks)
        "lx": _rows(xc + 0.08, xc + uT / 2),
        "ly": tip_y - _LABEL_DROP,
        "align": np.array([["left", "center"]] * K, dtype=object),
        "head": np.where(head, HEAD_SIZE, 0),
        # the triangle marker points up; turned to point along T
        "angle": _rows(0.0 * T, np.where(T < 0, math.pi / 2, -math.pi / 2)),
        # (every label while they touch, however short its arrow)
        "label": np.where(touching[:, None], labels, ""),
    }
    bound = {"x0": _rows(xc - uB, xc + uB), "x1": _rows(xc - uB, xc + uB),
             "y0": _rows(y - BOUND_TICK, y - BOUND_TICK),
             "y1": _rows(y + BOUND_TICK, y + BOUND_TICK),
             "y": _rows(y, y)}
    return forces, bound


def drawing(c: Contact, taus: np.ndarray) -> dict[str, dict[str, np.ndarray]]:
    """What the scene draws at each of the K times `taus`, in sphere radii: per source
    name, its columns as arrays of shape (K, n) (n rows per time).

    (One array operation per quantity for all K times: `update_tau` asks for one time
    on every move, where each numpy call's own cost is most of the work.)"""
    taus = np.atleast_1d(np.asarray(taus, float))
    K = taus.size
    line = c.at(taus)
    H, u0 = drawn_amplitudes(c)
    s0 = math.sin(c.tau0)
    gap = one_minus_sin_tau0(c)  # 1 - s0
    sin_t = np.sin(taus)
    # centre of the lower sphere (eq 3), the upper one's is (0, 1); its top at rest is
    # H s0 below the upper sphere's bottom (the gap h, eq 4)
    cx, cy = u0 * sin_t, -1.0 - H * s0 + H * sin_t
    touching = line.phase != 0
    # the plane midway between the undeformed surfaces (half their overlap): both are
    # flattened to it
    y = np.where(touching, np.maximum(H * (sin_t - s0), 0.0) / 2, 0.0)
    t, mid = touching[:, None], y[:, None]
    upper_y = np.where(t, np.maximum(_UPPER_Y, mid), _UPPER_Y)
    lower_y = cy[:, None] + _SIN
    lower_y = np.where(t, np.minimum(lower_y, mid), lower_y)
    # the patch: core's a / a* and b / a*, a* drawn as sqrt((H - h) / 2) radii (eq 7)
    a_star = math.sqrt(H * gap / 2)
    a, b = line.contact_radius * a_star, line.stick_radius * a_star
    xc = cx / 2  # midway between the centres
    looks = [style(p) for p in line.phase]
    ring = [look.ring_color for look in looks]
    patch = {
        "x0": _rows(xc - a, xc - b, xc + b),
        "x1": _rows(xc - b, xc + b, xc + a),
        "y": _rows(y, y, y),
        "color": np.array([[r, STICK_COLOR, r] for r in ring], dtype=object),
    }
    P, T = line.normal_force, line.tangential_force
    forces, bound = force_arrows(c, P, T, xc, y)
    forces.update({
        # the time and the contact, what every plot's stamp shows (`follow_clock`: this
        # source changes with each of them, on a slider move as on a played frame)
        "tau": _rows(taus, taus),
        "psi": np.full((K, 2), c.psi), "tau0": np.full((K, 2), c.tau0),
    })
    badge = {"text": np.array([[look.name] for look in looks], dtype=object),
             "color": np.array([[look.color] for look in looks], dtype=object)}
    return {
        "spheres_upper": {"x": np.ones((K, 1)) * _COS, "y": upper_y},
        "spheres_lower": {"x": cx[:, None] + _COS, "y": lower_y},
        "spheres_patch": patch,
        "spheres_forces": forces,
        "spheres_bound": bound,
        "spheres_badge": badge,
        "spheres_period_marker": {"x": strip_x(taus)[:, None], "y": strip_y(taus)[:, None]},
    }


class SpheresScene(Scene):
    """The two spheres in section, the drive, the patch, the forces and the phase."""

    name = "spheres"

    def __init__(self) -> None:
        first = drawing(Contact(0.5, 0.5), np.array([math.pi / 2]))
        self.sources = {name: ColumnDataSource({k: column(v[0]) for k, v in cols.items()},
                                               name=name)
                        for name, cols in first.items()}
        self.source = self.sources["spheres_lower"]
        self.still = ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": []},
                                      name="spheres_drive")
        self.rest = ColumnDataSource({"x": [], "y": []}, name="spheres_rest")
        #: the period strip: the height sin tau, the contact shaded, the words
        self.period = ColumnDataSource({"x": [], "y": []}, name="spheres_period")
        self.period_contact = ColumnDataSource({"x": [], "lo": [], "hi": []},
                                               name="spheres_period_contact")
        self.period_words = ColumnDataSource({"x": [], "text": []},
                                             name="spheres_period_words")
        #: the spheres at six times of the period (static per contact)
        self.pictograms = ColumnDataSource(
            {k: [] for k in pictograms.pictograms(Contact(0.5, 0.5))} | {"x_strip": [],
                                                                          "y_strip": []},
            name="spheres_pictograms")
        # equal scales on both axes: the plot area (about 400 x 560 px) spans 3.2 x 4.5
        # (scaled down, its aspect kept, on a screen narrower than that)
        # (and 1.65 R more below, for the period strip and the pictograms under it, their
        # labels in two rows: no taller, so that at 240 px wide it fits a 480 px screen)
        fig = figure(title="Two spheres in section", width=420, height=849, max_width=420,
                     sizing_mode="scale_width", x_range=Range1d(-1.6, 1.6),
                     y_range=Range1d(-4.1, 2.1), tools="save", toolbar_location="above",
                     x_axis_type=None, y_axis_type=None)  # (no axes, no grid)
        fig.select_one(SaveTool).filename = png_name(fig.title.text)
        s = self.sources
        draw(fig, Line, self.rest, x="x", y="y", line_dash="dashed", color="#999999",
             line_width=1.5)
        draw(fig, VArea, self.period_contact, x="x", y1="lo", y2="hi", fill_color="#D55E00",
             fill_alpha=0.2)
        draw(fig, Line, self.period, x="x", y="y", color="#333333", line_width=2)
        draw(fig, Text, self.period_words, x="x", y=STRIP_Y + STRIP_HEIGHT + 0.03,
             text="text", text_align="center", text_baseline="bottom", text_font_size="10pt",
             text_color="#333333")
        p = self.pictograms
        draw(fig, Segment, p, x0="x", y0=pictograms.TOP, x1="x_strip", y1="y_strip",
             color="#999999", line_width=1)
        for side, fill in (("upper", "#d9d9d9"), ("lower", "#bfbfbf")):
            draw(fig, Patches, p, xs=f"xs_{side}", ys=f"ys_{side}", fill_color=fill,
                 line_color="black", line_width=1.5)
        draw(fig, Text, p, x="x", y="label_y", text="label", text_align="center",
             text_baseline="top", text_font_size="10pt", text_color="color")
        draw(fig, Scatter, s["spheres_period_marker"], x="x", y="y", size=11,
             color="#D55E00", line_color="black", level=FRAME_LEVEL)
        for name, fill in (("spheres_upper", "#d9d9d9"), ("spheres_lower", "#bfbfbf")):
            draw(fig, Patch, s[name], x="x", y="y", fill_color=fill, line_color="black",
                 line_width=2, level=FRAME_LEVEL)
        # the line the lower sphere's centre moves along, over the sphere (it lies inside)
        draw(fig, Segment, self.still, x0="x0", y0="y0", x1="x1", y1="y1",
             line_dash="dotdash", color="#222222", line_width=2, level=FRAME_LEVEL,
             name="spheres_drive_line")
        draw(fig, Segment, s["spheres_patch"], x0="x0", y0="y", x1="x1", y1="y",
             color="color", line_width=9, level=FRAME_LEVEL)
        # the Coulomb bound +-mu P that T stays within: dashed, its ends ticked
        bound = s["spheres_bound"]
        draw(fig, Segment, bound, x0="x0", y0="y", x1="x1", y1="y", color="#a4161a",
             line_width=1.5, line_dash="dashed", line_alpha=0.7, level=FRAME_LEVEL)
        draw(fig, Segment, bound, x0="x0", y0="y0", x1="x1", y1="y1", color="#a4161a",
             line_width=2, level=FRAME_LEVEL)
        draw(fig, Segment, s["spheres_forces"], x0="x0", y0="y0", x1="x1", y1="y1",
             color="#a4161a", line_width=4, level=FRAME_LEVEL)
        draw(fig, Scatter, s["spheres_forces"], x="x1", y="y1", marker="triangle",
             size="head", angle="angle", color="#a4161a", level=FRAME_LEVEL)
        draw(fig, Text, s["spheres_forces"], x="lx", y="ly", text="label",
             text_font_size="13pt", text_color="#a4161a", text_baseline="middle",
             text_align="align", level=FRAME_LEVEL)
        self.badge = draw(fig, Text, s["spheres_badge"], x=-1.5, y=2.05, text="text",
                          text_color="color", text_font_size="20pt", text_font_style="bold",
                          text_baseline="top", level=FRAME_LEVEL)
        # (over the spheres, on a white ground: the lower sphere may pass behind them)
        ground = {"background_fill_color": "white", "background_fill_alpha": 0.85,
                  "level": FRAME_LEVEL}
        # the scale note right under the other notes' lines, at any size of the plot
        self.note = Label(x=-1.55, y=NOTES_TOP, text="", text_baseline="top",
                          text_color="#333333", name="spheres_note", **ground)
        self.h_label = Label(x=-1.55, y=NOTES_TOP, text="", text_baseline="top",
                             text_color="#333333", name="spheres_rest_note", **ground)
        self.set_note_size(NOTE_PT)
        fig.add_layout(self.note)
        fig.add_layout(self.h_label)
        # every plot's stamp follows the forces' time; this one top right, beside the
        # upper sphere
        follow_clock(s["spheres_forces"])
        stamp(fig, sep="\n", x=1.57, y=2.07, x_units="data", y_units="data",
              text_align="right", text_baseline="top")
        style_figure(fig)
        self.figure = fig

    def set_note_size(self, points: float) -> None:
        """The notes under the spheres in `points` pt type, the scale note right under the
        `NOTE_LINES` lines of the others (a line as BokehJS draws it: 1.35 times the
        type's size in px, measured in Chromium)."""
        self.h_label.text_font_size = self.note.text_font_size = f"{points:g}pt"
        self.note.y_offset = -round(NOTE_LINES * points * 4 / 3 * 1.35 + 2, 1)

    def update_contact(self, c: Contact) -> None:
        """The drive line and the scale note (they follow theta, so psi); the lower
        sphere at rest (tau = 0), the period strip and the pictograms (tau0 alone: drawn
        again only when tau0 changes)."""
        H, u0 = drawn_amplitudes(c)
        cy = -H * math.sin(c.tau0) - 1.0  # the rest centre: the gap h below the upper sphere
        reach = 1.6  # the drive line, beyond both ends of the stroke
        show(self.still, {"x0": [-reach * u0], "y0": [cy - reach * H],
                          "x1": [reach * u0], "y1": [cy + reach * H]})
        gap = "dashed: at rest, h > 0 (a gap)" if c.tau0 > 0 else \
            "dashed: at rest, h ≤ 0 (a preload)"
        put(self.h_label, text=f"{gap}\ndrive line at θ = {math.degrees(c.theta):.1f}°"
                                f"\n{BOUND_WORDS}")
        put(self.note, text=scale_note(c))
        if self.note_tau0(c):
            self._show_period(c, cy)

    def _show_period(self, c: Contact, cy: float) -> None:
        """The lower sphere at rest (centre (0, cy)), the period strip and the
        pictograms of contact `c` (they depend on its tau0 only)."""
        show(self.rest, {"x": _COS, "y": cy + _SIN})
        taus = np.unique(np.concatenate([np.linspace(*PERIOD, 241), [c.tau0, c.tau_end]]))
        show(self.period, {"x": strip_x(taus), "y": strip_y(taus)})
        inside = taus[(taus >= c.tau0) & (taus <= c.tau_end)]
        show(self.period_contact, {"x": strip_x(inside), "lo": strip_y(inside),
                                   "hi": np.full(inside.size, STRIP_Y + STRIP_HEIGHT)})
        words = {"apart": (PERIOD[0] + c.tau0) / 2, "contact": math.pi / 2,
                 "apart ": (c.tau_end + PERIOD[1]) / 2}
        # (a short gap's word kept inside the strip: centred at its end it would be cut)
        at = np.clip(strip_x(np.array(list(words.values()))), -WORDS_REACH, WORDS_REACH)
        show(self.period_words, {"x": list(at),
                                 "text": [w.strip() for w in words]})
        drawn = pictograms.pictograms(c)
        when = np.array(drawn["tau"])
        show(self.pictograms, drawn | {"x_strip": list(strip_x(when)),
                                       "y_strip": list(strip_y(when))})

    @staticmethod
    def drawing(c: Contact, taus: np.ndarray) -> dict[str, dict[str, np.ndarray]]:
        """`drawing(c, taus)` (what the browser's player copies, frame by frame)."""
        return drawing(c, taus)

    def update_tau(self, c: Contact, tau: float) -> None:
        for name, cols in drawing(c, np.array([tau])).items():
            show(self.sources[name], {k: column(v[0]) for k, v in cols.items()})

