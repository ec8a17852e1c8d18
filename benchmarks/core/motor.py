"""Cost of the motor's stall-thrust curve along the rod, as ratios to one np.sin pass over
the same number of points, and of one thrust-speed curve of the moving rotor, as ratios to
one closed-form contact; each measured interleaved in one run.

Target (the motor issue): the curve for 1000 points x0 costs no more than 20 np.sin passes
over 1000 points plus one root solve per point. The run prints the curve's ratio, the
share of the vectorised root solve (tau0 from eq 10, ``core.motor.balance.solve``) and of
the rest, and, for scale, the per-point alternative: scipy's brentq on core's F, one
point at a time.

Thrust-speed curve (``core.motor.thrust_speed_curve``, 40 speeds from stall to full
counter-slip at the default resolution, converged to 1e-4 in r): its absolute time, and
its ratio to one closed-form contact of core, (a) ``Contact(psi, tau0).impulse_ratio``
(eq 41, one number) and (b) ``Contact(psi, tau0).tangential_force`` on its 400-point
``tau_grid`` (one drawn T(tau) curve), for a few contacts.

Run: ``.venv/bin/python -m benchmarks.core.motor [--repeat 200] [--only stall|moving]``.
"""

from __future__ import annotations

import argparse
import math
import timeit
from collections.abc import Callable

import numpy as np
from scipy.optimize import brentq

from core import Contact
from core.elliptic import impulse_factor
from core.motor import Motor, Rod, balance, thrust_speed_curve

N_POINTS = 1000


def interleaved(fs: dict[str, Callable[[], object]], repeat: int) -> dict[str, float]:
    """Best wall time (s) of each f, the functions timed in turn so that all see the same
    load on a shared machine."""
    best = {name: math.inf for name in fs}
    for _ in range(repeat):
        for name, f in fs.items():
            best[name] = min(best[name], timeit.timeit(f, number=1))
    return best


def brentq_per_point(phi: np.ndarray) -> np.ndarray:
    """tau0 of each phi by scipy's brentq on core's F, one point at a time (phi < 8)."""
    def one(p: float) -> float:
        def f(t0: float) -> float:
            e = math.pi / 2 - t0
            return float(impulse_factor(math.sin(e / 2) ** 2, math.cos(e / 2) ** 2)) - p
        return brentq(f, -math.pi / 2 + 1e-15, math.pi / 2 - 1e-15, xtol=1e-14)
    return np.array([one(p) for p in phi])


#: Contacts of the thrust-speed benchmark: psi < 1, the paper's Fig. 4 and Fig. 7b cases,
#: a deep preload and a near-grazing contact.
CURVE_CASES = [(0.5, 0.3), (2.414, math.pi / 6), (28.35, 0.0), (5.0, -1.3), (3.0, 1.4)]
N_SPEEDS = 40


def moving_rotor_benchmark(repeat: int) -> None:
    """Time one thrust-speed curve of N_SPEEDS speeds against one closed-form contact."""
    thrust_speed_curve(2.0, 0.1, n=2)  # compile (or load) the MDR kernel outside the timing
    runs = max(repeat // 10, 5)
    print(f"\nthrust-speed curve, {N_SPEEDS} speeds (default resolution); "
          f"best of {runs} runs")
    print(f"{'psi':>7s} {'tau0':>7s} {'curve':>9s} {'eq 41':>8s} {'T(tau)':>8s} "
          f"{'/eq 41':>8s} {'/T(tau)':>8s}")
    for psi, tau0 in CURVE_CASES:
        def one_ratio(psi: float = psi, tau0: float = tau0) -> float:
            return Contact(psi, tau0).impulse_ratio

        def one_curve(psi: float = psi, tau0: float = tau0) -> object:
            c = Contact(psi, tau0)
            return c.tangential_force(c.tau_grid(400))

        t = interleaved(
            {
                "curve": lambda psi=psi, tau0=tau0: thrust_speed_curve(psi, tau0, n=N_SPEEDS),
                "ratio": one_ratio,
                "T": one_curve,
            },
            runs,
        )
        print(f"{psi:7.3f} {tau0:7.3f} {t['curve'] * 1e3:7.2f}ms {t['ratio'] * 1e6:6.1f}us "
              f"{t['T'] * 1e6:6.1f}us {t['curve'] / t['ratio']:8.0f} "
              f"{t['curve'] / t['T']:8.0f}")
    print("curve: thrust_speed_curve(psi, tau0, n=40); eq 41: Contact(psi, tau0).impulse_ratio;"
          " T(tau): Contact(psi, tau0).tangential_force(c.tau_grid(400));\n/eq 41, /T(tau):"
          " the curve's time over theirs.")


def stall_benchmark(repeat: int) -> None:
    """Time the stall-thrust curve along the rod against np.sin (see the module docstring)."""
    rod = Rod(half_length=0.02, thickness=4e-3, nu_rod=0.3, amplitude=10e-6, frequency=40e3)
    x0 = np.linspace(-rod.half_length, rod.half_length, N_POINTS + 2)[1:-1]
    cases = {}
    for preload in (0.05, 1e-3):
        motor = Motor(rod, R=5e-3, G=24e9, nu=0.31, mu=0.2, preload=preload)
        label = f"preload {preload:g} N (opens on {motor.opens(x0).mean():.1%} of the rod)"
        cases[label] = motor
    print(f"{N_POINTS} points x0 along the rod; times are the best of {repeat} runs")
    print(f"{'case':44s} {'np.sin':>8s} {'curve':>9s} {'ratio':>6s} {'solve':>6s} "
          f"{'rest':>6s} {'brentq/pt':>10s}")
    for label, motor in cases.items():
        phi = motor.load_factor(x0)
        opens = phi < balance.PHI_MAX
        t = interleaved(
            {
                "sin": lambda: np.sin(x0),
                "curve": lambda motor=motor: motor.stall_thrust(x0),
                "solve": lambda phi=phi: balance.solve(phi),
            },
            repeat,
        )
        sample = phi[opens][:: max(1, opens.sum() // 50)]
        t_brent = min(timeit.repeat(lambda s=sample: brentq_per_point(s), number=1,
                                    repeat=5)) / sample.size
        per_point = t_brent * opens.sum()
        print(f"{label:44s} {t['sin'] * 1e6:6.1f}us {t['curve'] * 1e6:7.1f}us "
              f"{t['curve'] / t['sin']:6.1f} {t['solve'] / t['sin']:6.1f} "
              f"{(t['curve'] - t['solve']) / t['sin']:6.1f} {per_point / t['sin']:10.0f}")
    print("ratio: curve / np.sin; solve: the vectorised root solve alone / np.sin; rest:"
          " (curve - solve) / np.sin (target <= 20);\nbrentq/pt: one scipy brentq per"
          " opening point on core's F, extrapolated from 50 points (best of 5), / np.sin.")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=200)
    parser.add_argument("--only", choices=("stall", "moving"), default=None)
    args = parser.parse_args()
    if args.only != "moving":
        stall_benchmark(args.repeat)
    if args.only != "stall":
        moving_rotor_benchmark(args.repeat)


if __name__ == "__main__":
    main()
