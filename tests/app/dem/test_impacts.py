"""app.dem.impacts: the shipped curves of the Impacts tab are core's numbers (the exact
reference solved again here, LAMMPS run again where `lmp` is installed), the published
values core's, the LAMMPS scores those of docs/impact.md; an uploaded CSV is read and
scored as core's impact scorer does, and each bad file is refused with its reason."""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from app.dem import data, impacts
from core.dem_check import impact as bench
from core.dem_check import impact_data
from core.dem_check.impact_cases import impact_test


@pytest.mark.parametrize(("test", "material", "angles"),
                         [(4, "alumina", (5.0, 30.0, 60.0)), (5, "polyethylene", (17.0,)),
                          (6, "aluminium_alloy", (40.0,))])
def test_the_shipped_reference_is_core_impact_solved_again(test, material, angles) -> None:
    shipped = impacts.exact_curves(test, material)
    assert tuple(shipped.incidence_deg) == impacts.EXACT_INCIDENCE
    for th in angles:
        r = bench.exact(impact_test(test).impact(material, th), impacts.SPRINGS, impacts.TOL)
        k = impacts.EXACT_INCIDENCE.index(th)
        for q in impacts.QUANTITIES:
            np.testing.assert_allclose(shipped.values[q][k], getattr(r, q), rtol=1e-10,
                                       atol=1e-12, err_msg=f"{q} at {th} deg")
    if test == 6:  # no centre tangential velocity: no tangential restitution
        assert np.isnan(shipped.values["tangential_cor"]).all()


@pytest.mark.skipif(shutil.which("lmp") is None, reason="Debian's LAMMPS (make lammps)")
def test_the_shipped_lammps_curve_is_lammps_run_again() -> None:
    """Test 5 (e = 1: no calibration of LAMMPS' dashpot) at 20 deg with mindlin."""
    shipped = impacts.lammps_curves(5, "steel", "mindlin")
    k = int(np.flatnonzero(shipped.incidence_deg == 20.0)[0])
    r = bench.run(impact_test(5).impact("steel", 20.0), "mindlin")
    for q in impacts.QUANTITIES:
        np.testing.assert_allclose(shipped.values[q][k], getattr(r, q), rtol=1e-9)


def test_the_lammps_scores_are_those_of_docs_impact_md() -> None:
    """docs/impact.md's test-4 table: alumina, mindlin: tangential_cor 0.215 (5) /
    0.0206, spin 73.1 (5) / 12.5, rebound angle 3.84 (5) / 0.666."""
    s = impacts.lammps_scores(4, "alumina", "mindlin")
    for q, worst, mean in (("tangential_cor", 0.215, 0.0206), ("rebound_spin", 73.1, 12.5),
                           ("rebound_angle", 3.84, 0.666)):
        assert s[q].worst_incidence == 5.0
        assert s[q].worst == pytest.approx(worst, rel=5e-3)
        assert s[q].mean == pytest.approx(mean, rel=5e-3)
    assert tuple(impacts.lammps_curves(4, "alumina", "mindlin").incidence_deg) == \
        impacts.LAMMPS_INCIDENCE


def test_the_published_values_are_cores_and_only_test_4s() -> None:
    cols = impacts.published(4, "aluminium_alloy", "published")
    x, y = impact_data.published("rebound_spin", "aluminium_alloy")
    np.testing.assert_array_equal(cols["rebound_spin_x"][:x.size], x)
    np.testing.assert_array_equal(cols["rebound_spin_y"][:y.size], y)
    assert np.isnan(cols["rebound_spin_x"][x.size:]).all()
    ex = impacts.published(4, "alumina", "experiment")
    x, y = impact_data.published("tangential_cor", "experiment")
    np.testing.assert_array_equal(ex["tangential_cor_y"][:y.size], y)
    assert impacts.published(4, "aluminium_alloy", "experiment")["tangential_cor_x"].size == 0
    assert impacts.published(5, "steel", "published")["rebound_angle_y"].size == 0


def upload_csv(rows: list[tuple[float, ...]], columns: tuple[str, ...] = impacts.COLUMNS
               ) -> bytes:
    body = "\n".join(",".join(f"{v:.17g}" for v in r) for r in rows)
    return f"# code: mine\n{','.join(columns)}\n{body}\n".encode()


def reference_rows(test: int, material: str, angles) -> list[tuple[float, ...]]:
    ref = impacts.exact_curves(test, material)
    out = []
    for th in angles:
        k = impacts.EXACT_INCIDENCE.index(th)
        out.append((th, *(float(ref.values[q][k]) for q in impacts.QUANTITIES)))
    return out


def test_an_upload_is_scored_as_cores_impact_scorer() -> None:
    rows = reference_rows(4, "alumina", impacts.LAMMPS_INCIDENCE)
    rows[3] = (rows[3][0], rows[3][1] + 0.01, rows[3][2] - 2.0, rows[3][3])  # at 20 deg
    results = impacts.read_upload(upload_csv(rows), 4)
    assert impacts.off_grid(results.incidence_deg) == 0
    s = impacts.scores(results, impacts.reference_at(4, "alumina", results.incidence_deg))
    assert s["tangential_cor"].worst == pytest.approx(0.01, abs=1e-12)
    assert s["tangential_cor"].worst_incidence == 20.0
    assert s["tangential_cor"].mean == pytest.approx(0.01 / 17, abs=1e-12)
    assert s["rebound_spin"].worst == pytest.approx(2.0, abs=1e-9)
    assert s["rebound_angle"].worst == 0.0
    assert impacts.score_text(s["tangential_cor"]) == "worst 0.01 at 20° · mean 0.000588"


def test_the_reference_off_the_grid_is_solved() -> None:
    inc = np.array([12.5, 30.0])
    ref = impacts.reference_at(5, "steel", inc)
    r = bench.exact(impact_test(5).impact("steel", 12.5), impacts.SPRINGS, impacts.TOL)
    assert impacts.off_grid(inc) == 1
    assert ref.values["rebound_spin"][0] == r.rebound_spin
    k = impacts.EXACT_INCIDENCE.index(30.0)
    assert ref.values["rebound_angle"][1] == impacts.exact_curves(5, "steel").values[
        "rebound_angle"][k]


def test_tests_6_to_8_take_results_without_tangential_restitution() -> None:
    rows = [r[:1] + r[2:] for r in reference_rows(6, "aluminium_alloy", (10.0, 50.0))]
    results = impacts.read_upload(upload_csv(rows, ("incidence_deg", "rebound_spin",
                                                    "rebound_angle")), 6)
    assert np.isnan(results.values["tangential_cor"]).all()
    s = impacts.scores(results, impacts.reference_at(6, "aluminium_alloy", results.incidence_deg))
    assert s["rebound_angle"].worst == 0.0 and impacts.score_text(s["tangential_cor"]) == "—"


GOOD = "incidence_deg,tangential_cor,rebound_spin,rebound_angle\n"


@pytest.mark.parametrize(("content", "test", "message"), [
    (b"", 4, "your file is empty: it needs a header row incidence_deg,tangential_cor,"
             "rebound_spin,rebound_angle and a row per incidence"),
    (b"\xff\xfe" + GOOD.encode(), 4, "your file is not a text CSV (byte 1 is not UTF-8)"),
    (GOOD.encode() + b"5,0.7,\x01,1\n", 4,
     "your file is not a text CSV (line 2 holds the control character 0x01)"),
    (b"incidence_deg,rebound_spin,rebound_angle\n5,1,1\n", 4,
     "your file, line 1: no column 'tangential_cor' in the header row (columns: "
     "incidence_deg, rebound_spin, rebound_angle)"),
    ((GOOD + "5,0.7,oops,1\n").encode(), 4,
     "your file, line 2, column 'rebound_spin': 'oops' is not a number"),
    ((GOOD + "5,nan,100,1\n").encode(), 5,
     "your file, line 2, column 'tangential_cor': 'nan' is not a finite number"),
    ((GOOD + "5,0.7,100,1\n90,1,0,0\n").encode(), 4,
     "your file, data row 2: incidence_deg = 90 is outside [0, 90) deg"),
    ((GOOD + "5,0.7,100,1\n" * 101).encode(), 4, "your file: more than 100 rows"),
    (GOOD.encode(), 4, "your file: no data rows after the header row"),
    (b"x" * (data.MAX_UPLOAD_BYTES + 1), 4,
     "your file has 2,097,153 bytes, more than the 2,097,152 accepted: keep every k-th step"),
])
def test_a_bad_upload_is_refused_with_its_reason(content, test, message) -> None:
    with pytest.raises(ValueError) as err:
        impacts.read_upload(content, test)
    assert str(err.value) == message


def test_bad_choices_are_refused() -> None:
    with pytest.raises(ValueError, match="test must be one of 4, 5, 6, 7, 8, got 3"):
        impacts.check_choice(3, "alumina")
    with pytest.raises(ValueError, match="material must be one of steel, polyethylene"):
        impacts.exact_curves(5, "alumina")
    with pytest.raises(ValueError, match="model must be one of linear_history"):
        impacts.lammps_curves(4, "alumina", "hooke")
