"""Play / Pause: one button the keyboard stays on, reporting the frame shown at a press.

BokehJS draws a new <button> whenever a Button's label or colour changes, so the focused
Play button was replaced by the Pause button under the keyboard (focus fell to the page's
body, and Space then scrolled the page).  This one is the browser's own <button>, built
once with Panel's public `ReactiveHTML` (as `app.kit.sliders.LabelledSlider` is): its
label and colour change in place, and the keyboard stays on it after Enter, Space or a
click.

A press also reports the tau (rad) of the frame the browser's player shows at that
moment (`app/contact/player.js` keeps it), so that a pause lands on that very frame;
`app.contact.animation.Animation.press` checks the report as any value from a browser.
"""

from __future__ import annotations

from typing import ClassVar

import panel as pn
import param

#: The button's label when stopped and while playing.
PLAY_LABEL, PAUSE_LABEL = "▶ Play", "‖ Pause"

#: JavaScript: the label and colour of the state the server holds.
_SHOW = """
button.textContent = data.label;
button.classList.toggle("playing", data.playing);
"""

#: JavaScript: a press, with the tau of the frame the player shows (null when stopped).
_PRESS = """
const player = window.__zharii_player;
data.frame_tau = player != null && player.shown != null ? player.shown : null;
data.clicks = data.clicks + 1;
"""


class PlayButton(pn.reactive.ReactiveHTML):
    """Play / Pause: `label` and colour follow `playing` (`show`); each press adds one to
    `clicks` after setting `frame_tau` to the tau (rad) of the frame the browser's player
    shows, None when it is stopped (a value from the browser: check it before use)."""

    label = param.String(default=PLAY_LABEL)
    playing = param.Boolean(default=False)
    clicks = param.Integer(default=0)
    frame_tau = param.Parameter(default=None)

    _template = '<button type="button" id="button" onclick="${script(\'press\')}"></button>'

    _scripts: ClassVar[dict[str, str]] = {
        **dict.fromkeys(("render", "label", "playing"), _SHOW),
        "press": _PRESS,
    }

    #: Bokeh's button look in the page's colours (`app.page.layout.CSS`: Play's green
    #: 5.5:1 and Pause's orange 5.3:1 under white text), 24 px high at least; the focus
    #: ring is the page's.
    CSS = """
button { width: 100%; min-height: 24px; padding: 6px 12px; cursor: pointer;
         font: inherit; font-size: var(--bokeh-font-size, 17px); white-space: nowrap;
         color: white; border-radius: 4px; border: 1px solid var(--success-border, #00664D);
         background-color: var(--success, #00785A); }
button:hover { background-color: var(--success-hover, #006A4F);
               border-color: var(--success-hover-border, #005A43); }
button:active { background-color: var(--success-active, #005C44);
                border-color: var(--success-active-border, #004D39); }
button.playing { background-color: var(--warning, #A85400);
                 border-color: var(--warning-border, #8F4700); }
button.playing:hover { background-color: var(--warning-hover, #944A00);
                       border-color: var(--warning-hover-border, #7F4000); }
button.playing:active { background-color: var(--warning-active, #7F4000);
                        border-color: var(--warning-active-border, #6B3600); }
"""

    def __init__(self, **params) -> None:
        params["stylesheets"] = [self.CSS, *params.get("stylesheets", [])]
        params.setdefault("margin", (5, 10))
        super().__init__(**params)

    def show(self, playing: bool) -> None:
        """The label and colour of `playing`."""
        self.param.update(playing=playing, label=PAUSE_LABEL if playing else PLAY_LABEL)
