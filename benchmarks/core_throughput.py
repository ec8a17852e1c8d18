"""Throughput of the closed form, as ratios to one np.sin pass measured in the same run.

Targets (issue 2): tangential_force over 1e6 tau points <= 3 np.sin passes;
impulse_ratio over 1e5 psi values <= 10 np.sin passes. Run: ``make bench``.
"""

from __future__ import annotations

import argparse
import math
import timeit
from collections.abc import Callable

import numpy as np

from core import Contact, impulse_ratio


def ratio_to_sin(f: Callable[[], object], x: np.ndarray, repeat: int) -> tuple[float, float]:
    """Best wall times (s) of ``f()`` and of ``np.sin(x)``, measured interleaved so that
    both see the same load on a shared machine."""
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
        rows.append((f"tangential_force, 1e6 tau, {label}", t_T, t_sin, 3.0))

    for label, psi in [
        ("psi in [0, 30]", np.linspace(0.0, 30.0, 10**5)),
        ("psi in [1, 1e6] log", np.logspace(0.0, 6.0, 10**5)),
    ]:
        t_I, t_sin = ratio_to_sin(
            lambda psi=psi: impulse_ratio(psi, math.pi / 6), tau[: psi.size], args.repeat
        )
        rows.append((f"impulse_ratio, 1e5 psi, {label}", t_I, t_sin, 10.0))

    print(f"{'case':58s} {'time':>9s} {'np.sin':>9s} {'ratio':>6s} {'target':>6s}")
    for name, t, t_sin, target in rows:
        ok = "ok" if t / t_sin <= target else "MISSED"
        print(
            f"{name:58s} {t * 1e3:7.2f}ms {t_sin * 1e3:7.2f}ms {t / t_sin:6.2f} "
            f"{'<=' + format(target, 'g'):>6s} {ok}"
        )


if __name__ == "__main__":
    main()
