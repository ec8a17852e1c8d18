"""The page's keyboard: the keys it answers to (`KEYS`), the sidebar's card listing them
(`keyboard_card`) and the one shortcut of its own, Alt + `PLAY_KEY` (`play_key`).

The sliders are `app.kit.sliders.LabelledSlider`s (range inputs with Page Up / Down
added), the curve tabs an `app.kit.a11y.TabList`; text boxes, menus, check boxes and
buttons are the browser's own.
"""

from __future__ import annotations

import html
from dataclasses import dataclass

import panel as pn

from app.contact.view import ContactView
from app.kit.a11y import KeyShortcut


@dataclass(frozen=True)
class Keys:
    """A line of the keyboard card: `keys` (DOM key names, as `KeyboardEvent.key` or
    Playwright spell them) pressed on a `target` do `action`; `opposite`: the keys do
    opposite things ('a / b', the action says both), else they are alternatives
    ('a or b')."""

    target: str
    keys: tuple[str, ...]
    action: str
    opposite: bool = False


#: The key that plays or pauses, anywhere but in a text box, with Alt
#: (`app.kit.a11y.KeyShortcut`).
PLAY_KEY = "k"

#: The keys the page answers to (the sliders are `app.kit.sliders.LabelledSlider`s, range
#: inputs with Page Up / Down added; the curve tabs an `app.kit.a11y.TabList`; text
#: boxes, menus, check boxes and buttons are the browser's own).
KEYS = (
    Keys("Anywhere", ("Tab", "Shift+Tab"), "next / previous control", opposite=True),
    Keys("Anywhere", (f"Alt+{PLAY_KEY.upper()}",), "play or pause (not in a text box)"),
    Keys("Slider", ("ArrowLeft", "ArrowRight"), "one step down / up", opposite=True),
    Keys("Slider", ("ArrowDown", "ArrowUp"), "one step down / up", opposite=True),
    Keys("Slider", ("PageDown", "PageUp"), "five steps down / up", opposite=True),
    Keys("Slider", ("Home", "End"), "to the start / end of its range", opposite=True),
    Keys("Number box", ("Enter",), "apply the typed number"),
    Keys("Button", ("Space", "Enter"), "press it"),
    Keys("Check box", ("Space",), "tick or untick it"),
    Keys("Menu", ("ArrowDown", "ArrowUp"), "next / previous choice", opposite=True),
    Keys("Card title", ("Enter", "Space"), "open or close the card"),
    Keys("Curve tabs", ("ArrowLeft", "ArrowRight"), "previous / next tab", opposite=True),
    Keys("Curve tabs", ("Home", "End"), "first / last tab", opposite=True),
    Keys("Curve tabs", ("Enter", "Space"), "open the tab"),
)

#: How the keyboard card shows a key.
KEY_NAMES = {"ArrowLeft": "←", "ArrowRight": "→", "ArrowDown": "↓", "ArrowUp": "↑",
             "PageDown": "Page Down", "PageUp": "Page Up", "Shift+Tab": "Shift + Tab",
             f"Alt+{PLAY_KEY.upper()}": f"Alt + {PLAY_KEY.upper()}"}

#: The keyboard card's look: a group per target, keys drawn as keycaps.
KEYS_CSS = """
table { border-collapse: collapse; width: 100%; }
caption { text-align: left; padding-bottom: 0.3em; }
th, td { text-align: left; vertical-align: top; padding: 0.15em 0.3em; }
tbody th[scope="rowgroup"] { padding-top: 0.5em; border-bottom: 1px solid #dddddd; }
tbody th[scope="row"] { font-weight: normal; white-space: nowrap; }
kbd { font: inherit; border: 1px solid #adb5bd; border-radius: 3px; padding: 0 0.25em;
      background: #f8f9fa; }
"""


def keys_html(keys: tuple[Keys, ...] = KEYS) -> str:
    """The keyboard card's table: a group of rows per target, the keys as <kbd>."""
    groups: dict[str, list[Keys]] = {}
    for k in keys:
        groups.setdefault(k.target, []).append(k)
    body = []
    for target, rows in groups.items():
        lines = [f'<tr><th scope="rowgroup" colspan="2">{html.escape(target)}</th></tr>']
        for k in rows:
            names = (f"<kbd>{html.escape(KEY_NAMES.get(n, n))}</kbd>" for n in k.keys)
            joined = (" / " if k.opposite else " or ").join(names)
            lines.append(f'<tr><th scope="row">{joined}</th>'
                         f"<td>{html.escape(k.action)}</td></tr>")
        body.append(f"<tbody>{''.join(lines)}</tbody>")
    return ("<table><caption>Keys of this page, on the control the keyboard is on "
            f"(the one with a ring)</caption>{''.join(body)}</table>")


def keyboard_card() -> pn.Card:
    """The sidebar's collapsed card listing the keys (`KEYS`)."""
    return pn.Card(pn.pane.HTML(keys_html(), stylesheets=[KEYS_CSS], disable_math=True,
                                sizing_mode="stretch_width"),
                   title="Keyboard", collapsed=True, sizing_mode="stretch_width")


def play_key(contact: ContactView) -> KeyShortcut:
    """Alt + `PLAY_KEY` anywhere on the page (not in a text box) does what Play / Pause
    does."""
    key = KeyShortcut(key=PLAY_KEY)
    key.param.watch(lambda _: setattr(contact.state, "playing", not contact.state.playing),
                    "presses")
    return key
