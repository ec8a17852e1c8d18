"""Accessibility of the explorer in a real browser (Debian's Chromium through Playwright).

An axe-core audit (axe-playwright-python), the size of the controls' text, the ring
around the control the keyboard is on, the names of the inputs as Chromium computes them
(its accessibility tree), the page's Tab stops, the derived-quantities table as text,
every key the "Keyboard" card lists, pressed where it says, the curve tabs by keyboard
(WAI-ARIA's tabs pattern), the play / pause key, the landmarks, the plots' names and
descriptions, and the live region's announcement of a change of phase.
"""

from __future__ import annotations

import pytest
from explorer_browser import column, open_explorer, steady, wait_until

from app.contact.data import readout_rows
from app.contact.readout import CAPTION
from app.contact.state import ExplorerState
from app.contact.view import TAB_TITLES
from app.kit.style import FOCUS_COLOR
from app.page.describe import PLOT_NAMES, announcement, descriptions
from app.page.keyboard import KEY_NAMES, KEYS, PLAY_KEY
from core import Contact

pytestmark = pytest.mark.browser

#: JavaScript: window.__deep(), the element the keyboard is on (inside shadow roots);
#: window.__all(keep), every element of the page and of its open shadow roots that
#: `keep` accepts; window.__role(el), the element's ARIA role (explicit, or implied by
#: its tag); window.__text(el), its text, shadow roots included; window.__plot(el), the
#: Figure view of the plot `el` is drawn in, or null.
JS_A11Y = r"""() => {
  window.__deep = () => {
    let a = document.activeElement;
    while (a && a.shadowRoot && a.shadowRoot.activeElement) a = a.shadowRoot.activeElement;
    return a;
  };
  window.__all = (keep) => {
    const found = [];
    const walk = (root) => {
      for (const el of root.querySelectorAll("*")) {
        if (keep(el)) found.push(el);
        if (el.shadowRoot) walk(el.shadowRoot);
      }
    };
    walk(document);
    return found;
  };
  window.__role = (el) => {
    if (el.hasAttribute("role")) return el.getAttribute("role");
    const tag = el.tagName.toLowerCase();
    if (tag === "button") return "button";
    if (tag === "select") return "combobox";
    if (tag === "textarea") return "textbox";
    if (tag === "input") {
      const type = el.type;
      if (type === "checkbox" || type === "radio") return type;
      if (type === "range") return "slider";
      return type === "number" ? "spinbutton" : "textbox";
    }
    return tag === "a" && el.hasAttribute("href") ? "link" : "";
  };
  window.__text = (el) => {
    let text = "";
    const walk = (node) => {
      for (const c of node.childNodes) {
        if (c.nodeType === Node.TEXT_NODE && c.parentNode.tagName !== "STYLE") {
          text += c.textContent;
        } else if (c.nodeType === Node.ELEMENT_NODE) {
          walk(c);
          if (c.shadowRoot) walk(c.shadowRoot);
        }
      }
    };
    walk(el);
    return text.replace(/\s+/g, " ").trim();
  };
  window.__plot = (el) => {
    const figures = new Map(__views((v) => v.model != null && v.model.type === "Figure")
                            .map((v) => [v.el, v]));
    for (let e = el; e != null; e = e.getRootNode().host) {
      if (figures.has(e)) return figures.get(e);
    }
    return null;
  };
}"""

#: Roles of the elements a user operates.
CONTROL_ROLES = {"button", "textbox", "combobox", "slider", "checkbox", "radio",
                 "spinbutton", "link", "tab"}

def page_with_cards_open(browser, url, width: int = 1600):
    """The explorer with the sidebar's collapsed cards (Physical inputs, Keyboard) open,
    and the helpers of this module."""
    page, console = open_explorer(browser, url, width=width)
    page.evaluate(JS_A11Y)
    for title in ("Physical inputs", "Keyboard"):
        page.get_by_role("button", name=title).click()
    page.get_by_role("combobox", name="Material").wait_for()
    page.locator("kbd").first.wait_for()
    return page, console


# ------------------------------------------------------------------------ axe


@pytest.fixture(scope="module")
def axe_findings(browser, url) -> list[dict]:
    """axe-core's findings on the page, its sidebar's cards open."""
    from axe_playwright_python.sync_playwright import Axe

    page, _ = page_with_cards_open(browser, url)
    wait_until(lambda: page.locator(".katex-display").count() >= 4,
               what="the formulas typeset")
    page.wait_for_function("() => Bokeh.documents[0].is_idle")  # every view drawn
    findings = Axe().run(page).response["violations"]
    page.close()
    return findings


def grave(findings: list[dict]) -> dict[str, list[dict]]:
    """The serious and critical findings: rule id -> the elements it found."""
    return {f["id"]: f["nodes"] for f in findings if f["impact"] in ("serious", "critical")}


def test_axe_finds_nothing_serious_or_critical(axe_findings) -> None:
    """No serious or critical finding: the sliders are range inputs named by their
    labels (BokehJS's noUiSlider handles had no name), the physical inputs text boxes
    (BokehJS's Spinner draws its buttons without text)."""
    assert {rule: [n["target"] for n in nodes]
            for rule, nodes in grave(axe_findings).items()} == {}


def test_axe_finds_no_landmark_problem(axe_findings) -> None:
    """A `main` landmark, and no content outside the landmarks (axe's rules 'region' and
    'landmark-*'; Panel's layouts carry no role: `app.kit.a11y.Landmark`)."""
    assert [(f["id"], len(f["nodes"])) for f in axe_findings
            if f["id"] == "region" or f["id"].startswith("landmark")] == []


# ---------------------------------------------------------------- type size

#: JavaScript: [what, font size in px] of the text of every control shown: the value
#: of text boxes and menus, the text in buttons, slider handles (their value, shown while
#: dragged) and tabs, the labels of text boxes, menus and check boxes, and the sliders'
#: titles.
JS_CONTROL_TEXT = """() => {
  const shown = (el) => el.getClientRects().length > 0;
  const px = (el) => parseFloat(getComputedStyle(el).fontSize);
  const out = [];
  const texts = (el, what) => {  // every element holding text under el, shadow roots too
    const walk = (node) => {
      for (const c of node.childNodes) {
        if (c.nodeType === Node.TEXT_NODE && c.textContent.trim() && shown(node)) {
          out.push([what + ": " + c.textContent.trim().slice(0, 30), px(node)]);
        } else if (c.nodeType === Node.ELEMENT_NODE) {
          walk(c);
          if (c.shadowRoot) walk(c.shadowRoot);
        }
      }
    };
    walk(el);
  };
  for (const el of __all(shown)) {
    const role = __role(el);
    const tag = el.tagName.toLowerCase();
    if (role === "textbox" || role === "combobox") {
      out.push([role + " " + (el.value || "").slice(0, 30), px(el)]);
    }
    if (["button", "slider", "tab"].includes(role) || el.classList.contains("bk-tab")) {
      texts(el, role || "tab");
    }
    if (tag === "label" || el.classList.contains("bk-slider-title")) texts(el, "label");
    if (role === "checkbox") texts(el.parentNode, "check box");
  }
  return out;
}"""


@pytest.mark.parametrize("width", [1600, 390], ids=["desktop", "phone"])
def test_controls_text_is_at_least_16px(browser, url, width: int) -> None:
    page, _ = page_with_cards_open(browser, url, width=width)
    sizes = page.evaluate(JS_CONTROL_TEXT)
    page.close()
    kinds = {what.split(":")[0].split(" ")[0] for what, _ in sizes}
    assert {"textbox", "combobox", "button", "label", "check"} <= kinds
    assert [(what, px) for what, px in sizes if px < 16] == []


# ------------------------------------------------------------------ focus ring

#: JavaScript: the element the keyboard is on: its role, name, whether it is a tab of
#: BokehJS's Tabs, the Figure view's tool count if it is drawn in a plot, and its outline
#: and box shadow (focused; the element is kept for `JS_UNFOCUSED`).
JS_FOCUSED = """() => {
  const el = __deep();
  if (el == null || el === document.body) return null;
  window.__stops.push(el);
  const s = getComputedStyle(el);
  const plot = __plot(el);
  return {
    role: __role(el),
    name: el.getAttribute("aria-label") || __text(el) || el.value || "",
    bokeh_tab: el.classList.contains("bk-tab"),
    plot_tools: plot == null ? null : plot.model.toolbar.tools.length,
    outline: [s.outlineStyle, parseFloat(s.outlineWidth), s.outlineColor],
    shadow: s.boxShadow,
  };
}"""

#: JavaScript: the outline and box shadow of each element `JS_FOCUSED` kept, unfocused.
JS_UNFOCUSED = """() => {
  __deep().blur();
  return window.__stops.map((el) => {
    const s = getComputedStyle(el);
    return {outline: [s.outlineStyle, parseFloat(s.outlineWidth), s.outlineColor],
            shadow: s.boxShadow};
  });
}"""


def tab_stops(page, limit: int = 120) -> list[dict]:
    """Press Tab from the top of the page (a click on its title) until the keyboard comes
    back to where it began; what `JS_FOCUSED` says of each stop."""
    page.evaluate("() => { window.__stops = []; window.scrollTo(0, 0); }")
    page.mouse.click(1, 1)  # (the page's title, once scrolled to the top)
    stops: list[dict] = []
    for _ in range(limit):
        page.keyboard.press("Tab")
        stop = page.evaluate(JS_FOCUSED)
        if stop is None or (stops and stop == stops[0]):
            if stop is not None:
                page.evaluate("() => window.__stops.pop()")
            return stops
        stops.append(stop)
    raise AssertionError(f"Tab did not come back to the start within {limit} presses")


def rgb(css: str) -> tuple[float, ...]:
    """The red, green and blue (0..255) of a computed colour 'rgb(r, g, b)'."""
    return tuple(float(x) for x in css[css.index("(") + 1:css.index(")")].split(",")[:3])


def contrast(a: tuple[float, ...], b: tuple[float, ...]) -> float:
    """WCAG 2 contrast ratio of two sRGB colours."""
    def lum(c):
        c = [x / 255 for x in c]
        c = [x / 12.92 if x <= 0.04045 else ((x + 0.055) / 1.055) ** 2.4 for x in c]
        return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
    hi, lo = sorted((lum(a), lum(b)), reverse=True)
    return (hi + 0.05) / (lo + 0.05)


def test_every_control_shows_a_focus_ring(browser, url) -> None:
    """Each control the keyboard reaches (BokehJS's tabs too) draws an outline it has
    not when unfocused: at least 2 px thick, at 3:1 at least against the white page
    (WCAG 2.4.13, 1.4.11)."""
    page, _ = page_with_cards_open(browser, url)
    stops = tab_stops(page)
    unfocused = page.evaluate(JS_UNFOCUSED)
    page.close()
    controls = [(s, u) for s, u in zip(stops, unfocused, strict=True)
                if s["role"] in CONTROL_ROLES or s["bokeh_tab"]]
    names = {s["name"] for s, _ in controls if s["role"] == "button"}
    assert {"Reset", "Step", "▶ Play", "CSV: curves", "CSV: traction", "CSV: impulse",
            "Physical inputs", "Keyboard"} <= names
    assert {"textbox", "combobox", "slider", "checkbox"} <= {s["role"] for s, _ in controls}
    bad = []
    for s, u in controls:
        style, width, color = s["outline"]
        if (style == "none" or width < 2 or contrast(rgb(color), (255, 255, 255)) < 3
                or (s["outline"], s["shadow"]) == (u["outline"], u["shadow"])):
            bad.append((s["role"], s["name"][:30], s["outline"], u["outline"]))
    assert bad == []


# ------------------------------------------------------------------- names


def accessible_names(page) -> dict[str, list[str]]:
    """Role -> the names Chromium gives the shown inputs of that role (its
    accessibility tree: what a screen reader announces)."""
    cdp = page.context.new_cdp_session(page)
    nodes = cdp.send("Accessibility.getFullAXTree")["nodes"]
    names: dict[str, list[str]] = {}
    for n in nodes:
        role = n.get("role", {}).get("value")
        if not n.get("ignored") and role in ("textbox", "combobox", "checkbox", "slider",
                                             "spinbutton"):
            names.setdefault(role, []).append(n.get("name", {}).get("value", ""))
    return names


@pytest.fixture(scope="module")
def names(browser, url) -> dict[str, list[str]]:
    page, _ = page_with_cards_open(browser, url)
    found = accessible_names(page)
    page.close()
    return found


def test_text_boxes_are_named_after_their_labels(names) -> None:
    for label in ("ψ = tan θ / tan θ₀", "τ₀ (rad): contact starts", "μ friction",
                  "ν Poisson ratio", "τ = ωt (rad): time", "R (mm): sphere radius",
                  "f (kHz): frequency, ω = 2πf"):
        assert label in names["textbox"]
    assert "" not in names["textbox"] and "" not in names.get("spinbutton", [])


def test_menus_are_named_after_their_labels(names) -> None:
    assert {"Preset: the paper's figures", "Material"} <= set(names["combobox"])
    assert "" not in names["combobox"]


def test_check_boxes_have_names(names) -> None:
    assert names["checkbox"] and "" not in names["checkbox"]


def test_sliders_are_named_after_their_labels(names) -> None:
    """Each slider (a range input, `app.kit.sliders.LabelledSlider`) is named by its label: the
    same words as its number box's."""
    assert sorted(names["slider"]) == sorted([
        "ψ = tan θ / tan θ₀", "θ (°): drive angle, tan θ = u₀/H", "τ₀ (rad): contact starts",
        "μ friction", "ν Poisson ratio", "τ = ωt (rad): time", "Speed"])


# ---------------------------------------------------------------- Tab stops


def test_no_plot_without_tools_is_a_tab_stop(browser, url) -> None:
    """A plot with no tool (nothing to do there, by mouse or keyboard) is not a Tab
    stop; every other stop is a control, a plot or a tab of BokehJS's Tabs."""
    page, _ = page_with_cards_open(browser, url)
    stops = tab_stops(page)
    page.close()
    assert [s for s in stops if s["plot_tools"] == 0] == []
    assert [s for s in stops if s["role"] not in CONTROL_ROLES and s["plot_tools"] is None
            and not s["bokeh_tab"]] == []


@pytest.mark.xfail(strict=True, reason=(
    "BokehJS gives every plot's canvas a tabIndex of 0 (CanvasView's events layer), and "
    "no property, of Bokeh or Panel, takes it out of the tab order"))
def test_no_plot_is_a_tab_stop(browser, url) -> None:
    page, _ = page_with_cards_open(browser, url)
    stops = tab_stops(page)
    page.close()
    assert [s for s in stops if s["plot_tools"] is not None] == []


# ------------------------------------------------------- derived quantities

#: JavaScript: the derived-quantities table: its caption, the scope of its header
#: cells, and its body's rows as [row header, cell] texts.
JS_READOUT = """() => {
  const t = __all((el) => el.tagName === "TABLE" && el.classList.contains("readout"));
  if (t.length !== 1) return null;
  return {
    caption: t[0].caption && t[0].caption.textContent,
    scopes: [...t[0].querySelectorAll("th")].map((th) => th.getAttribute("scope")),
    rows: [...t[0].tBodies[0].rows].map((r) => [r.cells[0].textContent,
                                                 r.cells[1].textContent]),
  };
}"""


def test_derived_quantities_are_a_table_of_text(browser, url) -> None:
    """The table shows, as text, the derived quantities of the page's contact, and
    follows a slider move."""
    page, _ = page_with_cards_open(browser, url)
    table = page.evaluate(JS_READOUT)
    assert table is not None and table["caption"] == CAPTION
    assert table["scopes"] == ["col", "col"] + ["row"] * len(table["rows"])
    state = ExplorerState()
    assert [tuple(r) for r in table["rows"]] == readout_rows(state.contact())
    psi_row = table["rows"][[q for q, _ in table["rows"]].index("ψ")]
    page.locator(".slider-psi input[type=range]").focus()
    page.keyboard.press("ArrowRight")
    page.wait_for_function(  # the psi row changed
        f"(old) => !JSON.stringify(({JS_READOUT})().rows).includes(JSON.stringify(old))",
        arg=psi_row, timeout=20_000)
    state.psi = page.evaluate("() => __psi()")
    table = page.evaluate(JS_READOUT)
    page.close()
    assert [tuple(r) for r in table["rows"]] == readout_rows(state.contact())


# ----------------------------------------------------------------- keyboard


def slider(page, name: str) -> float:
    return page.evaluate("(n) => __slider(n).value", name)


def wait_slider(page, name: str, value: float) -> None:
    """Wait until the named slider's model holds `value` (within rounding)."""
    page.wait_for_function("([n, v]) => Math.abs(__slider(n).value - v) < 1e-9",
                           arg=[name, value], timeout=20_000)


def test_keyboard_card_lists_keys_that_work(browser, url) -> None:
    """The card shows every key of `KEYS`, and each does what the card says on the
    control it names."""
    page, _ = page_with_cards_open(browser, url)
    text = page.locator("table:has(kbd)").inner_text()
    for k in KEYS:
        assert k.target in text and k.action in text
        assert all(KEY_NAMES.get(n, n) in text for n in k.keys)
    done: set[tuple[str, str]] = set()
    deep = "() => { const a = __deep(); return a && (a.getAttribute('aria-label') || "\
           "a.textContent || a.value || '').trim(); }"

    # Tab / Shift+Tab, from the preset menu to Reset and back
    menu = page.get_by_role("combobox", name="Preset: the paper's figures")
    menu.focus()
    page.keyboard.press("Tab")
    assert page.evaluate(deep) == "Reset"
    page.keyboard.press("Shift+Tab")
    assert page.evaluate("() => __role(__deep())") == "combobox"
    done |= {("Anywhere", "Tab"), ("Anywhere", "Shift+Tab")}

    # the menu: the next choice and back
    first = menu.input_value()
    page.keyboard.press("ArrowDown")
    page.wait_for_function("(v) => __deep().value !== v", arg=first, timeout=5000)
    second = menu.input_value()
    page.keyboard.press("ArrowUp")
    page.wait_for_function("(v) => __deep().value === v", arg=first, timeout=5000)
    assert second != first
    done |= {("Menu", "ArrowDown"), ("Menu", "ArrowUp")}

    # a slider: mu, by its step, five steps, its ends
    start, end, step = page.evaluate(
        "() => { const s = __slider('mu'); return [s.start, s.end, s.step]; }")
    page.locator(".slider-mu input[type=range]").focus()
    mu = slider(page, "mu")
    for key, change in (("ArrowRight", step), ("ArrowLeft", -step), ("ArrowUp", step),
                        ("ArrowDown", -step), ("PageUp", 5 * step), ("PageDown", -5 * step)):
        page.keyboard.press(key)
        mu += change
        wait_slider(page, "mu", mu)
        done.add(("Slider", key))
    page.keyboard.press("End")
    wait_slider(page, "mu", end)
    page.keyboard.press("Home")
    wait_slider(page, "mu", start)
    done |= {("Slider", "End"), ("Slider", "Home")}

    # a number box: a typed value applies on Enter (once the box shows the slider's value)
    box = page.get_by_role("textbox", name="μ friction")
    wait_until(lambda: float(box.input_value()) == start, what="the box to show mu")
    box.fill("0.35")
    page.wait_for_timeout(500)  # time let pass on purpose: nothing may apply the text
    assert slider(page, "mu") == start  # typed, not applied
    box.press("Enter")
    wait_slider(page, "mu", 0.35)
    done.add(("Number box", "Enter"))

    # a button: Step, by Space and by Enter
    step_button = page.get_by_role("button", name="Step")
    for key in ("Space", "Enter"):
        tau = slider(page, "tau")
        step_button.focus()
        page.keyboard.press(key)
        page.wait_for_function("(t) => __slider('tau').value !== t", arg=tau, timeout=20_000)
        done.add(("Button", key))

    # a check box: the log psi axis
    check = page.get_by_role("checkbox").first
    ticked = check.is_checked()
    check.focus()
    page.keyboard.press("Space")
    page.wait_for_function("(t) => __deep().checked !== t", arg=ticked, timeout=5000)
    done.add(("Check box", "Space"))

    # a card's title: the Keyboard card closes on Enter, opens on Space
    title = page.get_by_role("button", name="Keyboard")
    keys_table = page.locator("table:has(kbd)")
    title.focus()
    page.keyboard.press("Enter")
    keys_table.wait_for(state="hidden")
    page.keyboard.press("Space")
    keys_table.wait_for(state="visible")
    done |= {("Card title", "Enter"), ("Card title", "Space")}

    # the curve tabs: along the list and back, its ends, open a tab by Enter and Space
    page.evaluate(JS_TABS)
    page.get_by_role("tab", selected=True).focus()
    for key, focused in (("ArrowRight", "Impulse (Fig. 8)"), ("ArrowLeft", "T(τ) (Fig. 7)"),
                         ("End", "Centre motion (Fig. 9)"), ("Home", "T(τ) (Fig. 7)")):
        page.keyboard.press(key)
        assert tab_state(page)["focused"] == focused
        done.add(("Curve tabs", key))
    for key, index in (("ArrowRight", None), ("Enter", 1), ("ArrowRight", None),
                       ("Space", 2)):
        page.keyboard.press(key)
        if index is not None:
            wait_tab(page, index)
            done.add(("Curve tabs", key))

    # play and pause, the keyboard on a tab
    play = f"Alt+{PLAY_KEY.upper()}"
    page.keyboard.press(play)
    page.wait_for_function(f"() => ({JS_PLAY_LABEL})() === '‖ Pause'", timeout=20_000)
    page.keyboard.press(play)
    page.wait_for_function(f"() => ({JS_PLAY_LABEL})() === '▶ Play'", timeout=20_000)
    done.add(("Anywhere", play))
    page.close()
    assert done == {(k.target, key) for k in KEYS for key in k.keys}


# ---------------------------------------------------- screen readers: the tree


def ax_nodes(page) -> list[dict]:
    """The role, name and description of every node of Chromium's accessibility tree
    that is not ignored (what a screen reader meets)."""
    cdp = page.context.new_cdp_session(page)
    nodes = cdp.send("Accessibility.getFullAXTree")["nodes"]
    return [{"role": n.get("role", {}).get("value"),
             "name": n.get("name", {}).get("value", ""),
             "description": n.get("description", {}).get("value", "")}
            for n in nodes if not n.get("ignored")]


def test_page_has_its_landmarks(browser, url) -> None:
    """The header a banner, the sidebar a complementary region named "Controls", the
    scenes the main region: one of each."""
    page, _ = open_explorer(browser, url)
    roles = [(n["role"], n["name"]) for n in ax_nodes(page)
             if n["role"] in ("banner", "complementary", "main")]
    page.close()
    assert sorted(roles) == [("banner", ""), ("complementary", "Controls"), ("main", "")]


def figures(page) -> dict[str, str]:
    """Name -> description of every figure of the accessibility tree."""
    return {n["name"]: n["description"] for n in ax_nodes(page) if n["role"] == "figure"}


def test_every_plot_is_named_and_described_and_follows_psi(browser, url) -> None:
    """Each plot has a name (its card's title) and a description of what it shows, in
    core's numbers, which follows a psi move."""
    page, _ = open_explorer(browser, url)
    page.wait_for_function("() => Bokeh.documents[0].is_idle")
    state = ExplorerState()
    expected = descriptions(state.contact(), state.tau, 0)
    assert figures(page) == {PLOT_NAMES[k]: text for k, text in expected.items()}
    assert "partial stick" in expected["traction"]
    page.locator(".slider-psi input[type=range]").focus()
    page.keyboard.press("End")  # psi to the end of its range
    page.wait_for_function("() => __psi() === __slider('psi').end", timeout=20_000)
    state.psi = page.evaluate("() => __psi()")
    wait_until(lambda: figures(page)[PLOT_NAMES["traction"]] != expected["traction"],
               what="the traction plot's description to follow psi")
    tau = page.evaluate("() => __slider('tau').value")
    moved = descriptions(Contact(state.psi, state.tau0, mu=state.mu, nu=state.nu), tau, 0)
    wait_until(lambda: figures(page) == {PLOT_NAMES[k]: t for k, t in moved.items()},
               what="every description to follow psi")
    page.close()


def live_text(page) -> str:
    return page.locator("[role=status][aria-live=polite]").text_content().strip()


def test_live_region_announces_a_change_of_phase(browser, url) -> None:
    """A polite live region says the phase entered, and when it began: at psi = 2.414,
    back to the contact's start (its first phase), then past pi/2 (partial stick)."""
    page, _ = open_explorer(browser, url)
    state = ExplorerState()
    c = state.contact()
    assert c.psi == pytest.approx(2.414, abs=1e-3)
    assert live_text(page) == ""  # nothing said at load
    box = page.get_by_role("textbox", name="τ = ωt (rad): time")
    box.fill("0.6")
    box.press("Enter")
    first = announcement(c, 0.6)
    wait_until(lambda: live_text(page) == first, what=f"the live region to say {first!r}")
    box.fill("1.6")
    box.press("Enter")
    second = announcement(c, 1.6)
    assert second == "Partial stick from τ = 1.571 rad"
    wait_until(lambda: live_text(page) == second, what=f"the live region to say {second!r}")
    page.close()


# ------------------------------------------------------------- curve tabs

#: JavaScript: the curve tabs' Bokeh model (Panel's Tabs, its titles `TAB_TITLES`) and
#: the tab list's (`app.kit.a11y.TabList`).
JS_TABS = """() => {
  const models = [...Bokeh.documents[0].all_models];
  window.__tabs = models.find((m) => m.type.endsWith(".Tabs") && m.tabs.length > 0
                              && m.tabs[0].title === "T(τ) (Fig. 7)");
  window.__tablist = models.find((m) => m.data != null && m.data.titles !== undefined);
}"""


def tab_state(page) -> dict:
    """The tabs' aria-selected, the tab the keyboard is on, and the models' indices."""
    return page.evaluate("""() => ({
      selected: [...__all((el) => el.getAttribute("role") === "tab")].map(
        (el) => el.getAttribute("aria-selected")),
      focused: __deep() && __deep().getAttribute("role") === "tab" ? __deep().textContent
                                                                    : null,
      active: __tabs.active, value: __tablist.data.value})""")


def wait_tab(page, index: int) -> None:
    """Wait until tab `index` is open: the Tabs model's `active` and aria-selected."""
    page.wait_for_function(
        """(i) => __tabs.active === i && [...__all((el) => el.getAttribute("role") === "tab")]
           .map((el) => el.getAttribute("aria-selected") === "true").indexOf(true) === i""",
        arg=index, timeout=20_000)


def test_curve_tabs_follow_the_tabs_pattern(browser, url) -> None:
    """The curve tabs are a tab list (roles tablist, tab, tabpanel): the arrows move the
    keyboard along it (round), Home / End to its ends, Enter and Space open the tab the
    keyboard is on; only the open tab is a Tab stop; its panel is named after it."""
    page, _ = page_with_cards_open(browser, url)
    page.evaluate(JS_TABS)
    tabs = page.get_by_role("tab")
    assert [tabs.nth(i).text_content() for i in range(tabs.count())] == list(TAB_TITLES)
    assert page.get_by_role("tablist", name="Curves over the contact").count() == 1
    assert tab_state(page)["selected"] == ["true", "false", "false", "false"]
    assert page.evaluate("() => __all((el) => el.getAttribute('role') === 'tab')"
                         ".map((el) => el.tabIndex)") == [0, -1, -1, -1]
    assert column(page, "impulse", "psi") is None  # its tab is closed: not in the page
    page.get_by_role("tab", selected=True).focus()
    page.keyboard.press("ArrowRight")
    state = tab_state(page)
    assert state["focused"] == "Impulse (Fig. 8)" and state["active"] == 0  # moved only
    page.keyboard.press("Enter")
    wait_tab(page, 1)
    page.wait_for_function("() => (__col('impulse', 'psi') || []).length > 0",
                           timeout=20_000)
    assert page.get_by_role("tabpanel", name="Impulse (Fig. 8)").count() == 1
    page.keyboard.press("End")
    assert tab_state(page)["focused"] == "Centre motion (Fig. 9)"
    page.keyboard.press("Home")
    assert tab_state(page)["focused"] == "T(τ) (Fig. 7)"
    page.keyboard.press("ArrowLeft")  # round: from the first to the last
    assert tab_state(page)["focused"] == "Centre motion (Fig. 9)"
    page.keyboard.press("Space")
    wait_tab(page, 3)
    page.wait_for_function("() => (__col('motion', 'u2') || []).length > 0", timeout=20_000)
    page.close()


def test_a_tab_index_from_a_script_that_names_no_tab_changes_nothing(browser, url) -> None:
    page, _ = open_explorer(browser, url)
    page.evaluate(JS_A11Y)
    page.evaluate(JS_TABS)
    for bad in (7, -1, 1.5):
        page.evaluate("(v) => { __tablist.data.value = v; }", bad)
        page.wait_for_function("() => __tablist.data.value === 0", timeout=20_000)
        assert page.evaluate("() => __tabs.active") == 0
    page.close()


def test_tab_focus_ring_is_visible(browser, url) -> None:
    """The ring around the tab the keyboard is on: 3 px, 2 px outside it, at 3:1 at
    least against the white page and the unselected tabs' grey (WCAG 2.4.13)."""
    page, _ = open_explorer(browser, url)
    page.evaluate(JS_A11Y)
    page.get_by_role("tab", selected=True).focus()
    page.keyboard.press("ArrowRight")
    ring = page.evaluate("""() => { const s = getComputedStyle(__deep());
      return [s.outlineStyle, parseFloat(s.outlineWidth), parseFloat(s.outlineOffset),
              s.outlineColor, getComputedStyle(__deep()).backgroundColor]; }""")
    page.close()
    style, width, offset, color, background = ring
    assert style == "solid" and width >= 3 and offset >= 2
    assert rgb(color) == rgb_hex(FOCUS_COLOR)
    for behind in ((255, 255, 255), rgb(background)):
        assert contrast(rgb(color), behind) >= 3


def rgb_hex(color: str) -> tuple[float, ...]:
    return tuple(float(int(color[i:i + 2], 16)) for i in (1, 3, 5))


# ------------------------------------------------------------ play / pause key

#: JavaScript: the label of the Play / Pause button's model.
JS_PLAY_LABEL = """() => [...Bokeh.documents[0].all_models].find(
  (m) => /Play|Pause/.test(m.label || "")).label"""


def test_play_key_plays_and_pauses(browser, url) -> None:
    """Alt + K, wherever the keyboard is but in a text box, plays; again, pauses: the
    button says so and the time moves.  The plots' descriptions wait while playing and
    describe the frame the pause lands on."""
    page, _ = open_explorer(browser, url)
    assert page.evaluate(JS_PLAY_LABEL) == "▶ Play"
    state = ExplorerState()
    before = figures(page)
    tau = page.evaluate("() => __slider('tau').value")
    page.get_by_role("button", name="Step").focus()
    page.keyboard.press(f"Alt+{PLAY_KEY.upper()}")
    page.wait_for_function(f"() => ({JS_PLAY_LABEL})() === '‖ Pause'", timeout=20_000)
    page.wait_for_function("(t) => __slider('tau').value !== t", arg=tau, timeout=20_000)
    assert figures(page) == before  # (written at the pause)
    page.mouse.click(1, 1)  # the keyboard on the page itself
    page.keyboard.press(f"Alt+{PLAY_KEY.upper()}")
    page.wait_for_function(f"() => ({JS_PLAY_LABEL})() === '▶ Play'", timeout=20_000)
    paused = steady(lambda: page.evaluate("() => __slider('tau').value"))
    expected = descriptions(state.contact(), paused, 0)
    wait_until(lambda: figures(page) == {PLOT_NAMES[k]: t for k, t in expected.items()},
               what="the descriptions of the frame the pause landed on")
    page.close()


# ------------------------------------------------------- states of toggles and cards

METHODS_CARD = "Methods: numerical schemes against the closed form"


def test_toggle_and_cards_say_their_state_and_the_methods_box_its_name(browser,
                                                                         url) -> None:
    """The drive's psi/theta toggle said neither which button was pressed nor that it
    was one choice; a collapsible card's title did not say whether it was open; the
    Methods chooser's search box was named "null".  Now the toggle is a radio group
    (aria-checked, the arrows choose), each card's title button has aria-expanded,
    which follows every opening and closing, and the box is named."""
    page, console = open_explorer(browser, url)
    group = page.get_by_role("radiogroup", name="Set the drive by")
    psi, angle = group.get_by_role("radio", name="ψ"), group.get_by_role("radio",
                                                                          name="angle θ")
    assert (psi.get_attribute("aria-checked"), angle.get_attribute("aria-checked")) == (
        "true", "false")
    angle.click()
    page.wait_for_function("() => location.search.includes('drive=angle')",
                           timeout=20_000)  # (the server took it)
    assert (psi.get_attribute("aria-checked"), angle.get_attribute("aria-checked")) == (
        "false", "true")
    page.keyboard.press("ArrowLeft")  # (the keyboard is on angle θ: back to ψ)
    page.wait_for_function("() => !location.search.includes('drive=angle')",
                           timeout=20_000)
    assert psi.get_attribute("aria-checked") == "true"
    assert psi.evaluate("(el) => el.getRootNode().activeElement === el")  # the keyboard on it

    title = page.get_by_role("button", name=METHODS_CARD)
    assert title.get_attribute("aria-expanded") == "false"
    title.click()
    box = page.get_by_role("textbox", name="Add a method")
    box.wait_for()  # built on opening, and named
    wait_until(lambda: title.get_attribute("aria-expanded") == "true",
               what="the opened card's aria-expanded")
    page.wait_for_function("() => (__col('methods', 'xs') || []).length > 0",
                           timeout=60_000)  # (its first run drawn: the card drawn anew)
    assert title.get_attribute("aria-expanded") == "true"
    assert "null" not in accessible_names(page).get("textbox", [])
    title.click()
    wait_until(lambda: title.get_attribute("aria-expanded") == "false",
               what="the closed card's aria-expanded")
    for name in ("Motor: the rod", "Fig. 6 in full", "Physical inputs"):  # (every card)
        card = page.get_by_role("button", name=name)
        assert card.get_attribute("aria-expanded") == "false", name
        card.click()
        wait_until(lambda c=card: c.get_attribute("aria-expanded") == "true",
                   what=f"{name}'s aria-expanded when opened")
        card.click()
        wait_until(lambda c=card: c.get_attribute("aria-expanded") == "false",
                   what=f"{name}'s aria-expanded when closed")
    assert [m for m in console if "error" in m.lower()] == []
    assert [m for m in console if "could not be found" in m] == []  # (titles drawn first)
    page.close()
