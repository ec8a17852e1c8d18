"""The student view (`/main?view=student`): the contact for a class, in plain words.

The two spheres with Play, Step, the speed and the time; the traction profile, the
contact disc and T(tau), titled in plain words; the friction slider; a glossary of
every symbol on the page, each term explained when the pointer or the keyboard is on it
(`app.contact.glossary`); three guided activities (`app.contact.activities`), each a
contact, a question and a check of the answer typed; and a high-contrast setting (black
type on white, the plots' text black).  The expert cards (Methods, Motor, DEM, Fig. 6
in full), the formulas, the presets and the physical inputs are not on this page; the
header's button leads to the full page, the parameters kept.  The same scenes and
controls as the full page (`app.page.layout.page`): this module arranges them.
"""

from __future__ import annotations

import html
from collections.abc import Mapping, Sequence

import panel as pn
import param
from bokeh.models import Button as BokehButton
from bokeh.models import CustomJS

from app.contact.activities import ACTIVITIES
from app.contact.glossary import GLOSSARY
from app.contact.view import ContactView
from app.kit.a11y import Landmark
from app.kit.style import FOCUS_RING
from app.kit.widgets import LabelledCheckbox
from app.page import layout
from app.page.presentation import FULL_PAGE_JS
from app.page.projector import BOX_CSS

#: The name of the view in the URL (`view=student`).
VIEW = "student"

#: The plots' titles in plain words, by scene.
TITLES = {"traction": "How hard the surfaces rub, across the contact",
          "disc": "The patch from above",
          "force": "The friction force T over one contact"}

#: The glossary's terms: dotted, and their explanation shown under them while the
#: pointer or the keyboard is on them.
GLOSSARY_CSS = """
.terms { display: flex; flex-wrap: wrap; gap: 0.4em 1.2em; font-size: 17px; }
.term { position: relative; border-bottom: 2px dotted #1A5FB4; cursor: help; }
.term:focus-visible { outline: 3px solid #1A5FB4; outline-offset: 2px; }
.tip { display: none; position: absolute; left: 0; top: 1.6em; z-index: 10; width: 22em;
       padding: 0.4em 0.6em; background: #fff; color: #000; border: 2px solid #000; }
.term:hover .tip, .term:focus .tip { display: block; }
"""

#: A Bokeh button (the page's CSS for Panel's components does not reach it) with the
#: keyboard's ring.
BUTTON_CSS = f".bk-btn:focus-visible {{ {FOCUS_RING} }}"

#: The high-contrast setting's type (inherited into every component: black on white).
CONTRAST_CSS = ":host(.high-contrast) { color: #000; background: #fff; }"


def glossary() -> pn.pane.HTML:
    """Every symbol of the page, each explained on hover or focus (a Tab stop each)."""
    terms = "".join(f'<span class="term" tabindex="0">{html.escape(k)}<span class="tip" '
                    f'role="tooltip">{html.escape(v)}</span></span>'
                    for k, v in GLOSSARY.items())
    return pn.pane.HTML(f'<div class="terms">{terms}</div>', stylesheets=[GLOSSARY_CSS],
                        sizing_mode="stretch_width", name="glossary")


class ActivityCard(param.Parameterized):
    """The guided activities: choose one (its contact is loaded), read its question,
    type an answer and check it."""

    feedback = param.String(default="", doc="what the last check said")

    def __init__(self, contact: ContactView) -> None:
        super().__init__()
        self.contact = contact
        options = {"(choose an activity)": "", **{a.title: k for k, a in ACTIVITIES.items()}}
        self.choice = pn.widgets.Select(label="Activity", options=options, value="",
                                        sizing_mode="stretch_width")
        self.question = pn.pane.HTML("", sizing_mode="stretch_width", name="question")
        self.answer = pn.widgets.TextInput(label="Your answer", placeholder="e.g. 2.3",
                                           sizing_mode="stretch_width", disabled=True)
        self.check_button = pn.widgets.Button(label="Check", color="primary", width=100,
                                              disabled=True)
        self.result = pn.pane.HTML("", sizing_mode="stretch_width", name="feedback")
        self.choice.param.watch(lambda e: self.load(e.new), "value")
        self.check_button.on_click(lambda _: self.check())
        self.answer.param.watch(lambda _: self.check(), "value")  # (Enter in the box)

    def load(self, key: str) -> None:
        """Load activity `key` (its contact on screen, its question); '' none."""
        activity = ACTIVITIES.get(key)
        self.answer.param.update(value="", disabled=activity is None)
        self.check_button.disabled = activity is None
        self.feedback = ""
        if activity is None:
            self.question.object = ""
            return
        self.contact.state.param.update(**activity.values, playing=False)
        self.question.object = f"<p>{html.escape(activity.question)}</p>"

    def check(self) -> None:
        """Check the answer typed against the activity's (from core)."""
        activity = ACTIVITIES.get(self.choice.value)
        if activity is None or not self.answer.value.strip():
            return
        ok, self.feedback = activity.check(self.answer.value)
        color = "#00664D" if ok else "#a4161a"  # (7.3:1 and 7.7:1 on white)
        self.result.object = (f'<p style="color: {color}; font-weight: bold;">'
                              f"{html.escape(self.feedback)}</p>")

    def view(self) -> pn.Card:
        return pn.Card(self.choice, self.question, self.answer, self.check_button,
                       self.result, title="Activities", collapsible=False,
                       sizing_mode="stretch_width", margin=6)


#: The student view: this page's link with `view=student` (the parameters kept).
STUDENT_PAGE_JS = """
const q = new URLSearchParams(window.location.search);
q.set("view", "student");
window.location.search = q.toString();
"""


def link() -> pn.pane.Bokeh:
    """The full page's way here: a button that opens this view, the contact kept."""
    button = BokehButton(label="Student view: plain words, activities", width=310,
                         stylesheets=[BUTTON_CSS])
    button.js_on_event("button_click", CustomJS(code=STUDENT_PAGE_JS))
    return pn.pane.Bokeh(button, margin=(5, 10))


def header(contrast: LabelledCheckbox) -> Landmark:
    """The banner: the title, the high-contrast box, the way to the full page."""
    full = BokehButton(label="All scenes and controls (expert)", width=280,
                       stylesheets=[BUTTON_CSS])
    full.js_on_event("button_click", CustomJS(code=FULL_PAGE_JS))
    return Landmark(object=pn.FlexBox(layout.heading(), contrast, pn.pane.Bokeh(full),
                                      align_items="center", sizing_mode="stretch_width",
                                      styles={"background": layout.HEADER_STYLE["background"],
                                              "color": "white"}),
                    role="banner", margin=0, sizing_mode="stretch_width")


def student(contact: ContactView, message: pn.viewable.Viewable,
            descriptions: Mapping[str, pn.viewable.Viewable] | None = None,
            announcer: pn.viewable.Viewable | None = None,
            unseen: Sequence[pn.viewable.Viewable] = ()) -> pn.Column:
    """The student page of `contact`'s scenes; `message`, `descriptions`, `announcer` and
    `unseen` as for `app.page.layout.page`."""
    ui = contact.controls
    contact.tabs.active = 0  # T(tau): the one curve this page shows
    for name, title in TITLES.items():
        getattr(contact, name).figure.title.text = title
    activities = ActivityCard(contact)
    contrast = LabelledCheckbox(label="High contrast", value=False,
                                stylesheets=[BOX_CSS])  # (white on the header's blue)
    descriptions = descriptions or {}
    animation = layout.card(
        *layout.described(pn.pane.Bokeh(contact.spheres.figure, sizing_mode="stretch_width"),
                          "spheres", descriptions),
        pn.Row(ui.play_button, ui.step_button), ui.tau_slider, ui.speed_slider,
        title="The two spheres", flex="0 0 440px")
    plots = pn.Column(
        *layout.described(pn.pane.Bokeh(contact.traction.figure, sizing_mode="stretch_width"),
                          "traction", descriptions),
        *layout.described(pn.pane.Bokeh(contact.disc.figure), "disc", descriptions),
        pn.pane.Bokeh(contact.force.figure, sizing_mode="stretch_width"),
        sizing_mode="stretch_width", styles={"flex": "1 1 520px", "min-width": "0"})
    controls = Landmark(object=pn.Column(activities.view(), ui.mu_slider,
                                         pn.pane.HTML("<h2>The symbols</h2>"), glossary(),
                                         sizing_mode="stretch_width"),
                        role="complementary", label="Activities and symbols",
                        styles={"flex": "0 0 340px"})
    hidden = [*([announcer] if announcer is not None else []), *unseen]
    main = Landmark(object=pn.FlexBox(animation, plots, sizing_mode="stretch_width"),
                    role="main", styles={"flex": "1 1 900px", "min-width": "0"})
    page = pn.Column(header(contrast), message, *hidden,
                     pn.FlexBox(controls, main, sizing_mode="stretch_width"),
                     sizing_mode="stretch_width", margin=0, stylesheets=[CONTRAST_CSS])

    def set_contrast(event: param.parameterized.Event) -> None:
        classes = [c for c in page.css_classes if c != "high-contrast"]
        page.css_classes = [*classes, "high-contrast"] if event.new else classes
        for scene in (contact.spheres, contact.traction, contact.disc, contact.force):
            fig = scene.figure
            fig.title.text_color = "#000000" if event.new else "#444444"
            for axis in (*fig.xaxis, *fig.yaxis):
                axis.axis_label_text_color = axis.major_label_text_color = (
                    "#000000" if event.new else "#444444")

    contrast.param.watch(set_contrast, "value")
    layout.use_css()
    return page
