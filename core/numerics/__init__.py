"""Independent numerical methods for the Zharii (1996) contact, and a common front end.

Every method integrates the same loading history (eq 3) with Hertz geometry (eqs 5-9)
and Coulomb's law, never the closed form of ``core`` (except ``quad`` and
``gauss_legendre``, which integrate core's T(tau) to test the impulse formula eq 41).
Units: see ``core.numerics.result``. The time-stepping methods (MDR, annulus, DEM) are
numba kernels (``@njit(cache=True, nogil=True)``: they release the GIL, so a worker
thread running one does not stall the server's event loop): the first call in a fresh
environment compiles them (a few seconds, cached on disk afterwards), and ``solve`` times
the run only.

    from core.numerics import solve, METHODS, INTERACTIVE_RESOLUTION, MethodResult
    res = solve("mdr", contact, resolution=200)             # 200 springs, default steps
    res = solve("mdr", contact, resolution=200, steps=400)  # time steps chosen apart
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from core.numerics import annulus, dem, mdr, quadrature, textbook
from core.numerics.result import ContactLike, MethodResult, Params, check_resolution

__all__ = [
    "EXTRA_METHODS",
    "INTERACTIVE_RESOLUTION",
    "METHODS",
    "STEPPED",
    "MethodResult",
    "Params",
    "check_resolution",
    "solve",
]

METHODS: dict[str, str] = {
    "mdr": mdr.DESCRIPTION,
    "annulus": annulus.DESCRIPTION,
    **dem.DESCRIPTIONS,
    **quadrature.DESCRIPTIONS,
}
"""Registry: method name -> one-line description."""

EXTRA_METHODS: dict[str, str] = {"textbook": textbook.DESCRIPTION}
"""Methods accepted by ``solve`` but kept out of METHODS (reference for the stability map)."""

_SOLVERS: dict[str, Callable[..., tuple]] = {
    "mdr": mdr.solve,
    "annulus": annulus.solve,
    **dem.SOLVERS,
    **quadrature.SOLVERS,
    "textbook": textbook.solve,
}

INTERACTIVE_RESOLUTION: dict[str, int] = {
    "mdr": 400,
    "annulus": 32,
    "lammps_mindlin": 2000,
    "lammps_mindlin_force": 2000,
    "lammps_mindlin_rescale": 2000,
    "lammps_mindlin_rescale_force": 2000,
    "lammps_linear_history": 2000,
    "liggghts_history": 2000,
    "direnzo": 2000,
    "quad": 8,
    "gauss_legendre": 256,
}
"""Resolution per method for the app's live overlay: short solves of the compiled kernels
(scipy's adaptive quad the slowest) over psi in [0.3, 1e4] x tau0 in
[-1.4, 1.569], and a few hundred time points per curve (the DEM rules 2000);
``python -m benchmarks.core.methods`` times them."""

STEPPED = ("mdr", "annulus")
"""Methods whose time steps can be chosen apart from their resolution (``steps=``)."""


def solve(name: str, contact: ContactLike, resolution: int, steps: int | None = None
          ) -> MethodResult:
    """Run method ``name`` on ``contact`` (a ``core.Contact`` or ``Params``).

    resolution: springs (mdr), rings (annulus), equal time steps (DEM models), interval
    limit (quad) or nodes (gauss_legendre). steps: time steps of mdr and annulus (None:
    their default rule); refused for the other methods.

    Raises KeyError for an unknown name and ValueError for a bad resolution or steps (an
    int >= 2, not bool, below each method's work limit) or bad contact parameters.
    """
    if name not in _SOLVERS:
        raise KeyError(f"unknown method {name!r}; choose one of {sorted(_SOLVERS)}")
    check_resolution(resolution)
    if steps is not None and name not in STEPPED:
        raise ValueError(f"steps is only for {STEPPED}; {name!r} has one resolution")
    kwargs = {} if steps is None else {"steps": steps}
    start = time.perf_counter()
    tau, T, b, ratio = _SOLVERS[name](contact, resolution, **kwargs)
    wall = time.perf_counter() - start
    return MethodResult(
        method=name,
        resolution=int(resolution),
        tau=np.asarray(tau, dtype=float),
        T=np.asarray(T, dtype=float),
        b=None if b is None else np.asarray(b, dtype=float),
        impulse_ratio=float(ratio),
        wall_time=wall,
    )
