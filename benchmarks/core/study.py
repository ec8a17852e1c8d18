"""Cost of design studies (core.motor.designs, core.motor.study), each figure measured
within one run on this machine (timings on a shared machine are noisy: ratios are
measured interleaved).

1. kernel: the batched figures of merit (``design_merits``) against a loop over the
   scalar API giving the same numbers (``Motor.stall_thrust``, ``no_load_speed``,
   ``best_efficiency``, ``operating_point``, ``moving_rotor`` + ``moving_wear_rate``), per
   design, over the designs of ``DESIGNS`` (the README's rotor and a steel ball on
   PZT-4 along the rod, under a load; the default MDR), in ``--repeat`` paired rounds:
   the ratio of the best times and the median of the rounds' ratios. Target: at least
   3 times cheaper. Also the count of designs whose merits are equal bit for bit.
2. contact: the kernel's cost per design as a ratio to one closed-form contact,
   ``Contact(psi, tau0).impulse_ratio`` (eq 41), and its thrust-speed evaluations per
   design.
3. speeds: how the cost grows with the number of speeds per thrust-speed curve
   (``thrust_speed_curve`` with n speeds, per contact), against the kernel's design.
4. scaling: designs per second per worker of a study on a LocalCluster of 1 and of 2
   worker processes (``core.motor.study.run.local_cluster``; the same study; both
   clusters up and every worker warmed, then ``--repeat`` paired rounds, each timing
   both back to back, their order alternating), and the strong scaling t(1) / t(2) of
   best times (each the run the machine disturbed least: the figure) and of each
   round: the best, the median, that of the round the other jobs on the machine
   loaded least and the median of the quiet rounds (``QUIET_CORES``), with the CPU
   seen during each run (/proc/stat's busy cores
   less this process tree's: the other jobs' cores; and the hypervisor's steal).
5. projection: the wall time of a 1e7-design study on 64 cores, from the measured
   cost per design per worker and the measured parallel efficiency.

Run: ``.venv/bin/python -m benchmarks.core.study [--only kernel|contact|speeds|scaling]
[--repeat 5] [--write]`` (--write: benchmarks/results/study_benchmark.json).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from core import Contact
from core.materials import MATERIALS
from core.motor import (
    Motor,
    Rod,
    best_efficiency,
    design_merits,
    moving_rotor,
    moving_wear_rate,
    no_load_speed,
    operating_point,
    thrust_speed_curve,
)
from core.motor.designs import MERITS

RESULTS = Path(__file__).resolve().parents[1] / "results" / "study_benchmark.json"
ROD = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
STEEL, PZT = MATERIALS["steel"], MATERIALS["PZT-4"]
MOTORS = (Motor(ROD, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05),
          Motor(ROD, R=5e-3, G=STEEL.G, nu=STEEL.nu, mu=0.2, preload=0.05, rod_G=PZT.G,
                rod_nu=PZT.nu, rod_R=math.inf))
#: (motor, x0, load): two rotors at 8 points of the rod, under 1 mN.
DESIGNS = [(m, float(x), 1e-3) for m in MOTORS for x in np.linspace(-0.016, -0.0002, 8)]
K, HARD = 1e-6, 5e9
#: The study of the scaling figure: 96 x 80 designs, 24 chunks of 320 (~0.4 s each: the
#: client writes ~20 ms of CPU per chunk, so much smaller chunks would time the client,
#: and far fewer would leave one worker idle at the end).
#: A round is quiet when the other jobs on the machine took at most this many cores
#: during both of its runs.
QUIET_CORES = 0.5
SCALING_TOML = """
[study]
name = "bench"
block = 320
[design]
load = 1e-3
[axes.x0]
start = -0.016
stop = -0.0002
num = 96
[axes.preload]
start = 0.02
stop = 0.5
num = 80
spacing = "log"
"""


def scalar_loop(designs: list) -> list[dict[str, float]]:
    """Every merit of each design from the scalar API (nan where it raises)."""
    out = []
    for m, x0, load in designs:
        row = dict.fromkeys(MERITS, math.nan)
        row["stall_thrust"] = abs(float(m.stall_thrust(x0)))
        p = m.profile(x0)
        psi, tau0 = float(p.psi), float(p.tau0)
        scale = m.rod.omega * abs(float(m.rod.u0(x0)))
        row["no_load_speed"] = no_load_speed(psi, tau0) * scale
        b = best_efficiency(psi, tau0)
        row["best_efficiency"], row["best_speed"] = b.efficiency, b.v * scale
        row["best_thrust"] = b.thrust_ratio * (m.mu * m.preload)
        try:
            op = operating_point(m, x0, load)
        except ValueError:
            out.append(row)
            continue
        row["load_speed"], row["load_efficiency"] = op.speed, op.efficiency
        row["load_power"] = op.output_power
        row["wear_rate"] = float(moving_wear_rate(m, x0, moving_rotor(psi, tau0, op.v),
                                                  K, HARD))
        out.append(row)
    return out


def batch(designs: list):
    return design_merits([d[0] for d in designs], [d[1] for d in designs],
                         [d[2] for d in designs], K, HARD)


def interleaved(fs: dict[str, Callable[[], object]], repeat: int,
                rounds: list[dict[str, float]] | None = None) -> dict[str, float]:
    """Best wall time (s) of each f, timed in turn so that all see the same load (each
    round's times appended to ``rounds`` when given)."""
    best = dict.fromkeys(fs, math.inf)
    for _ in range(repeat):
        times = {}
        for name, f in fs.items():
            t0 = time.perf_counter()
            f()
            times[name] = time.perf_counter() - t0
            best[name] = min(best[name], times[name])
        if rounds is not None:
            rounds.append(times)
    return best


def kernel(repeat: int) -> dict[str, float]:
    got = batch(DESIGNS)  # compiles or loads the kernels
    ref = scalar_loop(DESIGNS)
    equal = sum(all((a == b) or (math.isnan(a) and math.isnan(b))
                    for a, b in ((float(getattr(got, n)[i]), ref[i][n]) for n in MERITS))
                for i in range(len(DESIGNS)))
    rounds: list[dict[str, float]] = []
    t = interleaved({"scalar": lambda: scalar_loop(DESIGNS), "batch": lambda: batch(DESIGNS)},
                    repeat, rounds)
    n = len(DESIGNS)
    per_round = [r["scalar"] / r["batch"] for r in rounds]
    res = {"designs": n, "scalar_ms_per_design": 1e3 * t["scalar"] / n,
           "batch_ms_per_design": 1e3 * t["batch"] / n, "ratio": t["scalar"] / t["batch"],
           "ratio_median_of_rounds": float(np.median(per_round)),
           "equal_bit_for_bit": equal,
           "evaluations_per_design": float(np.mean(got.evaluations))}
    print(f"kernel: {n} designs, scalar loop {res['scalar_ms_per_design']:.2f} ms/design, "
          f"batch {res['batch_ms_per_design']:.2f} ms/design (best of {repeat} paired "
          f"rounds): {res['ratio']:.2f} times cheaper, median of the rounds' ratios "
          f"{res['ratio_median_of_rounds']:.2f} (target >= 3); {equal} of {n} designs "
          f"equal bit for bit; {res['evaluations_per_design']:.1f} MDR contacts per design")
    return res


def contact(repeat: int) -> dict[str, float]:
    batch(DESIGNS[:1])
    psi = [float(m.psi(x)) for m, x, _ in DESIGNS]
    tau0 = [float(m.tau0(x)) for m, x, _ in DESIGNS]

    def closed() -> None:
        for p, t in zip(psi, tau0, strict=True):
            _ = Contact(p, t).impulse_ratio

    t = interleaved({"closed": closed, "batch": lambda: batch(DESIGNS)}, repeat)
    res = {"closed_form_us": 1e6 * t["closed"] / len(psi),
           "ratio_to_closed_form": t["batch"] / t["closed"]}
    print(f"contact: one closed-form contact (Contact(psi, tau0).impulse_ratio) "
          f"{res['closed_form_us']:.1f} us; one design of the kernel = "
          f"{res['ratio_to_closed_form']:.0f} closed-form contacts")
    return res


def speeds(repeat: int) -> dict[str, object]:
    cases = [(float(m.psi(x)), float(m.tau0(x))) for m, x, _ in DESIGNS[::4]]
    counts = (5, 10, 20, 40, 80)
    fs = {n: (lambda n=n: [thrust_speed_curve(p, t, n) for p, t in cases]) for n in counts}
    fs["batch"] = lambda: batch(DESIGNS[::4])
    t = interleaved(fs, max(1, repeat // 2))
    per = {n: 1e3 * t[n] / len(cases) for n in counts}
    slope = np.polyfit(np.array(counts, float), np.array([per[n] for n in counts]), 1)
    res = {"curve_ms": {str(n): per[n] for n in counts}, "ms_per_speed": float(slope[0]),
           "batch_ms_per_design": 1e3 * t["batch"] / len(cases)}
    print("speeds: thrust-speed curve per contact " + ", ".join(
        f"{n}: {per[n]:.1f} ms" for n in counts)
          + f" (least-squares slope {slope[0]:.3f} ms per speed); the kernel's design "
          f"{res['batch_ms_per_design']:.1f} ms ~ a curve of "
          f"{res['batch_ms_per_design'] / slope[0]:.0f} speeds")
    return res


def _cpu_jiffies() -> tuple[int, int, int]:
    """(busy, steal, total) jiffies of the machine since boot (/proc/stat's cpu line)."""
    with open("/proc/stat") as f:
        v = [int(x) for x in f.readline().split()[1:]]
    user, nice, system, _idle, _iowait, irq, softirq, steal = v[:8]
    return user + nice + system + irq + softirq, steal, sum(v[:8])


def _own_cpu() -> float:
    """CPU seconds of this process and its children (the LocalClusters' nannies and
    workers), living or reaped."""
    import psutil

    me = psutil.Process()
    total = sum(me.cpu_times()[:4])
    for child in me.children(recursive=True):
        try:
            total += sum(child.cpu_times()[:2])
        except psutil.Error:
            pass
    return total


def _timed(run: Callable[[], float]) -> dict[str, float]:
    """run()'s wall time (s) and, over it, the machine's busy cores, ours (this process
    tree) and the others' (busy - ours), and the hypervisor's steal (cores)."""
    cpus = os.cpu_count() or 1
    b0, s0, t0 = _cpu_jiffies()
    own0 = _own_cpu()
    w0 = time.perf_counter()
    seconds = run()
    wall = time.perf_counter() - w0
    b1, s1, t1 = _cpu_jiffies()
    own = _own_cpu() - own0
    total = max(t1 - t0, 1)
    busy = cpus * (b1 - b0) / total
    return {"seconds": seconds, "busy_cores": busy, "own_cores": own / wall,
            "other_cores": max(busy - own / wall, 0.0), "steal_cores": cpus * (s1 - s0) / total}


def scaling(repeat: int) -> dict[str, object]:
    """Strong scaling: the same study on a LocalCluster of 1 and of 2 worker processes,
    both up and warmed (every worker has evaluated a chunk, its kernels loaded), then
    ``repeat`` paired rounds, each timing both clusters back to back (their order
    alternating), with the CPU load seen during each run."""
    from contextlib import ExitStack

    from distributed import Client

    from core.motor.study import run_study, spec_from_toml
    from core.motor.study.chunks import evaluate_chunk
    from core.motor.study.run import local_cluster

    spec = spec_from_toml(SCALING_TOML)
    warm = spec_from_toml(SCALING_TOML.replace("num = 96", "num = 2")
                          .replace("num = 80", "num = 2"))
    rounds: list[dict[str, object]] = []
    with tempfile.TemporaryDirectory() as tmp, ExitStack() as stack:
        clients = {}
        for workers in (1, 2):
            cluster = stack.enter_context(local_cluster(workers, "1GiB"))
            clients[workers] = stack.enter_context(Client(cluster))
            clients[workers].run(evaluate_chunk, warm, (0, 0))  # on every worker
            run_study(warm, Path(tmp) / f"warm{workers}", client=clients[workers])
        for r in range(repeat):
            row: dict[str, object] = {}
            for workers in ((1, 2) if r % 2 == 0 else (2, 1)):
                client = clients[workers]
                folder = Path(tmp) / f"w{workers}-{r}"
                row[str(workers)] = _timed(
                    lambda c=client, f=folder: run_study(spec, f, client=c).seconds)
            row["ratio"] = row["1"]["seconds"] / row["2"]["seconds"]
            rounds.append(row)
            print(f"  round {r}: 1 worker {row['1']['seconds']:.2f} s, 2 workers "
                  f"{row['2']['seconds']:.2f} s: {row['ratio']:.2f}x; other jobs' CPU "
                  f"{row['1']['other_cores']:.2f} / {row['2']['other_cores']:.2f} cores, "
                  f"steal {row['1']['steal_cores']:.2f} / {row['2']['steal_cores']:.2f}")
    ratios = [float(row["ratio"]) for row in rounds]
    best = {w: min(float(row[str(w)]["seconds"]) for row in rounds) for w in (1, 2)}
    others = [max(float(row["1"]["other_cores"]), float(row["2"]["other_cores"]))
              for row in rounds]
    quiet = int(np.argmin(others))
    calm = [r for r, o in zip(ratios, others, strict=True) if o <= QUIET_CORES]
    out: dict[str, object] = {
        "designs": spec.size, "chunks": math.prod(math.ceil(n / c) for n, c in
                                                  zip(spec.shape, spec.chunk_shape,
                                                      strict=True)),
        "cpus": os.cpu_count(), "rounds": rounds,
        "seconds_1": best[1], "seconds_2": best[2],
        "designs_per_second_per_worker_1": spec.size / best[1],
        "designs_per_second_per_worker_2": spec.size / best[2] / 2,
        "strong_scaling_best": max(ratios), "strong_scaling_median": float(np.median(ratios)),
        "strong_scaling_of_best_times": best[1] / best[2],
        "strong_scaling_quietest_round": ratios[quiet],
        "other_cores_quietest_round": others[quiet],
        "quiet_rounds": len(calm),
        "strong_scaling_quiet_median": float(np.median(calm)) if calm else math.nan,
        "other_cores_median": float(np.median(others)),
        "load_average": os.getloadavg()[0],
    }
    out["strong_scaling"] = out["strong_scaling_of_best_times"]  # each the least disturbed
    print(f"scaling: {spec.size} designs in {out['chunks']} chunks of {spec.block}, "
          f"{repeat} paired rounds on {os.cpu_count()} CPUs: best 1 worker {best[1]:.2f} s "
          f"({out['designs_per_second_per_worker_1']:.0f} designs/s per worker), best 2 "
          f"workers {best[2]:.2f} s ({out['designs_per_second_per_worker_2']:.0f} designs/s "
          f"per worker); strong scaling of the best times {out['strong_scaling']:.2f}x; best "
          f"round {out['strong_scaling_best']:.2f}x, median "
          f"{out['strong_scaling_median']:.2f}x, quietest round {ratios[quiet]:.2f}x (other "
          f"jobs' CPU {others[quiet]:.2f} cores; median over rounds "
          f"{out['other_cores_median']:.2f}); median of the {len(calm)} rounds whose other "
          f"jobs took at most {QUIET_CORES} cores in both runs: "
          f"{out['strong_scaling_quiet_median']:.2f}x; load average "
          f"{out['load_average']:.1f}")
    return out


def projection(scale: dict[str, object]) -> dict[str, float]:
    per_design = 1.0 / float(scale["designs_per_second_per_worker_1"])  # s/design/worker
    efficiency = float(scale["strong_scaling"]) / 2.0  # of the best times, as per_design
    designs, cores = 1e7, 64
    hours = designs * per_design / (cores * efficiency) / 3600.0
    print(f"projection: 1e7 designs x {per_design * 1e3:.2f} ms per design per worker / "
          f"(64 cores x {efficiency:.2f} parallel efficiency) = {hours:.1f} h "
          f"({designs * per_design / 3600.0:.0f} core-hours)")
    return {"per_design_seconds": per_design, "parallel_efficiency": efficiency,
            "hours_1e7_on_64_cores": hours, "core_hours_1e7": designs * per_design / 3600.0}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", choices=("kernel", "contact", "speeds", "scaling"))
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--write", action="store_true")
    args = parser.parse_args()
    results: dict[str, object] = {}
    for name, f in (("kernel", kernel), ("contact", contact), ("speeds", speeds),
                    ("scaling", scaling)):
        if args.only in (None, name):
            results[name] = f(args.repeat)
    if "scaling" in results:
        results["projection"] = projection(results["scaling"])
    if args.write:
        RESULTS.write_text(json.dumps(results, indent=2) + "\n")
        print(f"wrote {RESULTS}")


if __name__ == "__main__":
    main()
