"""``python -m core.dem_check impact``: the JSON object, its values, and bad input (exit 2)."""

from __future__ import annotations

import json
import shutil

import pytest

from core.dem_check.__main__ import main
from core.dem_check.impact import exact
from core.dem_check.impact_cases import impact_test


@pytest.mark.parametrize("argv, word", [
    (["--test", "9"], "test must be one of 4, 5, 6, 7, 8"),
    (["--incidence", "95"], "incidence[0] = 95.0 deg is outside [0, 90)"),
    (["--material", "steel"], "material must be one of alumina, aluminium_alloy"),
    (["--model", "hooke"], "model must be one of"),
    (["--incidence", "10", "nan"], "incidence[1]"),
])
def test_bad_input_exits_2_with_one_line(capsys, argv, word):
    assert main(["impact", *argv]) == 2
    err = capsys.readouterr().err
    assert word in err and err.count("\n") == 1


def test_json_of_the_exact_reference(capsys):
    assert main(["impact", "--test", "4", "--material", "alumina", "--incidence", "5", "30",
                 "--no-lammps", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["incidence_deg"] == [5.0, 30.0] and out["lammps"] is None
    for i, th in enumerate((5.0, 30.0)):
        r = exact(impact_test(4).impact("alumina", th))
        assert out["exact"]["tangential_cor"][i] == r.tangential_cor
        assert out["exact"]["rebound_spin"][i] == r.rebound_spin
        assert out["exact"]["rebound_angle"][i] == r.rebound_angle


def test_json_without_centre_velocity_has_null_tangential_cor(capsys):
    assert main(["impact", "--test", "6", "--incidence", "30", "--no-lammps", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["exact"]["tangential_cor"] == [None]
    assert out["exact"]["rebound_angle"][0] < 0  # the spin drives the contact point back


@pytest.mark.skipif(shutil.which("lmp") is None,
                    reason="LAMMPS' lmp is not installed (make lammps)")
def test_the_issue_command_with_lammps(capsys):
    assert main(["impact", "--test", "4", "--material", "alumina", "--model", "mindlin",
                 "--incidence", "45", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) >= {"incidence_deg", "exact", "lammps"}
    for side in ("exact", "lammps"):
        assert set(out[side]) >= {"tangential_cor", "rebound_spin", "rebound_angle"}
    assert out["lammps"]["tangential_cor"][0] == pytest.approx(
        out["exact"]["tangential_cor"][0], abs=5e-4)
    assert out["scores"]["tangential_cor"]["worst_incidence"] == 45.0
