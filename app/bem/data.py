"""The numbers of the "How exact is the model?" card: pure functions over `core.bem`.

- `request`: the explorer's contact and a resolution, validated at the boundary into a
  `RunKey` (the resolutions this card runs are `RESOLUTIONS`, each bounded in cost; a
  larger grid is refused with the command line that runs it, `command_line`);
- `compute`: the referee's run of one key (`core.bem.paper.run_paper`, the paper's
  loading on identical bodies: beta = 0) with the state of every time step kept, as a
  `Referee`;
- `RunCache`: the last few runs of one card, by key (a key met again runs nothing);
- `field_columns`, `force_columns`: what the card's figures draw, at a time tau, of the
  referee and of the closed form (`core.Contact` on the same grid);
- `read_map`, `map_columns`, `map_at`: the closed form's error mapped over nu and beta
  (`core.bem.error_map`, the app's copy of benchmarks/results/bem_error_map.csv).

Units as `core.bem`: lengths in a* (the largest contact radius), tractions in mu p*
(the closed form's `Contact.traction`), forces T / T0.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass
from importlib import resources

import numpy as np
from numpy.typing import NDArray

from core import Contact
from core.bem.error_map import MapRow, read_csv
from core.bem.loading import PaperLoading
from core.bem.march import DEFAULT, stick_mask
from core.bem.pair import NU_RANGE, Pair
from core.bem.paper import run_paper

Array = NDArray[np.float64]

#: The app's copy of benchmarks/results/bem_error_map.csv (package data of `app`).
MAP_FILE = resources.files("app") / "results" / "bem_error_map.csv"
#: The error the map's readers compare with: 1 % of T0.
LEVEL = 0.01


@dataclass(frozen=True)
class Resolution:
    """Elements across the largest contact diameter and time steps over the contact."""

    grid: int
    steps: int

    @property
    def label(self) -> str:
        return f"{self.grid} elements across, {self.steps} time steps"


#: The resolutions the card runs (each well under ~3 s on one core here), coarse first.
RESOLUTIONS = (Resolution(16, 80), Resolution(24, 100), Resolution(32, 100))
#: The finest the card runs: anything finer is refused (`request`).
MAX_GRID = max(r.grid for r in RESOLUTIONS)
MAX_STEPS = max(r.steps for r in RESOLUTIONS)
#: A resolution offered to show where the command line takes over (refused here).
COMMAND_LINE_ONLY = Resolution(64, 200)
#: How many runs a card keeps (at most about 2 MB each: 32 across, 100 steps).
CACHE_SIZE = 4
#: The fields are kept for drawing, in single precision (half the memory).
FIELD_DTYPE = np.float32


@dataclass(frozen=True)
class RunKey:
    """What a run depends on: the contact (psi, tau0, mu, nu) and the resolution."""

    psi: float
    tau0: float
    mu: float
    nu: float
    grid: int
    steps: int

    def same_contact(self, c: Contact) -> bool:
        """Whether this run is of contact `c`."""
        return (self.psi, self.tau0, self.mu, self.nu) == (c.psi, c.tau0, c.mu, c.nu)


def command_line(psi: float, tau0: float, mu: float, nu: float, grid: int,
                 steps: int) -> str:
    """The command that runs this contact on the referee (docs/bem.md)."""
    return (f"python -m core.bem paper --psi {psi!r} --tau0 {tau0!r} --mu {mu!r} --nu {nu!r} "
            f"--grid {grid} --steps {steps} --json")


def request(c: Contact, resolution: Resolution) -> RunKey:
    """The run of contact `c` at `resolution`, validated.

    Raises
    ------
    ValueError
        When the resolution is finer than the card runs (`MAX_GRID`, `MAX_STEPS`: the
        message names the command line that runs it), or when the contact's nu is
        outside the referee's [0, 0.5).
    """
    grid, steps = resolution.grid, resolution.steps
    if not (isinstance(grid, int) and isinstance(steps, int) and 4 <= grid <= MAX_GRID
            and 4 <= steps <= MAX_STEPS and steps % 2 == 0):
        raise ValueError(
            f"{grid} elements across and {steps} time steps is more than this page runs "
            f"(at most {MAX_GRID} across and {MAX_STEPS} even steps, a few seconds); run "
            f"it on your own machine: {command_line(c.psi, c.tau0, c.mu, c.nu, grid, steps)}")
    if not NU_RANGE.contains(c.nu):
        raise ValueError(f"the referee takes nu in [0, 0.5) (core.bem), this contact has "
                         f"nu = {c.nu:g}")
    return RunKey(c.psi, c.tau0, c.mu, c.nu, grid, steps)


@dataclass(frozen=True)
class Referee:
    """One run of the referee: its times ``tau`` (rad), T / T0 (``T``; ``Ty``
    transverse), the equal-area stick radius (``stick``, a*), the element centres along
    one axis (``centres``, a*), and per time (first axis) the pressure ``p`` / p* and the
    traction ``qx``, ``qy`` / (mu p*) on the held body (``FIELD_DTYPE``), indexed
    [time, ix, iy], with the stuck elements (``stuck``); the closed form ``closed``
    (`core.Contact`), the worst |T - T_closed| / T0 over the contact and the run's wall
    time (s)."""

    key: RunKey
    tau: Array
    T: Array
    Ty: Array
    stick: Array
    centres: Array
    p: Array
    qx: Array
    qy: Array
    stuck: NDArray[np.bool_]
    closed: Contact
    worst_T_error: float
    seconds: float


def compute(key: RunKey) -> Referee:
    """The referee's run of `key` (`core.bem.paper.run_paper`, beta = 0), with every
    time step's fields. Times without contact (tau0 and pi - tau0) hold zeros."""
    loading = PaperLoading(key.psi, key.tau0, key.mu, Pair(key.nu), key.steps)
    run = run_paper(key.psi, key.tau0, key.nu, mu=key.mu, grid=key.grid, steps=key.steps,
                    snapshots=tuple(float(t) for t in loading.tau))
    m = run.grid.size
    shape = (len(run.tau), m, m)
    p, qx, qy = (np.zeros(shape, dtype=FIELD_DTYPE) for _ in range(3))
    stuck = np.zeros(shape, dtype=bool)
    for k, t in enumerate(loading.tau):
        state = run.snapshots.get(float(t))
        if state is None:
            continue
        p[k], qx[k], qy[k] = state.p, state.qx / key.mu, state.qy / key.mu
        # (the threshold of run_paper's stick radius: the same elements it counts)
        slip = np.hypot(state.sx, state.sy)
        stuck[k] = stick_mask(state, key.mu, max(10.0 * DEFAULT.slip_tol,
                                                 1e-6 * float(slip.max())))
    return Referee(key, run.tau, run.T, run.Ty, run.stick, run.grid.centres, p, qx, qy,
                   stuck, run.closed, run.worst_T_error, run.seconds)


class RunCache:
    """The last `size` runs, by key: `get` (None if absent; a hit becomes the newest),
    `put` (the oldest dropped past `size`)."""

    def __init__(self, size: int = CACHE_SIZE) -> None:
        self.size = size
        self._runs: OrderedDict[RunKey, Referee] = OrderedDict()

    def get(self, key: RunKey) -> Referee | None:
        run = self._runs.get(key)
        if run is not None:
            self._runs.move_to_end(key)
        return run

    def put(self, run: Referee) -> None:
        self._runs[run.key] = run
        self._runs.move_to_end(run.key)
        while len(self._runs) > self.size:
            self._runs.popitem(last=False)

    def __len__(self) -> int:
        return len(self._runs)


def step_at(run: Referee, tau: float) -> int:
    """The index of the run's time nearest `tau`."""
    return int(np.argmin(np.abs(run.tau - tau)))


def closed_traction(run: Referee, tau: float) -> tuple[Array, Array]:
    """The closed form's traction / (mu p*) (``Contact.traction``, along the drive) and
    pressure / p* on the run's element centres at `tau`, indexed [ix, iy]."""
    x = run.centres
    r = np.hypot(x[:, None], x[None, :])
    return run.closed.traction(r, tau), run.closed.pressure(r, tau)


def arrows(x: Array, qx: Array, qy: Array, length: float) -> dict[str, Array]:
    """Segments from each loaded element's centre along its traction, the largest
    `length` long (columns x0, y0, x1, y1)."""
    X, Y = np.meshgrid(x, x, indexing="ij")
    size = np.hypot(qx, qy)
    on = size > 0.0
    scale = length / float(size.max()) if on.any() else 0.0
    return {"x0": X[on], "y0": Y[on], "x1": X[on] + scale * qx[on],
            "y1": Y[on] + scale * qy[on]}


def field_columns(run: Referee, tau: float) -> dict[str, dict]:
    """What the field figures draw at the run's time nearest `tau`: the images
    (``referee``: |p_t| and p_y / (mu p*), ``closed``: |p_t| / (mu p*); each transposed
    to [iy, ix] as Bokeh's image takes them, with the image's corner ``x``, ``y`` and
    side ``dw``), the stuck elements' centres and side (``stuck``), the traction's
    direction (``referee_arrows``, ``closed_arrows``), the closed form's stick and
    contact circles (``circles``: centres and radii b, a in a*) and ``readout``: the
    time, T / T0 of both, Ty / T0 and the stick radii."""
    k = step_at(run, tau)
    t = float(run.tau[k])
    x = run.centres
    h = float(x[1] - x[0])
    corner, side = float(x[0]) - h / 2.0, float(x[-1] - x[0]) + h
    closed_q, _ = closed_traction(run, t)
    qx, qy = run.qx[k], run.qy[k]
    image = {"x": [corner], "y": [corner], "dw": [side]}
    X, Y = np.meshgrid(x, x, indexing="ij")
    c = run.closed
    b, a = float(c.stick_radius(t)), float(c.contact_radius(t))
    return {
        "referee": {**image, "pt": [np.hypot(qx, qy).T], "py": [qy.T]},
        "closed": {**image, "pt": [np.abs(closed_q).T]},
        "stuck": {"x": X[run.stuck[k]], "y": Y[run.stuck[k]],
                  "h": np.full(int(run.stuck[k].sum()), h)},
        "referee_arrows": arrows(x, qx, qy, 0.9 * h),
        "closed_arrows": arrows(x, closed_q, np.zeros_like(closed_q), 0.9 * h),
        "circles": {"x": [0.0, 0.0], "y": [0.0, 0.0], "r": [b, a]},
        "readout": {"tau": t, "T": float(run.T[k]), "T_closed": float(c.tangential_force(t)),
                    "Ty": float(run.Ty[k]), "stick": float(run.stick[k]), "stick_closed": b},
    }


def force_columns(run: Referee, points: int = 400) -> dict[str, dict]:
    """T / T0 of the referee on its times (``referee``: tau, T, and dT = T - T_closed)
    and of the closed form (``closed``: tau, T on ``Contact.tau_grid(points)``)."""
    tau = run.closed.tau_grid(points)
    return {"referee": {"tau": run.tau, "T": run.T,
                        "dT": run.T - run.closed.tangential_force(run.tau)},
            "closed": {"tau": tau, "T": run.closed.tangential_force(tau)}}


# ----------------------------------------------------------------------- the map


def read_map(path=MAP_FILE) -> list[MapRow]:
    """The error map's rows (`core.bem.error_map.read_csv`)."""
    with resources.as_file(path) as file:
        return read_csv(file)


def identical(rows: list[MapRow]) -> list[MapRow]:
    """The rows of identical bodies (over nu), by nu."""
    return sorted((r for r in rows if r.label.startswith("identical")), key=lambda r: r.nu)


def map_columns(rows: list[MapRow]) -> dict[str, dict]:
    """The map as drawn: ``nu`` (identical bodies) and ``sweep`` (beta at nu =
    SWEEP_NU), ``pairs`` (the presets' pairs): for each, x (nu or beta), the worst
    |T - T_closed| / T0 (``err``) with its grid estimate as whiskers (``lo``, ``hi``;
    lo clipped at err / 10 for a log axis), the error against the referee at nu = beta = 0
    (``model``: nan where 0, a log axis has no 0) and the label."""

    def columns(part: list[MapRow], x: str) -> dict:
        err = np.array([r.worst_T_error for r in part])
        grid = np.array([r.worst_T_error_grid for r in part])
        model = np.array([r.worst_T_model for r in part])
        return {"x": np.array([getattr(r, x) for r in part]), "err": err,
                "lo": np.maximum(err - grid, err / 10.0), "hi": err + grid,
                "model": np.where(model > 0.0, model, math.nan),
                "label": [r.label for r in part]}

    sweep = sorted((r for r in rows if r.label.startswith("sweep")), key=lambda r: r.beta)
    pairs = sorted((r for r in rows if not r.label.startswith(("sweep", "identical"))),
                   key=lambda r: r.beta)
    return {"nu": columns(identical(rows), "nu"), "sweep": columns(sweep, "beta"),
            "pairs": columns(pairs, "beta")}


def map_at(rows: list[MapRow], nu: float) -> float:
    """The map's worst |T - T_closed| / T0 of identical bodies at `nu`, interpolated
    linearly between its rows (the nearest row's outside them)."""
    part = identical(rows)
    return float(np.interp(nu, [r.nu for r in part], [r.worst_T_error for r in part]))
