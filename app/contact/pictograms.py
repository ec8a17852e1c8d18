"""The spheres over a whole period, in small pictures: apart, approaching, touching, in
contact, releasing and apart again (the contact is intermittent).

Under the period strip of the spheres' scene (`app.contact.spheres`) a row of small
pictograms shows the two spheres at `INSTANTS` of one period: the upper sphere held, the
lower one at its height u_z0 = H sin tau (eq 3) below it, the gap h - u_z0 = H (sin tau0 -
sin tau) open outside the contact (eq 4) and, inside it, the approach alpha = H (sin tau -
sin tau0) (eq 8, `Contact.approach`), both flattened at the plane midway between them as
in the main drawing.  They show the normal motion only (the spheres one above the other)
with H drawn as `PICTOGRAM_DRIVE` of their radius, so that the gap shows.  Each is joined
by a thin line to its time on the strip.  They depend on tau0 only: computed once per
contact (`pictograms(c)`), never per animation frame.
"""

from __future__ import annotations

import math

import numpy as np

from core import Contact

RADIUS = 0.12  # a pictogram sphere's radius, in the scene's units (main sphere radii)
PICTOGRAM_DRIVE = 0.5  # the drawn normal amplitude H, in pictogram radii
TOP = -3.02  # the pictograms' top (the upper spheres' tops), scene units
SPACING = 0.5  # between the pictograms' centres, scene units
OUTLINE_POINTS = 49  # points of each pictogram sphere's outline
#: the labels' top, under the lowest a lower sphere reaches (a gap of 2 H at tau0 -> pi/2)
LABEL_Y = TOP - 4 * RADIUS - 2 * PICTOGRAM_DRIVE * RADIUS - 0.03
#: how much lower every second label is (scene units): two rows, so that neighbours'
#: labels never run together ("contactrelease") on a plot 240 px wide
LABEL_STEP = 0.21

_ANGLES = np.linspace(0.0, 2.0 * math.pi, OUTLINE_POINTS)


def instants(c: Contact) -> list[tuple[str, float]]:
    """(label, tau in rad) of the pictograms: the widest gap (tau = -pi/2), halfway
    to the touch, the touch (tau0), mid contact (pi/2), the release (pi - tau0) and
    halfway from the release back to the widest gap (3 pi/2)."""
    start, end = -math.pi / 2, 3 * math.pi / 2
    return [("apart", start), ("closing", (start + c.tau0) / 2), ("touch", c.tau0),
            ("contact", math.pi / 2), ("release", c.tau_end),
            ("opening", (c.tau_end + end) / 2)]


def separation(c: Contact, taus: np.ndarray, drive: float) -> np.ndarray:
    """The distance between the spheres' surfaces (one above the other) at the times
    `taus` (rad), for a drawn normal amplitude `drive`: the gap H (sin tau0 - sin tau)
    outside the contact (> 0), minus the approach alpha = H (1 - sin tau0) alpha / (H - h)
    inside it (<= 0; eqs 3, 4, 8)."""
    taus = np.asarray(taus, float)
    s0 = math.sin(c.tau0)
    inside = (taus >= c.tau0) & (taus <= c.tau_end)
    gap = drive * (s0 - c.drive_displacement(taus))  # u_z0 / H = sin tau (eq 3)
    approach = drive * (1.0 - s0) * c.approach(taus)
    return np.where(inside, -approach, np.maximum(gap, 0.0))


def outline(cx: float, cy: float, r: float, cut: float | None, below: bool) -> np.ndarray:
    """The outline (2, n) of a circle of centre (cx, cy) and radius r, flattened at the
    height `cut` (None: not flattened) from below (`below`: the lower sphere) or above."""
    x, y = cx + r * np.cos(_ANGLES), cy + r * np.sin(_ANGLES)
    if cut is not None:
        y = np.minimum(y, cut) if below else np.maximum(y, cut)
    return np.stack([x, y])


def pictograms(c: Contact) -> dict[str, list]:
    """The pictograms' columns (one row each, scene units): tau (rad), label, the
    centres (xu, yu) of the upper and (xl, yl) of the lower sphere, their radius r, the
    surfaces' separation (`separation`: > 0 a gap, < 0 an approach), the outlines
    (xs_upper, ys_upper, xs_lower, ys_lower), the label's colour and the leader line from
    the pictogram's top (x, TOP) to its time on the strip (x_strip, y_strip: filled by the
    caller), and the label's top (label_y: every second one `LABEL_STEP` lower)."""
    marks = instants(c)
    taus = np.array([t for _, t in marks])
    gaps = separation(c, taus, PICTOGRAM_DRIVE * RADIUS)
    xs = (np.arange(len(marks)) - (len(marks) - 1) / 2) * SPACING
    yu = np.full(len(marks), TOP - RADIUS)
    yl = yu - 2 * RADIUS - gaps
    cols: dict[str, list] = {k: [] for k in ("xs_upper", "ys_upper", "xs_lower", "ys_lower")}
    for x, upper, lower, gap in zip(xs, yu, yl, gaps, strict=True):
        cut = upper - RADIUS - gap / 2 if gap < 0 else None  # the plane midway
        for name, cy, below in (("upper", upper, False), ("lower", lower, True)):
            line = outline(x, cy, RADIUS, cut, below)
            cols[f"xs_{name}"].append(line[0])
            cols[f"ys_{name}"].append(line[1])
    inside = (taus >= c.tau0) & (taus <= c.tau_end)
    return {"tau": list(taus), "label": [label for label, _ in marks], "x": list(xs),
            "xu": list(xs), "yu": list(yu), "xl": list(xs), "yl": list(yl),
            "r": [RADIUS] * len(marks), "separation": list(gaps),
            "color": ["#D55E00" if k else "#333333" for k in inside],
            "label_y": [LABEL_Y - LABEL_STEP * (k % 2) for k in range(len(marks))], **cols}
