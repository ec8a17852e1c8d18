"""The way a widget's value reaches a state, and the texts beside widgets.

`follow` and `sync` carry a widget's value into a parameter of a state (and back), a
value the parameter refuses changing nothing; `show_later` puts a widget back once the
browser's change of it has been handled.  `typed_value` reads a typed text, `shortened`
and `text_html` make a message safe to show; `LabelledCheckbox` is a check box named by
its label, for a screen reader.  The sliders are `app.kit.sliders`.
"""

from __future__ import annotations

import html
import logging
import math
import textwrap
from collections.abc import Callable
from functools import partial

import panel as pn
import param
from bokeh.model import Model
from bokeh.models import TextInput

from app.kit.batch import held
from app.kit.jobs import later

log = logging.getLogger(__name__)

#: Style of the message under a box (dark red on white: 7.7:1 contrast).
ERROR_STYLE = {"color": "#a4161a", "font-size": "0.9em", "margin-top": "0"}


def follow(widget: param.Parameterized, parameter: param.Parameter,
           setter: Callable[[str, object], None] | None = None) -> None:
    """Set `parameter` (of a Parameterized instance, e.g. `state.param.psi`) to each new
    `widget.value`: with `setter(name, value)` if given (e.g. `ExplorerState.set_input`,
    which sets what follows from the value in the same batch), else `setattr`.

    A widget value the parameter refuses (one no browser sends: NaN, or outside its
    bounds, from a script) changes nothing: the widget shows the parameter's value
    again, and the refusal is logged at debug level only (a client cannot fill the log).
    """
    owner, name = parameter.owner, parameter.name
    put = setter or partial(setattr, owner)

    def to_owner(event: param.parameterized.Event) -> None:
        try:
            put(name, event.new)
        except ValueError as err:
            log.debug("refused %s = %.80r from the browser: %s", name, event.new, err)
            show_later(widget, getattr(owner, name))

    widget.param.watch(to_owner, "value")


def sync(widget: param.Parameterized, parameter: param.Parameter,
         setter: Callable[[str, object], None] | None = None) -> None:
    """Keep `widget.value` and `parameter` equal, whichever of the two changes (the
    widget's values as `follow` takes them, with `setter` if given)."""
    follow(widget, parameter, setter)
    owner, name = parameter.owner, parameter.name
    owner.param.watch(lambda e: setattr(widget, "value", e.new), name)


def finite(value: object) -> bool:
    """Whether `value` is a real, finite number (what a slider of the page can send)."""
    return (isinstance(value, int | float) and not isinstance(value, bool)
            and math.isfinite(value))


def show_later(widget: param.Parameterized | Model, value: object) -> None:
    """Set `widget.value` once the browser's entry into it has been handled (Panel sends
    no change of a property back to the browser while handling the browser's change of
    it: `app.kit.jobs.later`)."""
    later(pn.state.curdoc, partial(held_set, widget, "value", value))


def held_set(obj: param.Parameterized | Model, name: str, value: object) -> None:
    """Set `obj.name` to `value` inside `held` (Panel's hold): a Bokeh model changed outside
    Panel's handling of a change (a next-tick callback, a watcher of another widget)
    must be, or Bokeh finds its document unlocked."""
    with held():
        setattr(obj, name, value)


def typed_value(box: pn.widgets.TextInput | TextInput, text: str, shown: str,
                parse: Callable[[str], float]) -> float | None:
    """What `text`, the new value of the text `box`, stands for, the box having shown
    `shown` (the text of the last good value): None when `text` is that text (the box was
    set from the server, or put back); else `parse(text)`.  When `parse` refuses the
    text (ValueError, raised on), the box shows `shown` again."""
    text = text.strip()
    if text == shown:
        return None
    try:
        return parse(text)
    except ValueError:
        show_later(box, shown)  # back to the last good value
        raise


#: A message longer than this (it quotes a long link or a file's line) is cut.
MESSAGE_CHARS = 400


def shortened(message: str) -> str:
    """`message` cut to MESSAGE_CHARS (blanks folded), for a message box."""
    return textwrap.shorten(message, MESSAGE_CHARS, placeholder=" …")


def text_html(text: str) -> str:
    """`text` as HTML that shows exactly that text (markup in it is not interpreted)."""
    return html.escape(text).replace("\n", "<br>")


class LabelledCheckbox(pn.viewable.Viewer):
    """A check box named by its label; `value` is True when it is ticked.

    Panel's `Checkbox` is BokehJS's, which puts its label in a <div> beside the box: a
    screen reader meets a check box without a name.  This one is BokehJS's one-option
    `CheckboxGroup`, whose box sits inside its <label>.
    """

    value = param.Boolean(default=False)
    disabled = param.Boolean(default=False)

    #: The label wraps (BokehJS keeps an option's label on one line): a long one stays
    #: inside a narrow column.
    CSS = "label { white-space: normal; }"

    def __init__(self, *, label: str, value: bool = False, **params) -> None:
        super().__init__(value=value)
        self.label = label
        params["stylesheets"] = [self.CSS, *params.get("stylesheets", [])]
        self._group = pn.widgets.CheckBoxGroup(options=[label], value=self._ticks(value),
                                               **params)
        self._group.param.watch(self._on_group, "value")

    @classmethod
    def from_param(cls, parameter: param.Parameter, *, label: str,
                   **params) -> LabelledCheckbox:
        """A check box kept equal to the boolean `parameter` of a Parameterized instance
        (e.g. `state.param.log_psi`), whichever of the two changes."""
        box = cls(label=label, value=getattr(parameter.owner, parameter.name), **params)
        sync(box, parameter)
        return box

    def __panel__(self) -> pn.widgets.CheckBoxGroup:
        return self._group

    def _ticks(self, value: bool) -> list[str]:
        return [self.label] if value else []

    def _on_group(self, event: param.parameterized.Event) -> None:
        self.value = self.label in event.new

    @param.depends("value", watch=True)
    def _show_value(self) -> None:
        self._group.value = self._ticks(self.value)  # (Panel sends only what changed)

    @param.depends("disabled", watch=True)
    def _show_disabled(self) -> None:
        self._group.disabled = self.disabled

