"""The abuse mode's report and its reading of the Methods card (benchmarks/app/abuse.py)."""

from __future__ import annotations

import json

import pytest

from benchmarks.app import abuse


def window(kind: str, p95: float, answered: int = 60, sent: int = 66, **more) -> dict:
    return {"kind": kind, "p50_ms": p95 / 2, "p95_ms": p95, "answered": answered,
            "moves_sent": sent, "server_cpu_pct": 40, "log_lines": 3, "tracebacks": 0,
            "abuser": more}


def test_abuse_summary_and_table():
    rows = [dict(window("baseline", 100.0), **{"for": "nan"}),
            dict(window("nan", 140.0, sent=100), **{"for": "nan"}),
            dict(window("baseline", 80.0), **{"for": "pull-doc"}),
            dict(window("pull-doc", 400.0, answered=20, replies=69), **{"for": "pull-doc"})]
    summary = abuse.abuse_summary(rows)
    assert [(s["kind"], s["ratio"], s["met"]) for s in summary] == [
        ("nan", pytest.approx(1.4), True), ("pull-doc", pytest.approx(5.0), False)]
    table = abuse.abuse_table(rows).splitlines()
    assert len(table) == 4
    assert table[2].startswith("| nan | 50 / 70 | 100 / 140 | 1.40 | yes | 60/66 / 60/100 |")
    assert table[3].startswith("| pull-doc | 40 / 200 | 80 / 400 | 5.00 | **no** |")
    assert table[3].endswith("| 0 | replies 69 |")


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
