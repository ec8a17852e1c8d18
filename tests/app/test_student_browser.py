"""The student view in headless Chromium: the glossary explains a symbol under the
pointer and under the keyboard, an activity checks an answer typed, and with high
contrast axe finds no text below its contrast rules."""

from __future__ import annotations

import pytest
from explorer_browser import open_explorer
from test_browser import errors

pytestmark = pytest.mark.browser


def test_the_glossary_explains_a_symbol_on_hover_and_on_focus(browser, url) -> None:
    page, console = open_explorer(browser, url + "?view=student")
    term = page.locator(".term", has_text="τ₁ (tau1)")
    tip = term.locator(".tip")
    assert not tip.is_visible()
    term.hover()
    tip.wait_for(state="visible", timeout=5_000)
    assert "stick disc disappears" in tip.inner_text()
    page.mouse.move(1, 1)
    tip.wait_for(state="hidden", timeout=5_000)
    term.focus()  # (as the Tab key puts the keyboard on it)
    tip.wait_for(state="visible", timeout=5_000)
    assert errors(console) == []
    page.close()


def test_an_activity_checks_the_answer_typed(browser, url) -> None:
    page, console = open_explorer(browser, url + "?view=student")
    page.get_by_label("Activity").select_option(label="Find where stick ends")
    page.get_by_text("green stick disc").wait_for(timeout=20_000)
    box = page.get_by_label("Your answer")
    box.fill("1.9")
    page.get_by_role("button", name="Check").click()
    page.get_by_text("Not quite.").wait_for(timeout=20_000)
    box.fill("3pi/4")
    page.get_by_role("button", name="Check").click()
    page.get_by_text("Right: τ = 2.356 rad.").wait_for(timeout=20_000)
    assert errors(console) == []
    page.close()


def test_high_contrast_passes_axes_contrast_rule(browser, url) -> None:
    from axe_playwright_python.sync_playwright import Axe

    page, _ = open_explorer(browser, url + "?view=student")
    page.get_by_label("High contrast").check()
    page.wait_for_function("() => [...Bokeh.documents[0].all_models].some((m) => "
                           "m.css_classes != null && m.css_classes.includes('high-contrast'))",
                           timeout=20_000)
    page.wait_for_function("() => Bokeh.documents[0].is_idle")
    found = Axe().run(page).response["violations"]
    assert [(f["id"], [n["target"] for n in f["nodes"]]) for f in found
            if f["id"] in ("color-contrast", "color-contrast-enhanced")] == []
    page.close()


def test_the_full_page_leads_to_the_student_view_and_back(browser, url) -> None:
    page, _ = open_explorer(browser, url + "?psi=3")
    page.get_by_role("button", name="Student view: plain words, activities").click()
    page.wait_for_function("() => location.search.includes('view=student')", timeout=20_000)
    page.get_by_text("The symbols").wait_for(timeout=30_000)
    assert "psi=3" in page.url
    page.get_by_role("button", name="All scenes and controls (expert)").click()
    page.wait_for_function("() => !location.search.includes('view=')", timeout=20_000)
    assert "psi=3" in page.url
    page.close()
