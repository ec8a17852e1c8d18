"""The load test's per-process and sizing figures (benchmarks/app/load_figures.py)."""

from __future__ import annotations

import pytest

from benchmarks.app import load_figures as lf


def test_cpu_spread_is_the_busiest_process_over_the_mean():
    cpu0 = {1: 10.0, 2: 20.0, 3: 0.0}
    cpu1 = {1: 13.0, 2: 21.0, 3: 5.0}  # 3 is not a serving process
    spread = lf.cpu_spread(cpu0, cpu1, wall=10.0, serving=[1, 2])
    assert spread == {"cpu_pct": [30, 10], "max_over_mean": 1.5}
    # a serving process that is gone counts as idle
    assert lf.cpu_spread(cpu0, {1: 13.0}, 10.0, [1, 2]) == {"cpu_pct": [30, 0],
                                                             "max_over_mean": 2.0}


def test_sessions_by_replica_follow_the_last_page_of_each_route():
    log = [
        {"request": "GET /main HTTP/1.1", "route": "a", "upstream": "h:1"},
        {"request": "GET /main/ws HTTP/1.1", "route": "a", "upstream": "h:2"},
        {"request": "GET /main HTTP/1.1", "route": "b", "upstream": "h:2"},
        {"request": "GET /main HTTP/1.1", "route": "c", "upstream": "h:1, h:2"},  # retried
        {"request": "GET /static/x.js HTTP/1.1", "route": "d", "upstream": "h:1"},
    ]
    assert lf.sessions_by_replica(log, ["a", "b", "c", "d"], ["h:1", "h:2"]) == [1, 2]


def _row(n: int, p95: float, errors: int = 0, ms: float = 20.0, spread: float = 1.1) -> dict:
    return {"sessions": n, "p95_ms": p95, "errors": errors, "cpu_ms_per_move": ms,
            "cpu_spread": {"cpu_pct": [50, 40], "max_over_mean": spread}}


def test_sizing_takes_the_most_sessions_that_hold():
    rows = [_row(10, 80, ms=18.0), _row(25, 150, ms=22.0, spread=1.2), _row(50, 190, errors=1),
            _row(100, 900)]
    rule = lf.sizing(rows, processes=2, interval=0.3)
    assert rule["sessions_held"] == 25 and rule["students_per_core"] == 12.5
    assert rule["spread_at_held"] == 1.2
    assert rule["cpu_ms_per_move"] == pytest.approx(20.0)
    assert rule["students_per_core_by_cpu"] == pytest.approx(15.0)
    assert "12.5 students per core" in lf.sizing_text(rule, 0.3)


def test_sizing_says_when_nothing_holds():
    rule = lf.sizing([_row(10, 458)], processes=2, interval=0.3)
    assert rule["sessions_held"] == 0
    assert lf.sizing_text(rule, 0.3).startswith("no level kept p95 <= 200 ms")


def test_per_move_in_ms_and_contacts():
    assert lf.per_move(cpu_s=0.9, moves=50, yardstick=15.0) == {"cpu_ms_per_move": 18.0,
                                                                "contacts_per_move": 1200}
    assert lf.per_move(1.0, 0, 15.0)["cpu_ms_per_move"] is None
