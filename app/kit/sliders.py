"""Sliders: `LabelledSlider` (the browser's own range input, named by its label),
`DirectSlider` (its browser moves taken by Bokeh alone) and `ExactSlider` (a slider with
a box for exact entry, and a message under the box for a bad entry).

`ExactSlider` shows one number three ways: a slider over a teaching range, a text box
taking any value of the parameter's whole domain, and, when the typed text is refused,
the reason under the box (the same words as for a bad URL value: both come from one
parse function).  A refused entry changes nothing and the box shows the last good value
again; a good value outside the slider's range widens the range to show it.

Built from Panel's public components only (the slider a `LabelledSlider`), kept in step
on the server: the slider's moves write the box, the box's entries write the slider,
both through `value`.  A value from the browser is applied inside `panel.io.hold` (or
`unlocked`, `ExactSlider.follow_browser`): everything it changes (the box, and what
watches `value`: the plots, the readout) goes to the browser as one message.  Bokeh
builds each message's serializer over every model of the document, so a move whose
changes went out as several messages cost more server CPU (`docs/deploy.md`, "Load").
"""

from __future__ import annotations

import asyncio
from collections.abc import Callable
from typing import ClassVar

import panel as pn
import param
from bokeh.document import Document
from bokeh.models import TextInput
from panel.io import unlocked
from panel.io.state import set_curdoc

from app.kit.batch import held
from app.kit.style import FOCUS_RING
from app.kit.texts import WrittenHTML
from app.kit.widgets import ERROR_STYLE, finite, show_later, text_html, typed_value

#: JavaScript of `LabelledSlider`: the input shows the model's range, step, value, name
#: and state (the range first: a value outside the old range would be clamped to it).
_SLIDER_SHOW = """
input.min = data.start; input.max = data.end; input.step = data.step;
input.value = data.value;
input.disabled = data.disabled;
input.setAttribute("aria-label", data.label);
if (data.show_title) { title.textContent = data.label + ": " + data.value; }
"""

#: JavaScript of `LabelledSlider`: the input's value into the model (`data.value`).
_SLIDER_SET = "data.value = parseFloat(input.value);"

#: JavaScript of `DirectSlider`: the value set with BokehJS's `setv`, which Panel does not
#: take for a change of the parameter (it takes what a script assigns, ``data.NAME = ...``).
_DIRECT_SET = "data.setv({value: parseFloat(input.value)});"


def _slider_page(set_value: str) -> str:
    """JavaScript of a slider's keys: Page Up / Page Down move five steps (as BokehJS's
    sliders do; the browser's range input moves one), the value then set by `set_value`."""
    return f"""
const pages = {{PageUp: 5, PageDown: -5}};
if (event != null && event.key in pages) {{
  event.preventDefault();
  input.stepUp(pages[event.key]);
  {set_value}
}}
"""


class LabelledSlider(WrittenHTML):
    """A slider over [start, end] by `step`, named by `label` for a screen reader.

    BokehJS's Slider draws a noUiSlider whose handle (role "slider") has no accessible
    name, and no property of Bokeh or Panel gives it one.  This one is the browser's own
    `<input type="range">` with `aria-label` set to `label`, built with Panel's public
    `ReactiveHTML` (its scripts run under the server's Content-Security-Policy, which
    allows `new Function` but no `blob:` module, what a `JSComponent` is loaded as).
    Its keys are those of BokehJS's sliders: arrows one step, Page Up / Page Down five,
    Home / End the ends of the range.  `show_title`: "label: value" shown above it.

    Its Bokeh model (Panel's `ReactiveHTML`) keeps the values in the model's `data`
    (a Bokeh `DataModel`): `value`, `start`, `end`, `step`, `label`, `disabled`.
    `write(value=...)` moves it from the server (`app.kit.texts.WrittenHTML`: within a
    served document's `panel.io.hold`, Panel sends the change and runs no watcher of
    the model's `value` for it; elsewhere Panel's watcher finds the parameter already
    equal).
    """

    value = param.Number(default=0.0, allow_refs=False)
    start = param.Number(default=0.0, allow_refs=False)
    end = param.Number(default=1.0, allow_refs=False)
    step = param.Number(default=0.1)
    label = param.String(default="")
    disabled = param.Boolean(default=False)
    show_title = param.Boolean(default=False)

    _template = (
        '<div id="title" class="slider-title"></div>'
        '<input type="range" id="input" '
        'oninput="${script(\'input\')}" onkeydown="${script(\'keydown\')}"></input>')

    _scripts: ClassVar[dict[str, str]] = {
        "render": _SLIDER_SHOW,
        **dict.fromkeys(("value", "start", "end", "step", "label", "disabled"),
                        _SLIDER_SHOW),
        "input": _SLIDER_SET,
        "keydown": _slider_page(_SLIDER_SET),
    }

    #: The input as wide as the component, 24 px high (WCAG 2.5.8's least target).
    CSS = ("input { display: block; width: 100%; height: 24px; margin: 0; }"
           ".slider-title:empty { display: none; }")

    def __init__(self, **params) -> None:
        params["stylesheets"] = [self.CSS, *params.get("stylesheets", [])]
        super().__init__(**params)


class DirectSlider(LabelledSlider):
    """A `LabelledSlider` whose moves in the browser reach the server through Bokeh alone.

    Panel takes a change of a `LabelledSlider` from the browser 50 ms after it arrives,
    through its own machinery (~1 ms of server CPU per move), and sets `value`.  This
    one's scripts set the value with BokehJS's `setv`, which Panel does not take: its
    `value` changes only from the server, and the browser's moves are taken by a Bokeh
    `on_change` of the model's `data` (`ExactSlider.follow_browser`), once each.
    """

    _scripts: ClassVar[dict[str, str]] = {
        **LabelledSlider._scripts,
        "input": _DIRECT_SET,
        "keydown": _slider_page(_DIRECT_SET),
    }


#: The box of an `ExactSlider` (a Bokeh `TextInput`, which the page's CSS for Panel's
#: components, `app.page.layout.CSS`, does not reach) drawn as those: the page's type
#: size, the keyboard's ring, a disabled box greyed.
ENTRY_CSS = (".bk-input { font-size: var(--bokeh-font-size, 16px); }"
             f".bk-input:focus-visible {{ {FOCUS_RING} }}"
             ".bk-input[disabled] { background-color: #f3f3f3; opacity: 0.5; }")


class ExactSlider(pn.viewable.Viewer):
    """A slider over [start, end] and a box taking whatever `parse` accepts.

    `parse(text)` returns the value a typed text stands for, or raises ValueError with
    the message to show.  `value` is the one to watch or set; `disabled` greys out both.
    `direct`: the slider is a `DirectSlider`, whose browser moves only `follow_browser`
    takes (it must be called with the served document; `name` is then required).
    """

    value = param.Number(default=0.0)
    start = param.Number(default=0.0)
    end = param.Number(default=1.0)
    disabled = param.Boolean(default=False)
    error = param.String(default="", doc="why the last typed text was refused, '' if not")

    def __init__(self, *, label: str, value: float, start: float, end: float, step: float,
                 parse: Callable[[str], float], digits: int = 6,
                 name: str | None = None, direct: bool = False) -> None:
        if not start < end:
            raise ValueError(f"{label}: start {start} must be below end {end}")
        if direct and not name:
            raise ValueError(f"{label}: a direct slider needs a name (`follow_browser`)")
        super().__init__(value=value, start=min(start, value), end=max(end, value))
        self._range = (start, end)  # the slider's own (teaching) range
        self._parse = parse
        self._digits = digits
        self._doc: Document | None = None  # the served document (`follow_browser`)
        self._due = value  # the browser's last move, for `_apply_due`
        self._moving = False  # (a move of the slider is being applied: `moved`)
        self._scheduled = False
        self._slider = (DirectSlider if direct else LabelledSlider)(
            label=label, value=value, start=self.start, end=self.end, step=step,
            sizing_mode="stretch_width", margin=(0, 8, 5, 8),
            css_classes=[f"slider-{name}"] if name else [],
            tags=[f"{name}-slider"] if name else [])
        # (Bokeh's own text input: written on every move of the slider, a change costs
        # the server ~0.02 ms against ~0.9 ms for Panel's TextInput)
        self._entry = TextInput(title=label, value=self.text(value),
                                sizing_mode="stretch_width", margin=(0, 8),
                                stylesheets=[ENTRY_CSS],
                                css_classes=[f"entry-{name}"] if name else [],
                                tags=[f"{name}-entry"] if name else [])
        self._message = pn.pane.HTML("", visible=False, styles=ERROR_STYLE,
                                     margin=(0, 8), sizing_mode="stretch_width",
                                     name=name and f"{name}_error")
        self._slider.param.watch(self._on_slider, "value")
        self._entry.on_change("value", self._on_entry)
        self._layout = pn.Column(pn.pane.Bokeh(self._entry, sizing_mode="stretch_width",
                                               margin=0), self._message, self._slider,
                                 sizing_mode="stretch_width")

    def __panel__(self) -> pn.Column:
        return self._layout

    def text(self, v: float) -> str:
        """How the box shows the value `v`."""
        return f"{v:.{self._digits}g}"

    def _on_slider(self, event: param.parameterized.Event) -> None:
        if not finite(event.new):  # (from a script: no slider sends it) put it back
            show_later(self._slider, self.value)
            return
        # everything the move changes (this box, the plots, the readout) goes to the
        # browser in one message
        with held():
            self.moved(event.new)

    def moved(self, value: float) -> None:
        """Set `value` as a move of the slider: its range is not narrowed (a range
        widened to show a value typed beyond it stays while the thumb is dragged back,
        so that the thumb stays under the pointer; it is the slider's own again at the
        next value typed or set)."""
        self._moving = True
        try:
            self.value = value
        finally:
            self._moving = False

    def follow_browser(self, doc: Document) -> None:
        """Take the slider's moves in the served document `doc` as Bokeh delivers them.

        Panel applies a widget change from the browser 50 ms after it arrives (it waits
        to merge the moves of a drag), a wait in which the server is idle and which is
        half of a move's time on screen.  Bokeh's own `on_change` of the slider's values
        (its model's `data`, see `LabelledSlider`) runs when the change arrives; the move
        is then applied by `_apply_due` on the event loop (inside `unlocked`, so that all
        it changes goes out as one message; the moves that arrive before it runs are
        merged into the last).  A `direct` slider's moves Panel does not take at all
        (`DirectSlider`); another's, Panel's delayed application finds already set and
        changes nothing.  The model is found by its tag (`{name}-slider`); a slider
        without a name is left to Panel, one not on the page (e.g. the presentation
        view's) has no moves to take.
        """
        tags = self._slider.tags
        model = doc.select_one({"tags": tags[0]}) if tags else None
        if model is not None:
            self._doc = doc
            model.data.on_change("value", self._on_browser_value)

    def _on_browser_value(self, attr: str, old: float, new: float) -> None:
        if new == self.value or not finite(new):  # (the server's own change, echoed by
            return  # Bokeh; or what no slider sends, which `_on_slider` puts back)
        self._due = new
        if not self._scheduled:
            self._scheduled = True
            self._doc.add_next_tick_callback(self._apply_due)

    async def _apply_due(self) -> None:
        """Apply the browser's last move (a coroutine: Bokeh runs it on the event loop,
        where Panel can send all that the move changes as one message).

        This callback wakes as Bokeh's handling of the browser's message releases the
        document lock, on the loop turn in which Bokeh starts writing its reply to that
        message; Panel, finding the socket busy, would then leave each change to Bokeh,
        one message per changed model.  One turn of the loop first lets the reply go.
        """
        self._scheduled = False
        await asyncio.sleep(0)
        with set_curdoc(self._doc), unlocked():
            self.moved(self._due)

    def _on_entry(self, attr: str, old: str, new: str) -> None:
        try:
            v = typed_value(self._entry, new, self.text(self.value), self._parse)
        except ValueError as err:  # (the box shows the last good value again)
            self.error = str(err)
            return
        if v is None:
            return  # the box shows the value (set from here, or the refused text reverted)
        self.error = ""
        if v == self.value:
            show_later(self._entry, self.text(v))
        with held():
            self.value = v


    @param.depends("value", watch=True)
    def _show_value(self) -> None:
        v = self.value
        # the slider's range: its own, widened to show a value typed beyond it, and its
        # own again once a value typed or set is back inside (`_show_range` follows); a
        # move of the slider only widens it (`moved`)
        lo, hi = (self.start, self.end) if self._moving else self._range
        start, end = min(lo, v), max(hi, v)
        with held():  # (the box is a Bokeh model: `held_set`)
            if (start, end) != (self.start, self.end):
                self.param.update(start=start, end=end)
            self._slider.write(value=v)  # (nothing when it holds v: the browser's move)
            self._entry.value = self.text(v)

    def set_range(self, start: float, end: float, value: float) -> None:
        """Give the slider a new range of its own and the value `value` (in it)."""
        if (start, end) == self._range and value == self.value:
            return  # (a move that changes neither: most of them, for the tau slider)
        self._range = (start, end)
        self.param.update(start=min(start, value), end=max(end, value), value=value)

    @param.depends("error", watch=True)
    def _show_error(self) -> None:
        self._message.param.update(object=text_html(self.error), visible=bool(self.error))

    @param.depends("start", "end", watch=True)
    def _show_range(self) -> None:
        self._slider.param.update(start=self.start, end=self.end)

    @param.depends("disabled", watch=True)
    def _show_disabled(self) -> None:
        with held():
            self._slider.disabled = self._entry.disabled = self.disabled
