"""The stability map of the numerical methods (stability_map.csv).

The error of one method at a fixed resolution over (psi, tau0), on a log colour scale
over the whole range of the data (from 1e-16 to the worst error, the printed closed
form's included); psi on a log axis, tau0 in radians on an axis spaced by
log(pi/2 - tau0 + `Y_SHIFT`), so that grazing contact (tau0 -> pi/2) stays visible
beside preload (tau0 < 0).  Built for the Methods card and the stand-alone page
(`app.methods.publish`).  Presentation only: every number is the benchmarks'.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from bokeh.models import (
    ColorBar,
    ColumnDataSource,
    CustomJSTickFormatter,
    FixedTicker,
    HoverTool,
    LogColorMapper,
    LogTicker,
)
from bokeh.palettes import Viridis256
from bokeh.plotting import figure

from app.methods.results import FLOOR

#: The tau0 axis is logarithmic in pi/2 - tau0 + Y_SHIFT (rad).
Y_SHIFT = 0.02
Y_TICKS = [-1.4, -0.84, 0.0, 0.84, 1.12, 1.4, 1.5, 1.55, 1.565, 1.569]
#: The quantities a map shows: title -> column.
STABILITY_FIELDS = {"combined error: max(|T error| / T0, |impulse-ratio error|)": "err",
                    "relative impulse-ratio error": "rel_err_impulse"}


def _edges(values: np.ndarray) -> np.ndarray:
    """Cell edges around increasing values: midpoints inside, half a step outside."""
    mids = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[values[0] - (mids[0] - values[0])], mids,
                           [values[-1] + (values[-1] - mids[-1])]])


@dataclass(frozen=True)
class StabilityData:
    """Per method, its resolution and its cells (left, right, top, bottom edges in
    plot coordinates, psi, tau0, and each quantity of `STABILITY_FIELDS`, at FLOOR at
    least); the plot's ranges; the colour scale's top (a power of ten at or above the
    worst error of any method, 1 at least)."""

    cells: dict[str, dict[str, list]]
    resolution: dict[str, int]
    x_range: tuple[float, float]
    y_range: tuple[float, float]
    high: float

    @property
    def methods(self) -> list[str]:
        return list(self.cells)


def stability_data(rows: list[dict]) -> StabilityData:
    """The cells of stability_map.csv's `rows` (methods in the file's order)."""
    psis = np.array(sorted({r["psi"] for r in rows}))
    tau0s = np.array(sorted({r["tau0"] for r in rows}))
    lx = _edges(np.log10(psis))
    gaps = np.pi / 2 + Y_SHIFT - tau0s  # decreasing as tau0 increases
    ly = _edges(np.log10(gaps[::-1]))[::-1]
    x_index = {float(p): i for i, p in enumerate(psis)}
    y_index = {float(t): i for i, t in enumerate(tau0s)}
    cells, resolution = {}, {}
    for name in dict.fromkeys(r["method"] for r in rows):
        sel = [r for r in rows if r["method"] == name]
        i = np.array([x_index[r["psi"]] for r in sel], dtype=int)
        j = np.array([y_index[r["tau0"]] for r in sel], dtype=int)
        cells[name] = {
            "left": (10.0 ** lx[i]).tolist(), "right": (10.0 ** lx[i + 1]).tolist(),
            "top": (10.0 ** ly[j]).tolist(), "bottom": (10.0 ** ly[j + 1]).tolist(),
            "psi": [r["psi"] for r in sel], "tau0": [r["tau0"] for r in sel],
            **{col: np.maximum([r[col] for r in sel], FLOOR).tolist()
               for col in STABILITY_FIELDS.values()}}
        resolution[name] = sel[0]["resolution"]
    worst = max(max(r[col] for col in STABILITY_FIELDS.values()) for r in rows)
    return StabilityData(cells, resolution, (10.0 ** lx[0], 10.0 ** lx[-1]),
                         (10.0 ** ly[0], 10.0 ** ly[-1]),
                         float(10.0 ** np.ceil(np.log10(max(worst, 1.0)))))


def error_mapper(data: StabilityData) -> LogColorMapper:
    """Viridis on a log scale from 1e-16 to the data's worst error."""
    return LogColorMapper(palette=Viridis256, low=1e-16, high=data.high,
                          low_color="#000004", nan_color="red")


def map_cells(data: StabilityData, method: str, field: str) -> dict[str, list]:
    """The columns of `method`'s map, the quantity `field` (a column) as `shown`."""
    cells = data.cells[method]
    return {**cells, "shown": cells[field]}


def map_title(data: StabilityData, method: str) -> str:
    return f"{method} (resolution {data.resolution[method]})"


def stability_figure(data: StabilityData, method: str, mapper: LogColorMapper,
                     field: str = "err", **kwargs) -> tuple[figure, ColumnDataSource]:
    """The map of one method (its quantity `field`) and its source; `kwargs` go to the
    figure."""
    source = ColumnDataSource(map_cells(data, method, field))
    fig = figure(title=map_title(data, method), x_axis_type="log", y_axis_type="log",
                 x_axis_label="ψ", y_axis_label="τ₀ (rad)", x_range=data.x_range,
                 y_range=data.y_range, **kwargs)
    fig.quad(left="left", right="right", top="top", bottom="bottom", source=source,
             line_color=None, fill_color={"field": "shown", "transform": mapper})
    fig.yaxis.ticker = FixedTicker(ticks=[float(np.pi / 2 + Y_SHIFT - t) for t in Y_TICKS])
    fig.yaxis.formatter = CustomJSTickFormatter(
        args=dict(shift=Y_SHIFT),
        code="const t = Math.PI / 2 + shift - tick; "
             "return t.toFixed(Math.abs(t) > 1.52 ? 3 : 2);")
    fig.add_tools(HoverTool(tooltips=[("ψ", "@psi{0.000}"), ("τ₀", "@tau0{0.0000} rad"),
                                      ("error", "@shown{0.0e}")]))
    return fig, source


def colour_bar(mapper: LogColorMapper) -> ColorBar:
    return ColorBar(color_mapper=mapper, ticker=LogTicker(desired_num_ticks=12), width=16,
                    title="error (log)")


STABILITY_NOTE = (
    "Error of each method against the closed form of <code>core</code> over (ψ, τ₀), "
    "each method at a fixed resolution. Colour: error on a log scale from 1e-16 (dark) "
    "to {high:.0e} (yellow), the whole range of the data. Rows are spaced by "
    f"log(π/2 − τ₀ + {Y_SHIFT:g}) so that grazing contact (τ₀ near π/2) stays visible "
    "next to preload (τ₀ &lt; 0); the axis reads τ₀ in radians. <b>textbook</b> is the "
    "closed form as printed (eq 11 with ellipk/ellipe, τ₁ = π − arcsin(...)).")
