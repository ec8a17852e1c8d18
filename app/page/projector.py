"""The presentation view's projector setting: larger type and thicker lines on every
plot, for the back of a lecture hall.

A check box in the header; ticking it scales the plots' titles, axis labels, tick labels
and legends by `TYPE_SCALE` (tick labels 12 pt -> 18 pt, 24 px) and their lines by
`LINE_SCALE`; unticking it restores them.  It changes the figures' styles once per tick,
never their data: a slider move or an animation frame costs the same either way.
"""

from __future__ import annotations

import re
from collections.abc import Iterator

from bokeh.models import GlyphRenderer, Model

from app.kit.batch import held
from app.kit.widgets import LabelledCheckbox

#: How much larger the type is with the projector setting (12 pt tick labels: 18 pt).
TYPE_SCALE = 1.5
#: How much larger the titles are (less than the rest: a plot's title stays on its width).
TITLE_SCALE = 1.2
#: How much thicker the lines are.
LINE_SCALE = 1.6
#: How many ticks the y axes ask for, times (fewer: the larger tick labels stay apart).
TICKS_SCALE = 0.4
#: How much larger the axis labels and legends are (less than the tick labels: on a
#: 1280 x 720 screen the plots keep a frame high enough for two tick labels).
LABEL_SCALE = 1.2
#: The check box's label in the header.
LABEL = "Projector: larger type"
#: The check box in the header's colours (white on the header's blue, 5.1:1).
BOX_CSS = "label, .bk-input-group { color: white; font-weight: bold; }"

_SIZE = re.compile(r"^(\d+(?:\.\d+)?)(pt|px|em|rem)$")


def scaled_size(size: str, factor: float) -> str:
    """A CSS font size ('12pt') times `factor` ('18pt'), in the same unit; other values
    unchanged."""
    m = _SIZE.match(size) if isinstance(size, str) else None
    return f"{float(m.group(1)) * factor:g}{m.group(2)}" if m else size


def styled(fig) -> Iterator[tuple[Model, str, float]]:
    """The (model, property, factor) that the projector setting scales in `fig`: its
    title (`TITLE_SCALE`), tick labels (`TYPE_SCALE`) and the number of the y axes'
    ticks (`TICKS_SCALE`), axis labels and legends (`LABEL_SCALE`) and the lines of its
    glyphs (`LINE_SCALE`)."""
    yield fig.title, "text_font_size", TITLE_SCALE
    for axis in (*fig.xaxis, *fig.yaxis):
        yield axis, "axis_label_text_font_size", LABEL_SCALE
        yield axis, "major_label_text_font_size", TYPE_SCALE
    for axis in fig.yaxis:
        if "desired_num_ticks" in axis.ticker.properties():
            yield axis.ticker, "desired_num_ticks", TICKS_SCALE
    for legend in fig.legend:
        yield legend, "label_text_font_size", LABEL_SCALE
    for r in fig.renderers:
        if isinstance(r, GlyphRenderer) and "line_width" in r.glyph.properties():
            yield r.glyph, "line_width", LINE_SCALE


def scaled(value, factor: float):
    """A font size, a line width (a number; a dict {'value': ...}) or a number of ticks
    (an int: rounded, at least 2) times `factor`."""
    if isinstance(value, str):
        return scaled_size(value, factor)
    if isinstance(value, int) and factor < 1:
        return max(2, round(value * factor))
    if isinstance(value, int | float):
        return value * factor
    if isinstance(value, dict) and isinstance(value.get("value"), int | float | str):
        return {**value, "value": scaled(value["value"], factor)}
    return value


class Projector:
    """The projector check box and the figures it restyles (`style` adds one)."""

    def __init__(self, figures: list) -> None:
        self.box = LabelledCheckbox(label=LABEL, stylesheets=[BOX_CSS])
        #: each styled property's value without the projector setting
        self._normal: dict[tuple[str, str], object] = {}
        self._figures: list = []
        for fig in figures:
            self.style(fig)
        self.box.param.watch(lambda *_: self.restyle(), "value")

    @property
    def on(self) -> bool:
        """Whether the projector setting is on."""
        return self.box.value

    def style(self, fig) -> None:
        """Keep `fig` in the projector setting's style (now and on every change)."""
        if all(f is not fig for f in self._figures):
            self._figures.append(fig)
        self._apply(fig)

    def restyle(self) -> None:
        """Every figure in the setting's style."""
        with held():  # (one message)
            for fig in self._figures:
                self._apply(fig)

    def _apply(self, fig) -> None:
        for model, prop, factor in styled(fig):
            key = (model.id, prop)
            normal = self._normal.setdefault(key, getattr(model, prop))
            value = scaled(normal, factor) if self.on else normal
            if getattr(model, prop) != value:
                setattr(model, prop, value)
