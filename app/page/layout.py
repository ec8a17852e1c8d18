"""The page: the explorer's controls in the sidebar, beside them the two spheres with
the animation's controls (Play, Step, the time, the speed), then the other scenes in
cards in the main area.

Sizes and type are for a projector (17 px base, never below 16 px); on a phone (at most
`PHONE_WIDTH` px wide) everything stacks in one column, the spheres and Play first (the
first screen), then the controls, then the other scenes; on a touch screen a swipe over
a plot scrolls the page (`app.kit.touch.PlotGestures`).  Every control shows a ring when
the keyboard is on it, and the sidebar's "Keyboard" card lists the keys the page
answers to.  For a screen reader the page has landmarks (banner, the sidebar a
complementary region, the animation a region, main), each plot a name and a description
that follows the state (`app.page.describe.descriptions`), a polite live region
announcing a change of phase, and the curve tabs are a keyboard-operable tab list
(`app.kit.a11y.TabList`).
"""

from __future__ import annotations

import html
from collections.abc import Mapping, Sequence

import panel as pn
from bokeh.models import Column as BokehColumn
from bokeh.models import CustomJS

from app.contact.phases import STYLES
from app.contact.state import PRESETS
from app.contact.view import TAB_TITLES, ContactView
from app.kit.a11y import Landmark, TabList
from app.kit.style import FOCUS_RING
from app.kit.touch import PlotGestures
from app.page.keyboard import keyboard_card, play_key
from core import Phase

#: Colour key of the contact disc (the figure has no legend, see DiscScene).
DISC_KEY = " ".join(
    f'<span style="color:{STYLES[p].color}; font-size: 1.3em">●</span> {name}'
    for p, name in ((Phase.FULL_STICK, "stick"), (Phase.SLIP, "slip"),
                    (Phase.COUNTER_SLIP, "counter-slip")))


#: The widest screen (CSS px) laid out as a phone's: type at 16 px, one column.
PHONE_WIDTH = 700

#: The page's CSS, in the page and in every Panel component's shadow root
#: (`pn.config.raw_css`):
#:
#: * large type for a projector, 16 px on a phone (the least for a control's text);
#:   text boxes and menus take it too (a browser gives them 13.3 px of their own);
#: * a 3 px ring, 2 px outside the control the keyboard is on (`:focus-visible`), clear
#:   of a check box's label;
#: * Bokeh's button colours darkened for white text at 4.5:1 at least (WCAG AA):
#:   Play's green (success) 5.5:1, Pause's orange (warning) 5.3:1.
CSS = f"""
:root {{ --bokeh-font-size: 17px; }}
html {{ font-size: 17px; }}
@media (max-width: {PHONE_WIDTH}px) {{
  :root {{ --bokeh-font-size: 16px; }} html {{ font-size: 16px; }}
}}
input, select, textarea {{ font-size: inherit; }}
:host :focus-visible {{ {FOCUS_RING} }}
input[type="checkbox"] + * {{ margin-left: 0.5em; }}
:host {{
  --success: #00785A; --success-border: #00664D; --success-hover: #006A4F;
  --success-hover-border: #005A43; --success-active: #005C44; --success-active-border: #004D39;
  --warning: #A85400; --warning-border: #8F4700; --warning-hover: #944A00;
  --warning-hover-border: #7F4000; --warning-active: #7F4000; --warning-active-border: #6B3600;
}}
"""


def card(*objs, title: str, flex: str = "1 1 520px") -> pn.Card:
    """A fixed card of the main area, growing by `flex` (CSS) in its row."""
    return pn.Card(*objs, title=title, collapsible=False, margin=6,
                   styles={"flex": flex, "min-width": "0"})


#: The page's title (browser tab and header).
TITLE = "Zharii (1996): two elastic spheres in intermittent frictional contact"

#: The header bar (the page's one <h1>).
HEADER_STYLE = {"background": "#0072B2", "color": "white", "padding": "0.4em 1em",
                "font-size": "1.3em", "font-weight": "bold"}
#: The <h1> in the header bar, in the bar's type (smaller on a phone: two lines at 390 px).
HEADING_CSS = ("h1 { font-size: inherit; font-weight: inherit; margin: 0; }"
               f" @media (max-width: {PHONE_WIDTH}px) {{ h1 {{ font-size: 0.8em; }} }}")

#: The name of the region holding the two spheres and the animation's controls.
ANIMATION_LABEL = "Animation"

#: On a phone the animation (the spheres, Play and the time) comes first, above the
#: controls: the first screen shows them; the other scenes follow the controls.
PHONE_ORDER_CSS = f"@media (max-width: {PHONE_WIDTH}px) {{ .animation {{ order: -1; }} }}"

#: What a phone's first screen holds besides the spheres' plot (CSS px): the header (two
#: lines), the card's title, and the row of Play and Step under the plot.
PHONE_SPHERES_RIM = 175
#: What a wider screen's first screen holds besides the spheres' plot (CSS px): the
#: header, the card's title and margins, and the row of Play and Step under the plot.
SPHERES_RIM = 190
#: The spheres' card's width less its plot's (CSS px: the card's borders and padding).
SPHERES_CARD_RIM = 24
#: The least width of the animation's region on a screen wider than a phone's (CSS px:
#: its controls' labels on one line).
ANIMATION_LEAST = 340


def phone_fit_css(fig) -> str:
    """A stylesheet for a column holding `fig` (a plot scaled to its width, at the aspect
    of its `width` and `height`): no wider than lets the plot and the row of Play under
    it fit one screen's height (`100svh`: `PHONE_SPHERES_RIM` px of it on a phone,
    `SPHERES_RIM` px on a wider screen), centred."""
    aspect = fig.width / fig.height
    return (f":host {{ width: 100%; max-width: calc((100svh - {SPHERES_RIM}px) * "
            f"{aspect:.4f}); margin-inline: auto; }}"
            f"@media (max-width: {PHONE_WIDTH}px) {{ :host {{ width: 100%; max-width: "
            f"calc((100svh - {PHONE_SPHERES_RIM}px) * {aspect:.4f}); margin-inline: auto; }} }}")


def animation_width_css(fig) -> str:
    """A stylesheet for the animation's region: on a screen wider than a phone's no wider
    than its plot (`phone_fit_css`) and the card's rim, but `ANIMATION_LEAST` px, so that
    the other scenes take the rest of the first screen's width."""
    aspect = fig.width / fig.height
    return (f"@media (min-width: {PHONE_WIDTH + 0.02}px) {{ :host {{ max-width: max("
            f"{ANIMATION_LEAST}px, calc((100svh - {SPHERES_RIM}px) * {aspect:.4f} + "
            f"{SPHERES_CARD_RIM}px)); }} }}")


#: JavaScript (a `CustomJS` run when a plot of the page is first laid out; `titles`: the
#: titles of each preset's plots, by the preset's name in the menu, the option's value):
#: when the user picks a preset in a menu (a select's `input` event, which crosses the
#: shadow roots; the server's own changes of the menu, Reset or a link, fire none), its
#: plots are scrolled into view once they are drawn and have stayed in place for three
#: frames (the server's answer may open their tab: up to 5 s), the least way that shows
#: them whole, or their top (and the tab titles above it) when they are taller than the
#: window.
SCROLL_JS = """
if (window.__zharii_scrolls) { return; }
window.__zharii_scrolls = true;
const boxes = (wanted) => {
  const found = [];
  const walk = (view) => {
    const m = view.model;
    if (m != null && m.type === "Figure" && m.title != null && wanted.includes(m.title.text)) {
      const r = view.el.getBoundingClientRect();
      if (r.width > 0 && r.height > 0) { found.push(r); }
    }
    for (const child of view.children()) { walk(child); }
  };
  for (const root of Object.values(Bokeh.index)) { walk(root); }
  return found;
};
const follow = (key, since) => {
  let last = null, still = 0;
  const step = () => {
    if (Date.now() - since > 5000) { return; }
    const found = boxes(titles[key]);
    const box = found.length === 0 ? null : [Math.min(...found.map((r) => r.top)),
                                              Math.max(...found.map((r) => r.bottom))];
    still = box != null && last != null && box[0] === last[0] && box[1] === last[1]
      ? still + 1 : 0;
    last = box;
    if (still < 3) { requestAnimationFrame(step); return; }
    const [top, bottom] = box, room = 70;  // (the card's title or the tabs above)
    if (top >= 0 && bottom <= innerHeight) { return; }
    const by = bottom - top + room > innerHeight || top < 0 ? top - room
      : bottom - innerHeight + 8;
    window.scrollBy({top: by, behavior: "instant"});
  };
  requestAnimationFrame(step);
};
document.addEventListener("input", (e) => {
  const el = e.composedPath()[0];
  if (el != null && el.tagName === "SELECT" && el.value in titles) {
    follow(el.value, Date.now());
  }
}, {capture: true});
"""


def preset_titles(contact: ContactView) -> dict[str, list[str]]:
    """The titles of each preset's plots on the full page, by its name in the menu
    (`Preset.label`): the traction profile (Fig. 6), or the plots of the curve tab the
    preset opens (`Preset.tab`)."""
    scenes = {scene.name: scene for scene in contact.tabbed}
    out = {}
    for key, preset in PRESETS.items():
        if key.startswith("fig6"):
            figs = [contact.traction.figure]
        else:
            fig = scenes[preset.tab].figure
            figs = list(fig.children) if isinstance(fig, BokehColumn) else [fig]
        out[preset.label] = [f.title.text for f in figs]
    return out


def scroll_to_presets(contact: ContactView) -> None:
    """Bring a preset's plots into view when the user picks it in the menu
    (`SCROLL_JS`, started by the traction profile's first layout)."""
    contact.traction.figure.js_on_change("inner_width", CustomJS(
        code=SCROLL_JS, args={"titles": preset_titles(contact)}))


def within_width(obj: pn.viewable.Viewable) -> pn.Column:
    """`obj` in a column as wide as its place that scrolls sideways whatever of `obj` is
    wider (a card of fixed-width plots or controls on a phone), so that the page never
    does."""
    return pn.Column(obj, sizing_mode="stretch_width",
                     styles={"overflow-x": "auto", "min-width": "0"})


def heading() -> pn.pane.HTML:
    """The page's one <h1>, `TITLE`, in the header bar's type."""
    return pn.pane.HTML(f"<h1>{html.escape(TITLE)}</h1>", styles=HEADER_STYLE,
                        stylesheets=[HEADING_CSS], sizing_mode="stretch_width", margin=0)


def use_css() -> None:
    """Put `CSS` in the page and every component's shadow root (once per process)."""
    if CSS not in pn.config.raw_css:
        pn.config.raw_css.append(CSS)


#: <meta> tags of the page (Bokeh's page template reads them from the document).
META = {"viewport": "width=device-width, initial-scale=1",
        "description": "Interactive exact solution of two elastic spheres in intermittent "
                       "oblique frictional contact (O. Yu. Zharii, 1996)"}


def curve_tabs(contact: ContactView) -> TabList:
    """The contact's curve tabs under a keyboard-operable tab list (`TabList`)."""
    return TabList.for_tabs(contact.tabs, list(TAB_TITLES), label="Curves over the contact",
                            sizing_mode="stretch_width")


def described(pane: pn.viewable.Viewable, key: str,
              descriptions: Mapping[str, pn.viewable.Viewable]) -> list:
    """`pane` and, when there is one, the description `key` of its plot."""
    return [pane, descriptions[key]] if key in descriptions else [pane]


def page(contact: ContactView, message: pn.viewable.Viewable,
         cards: list[pn.viewable.Viewable],
         descriptions: Mapping[str, pn.viewable.Viewable] | None = None,
         announcer: pn.viewable.Viewable | None = None,
         unseen: Sequence[pn.viewable.Viewable] = (),
         teaching: Sequence[pn.viewable.Viewable] = ()) -> pn.Column:
    """The explorer's page: a header, the controls in a sidebar, the two spheres with the
    animation's controls beside it, the other scenes beside or below them (a plain Panel
    layout: a template's header, modal and theming tripled the server's work per page
    load); on a phone the spheres and Play come first, the controls below.  `contact`
    gives the scenes and controls, `message` is the page's banner, `cards` the cards
    below the scenes (Fig. 6 in full, Methods, Motor); `descriptions` the plots' names
    and descriptions for a screen reader (by `app.page.describe.PLOT_NAMES`' keys),
    `announcer` the live region that announces a change of phase, `unseen` components
    with nothing to show (out of sight: the URL's writer), `teaching` the ways to the
    class's forms of the contact (under the CSV downloads: the lesson file, the student
    view)."""
    ui = contact.controls
    descriptions = descriptions or {}
    sidebar = [
        ui.preset_select,
        ui.note,
        pn.Row(ui.reset_button, ui.downloads["curves"]),
        ui.drive_control,
        ui.psi_slider, ui.theta_slider, ui.tau0_slider, ui.mu_slider, ui.nu_slider,
        ui.drive_note,
        ui.log_box,
        ui.physical_card,
        pn.Row(ui.downloads["traction"], ui.downloads["impulse"]),
        *teaching,
        keyboard_card(),
        play_key(contact),
    ]
    animation = card(
        *described(pn.Column(pn.pane.Bokeh(contact.spheres.figure,
                                           sizing_mode="stretch_width"),
                             sizing_mode="stretch_width",
                             stylesheets=[phone_fit_css(contact.spheres.figure)]),
                   "spheres", descriptions),
        pn.Row(ui.play_button, ui.step_button), ui.tau_slider, ui.speed_slider,
        ui.period_box, title="The two spheres (Fig. 2)", flex="0 0 auto")
    traction = card(*described(pn.pane.Bokeh(contact.traction.figure,
                                             sizing_mode="stretch_width"),
                               "traction", descriptions),
                    title="Traction profile (Fig. 6)", flex="3 1 560px")
    curves = card(*described(curve_tabs(contact), "curves", descriptions),
                  title="Curves over the contact", flex="3 1 560px")
    scroll_to_presets(contact)
    # the preset's figures (the curves) come before the formulas and the table: beside
    # them on a wide screen, right under the traction profile otherwise
    main = [
        message,
        *([announcer] if announcer is not None else []),
        *unseen,
        PlotGestures(),
        pn.FlexBox(
            traction,
            card(*described(pn.pane.Bokeh(contact.disc.figure), "disc", descriptions),
                 pn.pane.HTML(DISC_KEY), title="Contact disc", flex="0 0 380px"),
            curves,
            card(ui.formulas, title="Formulas of the current phase", flex="2 1 480px"),
            card(contact.readout, title="Derived quantities", flex="1 1 380px"),
            sizing_mode="stretch_width", align_content="flex-start"),
        *map(within_width, cards),
    ]
    use_css()
    return pn.Column(
        Landmark(object=heading(), role="banner", sizing_mode="stretch_width", margin=0),
        pn.FlexBox(
            Landmark(object=pn.Column(*sidebar, sizing_mode="stretch_width"),
                     role="complementary", label="Controls",
                     styles={"flex": "0 1 340px", "min-width": "0"}),
            Landmark(object=pn.Column(animation, sizing_mode="stretch_width"),
                     role="region", label=ANIMATION_LABEL, css_classes=["animation"],
                     styles={"flex": "0 1 440px", "min-width": "0"},
                     stylesheets=[animation_width_css(contact.spheres.figure)]),
            Landmark(object=pn.Column(*main, sizing_mode="stretch_width"), role="main",
                     styles={"flex": "1 1 560px", "min-width": "0"}),
            flex_wrap="wrap", align_items="flex-start", sizing_mode="stretch_width",
            stylesheets=[PHONE_ORDER_CSS]),
        sizing_mode="stretch_width")
