"""The Motor card's design map, as data: a grid of designs over two of the card's inputs
around its current state, every figure of merit of each (`core.motor.designs.
design_merits`), and the Pareto front of two merits (`core.motor.study.summary.pareto`).

Pure functions of frozen values, no Panel: the view (`app.motor.map_view`) runs
`compute` on the job runner, one job per row block of a map (`blocks`, `assemble`), and
keeps the maps it has computed in a `MapCache`.

A map is a `MapRequest`: the card's state (display units, `MotorState.values()`) less
the two axes' own values (a map does not depend on them: a click that loads one of its
designs finds the same map), the two axes (names of `AXES`, fields of
`app.motor.fields.FIELDS`) and the points per axis. Each axis spans its slider's range
(x0: the rod, its ends excluded, as the card's x0 slider). A grid design that the card's
validation refuses (`app.motor.fields.joint`: a preload too small for the rod) has every
merit nan, as have those core's scalar API refuses (`core.motor.designs`).
"""

from __future__ import annotations

import math
from collections import OrderedDict
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from app.motor.fields import FIELDS, joint
from core.motor.designs import MERITS, design_merits

#: The inputs a map may sweep (names of `FIELDS`): x0, preload, amplitude, frequency,
#: rotor radius, load.
AXES: tuple[str, ...] = ("x0", "N", "A", "f", "R", "load")
#: The axes that change the motor (the others are arguments of `design_merits`).
MOTOR_AXES = frozenset(("N", "A", "f", "R"))
#: The figures of merit shown (every one of `core.motor.designs.MERITS`): name -> (label,
#: display unit, display units per SI unit).
SHOWN: dict[str, tuple[str, str, float]] = {
    "stall_thrust": ("stall thrust", "mN", 1e3),
    "no_load_speed": ("no-load speed", "mm/s", 1e3),
    "best_efficiency": ("best efficiency", "%", 100.0),
    "best_speed": ("speed at the best efficiency", "mm/s", 1e3),
    "best_thrust": ("thrust at the best efficiency", "mN", 1e3),
    "load_speed": ("speed under the load", "mm/s", 1e3),
    "load_efficiency": ("efficiency under the load", "%", 100.0),
    "load_power": ("output power under the load", "mW", 1e3),
    "wear_rate": ("wear rate under the load", "µm³/h", 1e18),
}
assert set(SHOWN) == set(MERITS)
#: Points per axis: the default, and the most a classroom server computes for a session
#: (60 x 60 = 3600 designs, ~10 s on one core here).
SIZE_DEFAULT, SIZE_MAX = 20, 60
SIZE_MIN = 2
#: The command line that computes larger maps (docs/study.md).
STUDY_COMMAND = "python -m core.motor.study run SPEC.toml"


def check_size(raw: Any) -> int:
    """The points per axis `raw` asks for, as an int in [SIZE_MIN, SIZE_MAX]; ValueError
    in plain words otherwise, naming the command line for a larger map."""
    try:
        value = float(str(raw).strip())
    except ValueError:
        raise ValueError(f"the map size {str(raw)[:40]!r} is not a number") from None
    if not math.isfinite(value) or value != int(value):
        raise ValueError(f"the map size must be a whole number of points per axis, "
                         f"not {raw}")
    n = int(value)
    if n < SIZE_MIN:
        raise ValueError(f"a map needs at least {SIZE_MIN} points per axis, not {n}")
    if n > SIZE_MAX:
        raise ValueError(f"a {n} × {n} map ({n * n} designs) is more than this server "
                         f"computes for one visitor (at most {SIZE_MAX} × {SIZE_MAX}): "
                         f"compute it as a design study on your own machine or a "
                         f"cluster, `{STUDY_COMMAND}` (docs/study.md)")
    return n


def check_axes(x: str, y: str) -> None:
    """ValueError unless `x` and `y` are two different names of `AXES`."""
    for name in (x, y):
        if name not in AXES:
            raise ValueError(f"{name!r} is not an axis of the map: choose among "
                             f"{', '.join(AXES)}")
    if x == y:
        raise ValueError(f"the map needs two different axes, got {FIELDS[x].symbol} twice")


@dataclass(frozen=True)
class MapRequest:
    """One map: the card's other inputs (sorted (name, value) pairs, display units), the
    axes (x, y: names of `AXES`) and the points per axis. Hashable: the cache's key."""

    others: tuple[tuple[str, Any], ...]
    x: str
    y: str
    size: int

    @classmethod
    def of(cls, values: Mapping[str, Any], x: str, y: str, size: Any) -> MapRequest:
        """The map of the card's `values` (`MotorState.values()`) over axes x, y;
        ValueError (plain words) for axes or a size the map refuses."""
        check_axes(x, y)
        n = check_size(size)
        others = tuple(sorted((k, v) for k, v in values.items() if k not in (x, y)))
        return cls(others, x, y, n)

    def values(self, x: float, y: float) -> dict[str, Any]:
        """The card's values of the design at (x, y) (display units)."""
        return {**dict(self.others), self.x: x, self.y: y}


def axis_values(name: str, others: Mapping[str, Any], size: int) -> NDArray[np.float64]:
    """The `size` values of axis `name` (display units, evenly spaced): its slider's
    range, x0's the rod's (±L less 0.1 %, as the card's x0 slider)."""
    if name == "x0":
        end = others["L"] * (1.0 - 1e-3)
        return np.linspace(-end, end, size)
    f = FIELDS[name]
    return np.linspace(f.start, f.end, size)


@dataclass(frozen=True)
class MapData:
    """A computed map: the axes' values (display units), and every merit of `MERITS`
    (SI), psi and tau0 (rad) as (len(y), len(x)) arrays, row j at y[j], column i at
    x[i]; nan where a design is refused."""

    request: MapRequest
    x: NDArray[np.float64]
    y: NDArray[np.float64]
    merits: dict[str, NDArray[np.float64]] = field(repr=False)
    psi: NDArray[np.float64] = field(repr=False)
    tau0: NDArray[np.float64] = field(repr=False)

    def image(self, merit: str) -> NDArray[np.float64]:
        """The merit's values as the map shows them: on the grid (rows y, columns x), in
        its display unit (`SHOWN`)."""
        return self.merits[merit] * SHOWN[merit][2]

    def design(self, j: int, i: int) -> dict[str, Any]:
        """The card's values of the design at row j, column i."""
        return self.request.values(float(self.x[i]), float(self.y[j]))

    def nearest(self, x: float, y: float) -> tuple[int, int]:
        """(row, column) of the grid design nearest the point (x, y) (display units)."""
        return int(np.argmin(np.abs(self.y - y))), int(np.argmin(np.abs(self.x - x)))


#: Designs per job of a map (``MapBlock``): a few rows, ~1-2 s of the runner here (a
#: 60 x 60 map is 15 jobs of 4 rows), so that other sessions' jobs take their turns
#: between a map's blocks.
BLOCK_DESIGNS = 240


@dataclass(frozen=True)
class MapBlock:
    """Rows ``start:stop`` of map ``request`` (one job of the runner)."""

    request: MapRequest
    start: int
    stop: int


    @property
    def designs(self) -> int:
        """The block's designs: its rows times the map's columns."""
        return (self.stop - self.start) * self.request.size


@dataclass(frozen=True)
class MapProgress:
    """How far a map computed block by block is: ``done`` of its ``blocks`` blocks
    finished, ``designs_done`` of its ``designs`` designs (the next block running)."""

    request: MapRequest
    blocks: int
    done: int
    designs_done: int

    @classmethod
    def of(cls, request: MapRequest, todo: list[MapBlock]) -> MapProgress:
        """The progress of ``request`` whose blocks ``todo`` remain (the first one
        running, every earlier one finished)."""
        total = blocks(request)
        left = sum(b.designs for b in todo)
        return cls(request, len(total), len(total) - len(todo), request.size ** 2 - left)

    @property
    def designs(self) -> int:
        return self.request.size ** 2

    def status(self) -> str:
        """The status line: the map, the block running and the designs done."""
        n = self.request.size
        part = (f": block {self.done + 1} of {self.blocks}, {self.designs_done} of "
                f"{self.designs} designs done" if self.blocks > 1 else "")
        return f"computing a {n} × {n} map ({self.designs} designs){part}…"


def blocks(request: MapRequest) -> list[MapBlock]:
    """The map's row blocks, in order: ``BLOCK_DESIGNS // size`` rows each (at least 1),
    the last one what remains."""
    n = request.size
    rows = max(1, BLOCK_DESIGNS // n)
    return [MapBlock(request, a, min(a + rows, n)) for a in range(0, n, rows)]


def compute(request: MapRequest | MapBlock) -> MapData:
    """Every merit of the map's designs, or of a block's rows (its ``y`` those rows'),
    in one call of `design_merits` (on the runner: the kernel releases the GIL). Each
    design is evaluated on its own, so a map assembled from its blocks (`assemble`)
    equals the map computed at once, bit for bit.

    Parameters
    ----------
    request : MapRequest or MapBlock

    Returns
    -------
    MapData
    """
    block = request if isinstance(request, MapBlock) else None
    request = block.request if block is not None else request
    others = dict(request.others)
    xs = axis_values(request.x, others, request.size)
    ys = axis_values(request.y, others, request.size)
    if block is not None:
        ys = ys[block.start:block.stop]
    X, Y = np.meshgrid(xs, ys)
    shape = X.shape
    motors, index, x0, load = [], [], [], []
    if not MOTOR_AXES & {request.x, request.y}:
        motor, _ = joint(request.values(float(xs[0]), float(ys[0])))
    for k, (a, b) in enumerate(zip(X.ravel(), Y.ravel(), strict=True)):
        values = request.values(float(a), float(b))
        if MOTOR_AXES & {request.x, request.y}:
            try:
                motor, _ = joint(values)
            except ValueError:  # the card refuses this design: its merits stay nan
                continue
        motors.append(motor)
        index.append(k)
        x0.append(FIELDS["x0"].si(values["x0"]))
        load.append(FIELDS["load"].si(values["load"]))
    merits = {name: np.full(X.size, np.nan) for name in MERITS}
    psi, tau0 = np.full(X.size, np.nan), np.full(X.size, np.nan)
    if index:
        out = design_merits(motors, np.array(x0), np.array(load),
                            FIELDS["k"].si(others["k"]), FIELDS["hardness"].si(others["hardness"]))
        for name in MERITS:
            merits[name][index] = getattr(out, name)
        psi[index], tau0[index] = out.psi, out.tau0
    return MapData(request, xs, ys, {k: v.reshape(shape) for k, v in merits.items()},
                   psi.reshape(shape), tau0.reshape(shape))


def assemble(request: MapRequest, parts: list[MapData]) -> MapData:
    """The map of `request` from its blocks' data (`compute` of each of `blocks`, in
    order)."""
    def rows(get) -> NDArray[np.float64]:
        return np.concatenate([get(p) for p in parts], axis=0)

    return MapData(request, parts[0].x, rows(lambda p: p.y),
                   {name: rows(lambda p, n=name: p.merits[n]) for name in MERITS},
                   rows(lambda p: p.psi), rows(lambda p: p.tau0))


def pareto_front(data: MapData, first: str, second: str) -> list[tuple[int, int]]:
    """(row, column) of the map's designs on the Pareto front of merits `first` and
    `second` (each the greater the better, the wear rate the smaller:
    `core.motor.study.SENSE`), best `first` first: core's `pareto` over the map as a
    study's Dataset."""
    import xarray as xr

    from core.motor.study.summary import pareto

    ny, nx = data.merits[first].shape
    dims = ("row", "column")
    ds = xr.Dataset({**{k: (dims, v) for k, v in data.merits.items()},
                     "psi": (dims, data.psi), "tau0": (dims, data.tau0)},
                    coords={"row": np.arange(ny), "column": np.arange(nx)})
    front = pareto(ds, first, second)
    return list(zip(front["row"].astype(int).tolist(), front["column"].astype(int).tolist(),
                    strict=True))


class MapCache:
    """The maps a card computed, the newest `capacity` kept (a map already computed is
    shown at once). Not shared between sessions."""

    def __init__(self, capacity: int = 12) -> None:
        self.capacity = capacity
        self._maps: OrderedDict[MapRequest, MapData] = OrderedDict()

    def get(self, request: MapRequest) -> MapData | None:
        """The map of `request`, if computed."""
        data = self._maps.get(request)
        if data is not None:
            self._maps.move_to_end(request)
        return data

    def put(self, data: MapData) -> None:
        """Keep `data` (dropping the oldest map beyond the capacity)."""
        self._maps[data.request] = data
        self._maps.move_to_end(data.request)
        while len(self._maps) > self.capacity:
            self._maps.popitem(last=False)

    def __len__(self) -> int:
        return len(self._maps)
