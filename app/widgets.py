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

The prompt change also waits, a few turns of the event loop at most, until no message
is being written to the browser.  Bokeh acknowledges the slider's change with a
message written over several loop turns; a change processed in between finds the
socket busy, and Panel then queues the update and retries every 10 ms (measured: the
plots' update left the server 10-20 ms after it was ready).

`ExactSlider` pairs such a slider with a number box.  Unlike Panel's
EditableFloatSlider, the two are linked in the browser: the box follows the slider
without reporting back (`SLIDER_TO_ENTRY_JS`), and a number typed in the box moves the
slider (widening its range if needed), so the server hears of every change through
the slider alone.  The server never writes to the box: a value it gives the slider
(a preset, the URL) reaches the box by the same link in the browser.  The server also
ignores values the box reports: acting on a late one would move the slider back.
"""

from __future__ import annotations

import asyncio
import typing as t

import panel as pn
import param

try:  # Panel's own test of a socket's write lock (private: a later Panel may lack it)
    from panel.io.document import _is_write_locked
except ImportError:  # then the slider does not wait, and only speed is lost
    _is_write_locked = None

#: The box shows the slider's value without telling the server (it hears the slider).
SLIDER_TO_ENTRY_JS = "entry.setv({value: cb_obj.value}, {sync: false});"

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
    # a move is not "busy": flagging it costs ~1.5 ms of watchers per move, for no
    # indicator (the template has none: it restyled the page on every message)
    _busy__ignore: t.ClassVar[list[str]] = ["value", "value_throttled"]

    async def _change_coroutine(self, doc, event_id: str | None = None) -> None:
        await socket_free(doc)
        await super()._change_coroutine(doc, event_id)


async def socket_free(doc, turns: int = 50) -> None:
    """Yield to the event loop until no message is being written to `doc`'s browsers.

    Gives up after `turns` loop turns (a long write: Panel's own queue then handles it).
    Outside a server session it returns at once.
    """
    if _is_write_locked is None:
        return
    session = getattr(doc.session_context, "_session", None)
    connections = getattr(session, "_subscribed_connections", ())
    for _ in range(turns):
        if not any(_is_write_locked(c) for c in connections):
            return
        await asyncio.sleep(0)


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
        self._slider.jscallback(args={"entry": self._entry}, value=SLIDER_TO_ENTRY_JS)
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

    @param.depends("start", "end", watch=True)
    def _show_range(self) -> None:
        self._slider.param.update(start=self.start, end=self.end)

    @param.depends("disabled", watch=True)
    def _show_disabled(self) -> None:
        self._slider.disabled = self._entry.disabled = self.disabled
