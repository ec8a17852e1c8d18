"""The DEM card's Impacts tab in Chromium (the card served alone): opened with the mouse
and with the keyboard on the card's tab list, a test, material and LAMMPS model chosen in
the page's selects, the curves held in the browser are the shipped numbers; an upload is
scored in the page."""

from __future__ import annotations

import numpy as np
import pytest
from test_dem_browser import JS_LENGTH, card_url  # noqa: F401 (the fixture)

from app.dem import impacts
from app.dem.impacts_view import TEST_OPTIONS
from app.dem.view import TITLE

pytestmark = pytest.mark.browser

JS_COL = """([name, col]) => {
  const m = window.Bokeh.documents[0].get_model_by_name(name);
  const v = m && (m.data instanceof Map ? m.data.get(col) : m.data[col]);
  return v == null ? null : Array.from(v, (x) => (Number.isNaN(x) ? null : x));
}"""


def held(page, name: str, col: str) -> np.ndarray:
    return np.array([np.nan if v is None else v for v in page.evaluate(JS_COL, [name, col])],
                    dtype=float)


def test_choosing_a_test_and_model_shows_their_curves(browser, card_url) -> None:  # noqa: F811
    page = browser.new_page(viewport={"width": 1280, "height": 1200})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(card_url)
        page.get_by_text(TITLE).click()
        page.wait_for_function(JS_LENGTH, arg=["dem_exact", "T"], timeout=30_000)
        tab = page.get_by_role("tab", name="Impacts")
        assert tab.get_attribute("aria-selected") == "false"
        page.get_by_role("tab", name="The paper's loading").focus()
        page.keyboard.press("ArrowRight")
        page.keyboard.press("Enter")
        page.wait_for_function(JS_LENGTH, arg=["dem_impact_exact", "rebound_spin"],
                               timeout=30_000)
        assert tab.get_attribute("aria-selected") == "true"
        # test 4, alumina, mindlin: the reference, LAMMPS and both published series
        assert page.evaluate(JS_LENGTH, ["dem_impact_experiment", "tangential_cor_y"]) > 0
        np.testing.assert_array_equal(
            held(page, "dem_impact_lammps", "tangential_cor"),
            impacts.lammps_curves(4, "alumina", "mindlin").values["tangential_cor"])

        test5 = next(k for k, v in TEST_OPTIONS.items() if v == 5)
        page.locator("select").filter(has_text=test5).select_option(label=test5)
        material = page.locator("select").filter(has_text="polyethylene")
        material.wait_for(state="visible", timeout=30_000)
        material.select_option(label="polyethylene")
        page.locator("select").filter(has_text="mindlin_rescale/force").select_option(
            label="mindlin_rescale/force")
        want = impacts.lammps_curves(5, "polyethylene", "mindlin_rescale/force")
        page.wait_for_function(
            """([n, c, v]) => { const m = window.Bokeh.documents[0].get_model_by_name(n);
                 const d = m.data instanceof Map ? m.data.get(c) : m.data[c];
                 return d != null && d.length > 0 && d[0] === v; }""",
            arg=["dem_impact_lammps", "rebound_spin", float(want.values["rebound_spin"][0])],
            timeout=30_000)
        np.testing.assert_array_equal(held(page, "dem_impact_lammps", "rebound_angle"),
                                      want.values["rebound_angle"])
        np.testing.assert_array_equal(
            held(page, "dem_impact_exact", "rebound_spin"),
            impacts.exact_curves(5, "polyethylene").values["rebound_spin"])
        assert page.evaluate(JS_LENGTH, ["dem_impact_published", "rebound_angle_y"]) == 0
        page.get_by_text("Test 5, polyethylene: worst and mean").wait_for(timeout=10_000)

        ref = impacts.exact_curves(5, "polyethylene")
        k = impacts.EXACT_INCIDENCE.index(30.0)
        row = [30.0, *(float(ref.values[q][k]) for q in impacts.QUANTITIES)]
        row[2] += 1000.0  # the spin 1000 rad/s off
        body = ",".join(impacts.COLUMNS) + "\n" + ",".join(f"{v:.17g}" for v in row) + "\n"
        page.locator("input[type=file]").set_input_files(files=[
            {"name": "mine.csv", "mimeType": "text/csv", "buffer": body.encode()}])
        page.get_by_role("columnheader", name="your file").wait_for(timeout=30_000)
        assert page.get_by_text("worst 1e+03 at 30° · mean 1e+03").is_visible()
        assert errors == []
    finally:
        page.close()
