"""The plots' psi/tau0/tau stamps cover no data (issue 39), in Debian's Chromium: on the
full page at 1920x1080, 1280x720 and on a 390x844 phone, T(tau)'s stamp stands under its
x axis (in a corner it crossed the Coulomb bound on a phone), Fig. 8's where the impulse
ratio has fallen
from its peak (it covered Fig. 7's rising curves and Fig. 8's point "3") and the disc's in
a band below the circle of the largest contact (it crossed that circle).  Measured on
BokehJS's own text boxes and data points (`present_texts`)."""

from __future__ import annotations

import pytest
from explorer_browser import open_explorer, steady
from present_texts import JS_CANVAS_TEXTS, stamp_over_data

from app.contact.state import PRESETS

pytestmark = pytest.mark.browser

FORCE, IMPULSE = "Tangential force T / T₀", "Tangential impulse T_imp / (μ P_imp)"
DISC = "Contact disc (top view)"


def plots_titled(page, title: str) -> list[dict]:
    """The painted plots titled `title` with their texts and data points, once steady."""
    page.wait_for_function("() => Bokeh.documents[0].is_idle", timeout=20_000)
    plots = steady(lambda: page.evaluate(JS_CANVAS_TEXTS))
    found = [p for p in plots if p["title"] == title]
    assert found, [p["title"] for p in plots]
    assert sum(t["stamp"] for p in found for t in p["texts"]) == 1
    return found


@pytest.mark.parametrize("screen", [(1920, 1080), (1280, 720), (390, 844)],
                         ids=["1920x1080", "1280x720", "390x844"])
def test_the_curve_stamps_cover_no_data(browser, url, screen) -> None:
    page, console = open_explorer(browser, url, *screen)
    page.get_by_role("tab", name="T(τ) (Fig. 7)").scroll_into_view_if_needed()
    assert stamp_over_data(plots_titled(page, FORCE)) == []
    assert stamp_over_data(plots_titled(page, DISC)) == []  # (in its band, under a*'s circle)
    for preset in ("fig8", "fig7b"):  # Fig. 8's six points; Fig. 7's family of curves
        page.locator("select").first.select_option(label=PRESETS[preset].label)
        title = IMPULSE if preset == "fig8" else FORCE
        page.wait_for_function(
            "(t) => { const m = [...Bokeh.documents[0].all_models].find("
            "(m) => m.type.endsWith('.Tabs')); return m.tabs[m.active].title.startsWith(t); }",
            arg="Impulse" if preset == "fig8" else "T(τ)", timeout=20_000)
        page.wait_for_function("() => (__col('impulse', 'psi') || []).length > 0"
                               if preset == "fig8" else
                               "() => (__col('force_family', 'label') || []).length === 3",
                               timeout=20_000)
        assert stamp_over_data(plots_titled(page, title)) == [], preset
    assert [m for m in console if m.startswith(("error", "pageerror"))] == []
    page.close()
