"""The Motor card's design map without a browser: its data are core's batched kernel
(and so the scalar API), sizes beyond a classroom server's are refused naming the
study's command line, a map computed once is shown at once, its Pareto front is
non-dominated, and a click loads the design under it into the card."""

from __future__ import annotations

import math
import threading

import numpy as np
import pytest
from jobs_helpers import Watched
from test_motor_scene import wait

import app.motor.map_data as md
from app.kit.jobs import RUNNER
from app.motor import MotorScene
from app.motor.state import MotorState
from core.motor import Motor, Rod, best_efficiency, no_load_speed, operating_point
from core.motor.designs import MERITS, design_merits
from core.motor.study import SENSE


def motor_at(values: dict, **si: float) -> Motor:
    """The motor of the card's default values (display units), built here, with SI
    overrides (preload, amplitude, frequency, R)."""
    rod = Rod(half_length=values["L"] / 1e3, thickness=values["delta"] / 1e3,
              nu_rod=values["nu_rod"], amplitude=si.get("amplitude", values["A"] / 1e6),
              frequency=si.get("frequency", values["f"] * 1e3))
    return Motor(rod, R=si.get("R", values["R"] / 1e3), G=values["G"] * 1e9, nu=values["nu"],
                 mu=values["mu"], preload=si.get("preload", values["N"]))


def same(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or a == b


@pytest.mark.parametrize(("x", "y"), [("x0", "N"), ("A", "R"), ("x0", "load")])
def test_the_map_is_design_merits_at_its_grid_points(x: str, y: str) -> None:
    values = MotorState().values()
    data = md.compute(md.MapRequest.of(values, x, y, 7))
    assert data.x.size == data.y.size == 7 and data.merits["stall_thrust"].shape == (7, 7)
    L = values["L"]
    if x == "x0":
        np.testing.assert_allclose(data.x[[0, -1]], [-0.999 * L, 0.999 * L], rtol=1e-15)
    checked = 0
    finite = list(zip(*np.nonzero(np.isfinite(data.merits["best_efficiency"])), strict=True))
    for j, i in [(0, 0), (6, 6), *finite[:: max(1, len(finite) // 4)]]:
        v = {**values, x: data.x[i], y: data.y[j]}
        m = motor_at(v, preload=v["N"], amplitude=v["A"] / 1e6, frequency=v["f"] * 1e3,
                     R=v["R"] / 1e3)
        ref = design_merits(m, v["x0"] / 1e3, v["load"], v["k"] * 1e-6, v["hardness"] * 1e9)
        for name in MERITS:
            assert same(float(data.merits[name][j, i]), float(getattr(ref, name))), name
        checked += np.isfinite(ref.best_efficiency)
    assert checked >= 3  # the points compared are in the model's range
    assert np.isfinite(data.merits["stall_thrust"]).sum() >= 10


def test_one_design_of_the_map_is_the_scalar_api_to_1e_12() -> None:
    values = MotorState().values()
    data = md.compute(md.MapRequest.of(values, "x0", "load", 21))
    j, i = 1, 5  # x0 = -9.99 mm, a load of 10 mN
    m, x0 = motor_at(values), data.x[i] / 1e3
    load = data.y[j]
    p = m.profile(x0)
    psi, tau0 = float(p.psi), float(p.tau0)
    scale = m.rod.omega * abs(float(m.rod.u0(x0)))
    b = best_efficiency(psi, tau0)
    expected = {"stall_thrust": abs(float(m.stall_thrust(x0))),
                "no_load_speed": no_load_speed(psi, tau0) * scale,
                "best_efficiency": b.efficiency, "best_speed": b.v * scale,
                "best_thrust": b.thrust_ratio * m.mu * m.preload}
    op = operating_point(m, x0, load)
    expected |= {"load_speed": op.speed, "load_efficiency": op.efficiency,
                 "load_power": op.output_power}
    assert 0 < op.efficiency < 1
    for name, value in expected.items():
        assert data.merits[name][j, i] == pytest.approx(value, rel=1e-12, abs=0), name


def test_sizes_beyond_a_classroom_server_are_refused_naming_the_command_line() -> None:
    assert md.check_size("60") == 60 and md.check_size(20) == 20
    with pytest.raises(ValueError, match=r"a 61 × 61 map \(3721 designs\).*at most 60 × 60"
                       r".*`python -m core\.motor\.study run SPEC\.toml`"):
        md.check_size(61)
    for bad, words in (("1", "at least 2"), ("12.5", "whole number"), ("x", "not a number")):
        with pytest.raises(ValueError, match=words):
            md.check_size(bad)
    with pytest.raises(ValueError, match="two different axes"):
        md.MapRequest.of(MotorState().values(), "x0", "x0", 10)


def opened(scene: MotorScene):
    scene.design_map.card.collapsed = False
    m = scene.design_map.map
    m.size_input.value = "6"
    wait()
    return m


def test_the_card_refuses_a_large_map_in_words_and_keeps_its_map(scene) -> None:
    m = opened(scene)
    shown = m.data
    with Watched(RUNNER) as jobs:
        m.size_input.value = "200"
    assert m.message.visible and "python -m core.motor.study run SPEC.toml" in m.message.object
    assert jobs.waiting == 0 and m.data is shown and not m.progress.busy
    m.size_input.value = "6"
    assert not m.message.visible


def test_a_map_computed_once_is_shown_at_once(scene, monkeypatch) -> None:
    m = opened(scene)
    first = m.data
    assert first.request.size == 6 and len(m.cache) >= 1
    assert m.source.data["image"][0].shape == (6, 6)
    np.testing.assert_array_equal(m.source.data["image"][0], first.merits["stall_thrust"] * 1e3)
    m.x_select.value = "A"
    wait()
    assert m.data.request.x == "A" and m.data is not first
    calls = []
    monkeypatch.setattr(md, "compute", lambda r: calls.append(r))  # no computing now
    m.x_select.value = "x0"  # back: from the cache, with no job
    assert m.data is first and not m.progress.busy and calls == []
    m.merit_select.value = "best_efficiency"  # another colour: the same map
    np.testing.assert_array_equal(m.source.data["image"][0], first.merits["best_efficiency"] * 100)
    assert m.colorbar.title == "best efficiency (%)"


def test_the_pareto_front_is_not_dominated_and_dominates_the_rest() -> None:
    data = md.compute(md.MapRequest.of(MotorState().values(), "A", "R", 8))
    for a, b in (("stall_thrust", "best_efficiency"), ("no_load_speed", "wear_rate")):
        front = md.pareto_front(data, a, b)
        A = SENSE[a] * data.merits[a]
        B = SENSE[b] * data.merits[b]
        ok = np.isfinite(A) & np.isfinite(B)
        assert len(front) >= 2
        fa = np.array([A[p] for p in front])
        fb = np.array([B[p] for p in front])
        assert np.all(np.diff(fa) < 0) and np.all(np.diff(fb) > 0)  # best first merit first
        for p in front:  # no design is at least as good in both and better in one
            better = ok & (A >= A[p]) & (B >= B[p]) & ((A > A[p]) | (B > B[p]))
            assert not better.any()
        on = np.zeros_like(ok)
        on[tuple(np.array(front).T)] = True
        for j, i in zip(*np.nonzero(ok & ~on), strict=True):  # each other design: beaten
            assert np.any((fa >= A[j, i]) & (fb >= B[j, i]))


def test_a_click_on_the_map_loads_that_design_into_the_card(scene) -> None:
    m = opened(scene)
    d = m.data
    j, i = 2, 4
    assert m.load(d.x[i] + 0.3 * np.ptp(d.x) / 5, d.y[j] - 0.02)  # the nearest design
    assert scene.state.x0 == d.x[i] and scene.state.N == d.y[j]
    assert scene.inputs["x0"].value == d.x[i] and scene.inputs["N"].value == d.y[j]
    assert m.data is d  # the same map (its other inputs unchanged), now marking the design
    assert m.mark.data == {"x": [d.x[i]], "y": [d.y[j]]}
    wait()
    assert scene.motor.preload == d.y[j] and scene.x0 == pytest.approx(d.x[i] / 1e3, rel=1e-15)
    assert not m.message.visible


def test_a_click_the_card_refuses_says_why_and_changes_nothing(scene, monkeypatch) -> None:
    """A click on a map whose rod is longer than the card's now (the shorter rod's map
    still computing) asks for an x0 off the rod: refused in the card's words."""
    m = opened(scene)
    d = m.data
    release = threading.Event()
    compute = md.compute
    monkeypatch.setattr(md, "compute", lambda r: (release.wait(30), compute(r))[1])
    scene.state.L = 10.0  # x0 = -5 mm stays on the rod; the map of L = 10 mm is asked for
    assert m.data is d and m.progress.busy
    try:
        assert not m.load(d.x[0], d.y[3])  # x0 = -19.98 mm: off a 10 mm rod
    finally:
        release.set()
    assert m.message.visible and "off the rod" in m.message.object
    assert scene.state.x0 == -5.0 and scene.state.N == 0.5
    wait()
    assert m.data.request.size == 6 and dict(m.data.request.others)["L"] == 10.0
    np.testing.assert_allclose(m.data.x[[0, -1]], [-9.99, 9.99], rtol=1e-15)


def test_a_map_from_its_row_blocks_is_the_map_computed_at_once(monkeypatch) -> None:
    """A map is computed in row blocks (one runner job each): assembled, they are the
    map computed in one call, bit for bit."""
    monkeypatch.setattr(md, "BLOCK_DESIGNS", 14)  # 7 x 7: blocks of 2 rows, the last 1
    request = md.MapRequest.of(MotorState().values(), "x0", "N", 7)
    parts = md.blocks(request)
    assert [(b.start, b.stop) for b in parts] == [(0, 2), (2, 4), (4, 6), (6, 7)]
    whole = md.compute(request)
    got = md.assemble(request, [md.compute(b) for b in parts])
    np.testing.assert_array_equal(got.x, whole.x)
    np.testing.assert_array_equal(got.y, whole.y)
    for name in MERITS:
        np.testing.assert_array_equal(got.merits[name], whole.merits[name])
    np.testing.assert_array_equal(got.psi, whole.psi)
    assert [len(md.blocks(md.MapRequest.of(MotorState().values(), "x0", "N", n)))
            for n in (6, 60)] == [3, 60]  # rows of 14 // n designs, at least one


def test_a_map_s_progress_counts_its_blocks_and_designs(monkeypatch) -> None:
    """The progress of a map in blocks: the block running, the blocks and designs done
    (the last block what remains), and no block named for a map of one block."""
    monkeypatch.setattr(md, "BLOCK_DESIGNS", 14)  # 7 x 7: blocks of 2 rows, the last 1
    request = md.MapRequest.of(MotorState().values(), "x0", "N", 7)
    parts = md.blocks(request)
    seen = [md.MapProgress.of(request, parts[k:]) for k in range(len(parts))]
    assert [(p.done, p.blocks, p.designs_done, p.designs) for p in seen] == [
        (0, 4, 0, 49), (1, 4, 14, 49), (2, 4, 28, 49), (3, 4, 42, 49)]
    assert seen[3].status() == ("computing a 7 × 7 map (49 designs): block 4 of 4, 42 of 49 "
                                "designs done…")
    small = md.MapRequest.of(MotorState().values(), "x0", "N", 3)
    assert md.MapProgress.of(small, md.blocks(small)).status() == ("computing a 3 × 3 map "
                                                                   "(9 designs)…")


def finished(m) -> None:
    """Wait until the card's map has all its blocks (each asks for the next when done)."""
    for _ in range(100):
        wait()
        if m._computing is None:
            return
    raise AssertionError("the map's blocks did not finish")


def test_the_card_computes_a_map_block_by_block_and_a_newer_map_replaces_it(
        scene, monkeypatch) -> None:
    m = opened(scene)
    monkeypatch.setattr(md, "BLOCK_DESIGNS", 12)  # 6 x 6: 3 blocks of 2 rows
    bar = m.progress.__panel__()
    seen: list[tuple] = []  # (status, bar's value, bar's max, shown) as each block starts
    m.status.param.watch(lambda e: seen.append((e.new, bar.value, bar.max,
                                                bar.styles["visibility"])), "object")
    with Watched(RUNNER) as jobs:
        m.x_select.value = "A"
        finished(m)
    assert jobs.ran.count(m) == 3  # one job per block
    seen = [row for row in seen if row[0].startswith("computing")]
    assert [row[1:] for row in seen] == [(0, 36, "visible"), (12, 36, "visible"),
                                         (24, 36, "visible")]
    assert [f"block {k} of 3, {12 * (k - 1)} of 36 designs done" in row[0]
            for k, row in enumerate(seen, 1)] == [True] * 3
    assert bar.styles["visibility"] == "hidden" and not m.progress.busy  # the map shown
    expected = md.compute(md.MapRequest.of(scene.state.values(), "A", "N", 6))
    assert m.data.request == expected.request and m.cache.get(expected.request) is m.data
    np.testing.assert_array_equal(m.data.merits["stall_thrust"], expected.merits["stall_thrust"])
    release = threading.Event()
    compute = md.compute
    monkeypatch.setattr(md, "compute", lambda r: (release.wait(30), compute(r))[1])
    with Watched(RUNNER) as jobs:
        m.x_select.value = "R"  # its first block runs, held ...
        assert "block 1 of 3" in m.status.object and m.progress.busy
        m.x_select.value = "f"  # ... a newer map replaces the blocks to come
        release.set()
        finished(m)
    assert m.data.request.x == "f" and not m.progress.busy
    assert m.cache.get(md.MapRequest.of(scene.state.values(), "R", "N", 6)) is None
    assert jobs.ran.count(m) <= 4  # R's running block at most, then f's three
