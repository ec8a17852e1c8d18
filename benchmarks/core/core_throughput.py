"""Throughput of the closed form, as ratios to one np.sin pass measured in the same run.

Targets (issue 15): T / T0 of one contact over 1e6 tau points (``Contact.tangential_force``)
<= 1.3 np.sin passes; ``core.batch.tangential_force`` for 1e4 contacts x 200 tau <= 1.5
np.sin passes over the same 2e6 points; ``core.impulse_ratio`` over 1e5 psi at one tau0
<= 1 np.sin pass over 1e5 points. Every np.sin pass is over whole periods, [0, 2 pi]
(numpy's SIMD sine is faster on small arguments: 0.42 against 0.57 ms for 1e5 points on
[0, 0.63] and on [0, 2 pi] here). Every time, np.sin's included, is the best of
``--repeat`` single calls, interleaved. Run: ``make bench``.
"""

from __future__ import annotations

import argparse
import math
import timeit
from collections.abc import Callable

import numpy as np

from core import Contact, batch, impulse_ratio


def ratio_to_sin(f: Callable[[], object], x: np.ndarray, repeat: int) -> tuple[float, float]:
    """Best wall times (s) of ``f()`` and of ``np.sin(x)``, measured interleaved so that
    both see the same load on a shared machine (after one warm-up call of each)."""
    f()
    np.sin(x)
    t_f, t_sin = [], []
    for _ in range(repeat):
        t_sin.append(timeit.timeit(lambda: np.sin(x), number=1))
        t_f.append(timeit.timeit(f, number=1))
    return min(t_f), min(t_sin)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=25)
    args = parser.parse_args()
    rows = []

    tau = np.linspace(0.0, 2 * math.pi, 10**6)  # half the points are outside contact
    for label, c in [
        ("psi=2.414 (three phases)", Contact(math.sqrt(2) + 1, math.pi / 6)),
        ("psi=0.4 (full stick)", Contact(0.4, math.pi / 6)),
        ("psi=1e6, preload", Contact(1e6, -0.9)),
    ]:
        t_T, t_sin = ratio_to_sin(lambda c=c: c.tangential_force(tau), tau, args.repeat)
        rows.append((f"tangential_force, 1e6 tau, {label}", t_T, t_sin, 1.3))

    rng = np.random.default_rng(1)
    psi = rng.uniform(0.0, 30.0, (10**4, 1))
    tau0 = rng.uniform(-1.5, 1.5, (10**4, 1))
    times = np.linspace(-0.5, 3.5, 200)
    t_B, t_sin = ratio_to_sin(lambda: batch.tangential_force(psi, tau0, times),
                              np.linspace(0.0, 2 * math.pi, psi.size * times.size),
                              args.repeat)
    rows.append(("batch.tangential_force, 1e4 contacts x 200 tau", t_B, t_sin, 1.5))

    for label, p in [
        ("psi in [0, 30]", np.linspace(0.0, 30.0, 10**5)),
        ("psi in [1, 1e6] log", np.logspace(0.0, 6.0, 10**5)),
    ]:
        t_I, t_sin = ratio_to_sin(lambda p=p: impulse_ratio(p, math.pi / 6),
                                  np.linspace(0.0, 2 * math.pi, p.size), args.repeat)
        rows.append((f"impulse_ratio, 1e5 psi, {label}", t_I, t_sin, 1.0))

    print(f"{'case':58s} {'time':>9s} {'np.sin':>9s} {'ratio':>6s} {'target':>6s}")
    for name, t, t_sin, target in rows:
        ok = "ok" if t / t_sin <= target else "MISSED"
        print(
            f"{name:58s} {t * 1e3:7.2f}ms {t_sin * 1e3:7.2f}ms {t / t_sin:6.2f} "
            f"{'<=' + format(target, 'g'):>6s} {ok}"
        )


if __name__ == "__main__":
    main()
