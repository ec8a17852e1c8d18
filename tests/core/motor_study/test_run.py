"""Design studies on a real Dask LocalCluster (two worker processes, shared by these
tests and closed at the end): the store against the in-process evaluation, bit for bit;
an interrupted study resumed; the same spec reusing its store; a worker killed
mid-study; the summary, the Pareto front, the CSV and the command line."""

from __future__ import annotations

import os
import signal
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from core.motor.study import (
    Axis,
    BaseDesign,
    StudySpec,
    best,
    open_study,
    pareto,
    run_study,
)
from core.motor.study.__main__ import main
from core.motor.study.chunks import VARIABLES, chunk_ids, chunk_slices, evaluate_chunk
from core.motor.study.run import local_cluster

distributed = pytest.importorskip("distributed")
pytestmark = pytest.mark.slow  # a real cluster: ~30 s for the module on two cores

#: A small study at a coarse MDR: 6 x 4 designs in 6 chunks of 4.
SPEC = StudySpec("t", (Axis.grid("x0", -0.012, -0.0005, 6),
                       Axis.grid("preload", 0.02, 0.2, 4, "log")),
                 base=BaseDesign(load=1e-3), block=4, springs=40, steps=120)


@pytest.fixture(scope="module")
def client():
    cluster = local_cluster(2, "1GiB")
    c = distributed.Client(cluster)
    try:
        yield c
    finally:
        c.close()
        cluster.close()


def reference(spec: StudySpec) -> dict[str, np.ndarray]:
    """Every variable of the study computed here, chunk by chunk, without Dask."""
    out = {name: np.full(spec.shape, np.nan) for name in VARIABLES}
    for c in chunk_ids(spec):
        values = evaluate_chunk(spec, c)
        for name in VARIABLES:
            out[name][chunk_slices(spec, c)] = values[name]
    return out


def assert_store_equals(path: Path, ref: dict[str, np.ndarray]) -> None:
    ds = open_study(path)
    assert ds.attrs["finished"] == ds.attrs["chunks"]
    for name in VARIABLES:
        assert ds[name].values.tobytes() == ref[name].tobytes(), name


def test_a_study_on_the_cluster_is_the_kernel_bit_for_bit(client, tmp_path: Path) -> None:
    run = run_study(SPEC, tmp_path, client=client)
    assert run.complete and run.computed == 6 and run.designs == 24
    ref = reference(SPEC)
    assert_store_equals(run.path, ref)
    assert np.isfinite(ref["no_load_speed"]).sum() >= 20  # real numbers, not a nan study
    ds = open_study(run.path)
    assert ds["no_load_speed"].attrs["units"] == "m/s"
    assert ds["x0"].attrs["units"] == "m" and ds["preload"].attrs["units"] == "N"
    assert ds["x0"].values.tolist() == list(SPEC.axis("x0").values)
    assert ds.attrs["key"] == SPEC.key
    again = run_study(SPEC, tmp_path, client=client)  # the same spec: the same store
    assert again.path == run.path and again.computed == 0 and again.reused == 6


def test_an_interrupted_study_resumes_without_recomputing(client, tmp_path: Path) -> None:
    seen: list[tuple[int, ...]] = []

    def stop_after_three(chunk: tuple[int, ...], finished: int) -> None:
        seen.append(chunk)
        if finished == 3:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_study(SPEC, tmp_path / "a", client=client, on_chunk=stop_after_three)
    part = open_study(SPEC.store_path(tmp_path / "a"))
    assert part.attrs["finished"] == 3
    resumed = run_study(SPEC, tmp_path / "a", client=client, on_chunk=stop_after_three)
    assert resumed.reused == 3 and resumed.computed == 3 and resumed.complete
    assert len(seen) == 6 and len(set(seen)) == 6  # each chunk written once
    whole = run_study(SPEC, tmp_path / "b", client=client)
    a, b = open_study(resumed.path), open_study(whole.path)
    for name in VARIABLES:
        assert a[name].values.tobytes() == b[name].values.tobytes(), name


def test_summary_pareto_and_csv(client, tmp_path: Path, capsys) -> None:
    run = run_study(SPEC, tmp_path, client=client)
    ds = open_study(run.path)
    thrust = ds["stall_thrust"].values
    row = best(ds, "stall_thrust")
    assert row["stall_thrust"] == np.nanmax(thrust)
    i, j = np.unravel_index(np.nanargmax(thrust), thrust.shape)
    assert (row["x0"], row["preload"]) == (ds["x0"].values[i], ds["preload"].values[j])
    assert best(ds, "wear_rate")["wear_rate"] == np.nanmin(ds["wear_rate"].values)
    front = pareto(ds, "stall_thrust", "no_load_speed")
    a, b = ds["stall_thrust"].values.ravel(), ds["no_load_speed"].values.ravel()
    for _, r in front.iterrows():  # nothing beats a front design in both merits
        assert not np.any((a > r["stall_thrust"]) & (b >= r["no_load_speed"]))
    on = np.isfinite(a) & np.isfinite(b)
    for x, y in zip(a[on], b[on], strict=True):  # every other design is beaten by one
        if not ((front["stall_thrust"] == x) & (front["no_load_speed"] == y)).any():
            assert ((front["stall_thrust"] >= x) & (front["no_load_speed"] >= y)).any()
    assert main(["export", str(run.path), "--csv", str(tmp_path / "t.csv")]) == 0
    table = pd.read_csv(tmp_path / "t.csv")
    assert len(table) == 24 and "no_load_speed (m/s)" in table.columns
    assert np.array_equal(table["stall_thrust (N)"].to_numpy(), thrust.ravel(),
                          equal_nan=True)
    assert main(["summary", str(run.path), "--pareto", "stall_thrust,no_load_speed"]) == 0
    out = capsys.readouterr().out
    assert f"stall_thrust = {float(row['stall_thrust']):.6g} N" in out
    assert f"Pareto front of stall_thrust (N) and no_load_speed (m/s): {len(front)}" in out


def test_the_command_line_runs_on_an_existing_scheduler(client, tmp_path: Path,
                                                        capsys) -> None:
    spec = tmp_path / "s.toml"
    spec.write_text("[study]\nname = 'cli'\nblock = 4\nsprings = 40\nsteps = 120\n"
                    "[design]\nload = 1e-3\n"
                    "[axes.x0]\nstart = -0.012\nstop = -0.0005\nnum = 6\n"
                    "[axes.preload]\nstart = 0.02\nstop = 0.2\nnum = 4\nspacing = 'log'\n")
    address = client.scheduler.address
    t0 = time.perf_counter()
    assert main(["run", str(spec), "--scheduler", address, "--quiet"]) == 0
    assert time.perf_counter() - t0 < 30
    out = capsys.readouterr().out
    assert "6 chunks computed, 0 reused, of 6; 24 designs" in out
    stores = list(tmp_path.glob("cli-*.zarr"))
    assert len(stores) == 1
    assert_store_equals(stores[0], reference(SPEC))
    other = run_study(SPEC, tmp_path / "o", client=client)
    assert main(["compare", str(stores[0]), str(other.path)]) == 0
    assert main(["run", str(spec), "--set", "wheels=3"]) == 2
    assert "unknown design value(s) wheels" in capsys.readouterr().err


# (last: the nanny restarts the killed worker, which then loads the kernels again)
def test_a_worker_killed_mid_study_loses_and_duplicates_nothing(client,
                                                                tmp_path: Path) -> None:
    # a fine MDR: ~0.2 s per chunk, so that both workers are busy when one is killed
    spec = StudySpec("k", SPEC.axes, base=SPEC.base, block=4, springs=800, steps=2400)
    written: list[tuple[int, ...]] = []
    killed: list[int] = []

    def kill_a_busy_worker(chunk: tuple[int, ...], finished: int) -> None:
        written.append(chunk)
        if killed:
            return
        busy = [w for w, tasks in client.processing().items() if tasks]
        if busy:
            pid = client.run(os.getpid, workers=[busy[0]])[busy[0]]
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)

    run = run_study(spec, tmp_path, client=client, on_chunk=kill_a_busy_worker)
    assert killed and run.complete and run.computed == 6
    assert sorted(written) == sorted(chunk_ids(spec))  # none lost, none twice
    assert_store_equals(run.path, reference(spec))
