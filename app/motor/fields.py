"""The Motor card's inputs: each field's unit, range and core's domain, the presets, and
the one check of a value in the unit of its box (messages in that unit, in plain words).

Display units are the ones people think in (mm, µm, kHz, GPa, N, g); a field converts to
SI at the boundary (`Field.si`), where core's domain tables (`core.validation.DOMAIN`,
`MOTOR_DOMAIN`) decide what is allowed, and the joint conditions (x0 on the rod, the
preload against the rod) are core's `Motor`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from core import MOTOR_DOMAIN
from core.materials import MATERIALS, MOTOR_MATERIALS
from core.motor import Motor, Rod
from core.validation import DOMAIN, Interval

#: Prefix of the card's URL query keys.
PREFIX = "motor_"


@dataclass(frozen=True)
class Field:
    """One input: its symbol, core's name, label and display unit, the SI value of one
    display unit (`factor / divisor`, so that e.g. 20 mm is exactly the double nearest
    0.02 m), the slider's teaching range (display units) and core's domain of the SI
    value (None: x0, whose range is the rod)."""

    symbol: str
    core: str
    label: str
    unit: str
    factor: float
    divisor: float
    start: float
    end: float
    step: float
    domain: Interval | None

    def si(self, value: float) -> float:
        """`value` (display unit) in SI."""
        return value / self.divisor * self.factor

    def display(self, si: float) -> float:
        """An SI value in the display unit."""
        return si / self.factor * self.divisor

    def title(self) -> str:
        """The label with its unit, e.g. 'L, rod half-length (mm)'."""
        return f"{self.label} ({self.unit})" if self.unit else self.label

    def text(self, value: float) -> str:
        """'L = 20 mm': the value with its symbol and unit."""
        return f"{self.symbol} = {value:.6g}{f' {self.unit}' if self.unit else ''}"

    def allowed(self) -> str:
        """Core's domain in the display unit, e.g. '[0.001, 1e+05] mm'."""
        d = self.domain
        scaled = Interval(None if d.lo is None else self.display(d.lo),
                          None if d.hi is None else self.display(d.hi), d.lo_open, d.hi_open)
        return scaled.describe() + (f" {self.unit}" if self.unit else "")


M = MOTOR_DOMAIN
#: Inputs in display units: rod (L, delta, nu_rod, A, f), rotor (R, G, nu, mu, N), x0,
#: wear (k, hardness) and load (F_L, m).
FIELDS: dict[str, Field] = {
    "L": Field("L", "half_length", "L, rod half-length", "mm", 1.0, 1e3, 5.0, 50.0, 0.5,
               M["half_length"]),
    "delta": Field("δ", "thickness", "δ, rod thickness", "mm", 1.0, 1e3, 0.5, 10.0, 0.1,
                   M["thickness"]),
    "nu_rod": Field("ν_rod", "nu_rod", "ν_rod, Poisson ratio of the rod", "", 1.0, 1.0, 0.0,
                    0.5, 0.01, M["nu_rod"]),
    "A": Field("A", "amplitude", "A, amplitude at the rod's end", "µm", 1.0, 1e6, 0.5, 30.0,
               0.5, M["amplitude"]),
    "f": Field("f", "frequency", "f, frequency", "kHz", 1e3, 1.0, 10.0, 100.0, 0.5,
               M["frequency"]),
    "R": Field("R", "R", "R, rotor radius", "mm", 1.0, 1e3, 0.5, 20.0, 0.1, DOMAIN["R"]),
    "G": Field("G", "G", "G, shear modulus", "GPa", 1e9, 1.0, 5.0, 200.0, 1.0, DOMAIN["G"]),
    "nu": Field("ν", "nu", "ν, Poisson ratio", "", 1.0, 1.0, 0.0, 0.5, 0.01, DOMAIN["nu"]),
    "mu": Field("μ", "mu", "μ, friction coefficient", "", 1.0, 1.0, 0.05, 1.0, 0.01,
                DOMAIN["mu"]),
    "N": Field("N", "preload", "N, preload", "N", 1.0, 1.0, 0.01, 5.0, 0.01, M["preload"]),
    "x0": Field("x₀", "x0", "x₀, contact point", "mm", 1.0, 1e3, -20.0, 20.0, 0.01, None),
    "k": Field("k", "wear_coefficient", "k, Archard wear coefficient", "× 10⁻⁶", 1e-6, 1.0,
               0.0, 100.0, 0.5, M["wear_coefficient"]),
    "hardness": Field("H_V", "hardness", "H_V, hardness of the softer body", "GPa", 1e9, 1.0,
                      0.1, 20.0, 0.1, M["hardness"]),
    "load": Field("F_L", "load", "F_L, load force on the rotor", "N", 1.0, 1.0, 0.0, 0.2,
                  0.001, M["load"]),
    "mass": Field("m", "mass", "m, rotor mass", "g", 1.0, 1e3, 0.1, 100.0, 0.1, M["mass"]),
}
ROD_FIELDS = ("L", "delta", "nu_rod", "A", "f")
ROTOR_FIELDS = ("R", "G", "nu", "mu", "N")
WEAR_FIELDS = ("k", "hardness")
LOAD_FIELDS = ("load", "mass")
#: The SI unit of each display unit (core's).
SI_UNITS = {"mm": "m", "µm": "m", "kHz": "Hz", "GPa": "Pa", "N": "N", "g": "kg",
            "× 10⁻⁶": "", "": ""}


@dataclass(frozen=True)
class Preset:
    """Values of some fields (display units) under a label."""

    label: str
    values: dict[str, float]


#: A piezoceramic (PZT) rod in its first longitudinal mode near 40 kHz.
ROD_PRESETS: dict[str, Preset] = {
    "pzt40": Preset("PZT rod, 2L = 40 mm, δ = 4 mm, A = 10 µm, 40 kHz",
                    {"L": 20.0, "delta": 4.0, "nu_rod": 0.31, "A": 10.0, "f": 40.0}),
    "pzt60": Preset("PZT rod, 2L = 26 mm, δ = 3 mm, A = 6 µm, 60 kHz",
                    {"L": 13.0, "delta": 3.0, "nu_rod": 0.31, "A": 6.0, "f": 60.0}),
}


def _rotor(key: str, mu: float) -> Preset:
    """A rotor of material `key` (G, nu from `core.materials.MATERIALS`), R = 5 mm,
    N = 0.5 N, and a dry friction coefficient mu."""
    m = MATERIALS[key]
    return Preset(f"{key} rotor, R = 5 mm, N = 0.5 N",
                  {"R": 5.0, "G": m.G / 1e9, "nu": m.nu, "mu": mu, "N": 0.5})


ROTOR_PRESETS: dict[str, Preset] = {"steel": _rotor("steel", 0.2),
                                    "alumina": _rotor("alumina", 0.3)}
#: The rod's contact layer: '' the rotor's material (the paper's identical bodies), or a
#: material of `core.materials.MOTOR_MATERIALS`.
ROD_MATERIALS: dict[str, str] = {"": "same as the rotor (the paper's identical bodies)",
                                 **{k: MATERIALS[k].name for k in MOTOR_MATERIALS}}
DEFAULT_ROD, DEFAULT_ROTOR, DEFAULT_X0 = "pzt40", "steel", -5.0


def softer_hardness(rotor_preset: str, rod_material: str) -> float | None:
    """The hardness (GPa) of the softer body by the presets' materials (Archard's H), or
    None when the rotor is not a preset."""
    if rotor_preset not in ROTOR_PRESETS:
        return None
    values = [MATERIALS[rotor_preset].hardness]
    if rod_material:
        values.append(MATERIALS[rod_material].hardness)
    return min(values) / 1e9


def number(raw: Any) -> float:
    """The float a value or text stands for; ValueError in plain words if none."""
    if isinstance(raw, bool):
        raise ValueError(f"{raw!r} is not a number")
    if isinstance(raw, int | float):
        return float(raw)
    try:
        return float(str(raw).strip())
    except ValueError:
        raise ValueError(f"{str(raw)[:40]!r} is not a number") from None


def build_motor(values: Mapping[str, Any]) -> tuple[Motor, float]:
    """The core `Motor` and x0 (m) of `values` (display units for every key of FIELDS,
    `rod_material` and `flat`), each field already checked (`check`); core's
    ValueError for a joint refusal (the preload against the rod)."""
    si = {name: f.si(values[name]) for name, f in FIELDS.items()}
    rod = Rod(**{FIELDS[k].core: si[k] for k in ROD_FIELDS})
    material = MATERIALS.get(values["rod_material"])
    motor = Motor(rod, **{FIELDS[k].core: si[k] for k in ROTOR_FIELDS},
                  rod_G=material and material.G, rod_nu=material and material.nu,
                  rod_R=math.inf if values["flat"] else None)
    return motor, si["x0"]


def joint(values: Mapping[str, Any]) -> tuple[Motor, float]:
    """`build_motor` of `values` whose fields were each checked, with the joint
    conditions: the rotor on the rod, then core's (the preload against the rod);
    ValueError in plain words otherwise."""
    L, x0 = values["L"], values["x0"]
    if not abs(x0) < L:
        raise ValueError(f"the rotor (x₀ = {x0:.6g} mm) would be off the rod: x₀ must lie "
                         f"between -{L:.6g} and {L:.6g} mm (the rod's ends excluded)")
    return build_motor(values)


def check(name: str, raw: Any, values: Mapping[str, Any]) -> float:
    """Field `name` = `raw` (a number or the text of its box) as a float, checked alone
    (core's domain) and with the other `values` (`joint`); ValueError in the box's unit
    and in plain words otherwise."""
    f = FIELDS[name]
    try:
        value = number(raw)
    except ValueError as err:
        raise ValueError(f"{f.symbol} = {err}") from None
    if not math.isfinite(value):
        raise ValueError(f"{f.symbol} must be a finite number, not {value}")
    if f.domain is not None and not f.domain.contains(f.si(value)):
        raise ValueError(f"{f.text(value)} is outside the allowed range {f.allowed()}")
    L, x0 = (value, values["x0"]) if name == "L" else (values["L"], value)
    if name == "x0" and not abs(x0) < L:
        raise ValueError(f"{f.text(value)} is off the rod: x₀ must lie between "
                         f"-{L:.6g} and {L:.6g} mm (the rod's ends excluded)")
    if name == "L" and not abs(x0) < L:
        raise ValueError(f"{f.text(value)} would leave the rotor (x₀ = {x0:.6g} mm) off "
                         f"the rod: move x₀ inside ±{L:.6g} mm first")
    try:
        joint({**values, name: value})
    except ValueError as err:
        raise ValueError(f"{f.text(value)} is refused: {err}") from None
    return value
