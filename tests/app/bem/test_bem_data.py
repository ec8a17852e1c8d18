"""The numbers of the "How exact is the model?" card (`app.bem.data`): core.bem's runs,
the referee equal to the closed form at nu = 0 within its discretisation error (as
tests/core/bem/test_paper.py states it), the closed form's traction on the same grid,
the error map equal to its CSV, the cache, and a too-large request refused with the
command line that runs it."""

from __future__ import annotations

import csv
import math
import shlex
from pathlib import Path

import numpy as np
import pytest

from app.bem import data
from core import Contact
from core.bem.__main__ import parser
from core.bem.paper import run_paper

ROOT = Path(__file__).resolve().parents[3]
PSI, TAU0 = 1 + math.sqrt(2), math.pi / 6  # Fig. 4b
COARSE = data.RESOLUTIONS[0]


@pytest.fixture(scope="module")
def nu0() -> data.Referee:
    return data.compute(data.request(Contact(PSI, TAU0, mu=0.2, nu=0.0), COARSE))


@pytest.fixture(scope="module")
def nu3() -> data.Referee:
    return data.compute(data.request(Contact(PSI, TAU0, mu=0.2, nu=0.3), COARSE))


def test_the_run_is_core_bems(nu3) -> None:
    ref = run_paper(PSI, TAU0, 0.3, mu=0.2, grid=COARSE.grid, steps=COARSE.steps)
    np.testing.assert_array_equal(nu3.tau, ref.tau)
    np.testing.assert_allclose(nu3.T, ref.T, rtol=0, atol=1e-13)
    np.testing.assert_allclose(nu3.stick, ref.stick, rtol=0, atol=1e-13)
    assert nu3.worst_T_error == pytest.approx(ref.worst_T_error, abs=1e-13)
    assert nu3.closed == Contact(PSI, TAU0, mu=0.2, nu=0.3)
    # the traction kept, summed over the elements, is the run's force (one scale
    # T0 / (mu p* h^2) for every time)
    assert nu3.centres[1] - nu3.centres[0] == pytest.approx(2 / COARSE.grid)
    loaded = np.abs(nu3.T) > 1e-3
    ratio = nu3.qx.sum(axis=(1, 2))[loaded] / nu3.T[loaded]
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-5)  # (fields kept in float32)


def test_at_nu_0_the_referee_is_the_closed_form_within_its_discretisation(nu0) -> None:
    assert nu0.worst_T_error < 1e-3  # 6.1e-4 on 16 across (docs/bem.md)
    assert np.abs(nu0.Ty).max() < 1e-12 and np.abs(nu0.qy).max() < 1e-12
    for tau in (1.0, 2.2, 2.5):  # slip, partial stick, counter-slip
        k = data.step_at(nu0, tau)
        q, p = data.closed_traction(nu0, nu0.tau[k])
        inside = p > 0
        assert np.abs(nu0.qx[k] - q)[inside].mean() < 0.02  # units mu p*
        assert np.abs(nu0.p[k] - p)[inside].mean() < 0.01  # units p*


def test_the_fields_obey_coulomb_and_the_stuck_elements_are_the_runs(nu3) -> None:
    h = nu3.centres[1] - nu3.centres[0]
    size = np.hypot(nu3.qx, nu3.qy)
    assert (size <= nu3.p * (1 + 1e-6) + 1e-12).all()  # |q| <= mu p (q in mu p*)
    # the stuck elements counted as an equal-area circle are the run's stick radius
    np.testing.assert_allclose(np.sqrt(nu3.stuck.sum(axis=(1, 2)) * h * h / math.pi),
                               nu3.stick, atol=1e-12)
    k = data.step_at(nu3, 2.2)
    qy = nu3.qy[k]
    assert np.abs(qy).max() > 0.01  # Poisson's transverse traction (nu = 0.3)
    np.testing.assert_allclose(qy[:, ::-1], -qy, atol=1e-7)  # odd in y (float32)


def test_field_columns_draw_the_run_and_the_closed_form_at_the_nearest_step(nu3) -> None:
    f = data.field_columns(nu3, 2.21)
    k = data.step_at(nu3, 2.21)
    t = nu3.tau[k]
    assert f["readout"]["tau"] == t and abs(t - 2.21) <= (nu3.tau[1] - nu3.tau[0]) / 2
    x = nu3.centres
    X, Y = np.meshgrid(x, x, indexing="ij")
    c = Contact(PSI, TAU0, mu=0.2, nu=0.3)
    np.testing.assert_allclose(f["closed"]["pt"][0],
                               np.abs(c.traction(np.hypot(X, Y), t)).T, rtol=0, atol=0)
    np.testing.assert_array_equal(f["referee"]["pt"][0], np.hypot(nu3.qx[k], nu3.qy[k]).T)
    np.testing.assert_array_equal(f["referee"]["py"][0], nu3.qy[k].T)
    assert f["circles"]["r"] == [float(c.stick_radius(t)), float(c.contact_radius(t))]
    assert f["readout"]["T_closed"] == pytest.approx(float(c.tangential_force(t)), abs=0)
    assert len(f["stuck"]["x"]) == nu3.stuck[k].sum() > 0
    # the image covers the elements: corner and side
    h = x[1] - x[0]
    assert f["referee"]["x"][0] == pytest.approx(x[0] - h / 2)
    assert f["referee"]["dw"][0] == pytest.approx(len(x) * h)
    arrows = f["referee_arrows"]
    length = np.hypot(arrows["x1"] - arrows["x0"], arrows["y1"] - arrows["y0"])
    assert length.max() == pytest.approx(0.9 * h)


def test_force_columns_are_the_run_and_contact_tangential_force(nu3) -> None:
    f = data.force_columns(nu3, points=200)
    np.testing.assert_array_equal(f["referee"]["T"], nu3.T)
    np.testing.assert_array_equal(f["referee"]["dT"], nu3.T - nu3.closed.tangential_force(nu3.tau))
    assert np.abs(f["referee"]["dT"]).max() == nu3.worst_T_error
    tau = nu3.closed.tau_grid(200)
    np.testing.assert_array_equal(f["closed"]["T"], nu3.closed.tangential_force(tau))


def test_the_map_is_the_csv_and_the_apps_copy_is_the_benchmarks() -> None:
    app_copy = ROOT / "app" / "results" / "bem_error_map.csv"
    assert app_copy.read_bytes() == (ROOT / "benchmarks" / "results" /
                                     "bem_error_map.csv").read_bytes()
    with app_copy.open(newline="") as fh:
        table = list(csv.DictReader(fh))
    rows = data.read_map()
    assert [r.label for r in rows] == [d["label"] for d in table]
    cols = data.map_columns(rows)
    same = [d for d in table if d["label"].startswith("identical")]
    np.testing.assert_array_equal(cols["nu"]["x"], [float(d["nu"]) for d in same])
    np.testing.assert_array_equal(cols["nu"]["err"], [float(d["worst_T_error"]) for d in same])
    pairs = sorted((d for d in table if not d["label"].startswith(("identical", "sweep"))),
                   key=lambda d: float(d["beta"]))
    np.testing.assert_array_equal(cols["pairs"]["x"], [float(d["beta"]) for d in pairs])
    np.testing.assert_array_equal(cols["pairs"]["err"],
                                  [float(d["worst_T_error"]) for d in pairs])
    assert len(cols["sweep"]["x"]) == sum(d["label"].startswith("sweep") for d in table)
    # whiskers: the grid estimate; no 0 on the log axis
    e, g = cols["sweep"]["err"], np.array(
        [float(d["worst_T_error_grid"]) for d in sorted(
            (d for d in table if d["label"].startswith("sweep")), key=lambda d: float(d["beta"]))])
    np.testing.assert_allclose(cols["sweep"]["hi"], e + g)
    assert math.isnan(cols["nu"]["model"][0])  # nu = 0: 0, not drawn on a log axis
    # the map read at its rows' nu, and between them linearly
    assert data.map_at(rows, 0.3) == float(same[3]["worst_T_error"])
    mid = 0.5 * (float(same[3]["worst_T_error"]) + float(same[4]["worst_T_error"]))
    assert data.map_at(rows, 0.35) == pytest.approx(mid, rel=1e-12)


def test_a_larger_request_is_refused_with_the_command_line_that_runs_it() -> None:
    c = Contact(PSI, TAU0, mu=0.25, nu=0.3)
    with pytest.raises(ValueError, match=r"python -m core\.bem paper") as err:
        data.request(c, data.COMMAND_LINE_ONLY)
    message = str(err.value)
    command = message[message.index("python -m core.bem"):]
    args = parser().parse_args(shlex.split(command)[3:])
    assert (args.case, args.psi, args.tau0, args.mu, args.nu, args.beta) == (
        "paper", c.psi, c.tau0, c.mu, c.nu, 0.0)
    assert (args.grid, args.steps, args.json) == (64, 200, True)
    for res in (data.Resolution(data.MAX_GRID + 1, 80), data.Resolution(16, data.MAX_STEPS + 2),
                data.Resolution(16, 81)):
        with pytest.raises(ValueError, match="more than this page runs"):
            data.request(c, res)
    for r in data.RESOLUTIONS:  # every resolution offered is run
        assert data.request(c, r).grid == r.grid


@pytest.mark.parametrize("nu", [-0.2, 0.5])
def test_a_contact_outside_the_referees_nu_is_refused(nu: float) -> None:
    with pytest.raises(ValueError, match=r"nu in \[0, 0.5\)"):
        data.request(Contact(PSI, TAU0, mu=0.2, nu=nu), COARSE)


def test_the_cache_keeps_the_newest_few(nu0, nu3) -> None:
    from dataclasses import replace

    cache = data.RunCache(size=2)
    keys = [replace(nu0.key, psi=p) for p in (1.0, 2.0, 3.0)]
    runs = [replace(nu0, key=k) for k in keys]
    cache.put(runs[0])
    cache.put(runs[1])
    assert cache.get(keys[0]) is runs[0]  # now the newest
    cache.put(runs[2])  # drops keys[1], the oldest
    assert len(cache) == 2 and cache.get(keys[1]) is None
    assert cache.get(keys[0]) is runs[0] and cache.get(keys[2]) is runs[2]
