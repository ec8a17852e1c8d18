"""app.dem.data: the card's numbers without Bokeh or Panel. The exact columns are
core.dem_check's; an upload is read in memory by core.dem_check's own reader and scored
by its `score`; a malformed upload is refused in words naming the line and column."""

from __future__ import annotations

import math
import shutil
import subprocess
import sys

import numpy as np
import pytest

from app.dem import data
from app.dem.state import DemState
from core.dem_check import CASES, exact, lammps, score
from core.dem_check.vectors import read_history


def csv_bytes(tau, T, P, head: str = "") -> bytes:
    """A history as a CSV file's bytes (17 significant digits: the floats exactly)."""
    rows = (f"{a:.17g},{b:.17g},{c:.17g}" for a, b, c in zip(tau, T, P, strict=True))
    return (head + "tau,T,P\n" + "\n".join(rows) + "\n").encode()


def test_exact_columns_are_core_dem_check_exact() -> None:
    cols = data.exact_columns("partial_stick")
    ref = exact(CASES["partial_stick"], data.EXACT_POINTS)
    np.testing.assert_array_equal(cols["tau"], ref.tau)
    np.testing.assert_array_equal(cols["T"], ref.T)
    np.testing.assert_array_equal(cols["P"], ref.P)
    np.testing.assert_array_equal(cols["minus_P"], -ref.P)


def test_overlay_columns_hold_the_chosen_models_in_lammps_order() -> None:
    cols = data.overlay_columns("fig7_psi2.41", ["mindlin/force", "linear_history"])
    assert cols["label"] == ["LAMMPS linear_history", "LAMMPS mindlin/force"]
    assert cols["color"] == [data.COLORS["linear_history"], data.COLORS["mindlin/force"]]
    tau = cols["xs"][0]
    assert tau.size == 401 and tau[0] == pytest.approx(math.pi / 6, abs=1e-12)
    assert tau[-1] == pytest.approx(5 * math.pi / 6, abs=1e-12)
    # every model rides the Coulomb bound while loading (tau < pi/2) at psi > 1
    load = tau < 1.5
    bound = np.maximum(np.sin(tau[load]) - 0.5, 0.0) ** 1.5
    for T in cols["ys"]:
        np.testing.assert_allclose(T[load], bound, atol=1e-6)
    assert data.overlay_columns("full_stick", [])["xs"] == []


def test_an_upload_of_the_exact_history_scores_no_error() -> None:
    case = CASES["fig7_psi6.46"]
    ref = exact(case)
    h = data.read_upload(csv_bytes(ref.tau, ref.T, ref.P))
    s = data.score_history("fig7_psi6.46", h)
    assert s.max_T_error == 0.0 and s.max_P_error == 0.0
    assert abs(s.impulse_ratio_error) < 1e-6 and abs(s.energy_error) < 1e-6
    assert s.energy_gain == 0.0 and s.coulomb_excess == pytest.approx(0.0, abs=1e-15)
    rows = dict(data.score_rows(s))
    assert rows["impulse ratio T_imp / (μ P_imp)"] == (
        f"{s.impulse_ratio:.7f} (exact {case.contact.impulse_ratio:.7f})")
    assert rows["worst |T − T_exact|"].startswith("0.000e+00 T₀")


@pytest.mark.skipif(shutil.which("lmp") is None,
                    reason="LAMMPS (lmp) is not installed: `make lammps`")
def test_an_upload_of_a_lammps_run_scores_what_score_gives() -> None:
    case = CASES["preload"]
    run = lammps.run(case, "mindlin_rescale", steps=2000)
    h = data.read_upload(csv_bytes(run.tau, run.T, run.P, head="# code: LAMMPS\n"))
    assert data.score_history("preload", h) == score(case, run.tau, run.T, run.P)


def test_the_exported_vectors_upload_and_switch_to_their_case() -> None:
    """The downloaded test vectors read back as the exact history, and their `# name:`
    line picks the case."""
    text = data.vectors_text("grazing")
    assert text.startswith("# schema: zharii-dem-vectors")
    state = DemState(case="critical")
    state.upload(text.encode())
    assert state.case == "grazing" and state.message == ""
    assert state.score.max_T_error == 0.0
    np.testing.assert_array_equal(state.history.T, exact(CASES["grazing"]).T)


def test_an_upload_for_another_case_says_what_it_lacks() -> None:
    ref = exact(CASES["full_stick"])
    state = DemState(case="preload")
    state.upload(csv_bytes(ref.tau, ref.T, ref.P))
    assert state.score is None and state.history is not None
    assert state.message == ("your file cannot be scored against preload: tau must cover "
                             "the contact [-0.5, 3.64159] (rad), got [0.523599, 2.61799]")
    state.case = "full_stick"  # the same history, scored against its own case
    assert state.message == "" and state.score.max_T_error == 0.0


def test_the_upload_cap_is_reachable_by_the_row_cap_and_said_in_words() -> None:
    """The file goes in pieces (`app.dem.upload`): the cap is not the websocket's."""
    assert data.MAX_UPLOAD_BYTES == 2 * 1024 * 1024
    assert 6 * (data.MAX_UPLOAD_ROWS + 1) < data.MAX_UPLOAD_BYTES
    assert data.size_text(data.MAX_UPLOAD_BYTES) == "2 MiB"
    assert data.size_text(360 * 1024) == "360 KiB"
    assert data.size_text(1000) == "1,000 bytes"


GOOD = "tau,T,P\n0,0,0\n3.2,0,0\n"


@pytest.mark.parametrize(("content", "message"), [
    (b"time,T,P\n0,0,0\n", "your file, line 1: no column 'tau' in the header row "
                           "(columns: time, T, P)"),
    (b"# case: x\ntau,T,P\n0,0,0\n1,0.5,0\n2,abc,1\n",
     "your file, line 5, column 'T': 'abc' is not a number"),
    (b"tau,T,P\n0,0,0\n1,0,nan\n", "your file, line 3, column 'P': 'nan' is not a finite "
                                   "number"),
    (b"tau,T,P\n0,0,0\n1,-inf,0\n", "your file, line 3, column 'T': '-inf' is not a finite "
                                    "number"),
    (b"tau,T,P\n0,0\n", "your file, line 2: 2 values, expected 3 (tau, T, P)"),
    (b"tau,T,P\n" + b"0,0,0\n" * 50_001, "your file: more than 50000 rows"),
    (b"tau,T,P\n" + b"0" * (2 * 1024 * 1024), "your file has 2,097,160 bytes, more than "
                                               "the 2,097,152 accepted: keep every k-th "
                                               "step"),
    (b"", "your file is empty: it needs a header row tau,T,P"),
    (b" \n\n", "your file is empty"),
    (b"tau,T,P\n", "your file: no data rows after the header row"),
    (b"\x89PNG\r\n\x1a\n\x00\x00", "your file is not a text CSV (byte 1 is not UTF-8)"),
    (b"tau,T,P\n0,0,0\n\x00\x01garbage", "your file is not a text CSV (line 3 holds the "
                                         "control character 0x00)"),
    (b"tau,T,P\n0,0,0\n1,1.2.3,0\n", "your file, line 3, column 'T': '1.2.3' is not a "
                                     "number"),
    (b"tau,T,P\n" + b"1" * 200_000 + b"\n", "your file, line 2: not a CSV line"),
    (["tau,T,P"], "upload one CSV file"),
    (None, "upload one CSV file"),
])
def test_a_malformed_upload_is_refused_in_plain_words(content, message) -> None:
    with pytest.raises(ValueError) as err:
        data.read_upload(content)
    assert str(err.value).startswith(message)
    state = DemState()
    state.upload(GOOD.encode())
    state.upload(content)  # the last good upload is dropped, the reason kept
    assert state.history is None and state.score is None
    assert state.message == str(err.value)


def test_a_history_that_goes_back_names_its_row() -> None:
    text = "tau,T,P\n0.5,0,0\n1,0,0\n0.9,0,0\n2.7,0,0\n"
    h = data.read_upload(text.encode())
    with pytest.raises(ValueError, match=r"tau must increase: tau\[2\] = 0\.9 <= tau\[1\] = "
                                         r"1\.0 \(x\[k\]: the k-th data row, from 0\)"):
        data.score_history("fig7_psi2.41", h)


def test_a_long_upload_is_drawn_thinned_to_its_last_sample() -> None:
    n = 20_001
    tau = np.linspace(0.0, math.pi, n)
    cols = data.upload_columns(data.History(tau, np.sin(tau), np.sin(tau)))
    assert cols["tau"].size <= data.MAX_PLOT_POINTS + 1
    assert cols["tau"][0] == 0.0 and cols["tau"][-1] == math.pi
    assert data.upload_columns(None)["tau"].size == 0


@pytest.mark.parametrize("bad", ["nope", "", None, 3, ["fig7_psi2.41"], "../etc/passwd"])
def test_only_documented_cases_are_read(bad) -> None:
    with pytest.raises(ValueError, match="the cases are: full_stick, critical"):
        data.check_case(bad)
    with pytest.raises(ValueError):
        DemState(case=bad)


@pytest.mark.parametrize("bad", [["mindlin", "hooke"], [["mindlin"]], "mindlin", [None]])
def test_only_lammps_models_are_overlaid(bad) -> None:
    with pytest.raises(ValueError):
        data.check_models(bad)
    with pytest.raises(ValueError):
        DemState(models=bad)


def test_the_downloads_are_the_case_vectors_and_its_deck() -> None:
    text = data.vectors_text("fig7_psi28.35")
    assert "# name: fig7_psi28.35" in text
    assert data.vectors_filename("fig7_psi28.35") == "fig7_psi28.35.csv"
    model = data.deck_model(["mindlin_rescale/force", "mindlin"])
    assert model == "mindlin"  # the first in LAMMPS' order
    assert data.deck_model([]) == "mindlin"
    deck = data.deck_text("fig7_psi28.35", "mindlin/force")
    assert deck == lammps.deck(CASES["fig7_psi28.35"], "mindlin/force", data.DECK_STEPS)
    assert data.deck_filename("fig7_psi28.35", "mindlin/force") == \
        "fig7_psi28.35.mindlin_force.in"


def test_the_vectors_file_reads_back_with_core_dem_check(tmp_path) -> None:
    f = tmp_path / "v.csv"
    f.write_text(data.vectors_text("critical"))
    header, cols = read_history(f)
    assert header["name"] == "critical"
    np.testing.assert_array_equal(cols["T"], exact(CASES["critical"]).T)


def test_the_data_module_loads_neither_bokeh_nor_panel() -> None:
    code = ("import sys, app.dem.data, app.dem.overlays; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] in ('bokeh', 'panel')))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "[]"
