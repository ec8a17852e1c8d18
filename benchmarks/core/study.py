"""Cost of design studies (core.motor.designs, core.motor.study), each figure measured
within one run on this machine (timings on a shared machine are noisy: ratios are
measured interleaved).

1. kernel: the batched figures of merit (``design_merits``) against a loop over the
   scalar API giving the same numbers (``Motor.stall_thrust``, ``no_load_speed``,
   ``best_efficiency``, ``operating_point``, ``moving_rotor`` + ``moving_wear_rate``), per
   design, over the designs of ``DESIGNS`` (the README's rotor and a steel ball on
   PZT-4 along the rod, under a load; the default MDR). Target: at least 3 times
   cheaper. Also the count of designs whose merits are equal bit for bit.
2. contact: the kernel's cost per design as a ratio to one closed-form contact,
   ``Contact(psi, tau0).impulse_ratio`` (eq 41), and its thrust-speed evaluations per
   design.
3. speeds: how the cost grows with the number of speeds per thrust-speed curve
   (``thrust_speed_curve`` with n speeds, per contact), against the kernel's design.
4. scaling: designs per second per worker of a study on a LocalCluster of 1 and of 2
   worker processes (the same study; both clusters up and warmed, then timed in turn),
   and the strong scaling t(1) / t(2), with the machine's load average.
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
from core.materials import PRESETS
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
STEEL, PZT = PRESETS["steel"], PRESETS["PZT-4"]
MOTORS = (Motor(ROD, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=0.05),
          Motor(ROD, R=5e-3, G=STEEL.G, nu=STEEL.nu, mu=0.2, preload=0.05, rod_G=PZT.G,
                rod_nu=PZT.nu, rod_R=math.inf))
#: (motor, x0, load): two rotors at 8 points of the rod, under 1 mN.
DESIGNS = [(m, float(x), 1e-3) for m in MOTORS for x in np.linspace(-0.016, -0.0002, 8)]
K, HARD = 1e-6, 5e9
#: The study of the scaling figure: 48 x 20 designs, 12 chunks of 80 (the client writes
#: ~30 ms per chunk here: small chunks would time the client, not the workers).
SCALING_TOML = """
[study]
name = "bench"
block = 80
[design]
load = 1e-3
[axes.x0]
start = -0.016
stop = -0.0002
num = 48
[axes.preload]
start = 0.02
stop = 0.5
num = 20
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


def interleaved(fs: dict[str, Callable[[], object]], repeat: int) -> dict[str, float]:
    """Best wall time (s) of each f, timed in turn so that all see the same load."""
    best = dict.fromkeys(fs, math.inf)
    for _ in range(repeat):
        for name, f in fs.items():
            t0 = time.perf_counter()
            f()
            best[name] = min(best[name], time.perf_counter() - t0)
    return best


def kernel(repeat: int) -> dict[str, float]:
    got = batch(DESIGNS)  # compiles or loads the kernels
    ref = scalar_loop(DESIGNS)
    equal = sum(all((a == b) or (math.isnan(a) and math.isnan(b))
                    for a, b in ((float(getattr(got, n)[i]), ref[i][n]) for n in MERITS))
                for i in range(len(DESIGNS)))
    t = interleaved({"scalar": lambda: scalar_loop(DESIGNS), "batch": lambda: batch(DESIGNS)},
                    repeat)
    n = len(DESIGNS)
    res = {"designs": n, "scalar_ms_per_design": 1e3 * t["scalar"] / n,
           "batch_ms_per_design": 1e3 * t["batch"] / n, "ratio": t["scalar"] / t["batch"],
           "equal_bit_for_bit": equal,
           "evaluations_per_design": float(np.mean(got.evaluations))}
    print(f"kernel: {n} designs, scalar loop {res['scalar_ms_per_design']:.2f} ms/design, "
          f"batch {res['batch_ms_per_design']:.2f} ms/design: {res['ratio']:.2f} times "
          f"cheaper (target >= 3); {equal} of {n} designs equal bit for bit; "
          f"{res['evaluations_per_design']:.1f} MDR contacts per design")
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


def scaling(repeat: int) -> dict[str, float]:
    from contextlib import ExitStack

    from distributed import Client, LocalCluster

    from core.motor.study import run_study, spec_from_toml
    from core.motor.study.run import local_cluster_options

    spec = spec_from_toml(SCALING_TOML)
    warm = spec_from_toml(SCALING_TOML.replace("num = 48", "num = 2")
                          .replace("num = 20", "num = 2"))
    out: dict[str, float] = {}
    best = {1: math.inf, 2: math.inf}
    with tempfile.TemporaryDirectory() as tmp, ExitStack() as stack:
        clients = {}
        for workers in (1, 2):  # both clusters up, warmed, then timed in turn
            cluster = stack.enter_context(LocalCluster(**local_cluster_options(workers, "1GiB")))
            clients[workers] = stack.enter_context(Client(cluster))
            run_study(warm, Path(tmp) / f"warm{workers}", client=clients[workers])
        load = os.getloadavg()[0]
        for r in range(repeat):
            for workers, client in clients.items():
                run = run_study(spec, Path(tmp) / f"w{workers}-{r}", client=client)
                best[workers] = min(best[workers], run.seconds)
    for workers in (1, 2):
        out[f"seconds_{workers}"] = best[workers]
        out[f"designs_per_second_per_worker_{workers}"] = spec.size / best[workers] / workers
    out["strong_scaling"] = out["seconds_1"] / out["seconds_2"]
    out["designs"] = spec.size
    out["load_average"] = load
    print(f"scaling: {spec.size} designs in chunks of {spec.block} (load average {load:.1f} "
          f"on {os.cpu_count()} CPUs): 1 worker {out['seconds_1']:.1f} s "
          f"({out['designs_per_second_per_worker_1']:.0f} designs/s per worker), 2 workers "
          f"{out['seconds_2']:.1f} s ({out['designs_per_second_per_worker_2']:.0f} designs/s "
          f"per worker): strong scaling {out['strong_scaling']:.2f}x")
    return out


def projection(scale: dict[str, float]) -> dict[str, float]:
    per_design = 1.0 / scale["designs_per_second_per_worker_1"]  # s per design per worker
    efficiency = scale["strong_scaling"] / 2.0
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
