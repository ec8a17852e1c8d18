"""The Methods card (`app.methods`) in a document, no browser: the overlay holds what
`core.numerics` computes, on the job runner; the benchmark charts hold the results files'
numbers; the downloads carry the explorer's header block."""

from __future__ import annotations

import csv
import io
import re
from importlib.metadata import version

import numpy as np
import pandas as pd
import pytest
from bokeh.models import ColorBar
from jobs_helpers import Watched, blocked, drained
from test_document import assert_sources_match_core, contact_of

import app.methods.data
from app.kit.figures import CURVE_POINTS
from app.kit.jobs import RUNNER
from app.methods import DEFAULT_METHODS, MethodsScene
from app.methods.results import FILES, RESULTS
from app.methods.speed_chart import CHECKS, PEERS, STYLE
from app.page.explorer import Explorer
from core import Contact

eq = np.testing.assert_array_equal


@pytest.fixture
def ex() -> Explorer:
    return Explorer()


def ran(ex: Explorer) -> None:
    """Wait for the runner's jobs (and their results shown)."""
    assert drained(RUNNER, 60)


def test_methods_overlay_holds_what_numerics_computes(ex: Explorer) -> None:
    numerics = pytest.importorskip("core.numerics")
    ex.view()
    ex.methods.card.collapsed = False
    ex.methods.choice.value = ["mdr"]
    ran(ex)
    c = contact_of(ex)
    res = numerics.solve("mdr", c, numerics.INTERACTIVE_RESOLUTION["mdr"])
    d = ex.methods.source.data
    assert d["label"] == ["mdr"]
    eq(d["xs"][0], res.tau)
    eq(d["ys"][0], res.T)
    err = np.max(np.abs(res.T - c.tangential_force(res.tau)))
    assert f"| mdr | {res.resolution} | {err:.2e} |" in ex.methods.table.object
    eq(ex.methods.exact.data["T"], c.tangential_force(c.tau_grid(CURVE_POINTS)))
    assert not ex.methods.progress.busy and ex.methods.status.object == ""


def test_methods_run_at_the_resolution_chosen(ex: Explorer) -> None:
    """MDR at 16 x its interactive default (6400 springs) is what numerics computes at
    that resolution; the annulus, whose cost grows faster, stops at 128 rings."""
    numerics = pytest.importorskip("core.numerics")
    ex.methods.card.collapsed = False
    ex.methods.resolution.value = 16.0
    ex.methods.choice.value = ["mdr", "annulus"]
    ran(ex)
    c = contact_of(ex)
    mdr, annulus = ex.methods.results
    assert (mdr.resolution, annulus.resolution) == (
        16 * numerics.INTERACTIVE_RESOLUTION["mdr"], 128)
    eq(mdr.T, numerics.solve("mdr", c, mdr.resolution).T)
    eq(ex.methods.source.data["ys"][1], numerics.solve("annulus", c, 128).T)
    assert f"| mdr | {mdr.resolution} |" in ex.methods.table.object
    ex.methods.resolution.value = 0.25  # a change of resolution runs again
    ran(ex)
    assert ex.methods.results[0].resolution == numerics.INTERACTIVE_RESOLUTION["mdr"] // 4


def test_methods_rerun_live_after_a_change(ex: Explorer) -> None:
    pytest.importorskip("core.numerics")
    ex.methods.card.collapsed = False
    ex.methods.choice.value = ["lammps_mindlin"]
    ex.methods.live.value = True
    ex.contact.controls.psi_slider.value = 0.5
    ran(ex)
    assert ex.methods.results[0].T.shape == ex.methods.source.data["ys"][0].shape
    x = ex.methods.source.data["ys"][0]
    ex.contact.controls.psi_slider.value = 5.0
    ran(ex)
    assert not np.array_equal(ex.methods.source.data["ys"][0][:50], x[:50])


def test_methods_computes_nothing_while_collapsed(ex: Explorer) -> None:
    assert ex.methods.card.collapsed and ex.methods.exact.data["T"] == []
    ex.contact.controls.psi_slider.value = 5.0
    assert ex.methods.exact.data["T"] == []
    ex.methods.card.collapsed = False  # expanding catches up with the parameters
    c = contact_of(ex)
    eq(ex.methods.exact.data["T"], c.tangential_force(c.tau_grid(CURVE_POINTS)))
    # and draws the methods chosen by default, once
    ran(ex)
    assert ex.methods.source.data["label"] == list(DEFAULT_METHODS)
    ex.contact.controls.psi_slider.value = 0.7
    c = contact_of(ex)
    eq(ex.methods.exact.data["T"], c.tangential_force(c.tau_grid(CURVE_POINTS)))


def test_missing_numerics_shows_a_note(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(app.methods.data, "numerics", None)
    ex = Explorer()
    card = ex.methods.view()
    card.collapsed = False  # built when opened
    assert "not available" in card.objects[0].object
    ex.contact.controls.psi_slider.value = 3.0  # the rest still works
    assert_sources_match_core(ex)


# ------------------------------------------------------------ the job runner


def opened() -> MethodsScene:
    s = MethodsScene()
    s.update_contact(Contact(2.414, 0.5236))
    s.card.collapsed = False  # runs the default methods
    assert drained(RUNNER, 60)
    return s


def test_a_newer_run_replaces_the_waiting_one_and_only_it_is_shown() -> None:
    numerics = pytest.importorskip("core.numerics")
    s = opened()
    gate = blocked(RUNNER)
    try:
        with Watched(RUNNER) as jobs:
            s.choice.value = ["mdr"]
            s.choice.value = ["annulus"]  # replaces the waiting run
        assert jobs.waiting == 1 and s.progress.busy
        assert "computing annulus" in s.status.object
    finally:
        gate.set()
    assert drained(RUNNER, 60)
    assert [r.method for r in s.results] == ["annulus"]
    c = s._contact
    n = numerics.INTERACTIVE_RESOLUTION["annulus"]
    eq(s.source.data["ys"][0], numerics.solve("annulus", c, n).T)
    assert not s.progress.busy and s.status.object == ""


def test_a_closed_card_drops_its_waiting_run_and_asks_for_nothing_more() -> None:
    pytest.importorskip("core.numerics")
    s = opened()
    shown = s.source.data
    gate = blocked(RUNNER)
    try:
        with Watched(RUNNER) as jobs:
            s.choice.value = ["mdr"]
            assert jobs.waiting == 1
            s.close()
            assert jobs.waiting == 0  # dropped
            s.choice.value = ["annulus"]  # a closed card asks for nothing more
            assert jobs.waiting == 0
    finally:
        gate.set()
    assert drained(RUNNER, 60)
    assert s.source.data is shown  # nothing ran for it


def test_a_failed_run_ends_the_progress_and_says_why(monkeypatch: pytest.MonkeyPatch
                                                      ) -> None:
    pytest.importorskip("core.numerics")
    s = opened()

    def broken(c, resolutions):
        raise RuntimeError("out of memory")

    monkeypatch.setattr(app.methods.data, "solve_all", broken)
    s.run()
    assert drained(RUNNER, 60)
    assert not s.progress.busy
    assert s.status.object == "⚠ the methods could not run: out of memory"


def test_the_table_gives_times_in_microseconds(ex: Explorer) -> None:
    """Each method's wall time in µs, whole, so that a fast one does not read '0'."""
    pytest.importorskip("core.numerics")
    ex.methods.card.collapsed = False
    ex.methods.choice.value = ["quad", "mdr"]
    ran(ex)
    table = ex.methods.table.object
    assert "| time (µs) |" in table
    for res in ex.methods.results:
        cell = f"{res.wall_time * 1e6:,.0f}"
        assert f"| {res.method} | {res.resolution} |" in table
        assert re.search(rf"\| {res.method} \|.*\| {re.escape(cell)} \|$", table, re.M)
        assert cell != "0"
    assert " ms |" not in table


# ------------------------------------------------------------- benchmarks


def results_rows(name: str) -> list[dict]:
    """The app's results file `name` read with the csv module alone (numbers as floats)."""
    with (RESULTS / name).open(newline="") as fh:
        rows = list(csv.DictReader(fh))
    for r in rows:
        for k, v in r.items():
            if k not in ("method", "regime"):
                r[k] = float(v)
    return rows


def test_the_methods_card_serves_the_speed_chart_one_view_at_a_time(ex: Explorer) -> None:
    """The view picked is drawn from speed_accuracy.csv: per method, each run's median
    time and worst error over the view's cases, its Pareto front, the closed form's
    star (recomputed here from the file's rows)."""
    ex.methods.card.collapsed = False
    key = "regime: preload | relative error"
    ex.methods.speed_view.value = key
    chart = ex.methods.speed_chart
    rows = [r for r in results_rows("speed_accuracy.csv") if r["regime"] == "preload"]
    for name in ("mdr", "direnzo", "gauss_legendre"):
        runs: dict = {}
        for r in rows:
            if r["method"] == name:
                runs.setdefault((r["resolution"], r["steps"]), []).append(r)
        expected = sorted((float(np.median([r["wall_time"] for r in rs])),
                           max(max(r["err_rel"] for r in rs), 1e-17)) for rs in runs.values())
        every, front = chart.sources[name]
        assert sorted(zip(every.data["x"], every.data["y"], strict=True)) == expected
        # the front: the runs that no other run beats in both time and error
        assert list(zip(front.data["x"], front.data["y"], strict=True)) == [
            (t, e) for t, e in expected
            if not any(t2 <= t and e2 <= e and (t2, e2) != (t, e) for t2, e2 in expected)]
    cf = [r for r in rows if r["method"] == "closed_form"]
    assert chart.closed_form.data["x"] == [float(np.median([r["wall_time"] for r in cf]))]
    assert chart.closed_form.data["y"] == [max(r["err_rel"] for r in cf)]
    ex.methods.speed_view.value = "all cases | absolute error"
    assert max(chart.sources["annulus"][0].data["y"]) == max(
        r["err"] for r in results_rows("speed_accuracy.csv") if r["method"] == "annulus")


def test_the_methods_card_serves_the_stability_map_one_method_at_a_time(ex: Explorer
                                                                         ) -> None:
    ex.methods.card.collapsed = False
    method, quantity = ex.methods.stability_controls
    source = ex.methods.stability_source
    rows = results_rows("stability_map.csv")
    for name, col in (("mdr", "err"), ("textbook", "err"), ("textbook", "rel_err_impulse")):
        method.value, quantity.value = name, col
        cells = {(p, t): max(e, 1e-17) for p, t, e in zip(
            source.data["psi"], source.data["tau0"], source.data["shown"], strict=True)}
        assert cells == {(r["psi"], r["tau0"]): max(r[col], 1e-17)
                         for r in rows if r["method"] == name}
    # the colour scale reaches the worst error of any method (the textbook form's)
    bar = next(m for m in ex.methods.stability_plot.right if isinstance(m, ColorBar))
    worst = max(max(r["err"], r["rel_err_impulse"]) for r in rows)
    assert bar.color_mapper.low == 1e-16 and bar.color_mapper.high >= worst > 1e3


def test_every_method_has_its_own_colour_and_marker_in_each_chart() -> None:
    """The speed chart's peers and checks each get a distinct (colour, marker), and every
    method of core.numerics has one (the live overlay uses the same colours)."""
    from core.numerics import METHODS

    assert set(STYLE) == set(METHODS) == {*PEERS, *CHECKS}
    for group in (PEERS, CHECKS):
        assert len({STYLE[m][0] for m in group}) == len(group)
        assert len({STYLE[m][1] for m in group}) == len(group)


@pytest.mark.parametrize(("name", "command"), [
    ("speed_accuracy.csv", "python -m benchmarks.core.methods"),
    ("stability_map.csv", "python -m benchmarks.core.stability_map")])
def test_the_results_downloads_carry_the_explorers_header(ex: Explorer, name: str,
                                                          command: str) -> None:
    """Source, app version, command and each column with its unit, then the very rows
    of the file."""
    ex.methods.card.collapsed = False
    button = next(o for o in ex.methods.card.objects
                  if getattr(o, "filename", None) == name)
    text = button.callback().read().decode("utf-8")
    comments = [line[2:] for line in text.splitlines() if line.startswith("# ")]
    assert comments[0].startswith("Zharii 1996 explorer: ")
    assert any("Zharii" in line and "(1996)" in line for line in comments)
    assert f"app: zharii-contact {version('zharii-contact')}" in comments
    assert any(line.startswith(f"command: {command} ") for line in comments)
    names = (RESULTS / name).read_text().splitlines()[0].split(",")
    assert list(FILES[name].columns) == names  # every column described
    assert "  wall_time (s): " in "\n".join(comments)
    if name == "stability_map.csv":
        assert "  tau0 (rad): " in "\n".join(comments)
    got = pd.read_csv(io.StringIO(text), comment="#")
    pd.testing.assert_frame_equal(got, pd.read_csv(RESULTS / name))


def test_the_benchmark_scripts_are_named_as_code_not_as_links(ex: Explorer) -> None:
    ex.methods.card.collapsed = False
    headings = [o.object for o in ex.methods.card.objects
                if isinstance(getattr(o, "object", None), str) and "<h3>" in o.object]
    assert headings == [
        "<h3>Speed against accuracy (written by <code>benchmarks/core/methods.py</code>)"
        "</h3>",
        "<h3>Stability map (written by <code>benchmarks/core/stability_map.py</code>)</h3>"]


def test_prepare_computes_every_offered_gauss_legendre_rule_once() -> None:
    """The server computes the Gauss-Legendre nodes of every offered resolution at start
    (4,096 nodes took 1.66 s on a visitor's first run at 16 x): afterwards each is a
    cache hit."""
    from core.numerics import quadrature

    app.methods.data.prepare()
    before = quadrature._legendre.cache_info()
    for factor in app.methods.data.RESOLUTION_FACTORS.values():
        n = app.methods.data.resolution("gauss_legendre", factor)
        quadrature.gauss_legendre_nodes(0.0, 1.0, n)
    after = quadrature._legendre.cache_info()
    assert after.misses == before.misses
    assert after.hits - before.hits == len(app.methods.data.RESOLUTION_FACTORS)
    assert app.methods.data.resolution("gauss_legendre", 16.0) == 4096
