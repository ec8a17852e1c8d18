"""Widgets for keyboard and screen-reader users (WAI-ARIA Authoring Practices).

`TabList`: the tabs pattern over a Panel `Tabs` (roles, `aria-selected`, arrows,
Home/End, Enter/Space, a visible focus ring); `RadioGroup`: a choice of one among a few
as the radio group pattern (`aria-checked`, arrows); `CardTitle` and `expandable_card`:
a card whose header says whether it is open (`aria-expanded`); `KeyShortcut`: a
documented page-level key that clicks a button; `LiveText`: a polite live region;
`Landmark`: a layout carrying an ARIA landmark role.  Each is Panel's public
`ReactiveHTML` (its scripts run under the page's Content-Security-Policy);
values from the browser are checked before use.
"""

from __future__ import annotations

import logging
from typing import ClassVar

import panel as pn
import param

from app.kit.style import FOCUS_RING, HIDE_TAB_HEADERS_CSS, VISUALLY_HIDDEN_CSS
from app.kit.texts import WrittenHTML
from app.kit.widgets import finite, show_later

log = logging.getLogger(__name__)

#: JavaScript of `TabList`: one button (role "tab") per title, built once; the selected
#: one `aria-selected` and the only one in the tab order (a roving tab index); the panel
#: named by the selected title.
_TABS_SHOW = """
if (list.children.length !== data.titles.length) {
  list.replaceChildren(...data.titles.map((title, i) => {
    const tab = document.createElement("button");
    tab.type = "button";
    tab.setAttribute("role", "tab");
    tab.dataset.index = i;
    tab.textContent = title;
    return tab;
  }));
}
list.setAttribute("aria-label", data.label);
[...list.children].forEach((tab, i) => {
  const on = i === data.value;
  tab.setAttribute("aria-selected", on ? "true" : "false");
  tab.tabIndex = on ? 0 : -1;
});
panel.setAttribute("aria-label", data.titles[data.value] || data.label);
"""

#: JavaScript of `TabList`: the arrows move the keyboard to the next / previous tab
#: (round), Home / End to the first / last; Enter and Space press the tab (a button's
#: own keys), which selects it (`_TABS_CLICK`).
_TABS_KEYDOWN = """
const tabs = [...list.children];
const i = tabs.indexOf(event.target);
if (i < 0) { return; }
const n = tabs.length;
const to = {ArrowRight: (i + 1) % n, ArrowLeft: (i - 1 + n) % n, Home: 0, End: n - 1};
if (event.key in to) {
  event.preventDefault();
  tabs[to[event.key]].focus();
}
"""

_TABS_CLICK = """
const tab = event.target.closest("[role=tab]");
if (tab != null) { data.value = Number(tab.dataset.index); }
"""


class TabList(pn.reactive.ReactiveHTML):
    """Tabs operable by keyboard (WAI-ARIA Authoring Practices' tabs pattern, manual
    activation): a `tablist` of `tab` buttons, `titles`, over a `tabpanel` holding
    `panel`; `value` is the selected tab's index.

    BokehJS's Tabs draws its titles as focusable <div>s that answer to the mouse only,
    without roles.  This list is buttons with the roles and `aria-selected`: the arrow
    keys move along it (Home / End: its ends), Enter or Space select the tab the
    keyboard is on, and only the selected tab is a Tab stop.  Built with Panel's public
    `ReactiveHTML`, as `LabelledSlider` is (the page's Content-Security-Policy).
    `for_tabs` puts one over a Panel `Tabs`, whose own titles it hides.
    """

    value = param.Number(default=0)
    titles = param.List(default=[], item_type=str)
    label = param.String(default="")
    panel = param.Parameter()

    _template = (
        '<div id="list" role="tablist" onkeydown="${script(\'keydown\')}" '
        'onclick="${script(\'click\')}"></div>'
        '<div id="panel" role="tabpanel">${panel}</div>')

    _scripts: ClassVar[dict[str, str]] = {
        "render": _TABS_SHOW,
        **dict.fromkeys(("value", "titles", "label"), _TABS_SHOW),
        "keydown": _TABS_KEYDOWN,
        "click": _TABS_CLICK,
    }

    #: Tabs drawn as tabs: the selected one white, with a coloured top edge and bold
    #: title, joined to the panel; the titles wrap on a narrow screen; a 3 px ring.
    CSS = """
[role=tablist] { display: flex; flex-wrap: wrap; gap: 4px; padding: 4px 4px 0;
                 border-bottom: 1px solid #8a8a8a; }
[role=tab] { font: inherit; color: #212529; background: #f1f3f5; cursor: pointer;
             border: 1px solid #8a8a8a; border-bottom: none; border-top: 3px solid #8a8a8a;
             border-radius: 4px 4px 0 0; padding: 0.25em 0.8em; min-height: 24px;
             margin-bottom: -1px; }
[role=tab]:hover { background: #e2e6ea; }
[role=tab][aria-selected=true] { background: white; font-weight: bold;
                                 border-top-color: #0072B2; }
""" + f"[role=tab]:focus-visible {{ {FOCUS_RING} }}\n"

    def __init__(self, **params) -> None:
        params["stylesheets"] = [self.CSS, *params.get("stylesheets", [])]
        super().__init__(**params)

    def valid(self, value: object) -> bool:
        """Whether `value` is the index of one of the tabs."""
        return finite(value) and value == int(value) and 0 <= value < len(self.titles)

    @classmethod
    def for_tabs(cls, tabs: pn.Tabs, titles: list[str], label: str,
                 **params) -> TabList:
        """A tab list of `titles` over Panel's `tabs` (whose titles are hidden: the
        list shows them), its `value` and `tabs.active` kept equal whichever changes.

        An index that names no tab (from a script: no tab sends it) changes nothing:
        the list shows the open tab again."""
        tabs.stylesheets = [*tabs.stylesheets, HIDE_TAB_HEADERS_CSS]
        tablist = cls(titles=list(titles), label=label, value=tabs.active, panel=tabs,
                      **params)

        def to_tabs(event: param.parameterized.Event) -> None:
            if tablist.valid(event.new):
                tabs.active = int(event.new)
            else:
                log.debug("refused tab %.80r from the browser", event.new)
                show_later(tablist, tabs.active)

        tablist.param.watch(to_tabs, "value")
        tabs.param.watch(lambda e: setattr(tablist, "value", e.new), "active")
        return tablist


#: JavaScript of `KeyShortcut`: the page's keydown events (wherever the keyboard is;
#: not in a text box) with `key` and Alt held count in `presses`.
_SHORTCUT_LISTEN = """
if (state.listening) { return; }
state.listening = true;
document.addEventListener("keydown", (event) => {
  if (!event.altKey || event.ctrlKey || event.metaKey
      || event.code !== "Key" + data.key.toUpperCase()) { return; }
  const target = event.composedPath()[0];
  if (target != null && (target.isContentEditable
      || ["INPUT", "TEXTAREA", "SELECT"].includes(target.tagName)
         && !["range", "checkbox", "radio", "button"].includes(target.type))) { return; }
  event.preventDefault();
  data.presses = data.presses + 1;
});
"""


class KeyShortcut(pn.reactive.ReactiveHTML):
    """A page-wide key: Alt + `key` (a letter; its physical key, so that macOS's Option
    letters count) pressed anywhere but in a text box adds one to `presses`.

    With a modifier, so that typing or a screen reader's single-letter keys never
    trigger it (WCAG 2.1.4).  Draws nothing."""

    key = param.String(default="k")
    presses = param.Integer(default=0)

    _template = '<div id="shortcut" hidden></div>'
    _scripts: ClassVar[dict[str, str]] = {"render": _SHORTCUT_LISTEN}

    def __init__(self, **params) -> None:
        params.setdefault("margin", 0)
        params.setdefault("width", 0)
        params.setdefault("height", 0)
        super().__init__(**params)


class LiveText(WrittenHTML):
    """Text a screen reader announces when it changes, politely (an `aria-live="polite"`
    status region, kept in the page while its `text`, shown as text, changes); out of
    sight.  `write(text=...)` changes the text."""

    text = param.String(default="", allow_refs=False)

    _template = '<div id="region" role="status" aria-live="polite" aria-atomic="true"></div>'
    _scripts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("render", "text"), "region.textContent = data.text;")  # (text, never markup)

    def __init__(self, **params) -> None:
        params["stylesheets"] = [VISUALLY_HIDDEN_CSS, *params.get("stylesheets", [])]
        params.setdefault("margin", 0)
        super().__init__(**params)


#: JavaScript of `Landmark`: the region's role and name.
_LANDMARK_SHOW = """
region.setAttribute("role", data.role);
if (data.label) { region.setAttribute("aria-label", data.label); }
else { region.removeAttribute("aria-label"); }
"""


class Landmark(pn.reactive.ReactiveHTML):
    """`object` inside an ARIA landmark of `role` ('main', 'banner', 'complementary',
    'region', ...) named `label`.  Panel's layouts carry no role (no property of Panel
    or Bokeh gives a layout one): a screen reader's list of regions comes from these."""

    object = param.Parameter()
    role = param.String(default="region")
    label = param.String(default="")

    _template = '<div id="region">${object}</div>'
    _scripts: ClassVar[dict[str, str]] = {
        "render": _LANDMARK_SHOW, "role": _LANDMARK_SHOW, "label": _LANDMARK_SHOW}

    CSS = "#region { width: 100%; }"

    def __init__(self, **params) -> None:
        params["stylesheets"] = [self.CSS, *params.get("stylesheets", [])]
        super().__init__(**params)


#: JavaScript of `CardTitle`: the expanded state of the header
#: button of the card holding it (the button the title is drawn in, in Panel's row).
_CARD_TITLE_SHOW = """
const mark = (frames) => {
  let button = view.el;  // (up through the layouts, and their shadow roots, around it)
  for (let i = 0; i < 8 && button != null && button.tagName !== "BUTTON"; i++) {
    button = button.parentElement ?? button.getRootNode().host ?? null;
  }
  if (button != null && button.tagName === "BUTTON") {
    button.setAttribute("aria-expanded", data.expanded ? "true" : "false");
  } else if (frames > 0) {  // (drawn before the card put it in its button)
    requestAnimationFrame(() => mark(frames - 1));
  }
};
mark(120);
"""


class CardTitle(pn.reactive.ReactiveHTML):
    """The title of a collapsible Panel `Card` (its `header`) that tells a screen reader
    whether the card is open (WAI-ARIA Authoring Practices' disclosure pattern): the
    card's header button, in which Panel draws this title, gets `aria-expanded` =
    `expanded`, written again whenever the card draws its header anew.

    Panel's `Card` draws its header as a `<button>` without `aria-expanded`, and no
    property of Panel gives it one; the title, drawn inside that button, is the one part
    of the card the page draws itself.  `expandable_card` keeps `expanded` equal to
    the card's `not collapsed`."""

    title = param.String(default="")
    expanded = param.Boolean(default=False)

    #: (the title as the template's text, not written by the script: a script naming
    #: the span would run, and warn, before the span is drawn)
    _template = '<span id="label">${title}</span>'
    _child_config: ClassVar[dict[str, str]] = {"title": "literal"}  # (the page's own text)
    _scripts: ClassVar[dict[str, str]] = dict.fromkeys(
        ("render", "after_layout", "expanded"), _CARD_TITLE_SHOW)

    #: As Panel's card title (`.card-title`: large and bold).
    CSS = "#label { font-size: 1.4em; font-weight: bold; }"

    def __init__(self, **params) -> None:
        params["stylesheets"] = [self.CSS, *params.get("stylesheets", [])]
        params.setdefault("margin", (5, 0))
        super().__init__(**params)


def expandable_card(*objects, title: str, collapsed: bool = True, **params) -> pn.Card:
    """A Panel `Card` of `objects` titled `title` by a `CardTitle`, so that its header
    button says whether it is open (`aria-expanded`), followed on every change of the
    card's `collapsed`; `params` go to the card."""
    header = CardTitle(title=title, expanded=not collapsed)
    card = pn.Card(*objects, title=title, header=header, collapsed=collapsed, **params)
    card.param.watch(lambda e: setattr(header, "expanded", not e.new), "collapsed")
    return card


#: JavaScript of `RadioGroup`: one button (role "radio") per option, built when the
#: options change; the chosen one `aria-checked` and the only one in the tab order.
_RADIO_SHOW = """
const options = Object.entries(data.options);
if (group.children.length !== options.length
    || options.some(([label], i) => group.children[i].textContent !== label)) {
  group.replaceChildren(...options.map(([label, value]) => {
    const radio = document.createElement("button");
    radio.type = "button";
    radio.setAttribute("role", "radio");
    radio.dataset.value = value;
    radio.textContent = label;
    return radio;
  }));
}
group.setAttribute("aria-label", data.label);
const chosen = [...group.children].findIndex((r) => r.dataset.value === data.value);
[...group.children].forEach((radio, i) => {
  radio.setAttribute("aria-checked", i === chosen ? "true" : "false");
  radio.tabIndex = i === Math.max(chosen, 0) ? 0 : -1;
});
"""

#: JavaScript of `RadioGroup`: the arrows move to the next / previous option (round) and
#: choose it; Space (a button's own key) or a click chooses the option it is on.
_RADIO_KEYDOWN = """
const radios = [...group.children];
const i = radios.indexOf(event.target);
if (i < 0) { return; }
const n = radios.length;
const step = {ArrowRight: 1, ArrowDown: 1, ArrowLeft: -1, ArrowUp: -1}[event.key];
if (step != null) {
  event.preventDefault();
  const next = radios[(i + step + n) % n];
  next.focus();
  data.value = next.dataset.value;
}
"""

_RADIO_CLICK = """
const radio = event.target.closest("[role=radio]");
if (radio != null) { data.value = radio.dataset.value; }
"""


class RadioGroup(pn.reactive.ReactiveHTML):
    """One of `options` ({label: value}) chosen, `value`, as a row of buttons in the
    WAI-ARIA Authoring Practices' radio group pattern: a `radiogroup` named `label` of
    `radio` buttons, the chosen one `aria-checked="true"`; the arrows move along the
    row and choose, and only the chosen button is a Tab stop.

    Panel's `RadioButtonGroup` (BokehJS's) draws plain buttons, the chosen one only
    coloured: a screen reader hears neither the group nor which button is pressed.
    A value the browser sends is a string; the state it is bound to checks it
    (`app.kit.widgets.sync`)."""

    value = param.String(default="")
    options = param.Dict(default={})
    label = param.String(default="")

    _template = ('<div id="group" onkeydown="${script(\'keydown\')}" '
                 'onclick="${script(\'click\')}" role="radiogroup"></div>')
    _scripts: ClassVar[dict[str, str]] = {
        **dict.fromkeys(("render", "value", "options", "label"), _RADIO_SHOW),
        "keydown": _RADIO_KEYDOWN,
        "click": _RADIO_CLICK,
    }

    #: As a button group: the buttons side by side, the chosen one filled (white on
    #: #0072B2, 5.1:1); a 3 px ring on the one the keyboard is on.
    CSS = """
#group { display: flex; width: 100%; }
[role=radio] { flex: 1; font: inherit; color: #212529; background: white; cursor: pointer;
               border: 1px solid #6c757d; padding: 0.3em 0.8em; min-height: 32px; }
[role=radio]:first-child { border-radius: 4px 0 0 4px; }
[role=radio]:last-child { border-radius: 0 4px 4px 0; }
[role=radio] + [role=radio] { border-left: none; }
[role=radio]:hover { background: #e2e6ea; }
[role=radio][aria-checked=true] { background: #0072B2; color: white; font-weight: bold; }
""" + f"[role=radio]:focus-visible {{ {FOCUS_RING} position: relative; z-index: 1; }}\n"

    def __init__(self, **params) -> None:
        params["stylesheets"] = [self.CSS, *params.get("stylesheets", [])]
        super().__init__(**params)
