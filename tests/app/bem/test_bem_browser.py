"""The "How exact is the model?" card in a real browser (Debian's Chromium through
Playwright): opened, it draws the error map and computes nothing; Compute runs the
referee on the job runner and the browser then holds core.bem's T(tau), stick zone and
fields; a resolution beyond the page's is refused with the command line."""

from __future__ import annotations

import numpy as np
import pytest
from explorer_browser import column, open_explorer
from test_browser import errors

from app.bem import data
from app.bem.view import TITLE
from app.contact.state import ExplorerState

pytestmark = pytest.mark.browser


def test_the_card_computes_on_demand_and_holds_the_referees_numbers(browser, url) -> None:
    page, console = open_explorer(browser, url)
    assert column(page, "bem_map_nu", "err") is None  # not built until opened
    page.get_by_text(TITLE).click()
    page.wait_for_function("() => (__col('bem_map_nu', 'err') || []).length == 7",
                           timeout=30_000)
    rows = data.read_map()
    np.testing.assert_array_equal(column(page, "bem_map_nu", "err"),
                                  [r.worst_T_error for r in data.identical(rows)])
    assert column(page, "bem_T", "T") == []  # nothing computed before Compute
    page.get_by_text("Nothing computed yet: press Compute").wait_for()

    page.get_by_role("button", name="Compute").click()
    steps = data.RESOLUTIONS[0].steps
    page.wait_for_function(f"() => (__col('bem_T', 'T') || []).length == {steps + 1}",
                           timeout=60_000)
    state = ExplorerState()
    run = data.compute(data.request(state.contact(), data.RESOLUTIONS[0]))
    np.testing.assert_allclose(column(page, "bem_T", "T"), run.T, rtol=0, atol=1e-10)
    f = data.field_columns(run, state.tau)
    np.testing.assert_allclose(column(page, "bem_stuck", "x"), f["stuck"]["x"], atol=1e-12)
    np.testing.assert_allclose(column(page, "bem_circles", "r"), f["circles"]["r"],
                               atol=1e-12)
    page.get_by_text("The referee on 16 elements across and 80 time steps").wait_for()
    # the fields are painted: an image renderer of each source has a view
    for source in ("bem_referee", "bem_closed"):
        assert page.evaluate(f"() => __renderer('{source}', 'Image') != null")

    big = data.COMMAND_LINE_ONLY
    page.get_by_label("Resolution").select_option(label=f"{big.label} (command line only)")
    page.get_by_role("button", name="Compute").click()
    page.get_by_text("is more than this page runs").wait_for()
    assert "--grid 64 --steps 200 --json" in page.get_by_text(
        "is more than this page runs").inner_text()
    assert errors(console) == []
    page.close()
