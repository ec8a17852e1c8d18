"""The Motor card's state (`MotorState`, display units) and its URL codec (`motor_*`).

A URL names the presets it uses (`motor_rod`, `motor_rotor`) and writes the other fields
whose values differ from the presets' or the defaults' as the shortest text that reads
back as the same float; x0 always.  `motor_material` is the rod's contact layer (one of
`core.materials.MOTOR_MATERIALS`; absent: the rotor's material), `motor_flat=1` a flat
rod face.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import param

from app.motor.fields import (
    DEFAULT_ROD,
    DEFAULT_ROTOR,
    DEFAULT_X0,
    FIELDS,
    LOAD_FIELDS,
    PREFIX,
    ROD_FIELDS,
    ROD_MATERIALS,
    ROD_PRESETS,
    ROTOR_FIELDS,
    ROTOR_PRESETS,
    WEAR_FIELDS,
    Preset,
    check,
    joint,
)
from core.motor import Motor

#: URL keys of the card, in order.
QUERY_KEYS = tuple(PREFIX + k for k in ("rod", "rotor", "material", "flat", *FIELDS))
#: The state's parameters a URL holds (a change of any of them changes the URL).
URL_PARAMS = ("rod_preset", "rotor_preset", "rod_material", "flat", *FIELDS)


class MotorState(param.Parameterized):
    """What the user set, in display units (mm, µm, kHz, GPa, N, g); never a refused
    value."""

    rod_preset = param.String(default=DEFAULT_ROD, doc="rod preset key, '' once edited")
    rotor_preset = param.String(default=DEFAULT_ROTOR, doc="rotor preset key, '' once edited")
    rod_material = param.Selector(default="", objects=list(ROD_MATERIALS), doc=(
        "the rod's contact layer: a key of core.materials.MOTOR_MATERIALS, '' the rotor's"))
    flat = param.Boolean(default=False, doc="the rod's face is flat (rod_R = inf)")
    L = param.Number(default=20.0, doc="rod half-length (mm)")
    delta = param.Number(default=4.0, doc="rod thickness (mm)")
    nu_rod = param.Number(default=0.31, doc="Poisson ratio of the rod")
    A = param.Number(default=10.0, doc="longitudinal amplitude at x = L (µm)")
    f = param.Number(default=40.0, doc="frequency (kHz)")
    R = param.Number(default=5.0, doc="rotor radius (mm)")
    G = param.Number(default=79.3, doc="shear modulus (GPa)")
    nu = param.Number(default=0.29, doc="Poisson ratio")
    mu = param.Number(default=0.2, doc="friction coefficient")
    N = param.Number(default=0.5, doc="preload (N)")
    x0 = param.Number(default=DEFAULT_X0, doc="contact point (mm)")
    k = param.Number(default=10.0, doc="Archard wear coefficient (units of 1e-6)")
    hardness = param.Number(default=7.4, doc="hardness of the softer body (GPa)")
    load = param.Number(default=0.02, doc="load force opposing the rotor (N)")
    mass = param.Number(default=10.0, doc="rotor mass, translational equivalent (g)")

    def values(self) -> dict[str, Any]:
        """Every field's value (display units), the rod's material and face."""
        return {k: getattr(self, k) for k in (*FIELDS, "rod_material", "flat")}

    def motor(self) -> tuple[Motor, float]:
        """The core `Motor` of the state and x0 in m."""
        return joint(self.values())

    def matches(self, presets: Mapping[str, Preset], name: str) -> bool:
        """Whether the fields of preset `name` hold its values."""
        return name in presets and all(
            getattr(self, k) == v for k, v in presets[name].values.items())

    @param.depends(*ROD_FIELDS, *ROTOR_FIELDS, watch=True)
    def _leave_presets(self) -> None:
        """A preset names what is on screen: any other value of its fields leaves it."""
        if self.rod_preset and not self.matches(ROD_PRESETS, self.rod_preset):
            self.rod_preset = ""
        if self.rotor_preset and not self.matches(ROTOR_PRESETS, self.rotor_preset):
            self.rotor_preset = ""

    def query(self) -> dict[str, str]:
        """The state as URL values: preset keys (their fields only where they differ),
        the rod's material and face where not the paper's, x0, and the wear and load
        fields where not their defaults."""
        q: dict[str, str] = {}
        for key, names in (("rod", ROD_FIELDS), ("rotor", ROTOR_FIELDS)):
            name = getattr(self, f"{key}_preset")
            if name:
                q[PREFIX + key] = name
            else:
                q.update({PREFIX + k: repr(float(getattr(self, k))) for k in names})
        if self.rod_material:
            q[PREFIX + "material"] = self.rod_material
        if self.flat:
            q[PREFIX + "flat"] = "1"
        q[PREFIX + "x0"] = repr(float(self.x0))
        for k in (*WEAR_FIELDS, *LOAD_FIELDS):
            if getattr(self, k) != self.param[k].default:
                q[PREFIX + k] = repr(float(getattr(self, k)))
        return q


def _text(raw: str | bytes | list) -> str:
    """A URL value as text (the last of repeated values)."""
    if isinstance(raw, list):
        raw = raw[-1] if raw else ""
    if isinstance(raw, bytes):
        raw = raw.decode("utf-8", "replace")
    return str(raw).strip()


def decode(query: Mapping[str, str | bytes | list], state: MotorState
           ) -> tuple[dict[str, Any], list[str]]:
    """The updates of `state` a URL query asks for (its `motor_*` keys; others ignored)
    and one message per refused value, in the unit of its box. Presets, the rod's
    material and face first, then the fields, each checked with those accepted before
    it, x0 last."""
    flat = {k.removeprefix(PREFIX): _text(v) for k, v in query.items() if k.startswith(PREFIX)}
    messages = [f"unknown parameter {PREFIX + k!r} ignored (known: {', '.join(QUERY_KEYS)})"
                for k in flat if PREFIX + k not in QUERY_KEYS]
    values = state.values()
    updates: dict[str, Any] = {}
    for part, table in (("rod", ROD_PRESETS), ("rotor", ROTOR_PRESETS)):
        if part in flat:
            if flat[part] in table:
                values.update(table[flat[part]].values)
                updates[f"{part}_preset"] = flat[part]
            else:
                messages.append(f"{PREFIX}{part} = {flat[part]!r} is unknown "
                                f"(known: {', '.join(table)})")
    if "material" in flat:
        if flat["material"] in ROD_MATERIALS:
            values["rod_material"] = updates["rod_material"] = flat["material"]
        else:
            messages.append(f"{PREFIX}material = {flat['material']!r} is unknown (known: "
                            f"{', '.join(k for k in ROD_MATERIALS if k)})")
    if "flat" in flat:
        if flat["flat"] in ("0", "1"):
            values["flat"] = updates["flat"] = flat["flat"] == "1"
        else:
            messages.append(f"{PREFIX}flat = {flat['flat']!r} must be 0 or 1")
    try:
        joint(values)
    except ValueError as err:  # presets that do not fit the current x0 or preload
        messages.append(f"the presets are refused: {err}")
        values, updates = state.values(), {}
    for name in FIELDS:
        if name in flat:
            try:
                values[name] = updates[name] = check(name, flat[name], values)
            except ValueError as err:
                messages.append(f"{PREFIX}{name}: {err}")
    return updates, messages
