"""The presentation view (`/main?view=present`) in front of a class, in Debian's Chromium.

Browser zoom is emulated as Chromium applies it to a page: a zoom z divides the window's
size in CSS px by z and multiplies the device pixels per CSS px by z (a 1280 x 720
screen at 150 % is a page of 853 x 480 CSS px drawn at 1.5 device px per CSS px), so
each case opens a page with viewport = screen / z and device_scale_factor = z.  Checked:
the plots' canvases at least `MIN_PLOT`, no text over other text or over a plot, nothing
wider than the window, the spheres, the traction profile and T(tau) on one screen up
to 150 %; the projector box (tick labels of 24 px at least); the figure of the presets
of Figs. 4, 8 and 9 under the traction profile; the landmarks, and axe-core's audit.
"""

from __future__ import annotations

import re

import pytest
from explorer_browser import JS_HELPERS, JS_READY, ROOT, steady, wait_until

from app.contact.state import PRESETS
from app.page.present_css import MIN_PLOT
from app.page.projector import LABEL as PROJECTOR_LABEL

pytestmark = pytest.mark.browser

ARTIFACTS = ROOT / "artifacts"
SCREENS = [(1280, 720), (1920, 1080)]
ZOOMS = [1.0, 1.25, 1.5, 1.75, 2.0]
#: The three plots a class must see together (their titles).
FIRST = ("Two spheres in section", "Traction profile", "Tangential force T / T₀")

#: JavaScript: every plot drawn on the page (title, box, its largest canvas's size), the
#: tight boxes of every visible text outside the plots (not the text for screen readers
#: only, which is clipped to nothing), and the page's scroll extent.
JS_LAYOUT = r"""() => {
  const figs = __views((v) => v.model != null && v.model.type === "Figure")
    .filter((v) => v.el.getBoundingClientRect().width > 0);
  const els = new Set(figs.map((v) => v.el));
  const box = (r) => [r.left, r.top, r.right, r.bottom];
  const sides = (m) => [...m.left, ...m.right, ...m.above, ...m.below];
  const font = (s) => (typeof s === "object" && s != null ? s.value : s);
  const canvases = (root, found) => {
    for (const el of root.querySelectorAll("*")) {
      if (el.tagName === "CANVAS") found.push(el.getBoundingClientRect());
      if (el.shadowRoot) canvases(el.shadowRoot, found);
    }
    return found;
  };
  const plots = figs.map((v) => {
    const c = canvases(v.shadow_el || v.el.shadowRoot, []);
    const big = c.reduce((a, r) => (r.width * r.height > a.width * a.height ? r : a),
                         {width: 0, height: 0});
    return {title: v.model.title.text, box: box(v.el.getBoundingClientRect()),
            canvas: [big.width, big.height], ticks: sides(v.model)
              .filter((a) => a.major_label_text_font_size !== undefined)
              .map((a) => font(a.major_label_text_font_size))};
  });
  const texts = [];
  const hidden = (el) => {
    for (let e = el; e != null; e = e.parentNode || e.host) {
      if (e.nodeType !== 1) continue;
      if (els.has(e)) return true;
      const cs = getComputedStyle(e);
      if (cs.clipPath === "inset(50%)" || cs.display === "none" || cs.visibility === "hidden")
        return true;
    }
    return false;
  };
  const walk = (root) => {
    for (const el of root.querySelectorAll("*")) {
      if (el.shadowRoot) walk(el.shadowRoot);
      if (["STYLE", "SCRIPT", "OPTION", "SELECT", "TEXTAREA"].includes(el.tagName)) continue;
      for (const n of el.childNodes) {
        if (n.nodeType !== 3 || !n.textContent.trim()) continue;
        const range = document.createRange();
        range.selectNodeContents(n);
        for (const r of range.getClientRects()) {
          if (r.width > 2 && r.height > 2 && !hidden(el)) {
            texts.push({text: n.textContent.trim().slice(0, 40), box: box(r)});
          }
        }
      }
    }
  };
  walk(document);
  const s = document.scrollingElement;
  return {plots, texts, scroll: [s.scrollWidth, s.scrollHeight], view: [innerWidth, innerHeight]};
}"""


def open_present(browser, query: str, screen: tuple[int, int], zoom: float = 1.0):
    """The presentation view of `query` on a `screen` (device px) at browser zoom
    `zoom`, once its data arrived, and its console."""
    width, height = screen
    page = browser.new_page(viewport={"width": round(width / zoom), "height": round(height / zoom)},
                            device_scale_factor=zoom)
    console: list[str] = []
    page.on("console", lambda m: console.append(f"{m.type}: {m.text}"))
    page.on("pageerror", lambda e: console.append(f"pageerror: {e}"))
    page.goto(query)
    page.wait_for_function("() => window.Bokeh && Bokeh.documents.length > 0", timeout=60_000)
    page.evaluate(JS_HELPERS)
    return page, console


def laid_out(page) -> dict:
    """JS_LAYOUT once the fonts are loaded and the layout has stayed the same for 0.5 s."""
    page.evaluate("() => document.fonts.ready.then(() => true)")
    page.wait_for_function("() => Bokeh.documents[0].is_idle", timeout=20_000)
    return steady(lambda: page.evaluate(JS_LAYOUT))


def overlap(a: list[float], b: list[float]) -> float:
    """How far two boxes [left, top, right, bottom] overlap (px; <= 0: apart)."""
    return min(min(a[2], b[2]) - max(a[0], b[0]), min(a[3], b[3]) - max(a[1], b[1]))


def assert_readable(shown: dict) -> None:
    """Every plot's canvas at least MIN_PLOT; no plot over another, no text over a plot
    or over other text; nothing wider than the window."""
    w, h = MIN_PLOT
    assert shown["scroll"][0] <= shown["view"][0], shown["scroll"]
    for p in shown["plots"]:
        assert p["canvas"][0] >= w - 0.5 and p["canvas"][1] >= h - 0.5, p
    items = [(p["title"], p["box"]) for p in shown["plots"]] + [
        (t["text"], t["box"]) for t in shown["texts"]]
    clashes = [(a, b, round(overlap(ba, bb), 1)) for i, (a, ba) in enumerate(items)
               for b, bb in items[i + 1:] if overlap(ba, bb) > 1]
    assert clashes == []


def plot(shown: dict, title: str) -> dict:
    return next(p for p in shown["plots"] if p["title"] == title)


@pytest.mark.parametrize("zoom", ZOOMS)
@pytest.mark.parametrize("screen", SCREENS, ids=lambda s: f"{s[0]}x{s[1]}")
def test_the_presentation_reflows_under_browser_zoom(browser, url, screen, zoom) -> None:
    """From 100 % to 200 %: the plots at least MIN_PLOT, nothing over anything else,
    nothing wider than the window; up to 150 % the spheres, the traction profile and
    T(tau) are on one screen, unscrolled (at 200 % the page may scroll)."""
    page, console = open_present(browser, url + "?view=present", screen, zoom)
    page.wait_for_function(JS_READY, timeout=60_000)
    shown = laid_out(page)
    titles = [p["title"] for p in shown["plots"]]
    assert set(FIRST) | {"Contact disc (top view)"} <= set(titles), titles
    assert_readable(shown)
    if zoom <= 1.5:
        _, height = shown["view"]
        for title in FIRST:
            _, top, _, bottom = plot(shown, title)["box"]
            assert top >= -0.5 and bottom <= height + 0.5, (title, shown["view"], bottom)
    if zoom == 1.5:
        ARTIFACTS.mkdir(exist_ok=True)
        page.screenshot(path=str(ARTIFACTS / f"presentation-{screen[0]}x{screen[1]}-150.png"))
    assert [m for m in console if m.startswith(("error", "pageerror"))] == []
    page.close()


def test_the_presentation_fits_a_phone(browser, url) -> None:
    """At 390 x 844 nothing is wider than the phone (one column, scrolled down)."""
    page, _ = open_present(browser, url + "?view=present", (390, 844))
    page.wait_for_function(JS_READY, timeout=60_000)
    shown = laid_out(page)
    assert shown["scroll"][0] <= 390
    assert_readable(shown)
    page.close()


def px(size: str) -> float:
    """A Bokeh font size ('12pt', '16px') in CSS px."""
    value, unit = re.fullmatch(r"([\d.]+)(pt|px)", size).groups()
    return float(value) * (4 / 3 if unit == "pt" else 1)


def tick_sizes(page) -> list[float]:
    return [px(s) for p in page.evaluate(JS_LAYOUT)["plots"] for s in p["ticks"]]


def test_the_projector_box_enlarges_the_type(browser, url) -> None:
    """At 1920 x 1080 the projector box makes every tick label 24 px at least, and
    nothing collides; unticked, the type is as before."""
    page, _ = open_present(browser, url + "?view=present", (1920, 1080))
    page.wait_for_function(JS_READY, timeout=60_000)
    before = tick_sizes(page)
    assert before and max(before) < 24
    box = page.get_by_role("checkbox", name=PROJECTOR_LABEL)
    box.check()
    wait_until(lambda: min(tick_sizes(page)) >= 24, what="tick labels of 24 px")
    assert_readable(laid_out(page))
    box.uncheck()
    wait_until(lambda: tick_sizes(page) == before, what="the tick labels as before")
    page.close()


#: The presets whose figure is not T(tau), and the titles of that figure's plots.
FIGURES = {
    "fig4": ["Height of the lower sphere u_z0 / H (Fig. 4a)",
             "Approach α/(H−h), contact radius a/a*, stick radius b/a*"],
    "fig8": ["Tangential impulse T_imp / (μ P_imp)"],
    "fig9": ["Contact-centre velocity (Fig. 9a)", "Contact-centre displacement (Fig. 9b)"],
}


def curve_titles(page) -> list[str]:
    """The titles of the plots drawn but the spheres, the traction profile and the disc."""
    return sorted(p["title"] for p in page.evaluate(JS_LAYOUT)["plots"]
                  if p["title"] not in ("Two spheres in section", "Traction profile",
                                        "Contact disc (top view)"))


def test_a_presets_figure_replaces_t_of_tau(browser, url) -> None:
    """Choosing the preset of Fig. 4, 8 or 9 shows its figure under the traction
    profile, with its data; Reset (a T(tau) preset) shows T(tau) again."""
    page, console = open_present(browser, url + "?view=present", (1920, 1080))
    page.wait_for_function(JS_READY, timeout=60_000)
    assert curve_titles(page) == ["Tangential force T / T₀"]
    menu = page.get_by_role("combobox", name="Preset: the paper's figures")
    for preset, titles in FIGURES.items():
        menu.select_option(label=PRESETS[preset].label)
        wait_until(lambda t=titles: curve_titles(page) == sorted(t),
                   what=f"the plots of {preset}: {titles}")
        assert_readable(laid_out(page))
    page.get_by_role("button", name="Reset").click()
    wait_until(lambda: curve_titles(page) == ["Tangential force T / T₀"],
               what="T(tau) after Reset")
    assert [m for m in console if m.startswith(("error", "pageerror"))] == []
    page.close()


def ax_roles(page) -> list[tuple[str, str]]:
    """The landmarks of Chromium's accessibility tree: (role, name)."""
    cdp = page.context.new_cdp_session(page)
    nodes = cdp.send("Accessibility.getFullAXTree")["nodes"]
    return sorted((n["role"]["value"], n.get("name", {}).get("value", ""))
                  for n in nodes if not n.get("ignored")
                  and n.get("role", {}).get("value") in ("banner", "complementary", "main"))


def test_the_presentation_has_landmarks_and_passes_axe(browser, url) -> None:
    """The header a banner, the controls a complementary region named "Controls", the
    scenes the main region; axe-core finds nothing serious or critical, and nothing
    outside the landmarks."""
    from axe_playwright_python.sync_playwright import Axe

    page, _ = open_present(browser, url + "?view=present", (1920, 1080))
    page.wait_for_function(JS_READY, timeout=60_000)
    page.wait_for_function("() => Bokeh.documents[0].is_idle", timeout=20_000)
    assert ax_roles(page) == [("banner", ""), ("complementary", "Controls"), ("main", "")]
    findings = Axe().run(page).response["violations"]
    page.close()
    assert {f["id"]: [n["target"] for n in f["nodes"]] for f in findings
            if f["impact"] in ("serious", "critical")} == {}
    assert [(f["id"], len(f["nodes"])) for f in findings
            if f["id"] == "region" or f["id"].startswith("landmark")] == []
