"""core.dem_check.vectors and the command line: the exported files describe themselves,
round-trip to the exact values, and a malformed file is refused naming its row or column."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from core.dem_check import CASES, Case, exact, lammps
from core.dem_check.__main__ import main
from core.dem_check.vectors import SCHEMA_VERSION, export, lj_table, read_history


@pytest.fixture(scope="module")
def exported(tmp_path_factory) -> Path:
    two = {n: CASES[n] for n in ("full_stick", "fig7_psi2.41")}
    return export(tmp_path_factory.mktemp("vectors"), two).parent


def test_index_lists_cases_with_schema_and_exact_scalars(exported: Path) -> None:
    index = json.loads((exported / "index.json").read_text())
    assert index["schema"] == "zharii-dem-vectors" and index["schema_version"] == SCHEMA_VERSION
    entry = {e["name"]: e for e in index["cases"]}["fig7_psi2.41"]
    assert entry["impulse_ratio"] == pytest.approx(0.7580806319327227, rel=1e-15)
    assert entry["tau1"] == pytest.approx(3 * math.pi / 4)
    assert entry["lj"]["P0"] == 1.0 and entry["lj"]["T0"] == 0.2
    for f in entry["files"].values():
        assert (exported / f).is_file()


def test_csv_round_trips_to_the_exact_values(exported: Path) -> None:
    header, cols = read_history(exported / "fig7_psi2.41.csv")
    ref = exact(CASES["fig7_psi2.41"])
    assert header["name"] == "fig7_psi2.41" and header["schema"].endswith(str(SCHEMA_VERSION))
    for name in ("tau", "T", "P", "work"):
        np.testing.assert_array_equal(cols[name], getattr(ref, name))
    np.testing.assert_array_equal(cols["phase"], ref.phase)


def test_lj_vectors_are_the_decks_path() -> None:
    """Centre distance 2 - alpha; velocities the position increments; P0 = 1, T0 = mu."""
    c = Case(psi=2.0, tau0=0.3)
    t = lj_table(c, 400)
    tau = c.tau0 + t["time"]
    alpha = 1e-7 * (np.sin(tau) - math.sin(c.tau0))
    dist = np.hypot(t["x"], 2.0 - t["z"])
    np.testing.assert_allclose(2.0 - dist, alpha, atol=1e-15)
    np.testing.assert_allclose(np.cumsum(t["vx"] * t["time"][1]) + t["x"][0], t["x"],
                               atol=1e-20)
    assert t["fz"][200] == pytest.approx((math.sin(tau[200]) - math.sin(0.3)) ** 1.5)


def test_cli_scores_an_exported_file_clean(exported: Path, capsys) -> None:
    assert main(["score", str(exported / "fig7_psi2.41.csv"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["max_T_error"] == 0 and abs(out["impulse_ratio_error"]) < 1e-7


@pytest.mark.parametrize(("text", "match"), [
    ("tau,T\n0,0\n", "no column 'P'"),
    ("tau,T,P\n0,0,0\n1,0\n", "line 3: 2 values, expected 3"),
    ("# a: b\ntau,T,P\n0,0,0\n1,x,0\n", "line 4, column 'T': 'x' is not a number"),
    ("# only a header block\n", "no header row"),
    ("tau,T,P\n", "no data rows"),
    ("tau,T,P\n0,0,0\n3.2,nan,0\n", "T[1] = nan is not a finite number"),
])
def test_cli_names_the_row_or_column_of_a_malformed_file(tmp_path, capsys, text, match
                                                         ) -> None:
    f = tmp_path / "h.csv"
    f.write_text(text)
    assert main(["score", str(f), "--case", "partial_stick"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: ") and match in err


def test_cli_refuses_an_unknown_case_and_a_missing_one(tmp_path, capsys) -> None:
    f = tmp_path / "h.csv"
    f.write_text("tau,T,P\n0,0,0\n3.2,0,0\n")
    assert main(["score", str(f), "--case", "nope"]) == 2
    assert "no case named 'nope'; the cases are: full_stick" in capsys.readouterr().err
    assert main(["score", str(f)]) == 2
    assert "--case NAME" in capsys.readouterr().err


def test_deck_is_the_case_and_model(capsys) -> None:
    assert main(["deck", "--case", "preload", "--model", "mindlin/force", "--steps",
                 "500"]) == 0
    text = capsys.readouterr().out
    assert "variable tau0  index -0.5 " in text and "variable model index mindlin/force" in text
    assert "variable steps index 500 " in text
    assert "fix            drive lower move variable v_dx NULL v_dz v_vx NULL v_vz" in text
    assert "damping velocity" in text and "rolling" not in text.split("pair_coeff")[1]
    with pytest.raises(ValueError, match="model must be one of"):
        lammps.deck(CASES["preload"], "hooke")
    with pytest.raises(ValueError, match="steps must be an integer"):
        lammps.deck(CASES["preload"], "mindlin", 2.5)
