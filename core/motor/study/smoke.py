"""The deployment's smoke test of design studies (``make study-smoke``): a real
``dask scheduler`` and two ``dask worker`` processes on loopback (127.0.0.1, a free
port), the example study ``examples/smoke.toml`` run through ``--scheduler``, the same
study on an embedded LocalCluster, and the two stores compared bit for bit
(``python -m core.motor.study compare``). The scheduler and workers are stopped at the
end, also when a step fails or the run is interrupted.

    python -m core.motor.study.smoke [--keep DIR]
"""

from __future__ import annotations

import argparse
import shutil
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SPEC = Path(__file__).resolve().parent / "examples" / "smoke.toml"


def free_port() -> int:
    """A TCP port free on 127.0.0.1 at the time of asking."""
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _dask() -> str:
    """The ``dask`` command of this environment."""
    exe = Path(sys.executable).parent / "dask"
    return str(exe) if exe.exists() else "dask"


def _stop(procs: list[subprocess.Popen]) -> None:
    """Terminate the processes started here (workers first), then kill any left."""
    for p in reversed(procs):
        if p.poll() is None:
            p.terminate()
    deadline = time.monotonic() + 15
    for p in reversed(procs):
        try:
            p.wait(timeout=max(deadline - time.monotonic(), 0.1))
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()


def _study(*args: str) -> None:
    cmd = [sys.executable, "-m", "core.motor.study", *args]
    print("$", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)


def smoke(work: Path) -> int:
    """Run the smoke test in the folder work; 0 when the stores are equal."""
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    logs = work / "logs"
    logs.mkdir(parents=True, exist_ok=True)
    procs: list[subprocess.Popen] = []
    try:
        procs.append(subprocess.Popen(
            [_dask(), "scheduler", "--host", "127.0.0.1", "--port", str(port),
             "--no-dashboard"], stdout=subprocess.DEVNULL,
            stderr=(logs / "scheduler.log").open("w")))
        for i in range(2):
            procs.append(subprocess.Popen(
                [_dask(), "worker", address, "--host", "127.0.0.1", "--nthreads", "1",
                 "--nworkers", "1", "--no-dashboard", "--name", f"smoke-{i}",
                 "--memory-limit", "1GiB"], stdout=subprocess.DEVNULL,
                stderr=(logs / f"worker-{i}.log").open("w")))
        from distributed import Client

        with Client(address, timeout="60s") as client:
            client.wait_for_workers(2, timeout=120)
            print(f"scheduler {address} with workers "
                  f"{', '.join(sorted(client.scheduler_info()['workers']))}", flush=True)
        _study("run", str(SPEC), "--scheduler", address, "--out", str(work / "scheduler"),
               "--quiet")
        _study("run", str(SPEC), "--workers", "2", "--out", str(work / "local"), "--quiet")
        a = next((work / "scheduler").glob("*.zarr"))
        b = next((work / "local").glob("*.zarr"))
        _study("compare", str(a), str(b))
        print("study-smoke: the store made through the scheduler equals the LocalCluster's "
              "bit for bit")
        return 0
    except subprocess.CalledProcessError as err:
        print(f"study-smoke failed: {err}; logs in {logs}", file=sys.stderr)
        return 1
    finally:
        _stop(procs)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m core.motor.study.smoke")
    parser.add_argument("--keep", help="work in this folder and keep it (default: a "
                        "temporary folder, removed)")
    args = parser.parse_args(argv)
    if args.keep:
        return smoke(Path(args.keep))
    work = Path(tempfile.mkdtemp(prefix="study-smoke-"))
    code = 1
    try:
        code = smoke(work)
    finally:
        if code == 0:
            shutil.rmtree(work, ignore_errors=True)
        else:
            print(f"study-smoke: kept {work} (stores and logs)", file=sys.stderr)
    return code


if __name__ == "__main__":
    sys.exit(main())
