"""The DEM card's Impacts tab in a Bokeh document (no browser): two tabs under a tab
list, the Impacts tab built when first opened; the test, material and model update the
named sources in place with the shipped numbers; an upload is scored (off the shipped
grid on the job runner) and a bad one refused under the box."""

from __future__ import annotations

import numpy as np
import pytest
from bokeh.document import Document
from jobs_helpers import drained
from test_dem_card import send

from app.dem import impacts
from app.dem.view import TAB_TITLES, DemCard
from app.kit.a11y import TabList
from app.kit.jobs import RUNNER
from core.dem_check import impact as bench
from core.dem_check.impact_cases import impact_test


@pytest.fixture
def tab() -> tuple[DemCard, Document]:
    card = DemCard()
    doc = Document()
    doc.add_root(card.__panel__().get_root(doc))
    card.card.collapsed = False
    return card, doc


def test_the_card_has_two_tabs_and_builds_impacts_when_opened(tab) -> None:
    card, doc = tab
    tablist = card.card.objects[0]
    assert isinstance(tablist, TabList) and tablist.titles == list(TAB_TITLES)
    assert tablist.titles == ["The paper's loading", "Impacts"]
    assert doc.select_one({"name": "dem_exact"}) is not None
    assert card.impacts is None and doc.select_one({"name": "dem_impact_exact"}) is None
    tablist.value = 1  # as the browser's tab button sends it
    assert card.tabs.active == 1 and card.impacts is not None
    assert doc.select_one({"name": "dem_impact_exact"}) is card.impacts.sources["exact"]


def test_choosing_a_test_material_and_model_updates_the_sources(tab) -> None:
    card, doc = tab
    card.tabs.active = 1
    t = card.impacts
    lmp = doc.select_one({"name": "dem_impact_lammps"})
    ex = doc.select_one({"name": "dem_impact_exact"})
    assert len(doc.select_one({"name": "dem_impact_experiment"}).data["rebound_angle_y"]) > 0
    t.test_select.value = 5
    assert t.state.material == "steel" and t.material_select.value == "steel"
    assert t.material_select.options == {"steel": "steel", "polyethylene": "polyethylene"}
    t.material_select.value = "polyethylene"
    t.model_select.value = "mindlin_rescale/force"
    assert doc.select_one({"name": "dem_impact_lammps"}) is lmp
    k = int(np.flatnonzero(lmp.data["incidence_deg"] == 45.0)[0])
    shipped = impacts.lammps_curves(5, "polyethylene", "mindlin_rescale/force")
    assert lmp.data["rebound_spin"][k] == shipped.values["rebound_spin"][k]
    r = bench.exact(impact_test(5).impact("polyethylene", 45.0), impacts.SPRINGS, impacts.TOL)
    j = int(np.flatnonzero(ex.data["incidence_deg"] == 45.0)[0])
    assert ex.data["rebound_spin"][j] == pytest.approx(r.rebound_spin, rel=1e-10)
    assert len(doc.select_one({"name": "dem_impact_published"}).data["rebound_angle_y"]) == 0
    assert "LAMMPS mindlin_rescale/force" in t.score_table.object
    assert "Test 5, polyethylene" in t.score_table.object


def test_an_upload_is_scored_and_a_bad_one_refused(tab) -> None:
    card, _ = tab
    card.tabs.active = 1
    t = card.impacts
    ref = impacts.exact_curves(4, "alumina")
    rows = [(th, ref.values["tangential_cor"][k] + 0.02, ref.values["rebound_spin"][k],
             ref.values["rebound_angle"][k]) for k, th in enumerate(impacts.EXACT_INCIDENCE)
            if th in (10.0, 40.0)]
    rows.append((12.5, 0.7, 200.0, -1.0))  # off the grid: solved on the job runner
    text = "incidence_deg,tangential_cor,rebound_spin,rebound_angle\n" + "\n".join(
        ",".join(f"{v:.17g}" for v in r) for r in rows) + "\n"
    send(t, text.encode())
    assert drained(RUNNER, 60)
    assert t.state.scores is not None and not t.message.visible
    assert t.progress.busy is False
    r = bench.exact(impact_test(4).impact("alumina", 12.5), impacts.SPRINGS, impacts.TOL)
    worst = max(0.02, abs(0.7 - r.tangential_cor))
    assert t.state.scores["tangential_cor"].worst == pytest.approx(worst, rel=1e-9)
    assert "your file" in t.score_table.object
    np.testing.assert_array_equal(t.sources["upload"].data["incidence_deg"], [10, 40, 12.5])

    send(t, b"incidence_deg,tangential_cor,rebound_spin,rebound_angle\n5,x,1,1\n", "t")
    assert t.state.results is None and t.message.visible
    assert "your file, line 2, column &#x27;tangential_cor&#x27;: &#x27;x&#x27; is not a " \
           "number" in t.message.object
    assert "your file" not in t.score_table.object
    assert len(t.sources["upload"].data["incidence_deg"]) == 0
