"""A design study's declaration: the axes swept, their grids, the fixed design and the
resolution, validated once against ``core.MOTOR_DOMAIN`` (docs/study.md).

A study is a ``StudySpec``: a ``BaseDesign`` (every parameter of one motor design, SI)
and a tuple of ``Axis`` (a parameter of ``AXES`` and its grid), read from a TOML file
(``load_spec``) or built in Python. Its ``key`` hashes what determines its results (the
axes' values, the base design, the resolution, the block size, which sets the store's
chunks) together with the code version (``code_version``: the sources of ``core`` and
the versions of numpy, scipy and numba), so the same spec and the same code reuse the
same store.

    [study]
    name = "x0-preload"
    block = 2000                   # designs per task and per Zarr chunk

    [design]                       # the fixed values (SI); defaults: BaseDesign
    rotor_material = "steel"
    rod_material = "PZT-4"

    [axes.x0]                      # m
    start = -0.0199
    stop = -0.0001
    num = 200

    [axes.preload]                 # N
    start = 0.01
    stop = 1.0
    num = 200
    spacing = "log"

    [axes.rotor_material]
    values = ["steel", "alumina"]
"""

from __future__ import annotations

import hashlib
import json
import math
import tomllib
from dataclasses import asdict, dataclass, field, fields, replace
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np

from core.materials import MOTOR_MATERIALS
from core.motor.moving_rotor import SPRINGS, STEPS, _resolution
from core.validation import DOMAIN, MOTOR_DOMAIN, Interval, shown

#: The parameters a study may sweep: name -> (unit, description).
AXES: dict[str, tuple[str, str]] = {
    "x0": ("m", "contact point on the rod"),
    "preload": ("N", "force pressing the rotor on the rod"),
    "amplitude": ("m", "longitudinal amplitude A of the rod at x = L"),
    "frequency": ("Hz", "vibration frequency of the rod"),
    "rotor_radius": ("m", "radius R of the rotor's contact sphere"),
    "rotor_material": ("", "material of the rotor (core.materials.MOTOR_MATERIALS)"),
    "rod_material": ("", "material of the rod's contact face (core.materials.MOTOR_MATERIALS)"),
    "load": ("N", "load force opposing the rotor"),
}
MATERIAL_AXES = ("rotor_material", "rod_material")
#: rod_material = ROTOR: the rod's contact point is a sphere identical to the rotor
#: (the paper's model: Motor's rod_G, rod_nu, rod_R None).
ROTOR = "rotor"
#: Designs per task and per chunk: MOTOR_DOMAIN has no row for it; Dask's per-task
#: overhead (~1 ms) is 1e-4 of a block of 1000 designs of ~3 ms each.
BLOCK = Interval(1, 10**5)
#: Largest number of designs of one study (the store is 11 variables of 8 bytes each).
DESIGNS_MAX = 10**9
#: Largest number of points of one axis.
AXIS_MAX = 10**6


def _number(where: str, value: object, row: Interval) -> float:
    """value checked against row, the error naming ``where``."""
    return row.check(where, value)


@dataclass(frozen=True)
class BaseDesign:
    """Every parameter of one motor design (SI; the README's rod, a steel ball on a
    flat PZT-4 face): the rod (``core.motor.Rod``: half_length, thickness, nu_rod,
    amplitude, frequency), the rotor (radius, material, friction coefficient mu,
    preload), the rod's contact face (material, radius; ``ROTOR`` for the paper's
    identical sphere), the contact point x0, the load, and Archard's wear coefficient
    and hardness (None: the softer of the two materials' hardness).

    Validated (ValueError naming the parameter, its value and the range) against
    ``MOTOR_DOMAIN`` and ``DOMAIN``; materials against ``core.materials.MOTOR_MATERIALS``.
    """

    half_length: float = 0.02
    thickness: float = 4e-3
    nu_rod: float = 0.3
    amplitude: float = 10e-6
    frequency: float = 40e3
    rotor_radius: float = 5e-3
    rotor_material: str = "steel"
    mu: float = 0.2
    preload: float = 0.05
    rod_material: str = "PZT-4"
    rod_radius: float = math.inf
    x0: float = -0.2e-3
    load: float = 0.0
    wear_coefficient: float = 1e-6
    hardness: float | None = None

    def __post_init__(self) -> None:
        rows = {"half_length": MOTOR_DOMAIN["half_length"], "thickness": MOTOR_DOMAIN["thickness"],
                "nu_rod": MOTOR_DOMAIN["nu_rod"], "amplitude": MOTOR_DOMAIN["amplitude"],
                "frequency": MOTOR_DOMAIN["frequency"], "rotor_radius": DOMAIN["R"],
                "mu": DOMAIN["mu"], "preload": MOTOR_DOMAIN["preload"],
                "load": MOTOR_DOMAIN["load"],
                "wear_coefficient": MOTOR_DOMAIN["wear_coefficient"]}
        for name, row in rows.items():
            object.__setattr__(self, name, row.check(name, getattr(self, name)))
        if self.rod_radius != math.inf:
            object.__setattr__(self, "rod_radius", DOMAIN["R"].check("rod_radius",
                                                                     self.rod_radius))
        if self.hardness is not None:
            object.__setattr__(self, "hardness",
                               MOTOR_DOMAIN["hardness"].check("hardness", self.hardness))
        for name in MATERIAL_AXES:
            check_material(name, getattr(self, name))
        inside = Interval(-self.half_length, self.half_length, lo_open=True, hi_open=True)
        object.__setattr__(self, "x0", inside.check("x0", self.x0))


def check_material(name: str, value: object, where: str | None = None) -> str:
    """value if it names one of ``core.materials.MOTOR_MATERIALS`` (or, for rod_material,
    ``ROTOR``); ValueError naming the parameter (or ``where``) and the choices
    otherwise."""
    allowed = list(MOTOR_MATERIALS) + ([ROTOR] if name == "rod_material" else [])
    if not isinstance(value, str) or value not in allowed:
        raise ValueError(f"{where or name} = {shown(value)} is not a material: choose one of "
                         f"{', '.join(allowed)}")
    return value


@dataclass(frozen=True)
class Axis:
    """One swept parameter: ``name`` (a key of ``AXES``) and its grid ``values`` (floats
    in SI units, or material names), at least one, without repeats."""

    name: str
    values: tuple[Any, ...]

    def __post_init__(self) -> None:
        if self.name not in AXES:
            raise ValueError(f"axis {shown(self.name)} is not a study axis: choose among "
                             f"{', '.join(AXES)}")
        values = tuple(self.values) if not isinstance(self.values, str) else (self.values,)
        if not 1 <= len(values) <= AXIS_MAX:
            raise ValueError(f"axis {self.name}: {len(values)} values, allowed 1 to "
                             f"{AXIS_MAX:g}")
        if self.name in MATERIAL_AXES:
            values = tuple(check_material(self.name, v, f"axis {self.name}: {self.name}[{i}]")
                           for i, v in enumerate(values))
        else:
            row = _row(self.name)
            values = tuple(_number(f"axis {self.name}: {self.name}[{i}]", v, row)
                           for i, v in enumerate(values))
        if len(set(values)) != len(values):
            raise ValueError(f"axis {self.name}: a value is repeated")
        object.__setattr__(self, "values", values)

    @property
    def unit(self) -> str:
        return AXES[self.name][0]

    @classmethod
    def grid(cls, name: str, start: float, stop: float, num: int,
             spacing: str = "linear") -> Axis:
        """``num`` values from start to stop, equally spaced ("linear") or in ratio
        ("log", both ends of one sign)."""
        if spacing not in ("linear", "log"):
            raise ValueError(f"axis {name}: spacing = {shown(spacing)} must be 'linear' or "
                             "'log'")
        if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= AXIS_MAX:
            raise ValueError(f"axis {name}: num = {shown(num)} must be an integer in "
                             f"[1, {AXIS_MAX:g}]")
        a = _number(f"axis {name}: start", start, Interval(None, None))
        b = _number(f"axis {name}: stop", stop, Interval(None, None))
        if spacing == "log" and not a * b > 0.0:
            raise ValueError(f"axis {name}: a log spacing needs start and stop of one sign, "
                             f"got {shown(a)} and {shown(b)}")
        grid = np.linspace(a, b, num) if spacing == "linear" else np.geomspace(a, b, num)
        return cls(name, tuple(float(v) for v in grid))


def _row(name: str) -> Interval:
    """The domain row of a numeric axis (x0 is checked per rod by ``StudySpec``)."""
    return {"x0": Interval(None, None), "preload": MOTOR_DOMAIN["preload"],
            "amplitude": MOTOR_DOMAIN["amplitude"], "frequency": MOTOR_DOMAIN["frequency"],
            "rotor_radius": DOMAIN["R"], "load": MOTOR_DOMAIN["load"]}[name]


def code_version() -> str:
    """A hash of what the results depend on: every Python source of ``core`` (this
    package included) and the versions of numpy, scipy and numba."""
    import numba
    import scipy

    root = Path(__file__).resolve().parents[2]  # core/
    h = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        h.update(path.relative_to(root).as_posix().encode())
        h.update(path.read_bytes())
    for version in (np.__version__, scipy.__version__, numba.__version__):
        h.update(version.encode())
    return h.hexdigest()[:16]


@dataclass(frozen=True)
class StudySpec:
    """A design study: ``axes`` swept over the ``base`` design, with the MDR
    resolution (springs, steps; ``moving_rotor``'s defaults) and ``block`` designs per
    task and per chunk of the store. ``name`` names the store (letters, digits, '-',
    '_', '.')."""

    name: str
    axes: tuple[Axis, ...]
    base: BaseDesign = field(default_factory=BaseDesign)
    block: int = 2000
    springs: int = SPRINGS
    steps: int = STEPS

    def __post_init__(self) -> None:
        ok = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.")
        if not isinstance(self.name, str) or not self.name or not set(self.name) <= ok \
                or self.name.startswith("."):
            raise ValueError(f"name = {shown(self.name)} must be letters, digits, '-', '_' "
                             "or '.'")
        axes = tuple(self.axes)
        if not axes or not all(isinstance(a, Axis) for a in axes):
            raise ValueError("axes must be one Axis or more")
        names = [a.name for a in axes]
        if len(set(names)) != len(names):
            raise ValueError(f"axes: {', '.join(names)} names an axis twice")
        object.__setattr__(self, "axes", axes)
        if not isinstance(self.base, BaseDesign):
            raise ValueError("base must be a BaseDesign")
        block = BLOCK.check("block", self.block)
        if block != int(block):
            raise ValueError(f"block = {shown(self.block)} must be an integer")
        object.__setattr__(self, "block", int(block))
        n, m = _resolution(self.springs, self.steps)
        object.__setattr__(self, "springs", n)
        object.__setattr__(self, "steps", m)
        if "x0" in names:
            L = self.base.half_length
            inside = Interval(-L, L, lo_open=True, hi_open=True)
            for i, v in enumerate(self.axis("x0").values):
                inside.check(f"axis x0: x0[{i}]", v)
        if self.size > DESIGNS_MAX:
            raise ValueError(f"the study has {self.size:g} designs, more than {DESIGNS_MAX:g}")

    def axis(self, name: str) -> Axis:
        """The axis called name (KeyError if it is not swept)."""
        for a in self.axes:
            if a.name == name:
                return a
        raise KeyError(name)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(a.values) for a in self.axes)

    @property
    def size(self) -> int:
        return math.prod(self.shape)

    @cached_property
    def chunk_shape(self) -> tuple[int, ...]:
        """The store's chunks (and the tasks): whole trailing axes while they fit in
        ``block`` designs, then a slab of the next axis, 1 along the others."""
        out = [1] * len(self.shape)
        room = self.block
        for i in range(len(self.shape) - 1, -1, -1):
            take = min(self.shape[i], max(room, 1))
            out[i] = take
            room //= take
            if take < self.shape[i]:
                break
        return tuple(out)

    def to_dict(self) -> dict[str, Any]:
        """The declaration as plain data (what ``key`` hashes; ``from_dict`` inverts)."""
        base = asdict(self.base)
        if base["rod_radius"] == math.inf:
            base["rod_radius"] = "inf"
        return {"name": self.name, "block": self.block, "springs": self.springs,
                "steps": self.steps, "design": base,
                "axes": [[a.name, list(a.values)] for a in self.axes]}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> StudySpec:
        base = dict(data.get("design", {}))
        if base.get("rod_radius") == "inf":
            base["rod_radius"] = math.inf
        return cls(name=data["name"], axes=tuple(Axis(k, tuple(v)) for k, v in data["axes"]),
                   base=BaseDesign(**base), block=data.get("block", 2000),
                   springs=data.get("springs", SPRINGS), steps=data.get("steps", STEPS))

    @cached_property
    def key(self) -> str:
        """sha256 (16 hex digits) of the declaration but its name, and of
        ``code_version()``."""
        data = self.to_dict()
        del data["name"]
        text = json.dumps(data, sort_keys=True, separators=(",", ":"), allow_nan=False)
        return hashlib.sha256((text + code_version()).encode()).hexdigest()[:16]

    def store_path(self, folder: str | Path) -> Path:
        """The study's Zarr store in ``folder``: NAME-KEY.zarr."""
        return Path(folder) / f"{self.name}-{self.key}.zarr"

    def with_axes(self, *axes: Axis, **base: Any) -> StudySpec:
        """This study with other axes and base values (e.g. the follow-up study at the
        best x0 of a first one)."""
        return replace(self, axes=axes, base=replace(self.base, **base))


def _axis_from_toml(name: str, table: object) -> Axis:
    if not isinstance(table, dict):
        raise ValueError(f"axis {name}: expected a table with 'values', or 'start', 'stop' "
                         "and 'num'")
    keys = set(table)
    if "values" in keys:
        if keys - {"values"}:
            raise ValueError(f"axis {name}: 'values' goes alone, got {', '.join(sorted(keys))}")
        values = table["values"]
        if not isinstance(values, list):
            values = [values]
        return Axis(name, tuple(values))
    missing = {"start", "stop", "num"} - keys
    extra = keys - {"start", "stop", "num", "spacing"}
    if missing or extra:
        raise ValueError(f"axis {name}: needs 'values', or 'start', 'stop', 'num' (and "
                         f"'spacing'); missing {', '.join(sorted(missing)) or 'none'}, "
                         f"unknown {', '.join(sorted(extra)) or 'none'}")
    return Axis.grid(name, table["start"], table["stop"], table["num"],
                     table.get("spacing", "linear"))


def spec_from_toml(text: str, default_name: str = "study") -> StudySpec:
    """A StudySpec from the text of a TOML spec (module docstring)."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValueError(f"the spec is not valid TOML: {err}") from err
    unknown = set(data) - {"study", "design", "axes"}
    if unknown:
        raise ValueError(f"unknown table(s) {', '.join(sorted(unknown))}: a spec has "
                         "[study], [design] and [axes.NAME]")
    study = dict(data.get("study", {}))
    known = {"name", "block", "springs", "steps"}
    if set(study) - known:
        raise ValueError(f"[study]: unknown key(s) {', '.join(sorted(set(study) - known))}")
    design = dict(data.get("design", {}))
    allowed = {f.name for f in fields(BaseDesign)}
    if set(design) - allowed:
        raise ValueError(f"[design]: unknown key(s) {', '.join(sorted(set(design) - allowed))}"
                         f"; allowed: {', '.join(sorted(allowed))}")
    if design.get("rod_radius") == "inf":
        design["rod_radius"] = math.inf
    axes = tuple(_axis_from_toml(k, v) for k, v in data.get("axes", {}).items())
    return StudySpec(name=study.get("name", default_name), axes=axes,
                     base=BaseDesign(**design), block=study.get("block", 2000),
                     springs=study.get("springs", SPRINGS), steps=study.get("steps", STEPS))


def load_spec(path: str | Path) -> StudySpec:
    """The StudySpec of a TOML file (its name defaults to the file's stem)."""
    p = Path(path)
    return spec_from_toml(p.read_text(), default_name=p.stem)
