"""Sliders that reach the server at once, with a box for exact entry.

Panel holds every change coming from the browser for a fixed 50 ms (`Syncable._debounce`
in panel/reactive.py) so that a burst of events is merged into one; a change listed in a
widget's `_priority_changes` is scheduled on the next tick instead.  Bursts are still
merged (events arriving while one is pending join it, and the server handles one
message at a time), so dropping the wait costs nothing but the wait itself: half of
the explorer's 100 ms budget from a slider move to all plots updated.  Only `value` is
prompt: the `value_throttled` that follows every key press or release keeps its wait,
which keeps its processing off the path of the plots' update (measured: 10-40 ms less
per move than with both prompt).

`ExactSlider` pairs such a slider with a number box.  Unlike Panel's
EditableFloatSlider, the two are linked in the browser: the box follows the slider,
and a number typed in the box moves the slider (widening its range if needed), so the
server hears of every change through the slider alone and sends no echo of the box
back.  The server writes to the box only when the value comes from elsewhere (a
preset, the URL).  The server ignores the box's own value: the browser reports it
after every slider move, late, and acting on it would move the slider back.
"""

from __future__ import annotations

import typing as t

import panel as pn
import param

#: A number typed in the box moves the slider, widening its range to show it; an
#: emptied box shows the slider's value again.
ENTRY_TO_SLIDER_JS = """
const v = cb_obj.value;
if (v == null) { cb_obj.value = slider.value; return; }
if (v < slider.start) { slider.start = v; }
if (v > slider.end) { slider.end = v; }
slider.value = v;
"""


class PromptFloatSlider(pn.widgets.FloatSlider):
    """A FloatSlider whose value changes are not debounced."""

    _priority_changes: t.ClassVar[list[str]] = ["value"]


class ExactSlider(pn.viewable.Viewer):
    """A slider over [start, end] and a box taking any value in [fixed_start, fixed_end].

    A value typed beyond the slider's range widens the range to show it.  `value` is
    the one to watch or set; `disabled` greys out both.
    """

    value = param.Number(default=0.0)
    start = param.Number(default=0.0)
    end = param.Number(default=1.0)
    disabled = param.Boolean(default=False)

    def __init__(self, *, label: str, value: float, start: float, end: float, step: float,
                 fixed_start: float | None = None, fixed_end: float | None = None,
                 format: str = "0[.]000") -> None:
        if not start < end:
            raise ValueError(f"{label}: start {start} must be below end {end}")
        super().__init__(value=value, start=min(start, value), end=max(end, value))
        self.param.value.bounds = (fixed_start, fixed_end)
        self._from_slider = False
        self._slider = PromptFloatSlider(
            value=value, start=self.start, end=self.end, step=step, format=format,
            show_value=False, sizing_mode="stretch_width", margin=(0, 8, 5, 8))
        self._entry = pn.widgets.FloatInput(
            value=value, start=fixed_start, end=fixed_end, step=step, format=format,
            width=130, margin=(0, 8), align="end")
        self._label = pn.widgets.StaticText(value=f"{label}:", margin=(0, 10, 0, 8),
                                            align="end")
        self._slider.jslink(self._entry, value="value")
        self._entry.jscallback(args={"slider": self._slider}, value=ENTRY_TO_SLIDER_JS)
        self._slider.param.watch(self._on_slider, "value")
        self._layout = pn.Column(pn.Row(self._label, self._entry), self._slider,
                                 sizing_mode="stretch_width")

    def __panel__(self) -> pn.Column:
        return self._layout

    def _on_slider(self, event: param.parameterized.Event) -> None:
        self._from_slider = True
        try:
            self.value = event.new
        finally:
            self._from_slider = False

    @param.depends("value", watch=True)
    def _show_value(self) -> None:
        if self._from_slider:
            return
        v = self.value
        self.param.update(start=min(self.start, v), end=max(self.end, v))
        self._slider.param.update(start=self.start, end=self.end, value=v)
        self._entry.value = v

    @param.depends("start", "end", watch=True)
    def _show_range(self) -> None:
        self._slider.param.update(start=self.start, end=self.end)

    @param.depends("disabled", watch=True)
    def _show_disabled(self) -> None:
        self._slider.disabled = self._entry.disabled = self.disabled
