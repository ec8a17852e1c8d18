"""Run a design study on Dask distributed: the same code from a laptop to a cluster.

``run_study`` creates (or reopens) the study's store, and sends every unfinished chunk
as one task (``chunks.evaluate_chunk``: a block of ``StudySpec.block`` designs) to a
Dask cluster: an embedded ``LocalCluster`` of worker processes on this machine by
default, or an existing scheduler (``scheduler="tcp://HOST:8786"``, or the environment's
``DASK_SCHEDULER_ADDRESS``). Results come back to this process, which alone writes the
store, chunk by chunk, each chunk marked once its data are written (``store``).

Bounds: at most ``in_flight`` tasks (default: twice the cluster's threads) are
submitted or held at once, so neither the scheduler's queue nor this process's memory
grows with the study; a LocalCluster's workers each get ``memory_limit``. A worker lost
mid-study loses its running task, which the scheduler runs again elsewhere: every chunk
is written exactly once per run, with the bytes of any other run. Ctrl-C (or any
exception, e.g. from ``on_chunk``) cancels the tasks in flight and leaves the store
with its finished chunks: running the study again resumes it.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from core.motor.study import store
from core.motor.study.chunks import chunk_ids, chunk_name, evaluate_chunk
from core.motor.study.spec import StudySpec, code_version

#: Memory per LocalCluster worker process.
MEMORY_LIMIT = "2GiB"


@dataclass(frozen=True)
class StudyRun:
    """What one run did: the store, the chunks computed by this run and those already
    finished before it, the total, the designs per second of this run and its wall
    time (s)."""

    path: Path
    computed: int
    reused: int
    chunks: int
    designs: int
    seconds: float

    @property
    def complete(self) -> bool:
        return self.computed + self.reused == self.chunks


def scheduler_address(scheduler: str | None = None) -> str | None:
    """The scheduler to use: the argument, else DASK_SCHEDULER_ADDRESS, else None (an
    embedded LocalCluster)."""
    return scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS") or None


def local_cluster_options(workers: int, memory_limit: str = MEMORY_LIMIT) -> dict:
    """LocalCluster's arguments: ``workers`` single-threaded processes of
    ``memory_limit`` each, scheduler and workers on loopback, no dashboard (its HTTP
    server, which the scheduler always starts, on a free loopback port)."""
    return {"n_workers": workers, "threads_per_worker": 1, "processes": True,
            "memory_limit": memory_limit, "host": "127.0.0.1",
            "dashboard_address": "127.0.0.1:0", "scheduler_kwargs": {"dashboard": False}}


#: Dask's settings for a LocalCluster: its processes' periodic housekeeping made rare.
#: Idle, a worker process spends ~4 % of a core on its event loop's 20 ms tick, its
#: statistical profiler (a stack sample every 10 ms) and its 0.5 s system monitor, and
#: the scheduler and the nannies ~5 % more: on a machine whose every core runs a worker
#: that time is taken from the workers (measured with ``benchmarks.core.study``: ~0.7 %
#: per worker and ~2 % for the rest with these settings). A cluster of its own (a
#: scheduler's address) keeps its own settings (docs/study.md lists these for it).
LOCAL_CONFIG: dict[str, object] = {
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.profile.enabled": False,
    # a worker thread holds one task, the next sent when it ends (~ms): at the end of a
    # study no worker waits on a task queued behind another's (the default 1.1 sends 2)
    "distributed.scheduler.worker-saturation": 1.0,
}


def local_cluster(workers: int, memory_limit: str = MEMORY_LIMIT):
    """A LocalCluster of ``workers`` single-threaded processes (``local_cluster_options``)
    with ``LOCAL_CONFIG`` (its nannies hand the settings to their worker processes)."""
    import dask
    from distributed import LocalCluster

    with dask.config.set(LOCAL_CONFIG):
        return LocalCluster(**local_cluster_options(workers, memory_limit))


def _client(scheduler: str | None, workers: int | None, memory_limit: str):
    """(client, cluster or None): a Client of the scheduler, or of a new LocalCluster
    of ``workers`` single-threaded processes (default: one per CPU)."""
    from distributed import Client

    address = scheduler_address(scheduler)
    if address:
        return Client(address, timeout="30s"), None
    n = workers or os.cpu_count() or 1
    cluster = local_cluster(n, memory_limit)
    return Client(cluster), cluster


def run_study(spec: StudySpec, folder: str | Path, *, scheduler: str | None = None,
              workers: int | None = None, client: object | None = None,
              in_flight: int | None = None, memory_limit: str = MEMORY_LIMIT,
              progress: bool = False,
              on_chunk: Callable[[tuple[int, ...], int], None] | None = None) -> StudyRun:
    """Compute every unfinished chunk of ``spec`` into its store in ``folder``.

    Parameters
    ----------
    spec : StudySpec
        The study.
    folder : str or Path
        Where its store is (``spec.store_path(folder)``; made if missing).
    scheduler : str, optional
        An existing Dask scheduler's address (tcp://HOST:8786); default
        DASK_SCHEDULER_ADDRESS, else an embedded LocalCluster.
    workers : int, optional
        Worker processes of the LocalCluster (default: one per CPU).
    client : distributed.Client, optional
        A client to use as it is (neither made nor closed here).
    in_flight : int, optional
        Most tasks submitted at once (default: twice the cluster's threads).
    memory_limit : str
        Memory of each LocalCluster worker.
    progress : bool
        Show a progress bar (tqdm) of the designs.
    on_chunk : callable, optional
        Called as on_chunk(chunk, finished_count) after each chunk is written.

    Returns
    -------
    StudyRun
    """
    from distributed import as_completed

    path = spec.store_path(folder)
    store.create(spec, path)
    done = store.finished(path)
    todo = [c for c in chunk_ids(spec) if chunk_name(c) not in done]
    total = sum(1 for _ in chunk_ids(spec))
    start = time.perf_counter()
    if not todo:
        return StudyRun(path, 0, len(done), total, 0, 0.0)
    own = client is None
    cluster = None
    if own:
        client, cluster = _client(scheduler, workers, memory_limit)
    bar = None
    computed = designs = 0
    pending: dict[object, tuple[int, ...]] = {}
    try:
        if progress:
            from tqdm import tqdm

            bar = tqdm(total=spec.size, initial=spec.size - _designs(spec, todo),
                       unit="design", desc=spec.name, smoothing=0.1)
        check_workers(client)
        limit = in_flight or 2 * max(sum(client.nthreads().values()), 1)
        writer = store.Writer(spec, path)
        queue = iter(todo)
        flow = as_completed()
        for chunk in queue:
            fut = client.submit(evaluate_chunk, spec, chunk, key=_key(spec, chunk),
                                pure=False, retries=2)
            pending[fut] = chunk
            flow.add(fut)
            if len(pending) >= limit:
                break
        for fut in flow:
            chunk = pending.pop(fut)
            values = fut.result()
            fut.release()
            writer.write(chunk, values)
            computed += 1
            n = values["psi"].size
            designs += n
            if bar is not None:
                bar.update(n)
            if on_chunk is not None:
                on_chunk(chunk, len(done) + computed)
            nxt = next(queue, None)
            if nxt is not None:
                fut = client.submit(evaluate_chunk, spec, nxt, key=_key(spec, nxt),
                                    pure=False, retries=2)
                pending[fut] = nxt
                flow.add(fut)
    finally:
        for fut in list(pending):
            fut.cancel()
        if bar is not None:
            bar.close()
        if own:
            client.close()
            if cluster is not None:
                cluster.close()
    return StudyRun(path, computed, len(done), total, designs, time.perf_counter() - start)


def check_workers(client) -> None:
    """ValueError unless every worker runs this process's code (``code_version``): a
    store's key names the code that computed it."""
    mine = code_version()
    theirs = client.run(code_version)
    other = sorted(w for w, v in theirs.items() if v != mine)
    if other:
        raise ValueError(f"the workers {', '.join(other)} run other code than this client "
                         f"(code version {theirs[other[0]]}, here {mine}): run the study "
                         "from the workers' installation (e.g. their image)")


def _designs(spec: StudySpec, chunks: list[tuple[int, ...]]) -> int:
    from core.motor.study.chunks import chunk_slices

    count = 0
    for c in chunks:
        n = 1
        for s in chunk_slices(spec, c):
            n *= s.stop - s.start
        count += n
    return count


def _key(spec: StudySpec, chunk: tuple[int, ...]) -> str:
    """The task's key: the study's key and the chunk (unique per run, see pure=False)."""
    return f"study-{spec.key}-{chunk_name(chunk)}-{time.monotonic_ns()}"
