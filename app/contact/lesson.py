"""A lesson that works without a server: the current contact as one HTML file.

`lesson_html(state)` writes a standalone Bokeh page (BokehJS inline, no request to any
network) of the contact `state` holds: the two spheres, the traction profile and its
disc, T(tau) and the impulse curve, animated over the contact by the explorer's own
player (`app.contact.player`, its frames computed here by the scenes, from `core`, as
when Play is pressed in the explorer), with Play / Pause, Step and a speed menu
(`lesson.js`); then Fig. 6's six profiles, the note of the preset on screen and the
glossary of the symbols (`app.contact.glossary`).  A teacher puts it on a USB stick or a
learning platform and opens it from a file in any browser.

The file holds the frames of one contact (about 0.4 MB) beside BokehJS (about 2 MB);
`MAX_BYTES` bounds it.
"""

from __future__ import annotations

import html
from pathlib import Path

from bokeh.embed import file_html
from bokeh.layouts import column, row
from bokeh.models import Button, CustomJS, Div, Select
from bokeh.resources import Resources

from app.contact.animation import CONTACT_SECONDS
from app.contact.glossary import GLOSSARY
from app.contact.multiples import SmallMultiples
from app.contact.notes import NOTES
from app.contact.player import frame_taus
from app.contact.state import PRESETS, ExplorerState
from app.contact.view import ContactView

#: The script of the lesson's buttons (the body of a `CustomJS`).
_LESSON_JS = Path(__file__).with_name("lesson.js").read_text()

#: The largest lesson file (bytes): a learning platform's usual upload limit.
MAX_BYTES = 5 * 2**20

#: The speeds offered (contacts per 4 s, as the explorer's Speed).
SPEEDS = ("0.25", "0.5", "1", "2")

#: The file's style: a readable column; its texts in the explorer's type (a Div's own
#: stylesheet: BokehJS draws it in a shadow root the page's style does not reach).
CSS = "body { font-family: sans-serif; max-width: 1400px; margin: auto; padding: 0 1em; }"
TEXT_CSS = (":host { font-size: 17px; } dt { font-weight: bold; } "
            "dd { margin: 0 0 0.4em 1.5em; }")


def describe(state: ExplorerState) -> str:
    """The contact in words, for the file's heading: its psi, tau0, mu, nu and preset."""
    preset = PRESETS.get(state.preset)
    named = f" ({preset.label})" if preset else ""
    return (f"ψ = {state.psi:.6g}, τ₀ = {state.tau0:.4g} rad, μ = {state.mu:.3g}, "
            f"ν = {state.nu:.3g}{named}")


def _texts(state: ExplorerState) -> Div:
    """The preset's note (if the contact is a preset's) and the glossary, as HTML."""
    note = NOTES.get(state.preset, "")
    terms = "".join(f"<dt>{html.escape(k)}</dt><dd>{html.escape(v)}</dd>"
                    for k, v in GLOSSARY.items())
    return Div(text=(f"<p>{html.escape(note)}</p>" if note else "")
               + f"<h2>The symbols</h2><dl>{terms}</dl>", sizing_mode="stretch_width",
               stylesheets=[TEXT_CSS])


def lesson_layout(state: ExplorerState):
    """The lesson's Bokeh layout for the contact of `state` (which it leaves alone)."""
    values = {k: v for k, v in state.param.values().items() if k != "name"}
    view = ContactView(ExplorerState(**{**values, "playing": False}))
    view.catch_up(view.tabbed)  # (the explorer computes a closed tab when opened)
    c, tau = view.state.current, view.state.tau
    view.player.play(c, 0.0, 1.0, CONTACT_SECONDS)  # the frames, from core
    first = int(abs(frame_taus(c) - tau).argmin())
    play = Button(label="▶ Play", button_type="success", width=110)
    step = Button(label="Step", width=90)
    speed = Select(title="Speed", options=list(SPEEDS), value="1", width=100)
    for widget, action in ((play, "play"), (step, "step"), (speed, "speed")):
        callback = CustomJS(args={"frames": view.player.frames, "play": play, "step": step,
                                  "speed": speed, "action": action, "first": first},
                            code=_LESSON_JS)
        if widget is speed:
            speed.js_on_change("value", callback)
        else:
            widget.js_on_event("button_click", callback)
    heading = Div(text=f"<h1>Two elastic spheres in intermittent frictional contact</h1>"
                       f"<p>Zharii (1996), the exact solution: {html.escape(describe(state))}."
                       " Play runs through one contact; Step moves one frame.</p>",
                  sizing_mode="stretch_width", stylesheets=[TEXT_CSS])
    view.spheres.figure.sizing_mode = "fixed"  # (its scales equal: its own width, height)
    plots = column(view.traction.figure, view.disc.figure, view.force.figure,
                   view.impulse.figure, sizing_mode="stretch_width")
    gallery = Div(text="<h2>Fig. 6 in full: the six traction profiles (ψ = 2.414, "
                       "τ₀ = π/6)</h2>", sizing_mode="stretch_width")
    return column(heading, row(play, step, speed),
                  row(view.spheres.figure, plots, sizing_mode="stretch_width"),
                  gallery, SmallMultiples().figure, _texts(state),
                  sizing_mode="stretch_width")


class BokehJSInline(Resources):
    """BokehJS inline and no file beside it: Bokeh's inline resources also name every
    loaded extension's own scripts (Panel's, as relative URLs that a file opened from a
    disk cannot load), which the lesson's plain Bokeh models do not use."""

    def __init__(self, components: list[str] | None = None) -> None:
        super().__init__(mode="inline", components=components)

    def clone(self, *, components: list[str] | None = None) -> BokehJSInline:
        """(Bokeh clones the resources with the components a document needs.)"""
        return BokehJSInline(components if components is not None else list(self.components))

    @property
    def js_files(self) -> list[str]:
        return []

    @property
    def css_files(self) -> list[str]:
        return []


def file_name(state: ExplorerState) -> str:
    """The lesson file's name, after its contact: 'zharii_lesson_psi2.414_tau00.5236.html'."""
    return f"zharii_lesson_psi{state.psi:.4g}_tau0{state.tau0:.4g}.html"


def lesson_html(state: ExplorerState) -> str:
    """The lesson file's text: `lesson_layout` with BokehJS inline (no network)."""
    return file_html(lesson_layout(state), resources=BokehJSInline(),
                     title=f"Zharii contact lesson: {describe(state)}",
                     template_variables={}).replace("</head>", f"<style>{CSS}</style></head>",
                                                     1)
