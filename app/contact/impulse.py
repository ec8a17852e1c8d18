"""The impulse ratio against psi (Fig. 8, `ImpulseScene`, source `impulse`), with the
current contact marked."""

from __future__ import annotations

from functools import cached_property

import numpy as np
from bokeh.models import (
    ColumnDataSource,
    Label,
    Range1d,
)

from app.kit.changes import show
from app.kit.figures import (
    CURVE_POINTS,
    DATA_LEVEL,
    STAMP_TAG,
    new_figure,
    stamp,
    style_figure,
)
from app.kit.scene import Scene
from app.kit.wire import inline
from core import Contact, impulse_ratio


class ImpulseScene(Scene):
    """Fig. 8: T_imp / (mu P_imp) against psi at the current tau0, current psi marked.

    Two figures share the source: a linear psi axis (0 to 30, the paper's range) and a
    logarithmic one reaching psi = 1e6; `set_log` picks the one in `figure`, which the
    page shows (the other is not in the page at all: a hidden plot whose data changes
    still makes the browser lay out the page again).
    """

    name = "impulse"
    LINEAR_MAX = 30.0
    LOG_RANGE = (1e-3, 1e6)

    #: the psi of the curves of Fig. 7 (a: 0.4, 0.8, 1; b: 2.41, 6.46, 28.35), marked 1
    #: to 6 on the impulse curve as in Fig. 8
    FIG7_PSI = (0.4, 0.8, 1.0, 2.41, 6.46, 28.35)

    def __init__(self) -> None:
        super().__init__({"psi": [], "ratio": []})
        self.marker = ColumnDataSource({"psi": [], "ratio": []}, name="impulse_marker")
        self.points = ColumnDataSource({"psi": [], "ratio": [], "label": []},
                                       name="impulse_points")
        self.log = False
        self._shown: tuple = ()  # (tau0, log, first psi, last psi) of the curve shown

    @cached_property
    def linear_figure(self):
        """The plot with a linear psi axis, built on first use."""
        return self._make("linear")

    @cached_property
    def log_figure(self):
        """The plot with a logarithmic psi axis, built on first use."""
        return self._make("log")

    @property
    def figure(self):
        """The plot shown: `log_figure` or `linear_figure`."""
        return self.log_figure if self.log else self.linear_figure

    def _make(self, axis: str):
        x_range = Range1d(*self.LOG_RANGE) if axis == "log" else Range1d(0.0, self.LINEAR_MAX)
        fig = new_figure("Tangential impulse T_imp / (μ P_imp)", "ψ", "T_imp / (μ P_imp)",
                         x_axis_type=axis, x_range=x_range)
        fig.line("psi", "ratio", source=self.source, color="black", line_width=3)
        fig.scatter("psi", "ratio", source=self.points, size=11, color="white",
                    line_color="black", line_width=2)
        fig.text("psi", "ratio", text="label", source=self.points, text_font_size="13pt",
                 text_font_style="bold", x_offset=6, y_offset=-6)
        fig.scatter("psi", "ratio", source=self.marker, size=14, color="#D55E00",
                    line_color="black", level=DATA_LEVEL)
        # top right, where the ratio has fallen from its peak at psi = 1 (placed with the
        # ranges)
        stamp(fig, sep="\n", x_units="data", y_units="data", text_align="right",
              text_baseline="top", x_offset=-4, y_offset=-4)
        style_figure(fig)
        return fig

    def set_log(self, log: bool) -> None:
        """Pick the log-psi figure (True) or the linear one (False) as `figure`."""
        self.log = log

    def psi_grid(self, psi: float) -> np.ndarray:
        """The psi values plotted: screen-fine, through psi = 1 (the peak), reaching psi.

        It depends on psi only when psi lies beyond the default range, so that moving psi
        sends only the marker, not the curve (computed exactly by core either way)."""
        if self.log:
            lo, hi = self.LOG_RANGE
            grid = np.geomspace(min(lo, psi), max(hi, psi), CURVE_POINTS)
        else:
            grid = np.linspace(0.0, max(self.LINEAR_MAX, 1.1 * psi), CURVE_POINTS)
        return np.unique(np.concatenate([grid, [1.0]]))

    def update_contact(self, c: Contact) -> None:
        show(self.marker, {"psi": [c.psi], "ratio": [c.impulse_ratio]})
        psi = self.psi_grid(c.psi)
        key = (c.tau0, self.log, psi[0], psi[-1])
        if key == self._shown:
            return
        self._shown = key
        ratio = np.asarray(impulse_ratio(psi, c.tau0), float)
        self.source.data = inline({"psi": psi, "ratio": ratio})
        marked = np.array(self.FIG7_PSI)
        self.points.data = {"psi": marked, "ratio": np.asarray(impulse_ratio(marked, c.tau0)),
                            "label": [str(i) for i in range(1, marked.size + 1)]}
        fig = self.figure
        if self.log:
            fig.x_range.start, fig.x_range.end = psi[0], psi[-1]
        else:
            fig.x_range.start, fig.x_range.end = 0.0, psi[-1]
        fig.y_range.start, fig.y_range.end = 0.0, 1.05 * max(float(ratio.max()), 1e-9)
        corner = (fig.x_range.end, fig.y_range.end)
        for label in fig.select(type=Label):
            if STAMP_TAG in label.tags and (label.x, label.y) != corner:
                label.x, label.y = corner

    def table(self) -> dict[str, np.ndarray]:
        """The plotted curve for the CSV download: psi and the impulse ratio
        T_imp/(mu P_imp) (eq 41) at the contact's tau0."""
        d = {k: np.asarray(v) for k, v in self.source.data.items()}
        return {"psi": d["psi"], "T_imp/(mu P_imp)": d["ratio"]}
