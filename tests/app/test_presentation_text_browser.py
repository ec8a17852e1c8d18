"""The text drawn on the presentation view's plots, in Debian's Chromium (issue 39): at
125, 150 and 200 % zoom, on a phone and with the projector's larger type, no two texts
of a plot over each other (the traction caption over the psi/tau0/tau stamp, the phase
badge into the stamp, the pictograms' labels run together: "contactrelease"), none cut
by its frame or canvas (the pictograms' labels, the titles with larger type), no y
tick labels stacked, and no psi/tau0/tau stamp over a curve, a sphere's outline or the
disc's circles (the stamps are outside the frames: `app.kit.figures.stamp_outside`).
The boxes are BokehJS's own (`present_texts.JS_CANVAS_TEXTS`)."""

from __future__ import annotations

import pytest
from explorer_browser import JS_READY, steady
from present_texts import JS_CANVAS_TEXTS, stamp_over_data, text_defects
from test_presentation_browser import open_present

from app.page.projector import LABEL as PROJECTOR_LABEL

pytestmark = pytest.mark.browser

#: (screen in device px, zoom, projector box ticked)
CASES = [((1280, 720), 1.25, False), ((1280, 720), 1.5, False), ((1920, 1080), 2.0, False),
         ((390, 844), 1.0, False), ((1280, 720), 1.0, True)]


@pytest.mark.parametrize(("screen", "zoom", "projector"), CASES,
                         ids=[f"{s[0]}x{s[1]}-{round(100 * z)}{'-projector' if p else ''}"
                              for s, z, p in CASES])
def test_no_text_on_a_plot_collides_or_is_cut(browser, url, screen, zoom, projector) -> None:
    page, console = open_present(browser, url + "?view=present", screen, zoom)
    page.wait_for_function(JS_READY, timeout=60_000)
    if projector:
        page.get_by_role("checkbox", name=PROJECTOR_LABEL).check()
    page.evaluate("() => document.fonts.ready.then(() => true)")
    page.wait_for_function("() => Bokeh.documents[0].is_idle", timeout=20_000)
    plots = steady(lambda: page.evaluate(JS_CANVAS_TEXTS))
    titles = {p["title"] for p in plots}
    assert {"Two spheres in section", "Traction profile", "Contact disc (top view)",
            "Tangential force T / T₀"} <= titles, titles
    # the texts are there to be checked: the stamps, the caption, the badge, the labels
    assert sum(t["stamp"] for p in plots for t in p["texts"]) == 4
    assert sum(len(p["texts"]) for p in plots) >= 25
    if projector:  # the type is larger
        traction = next(p for p in plots if p["title"] == "Traction profile")
        assert min(t["height"] for t in traction["ticks"]) >= 21
    assert text_defects(plots) == []
    assert stamp_over_data(plots) == []
    assert [m for m in console if m.startswith(("error", "pageerror"))] == []
    page.close()


@pytest.mark.parametrize("link", ["psi=30&tau0=-1.2", "psi=1e4"])
def test_no_text_collides_or_is_cut_at_the_edges_of_the_domain(browser, url, link) -> None:
    """At the narrowest plots (1280x720 at 150 %): a contact from early in the period
    (a short gap before it: the strip's word "apart" at its end) and one whose sideways
    drive is beyond the drawing (the spheres' note says so, at length), with the y ticks
    of their T(tau)."""
    page, console = open_present(browser, f"{url}?view=present&{link}", (1280, 720), 1.5)
    page.wait_for_function(JS_READY, timeout=60_000)
    page.evaluate("() => document.fonts.ready.then(() => true)")
    page.wait_for_function("() => Bokeh.documents[0].is_idle", timeout=20_000)
    plots = steady(lambda: page.evaluate(JS_CANVAS_TEXTS))
    assert sum(t["stamp"] for p in plots for t in p["texts"]) == 4
    assert text_defects(plots) == []
    assert stamp_over_data(plots) == []
    assert [m for m in console if m.startswith(("error", "pageerror"))] == []
    page.close()
