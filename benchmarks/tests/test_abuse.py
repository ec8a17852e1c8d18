"""The abuse mode's report and its reading of the Methods card (benchmarks/app/abuse.py)."""

from __future__ import annotations

import json

import pytest

from benchmarks.app import abuse


def window(kind: str, latencies: list[float], for_kind: str, round_: int = 1,
           answered: int = 60, sent: int = 66, load: float = 1.0, **more) -> dict:
    """A window's row as `run_abuse` gives it: the probe's move latencies (ms) and what
    the abuser did."""
    return {"kind": kind, "for": for_kind, "round": round_,
            "p50_ms": abuse.pct(latencies, 50), "p95_ms": abuse.pct(latencies, 95),
            "answered": answered, "moves_sent": sent, "server_cpu_pct": 40, "log_lines": 3,
            "tracebacks": 0, "load_average": load, "latencies_ms": latencies,
            "abuser": more}


def test_abuse_summary_and_table():
    """Per kind the windows' latencies pooled: nan's p95 140 over 100 in both rounds
    (1.4, within its 1.5), pull-doc's 400 over 80 (5.0, over its 1.2)."""
    rows = [window("baseline", [100.0] * 20, "nan", 1),
            window("nan", [140.0] * 20, "nan", 1, sent=100),
            window("baseline", [50.0] * 10 + [100.0] * 10, "nan", 2),
            window("nan", [70.0] * 10 + [140.0] * 10, "nan", 2, sent=100, load=2.5),
            window("baseline", [80.0] * 20, "pull-doc"),
            window("pull-doc", [400.0] * 20, "pull-doc", answered=20, replies=69)]
    summary = abuse.abuse_summary(rows)
    assert [(s["kind"], s["ratio"], s["target"], s["met"]) for s in summary] == [
        ("nan", pytest.approx(1.4), 1.5, True), ("pull-doc", pytest.approx(5.0), 1.2, False)]
    assert summary[0]["round_ratios"] == [pytest.approx(1.4), pytest.approx(1.4)]
    table = abuse.abuse_table(rows).splitlines()
    assert len(table) == 4
    assert table[2].startswith("| nan | 100 / 140 | 100 / 140 | 1.40 | 1.5 | 1.40, 1.40 | yes "
                               "| 120/132 / 120/200 | 40 / 40 | 3 / 3 | 0 | 1.0-2.5 |")
    assert table[3].startswith("| pull-doc | 80 / 400 | 80 / 400 | 5.00 | 1.2 | 5.00 | **no** |")
    assert table[3].endswith("| replies 69 |")


def test_methods_controls_found_in_the_cards_patch():
    patch = {"events": [{"kind": "ModelChanged", "new": [
        {"type": "object", "name": "MultiChoice", "id": "p1",
         "attributes": {"options": ["mdr", "annulus"], "value": ["mdr"]}},
        {"type": "object", "name": "panel.models.widgets.CustomSelect", "id": "p2",
         "attributes": {"options": [["1.0", "default"], ["16.0", "16 × default"]]}},
        {"type": "object", "name": "CheckboxGroup", "id": "p3",
         "attributes": {"labels": [abuse.LIVE_LABEL]}}]}]}
    assert abuse.methods_controls([json.dumps(patch)]) == {
        "methods": ("p1", ["mdr", "annulus"]), "resolution": ("p2", "16.0"),
        "live": ("p3", [0])}
    with pytest.raises(LookupError, match="live"):
        patch["events"][0]["new"].pop()
        abuse.methods_controls([json.dumps(patch)])
