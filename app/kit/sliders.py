"""Sliders: `LabelledSlider` (the browser's own range input, named by its label, a Panel
component), `SliderModel` and `DirectSlider` (a slider's values as a Bokeh model the app
owns, and the range input that draws it) and `ExactSlider` (a slider with a box for exact
entry, and a message under the box for a bad entry).

`ExactSlider` shows one number three ways: a slider over a teaching range, a text box
taking any value of the parameter's whole domain, and, when the typed text is refused,
the reason under the box (the same words as for a bad URL value: both come from one
parse function).  A refused entry changes nothing and the box shows the last good value
again; a good value outside the slider's range widens the range to show it.

Its slider's values are a `SliderModel`; the browser's moves arrive as Bokeh changes of
that model's `value`, taken by one public ``on_change`` (`ExactSlider.take_move`, as
demo.bokeh.org's apps take a widget's value), and applied inside `panel.io.unlocked`
(or `panel.io.hold`): everything a move changes (the box, and what watches `value`: the
plots, the readout) goes to the browser as one message.  Bokeh builds each message's
serializer over every model of the document, so a move whose changes went out as
several messages cost more server CPU (`docs/deploy.md`, "Load").
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import ClassVar

import panel as pn
import param
from bokeh.core.properties import Bool, Float, String
from bokeh.model import DataModel
from bokeh.models import TextInput
from panel.io import unlocked
from panel.io.state import set_curdoc
from panel.reactive import ReactiveHTML

from app.kit.batch import held
from app.kit.style import FOCUS_RING
from app.kit.texts import WrittenHTML
from app.kit.widgets import ERROR_STYLE, finite, show_later, text_html, typed_value

log = logging.getLogger(__name__)

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


class SliderModel(DataModel):
    """What an `ExactSlider`'s slider shows, as a Bokeh model the app owns: the value,
    the range, the step, the label (its accessible name) and whether it is disabled.

    The browser's range input (`DirectSlider`) draws it and writes its moves into it
    (`value`); Bokeh sends that change to the server, where the slider takes it with
    the model's public ``on_change`` (`ExactSlider.take_move`).  The server's changes
    (a typed value, a preset, a widened range) are set on it and Bokeh sends them: one
    model, one property per quantity, each change sent once, the browser's own move
    never sent back to it (Bokeh does not echo a change to the client that made it, and
    the server finds the value already set)."""

    value = Float(default=0.0)
    start = Float(default=0.0)
    end = Float(default=1.0)
    step = Float(default=0.1)
    label = String(default="")
    disabled = Bool(default=False)


#: JavaScript of `DirectSlider`: the input shows its `SliderModel` (found by its id in
#: the document, BokehJS's public `get_model_by_id`) and follows each change of it
#: (the view's `connect` to the model's `change`, disconnected with the view).
_DIRECT_RENDER = """
const m = model.document.get_model_by_id(data.target);
state.model = m;
state.input = input;
const show = () => {
  const el = state.input;
  el.min = m.start; el.max = m.end; el.step = m.step;
  el.value = m.value;
  el.disabled = m.disabled;
  el.setAttribute("aria-label", m.label);
};
show();
if (!state.connected) { view.connect(m.change, show); state.connected = true; }
"""

#: JavaScript of `DirectSlider`: the input's value into its `SliderModel`.
_DIRECT_SET = "state.model.value = parseFloat(input.value);"


class DirectSlider(ReactiveHTML):
    """The browser's own range input drawing the `SliderModel` whose id is `target`,
    named by the model's label for a screen reader (`aria-label`), its moves written
    into that model (never into this component's parameters: the model is the one
    place the slider's value is held).  Its keys are those of `LabelledSlider`."""

    target = param.String(default="", doc="the id of the SliderModel drawn")

    _template = ('<input type="range" id="input" '
                 'oninput="${script(\'input\')}" onkeydown="${script(\'keydown\')}"></input>')

    _scripts: ClassVar[dict[str, str]] = {
        "render": _DIRECT_RENDER,
        "input": _DIRECT_SET,
        "keydown": _slider_page(_DIRECT_SET),
    }

    def __init__(self, **params) -> None:
        params["stylesheets"] = [LabelledSlider.CSS, *params.get("stylesheets", [])]
        super().__init__(**params)


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
    `model` is the `SliderModel` the slider draws (tagged ``{name}-value``); the
    browser's moves of the slider arrive as changes of its `value` (`take_move`).
    `name` names the slider's and the box's models (CSS classes ``slider-{name}``,
    ``entry-{name}``, tags ``{name}-slider``, ``{name}-entry``) and the message's pane.
    """

    value = param.Number(default=0.0)
    start = param.Number(default=0.0)
    end = param.Number(default=1.0)
    disabled = param.Boolean(default=False)
    error = param.String(default="", doc="why the last typed text was refused, '' if not")

    def __init__(self, *, label: str, value: float, start: float, end: float, step: float,
                 parse: Callable[[str], float], digits: int = 6,
                 name: str | None = None) -> None:
        if not start < end:
            raise ValueError(f"{label}: start {start} must be below end {end}")
        super().__init__(value=value, start=min(start, value), end=max(end, value))
        self._range = (start, end)  # the slider's own (teaching) range
        self._parse = parse
        self._digits = digits
        self._due = value  # the browser's last move, for `_apply_due`
        self._moving = False  # (a move of the slider is being applied: `moved`)
        self._scheduled = False
        #: what the slider shows, and where the browser's moves arrive
        self.model = SliderModel(value=value, start=self.start, end=self.end, step=step,
                                 label=label, tags=[f"{name}-value"] if name else [])
        self._slider = DirectSlider(
            target=self.model.id, sizing_mode="stretch_width", margin=(0, 8, 5, 8),
            css_classes=[f"slider-{name}"] if name else [],
            tags=[f"{name}-slider"] if name else [])
        # (Bokeh's own text input: written on every move of the slider, a change costs
        # the server far less than Panel's TextInput; `benchmarks.app.move_cost`); it
        # holds the slider's model, so that the model is in every document the slider
        # is drawn in
        self._entry = TextInput(title=label, value=self.text(value),
                                sizing_mode="stretch_width", margin=(0, 8),
                                stylesheets=[ENTRY_CSS],
                                css_classes=[f"entry-{name}"] if name else [],
                                tags=[*([f"{name}-entry"] if name else []), self.model])
        self._message = pn.pane.HTML("", visible=False, styles=ERROR_STYLE,
                                     margin=(0, 8), sizing_mode="stretch_width",
                                     name=name and f"{name}_error")
        self.model.on_change("value", self.take_move)
        self._entry.on_change("value", self._on_entry)
        self._layout = pn.Column(pn.pane.Bokeh(self._entry, sizing_mode="stretch_width",
                                               margin=0), self._message, self._slider,
                                 sizing_mode="stretch_width")

    def __panel__(self) -> pn.Column:
        return self._layout

    def text(self, v: float) -> str:
        """How the box shows the value `v`."""
        return f"{v:.{self._digits}g}"

    def take_move(self, attr: str, old: float, new: float) -> None:
        """Take a move of the slider in the browser: a change of `model.value` (Bokeh's
        public ``on_change``; the one path of a browser's move into the app).

        Panel would apply a widget change from the browser 50 ms after it arrives (it
        waits to merge the moves of a drag), a wait with the server idle.  In a served
        document the move is applied by `_apply_due` on the event loop's next turn
        (inside `unlocked`, so that all it changes goes out as one message; moves that
        arrive before it runs are merged into the last); in a document not served, at
        once.  The server's own change of the model (`_show_value`) finds the value
        equal and changes nothing."""
        if new == self.value:
            return
        self._due = new
        doc = self.model.document
        if doc is None or doc.session_context is None:
            with held():
                self._apply(new)
        elif not self._scheduled:
            self._scheduled = True
            doc.add_next_tick_callback(self._apply_due)

    def _apply(self, value: float) -> None:
        """A move to `value` (what no slider sends, a value not finite, is put back)."""
        if finite(value):
            self.moved(value)
        else:
            self.model.value = self.value

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
        doc = self.model.document
        if doc is None:  # (the session ended meanwhile)
            return
        with set_curdoc(doc), unlocked():
            self._apply(self._due)

    def feed(self, put: Callable[[float], None]) -> None:
        """Give each new `value` to `put` (e.g. a state's setter): the slider's moves, the
        values typed in the box and those set from Python.  A value `put` refuses
        (ValueError: outside the owner's domain, from a script) is logged at debug level
        only (a client cannot fill the log) and the slider shows its last value again."""
        def give(event: param.parameterized.Event) -> None:
            try:
                put(event.new)
            except ValueError as err:
                log.debug("refused %.80r from the browser: %s", event.new, err)
                show_later(self, event.old)

        self.param.watch(give, "value")

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
        with held():  # (the models are Bokeh models: Bokeh's lock)
            if (start, end) != (self.start, self.end):
                self.param.update(start=start, end=end)
            self.model.value = v  # (nothing sent when it holds v: the browser's move)
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
        with held():
            self.model.update(start=self.start, end=self.end)

    @param.depends("disabled", watch=True)
    def _show_disabled(self) -> None:
        with held():
            self.model.disabled = self._entry.disabled = self.disabled
