"""The Methods card's computation: the methods of `core.numerics` on one contact, and the
table of their errors against the closed form (no Bokeh or Panel here).

If `core.numerics` is missing (an installation without it) no method is offered.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core import Contact

try:
    from core import numerics
except ImportError:  # the app works without the numerics package
    numerics = None

DEFAULT_METHODS = ("mdr", "lammps_mindlin")

#: The resolutions offered, as factors of each method's interactive default
#: (`core.numerics.INTERACTIVE_RESOLUTION`), and the most a method is given whose cost
#: grows faster than its resolution (the annulus, MDR), so that a client's choice bounds
#: the work of one solve (``python -m benchmarks.core.methods`` times the methods).
RESOLUTION_FACTORS = {"¼ × default": 0.25, "½ × default": 0.5, "default": 1.0,
                      "2 × default": 2.0, "4 × default": 4.0, "8 × default": 8.0,
                      "16 × default": 16.0}
MAX_RESOLUTION = {"annulus": 128}
#: The table's columns.
TABLE_HEAD = ("| method | resolution | max abs(T − T_exact) / T₀ | impulse-ratio error | "
              "time (µs) |\n|---|---|---|---|---|\n")


def available_methods() -> dict[str, str]:
    """Method name -> description of the methods `core.numerics` offers (may be empty)."""
    if numerics is None or not hasattr(numerics, "solve"):
        return {}
    return dict(getattr(numerics, "METHODS", {}))


def resolution(name: str, factor: float) -> int:
    """The resolution of method `name` at `factor` times its interactive default (at
    most its `MAX_RESOLUTION`)."""
    n = max(2, round(numerics.INTERACTIVE_RESOLUTION.get(name, 200) * factor))
    return min(n, MAX_RESOLUTION.get(name, n))


def prepare() -> None:
    """Compute once, at the server's start, what a method would set up on its first run
    at any offered resolution: the Gauss-Legendre nodes (cached per n by
    `core.numerics.quadrature`; the largest sets, 4,096 nodes, are slow enough to compute
    that a visitor's first run at 16 x would otherwise wait for them)."""
    if numerics is None:
        return
    from core.numerics.quadrature import gauss_legendre_nodes

    for factor in RESOLUTION_FACTORS.values():
        gauss_legendre_nodes(0.0, 1.0, resolution("gauss_legendre", factor))


@dataclass(frozen=True)
class Run:
    """The methods solved for one contact: their results (`core.numerics.solve`'s, in
    the order asked) and one message per method that failed."""

    contact: Contact
    results: tuple
    errors: tuple[str, ...]


def solve_all(c: Contact, resolutions: dict[str, int]) -> Run:
    """Solve each method `name` of `resolutions` at its resolution for contact `c`; a
    method that refuses the contact or fails is reported, the others still run."""
    results, errors = [], []
    for name, n in resolutions.items():
        try:
            results.append(numerics.solve(name, c, n))
        except Exception as err:  # a method may be missing or reject parameters
            errors.append(f"{name}: {err}")
    return Run(c, tuple(results), tuple(errors))


def time_us(seconds: float) -> str:
    """A wall time in whole microseconds, thousands separated (e.g. '17,924')."""
    return f"{seconds * 1e6:,.0f}"


def table(run: Run) -> str:
    """The Markdown table of `run`: per method its resolution, the largest error of T
    (in T0) over its times and of the impulse ratio against the closed form, and its
    wall time (µs); '' without results."""
    c = run.contact
    rows = []
    for res in run.results:
        tau = np.asarray(res.tau, float)
        err_T = float(np.max(np.abs(np.asarray(res.T) - c.tangential_force(tau))))
        err_imp = abs(res.impulse_ratio - c.impulse_ratio)
        rows.append(f"| {res.method} | {res.resolution} | {err_T:.2e} | {err_imp:.2e} | "
                    f"{time_us(res.wall_time)} |")
    return TABLE_HEAD + "\n".join(rows) if rows else ""
