"""A link's query read into the explorer's state: `parse_query` (and `query_value`).

The state writes its own query (`ExplorerState.query`); this module reads one back by
applying it to a scratch `ExplorerState` in a defined order (`parse_query`), so that
the state's own rules (a preset's and a material's values, the drive, the physical
inputs, its corrections) decide what follows, and telling the user, value by value, what
was refused and why.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import param

from app.contact.state import (
    DRIVES,
    PRESETS,
    QUERY_KEYS,
    SI_KEYS,
    ExplorerState,
    material_values,
    parse_flag,
    parse_tau,
    parse_value,
)
from core import DRY_MU, Contact

#: A link's numbers and flags, read in this order and applied together (`read_values`).
NUMBERS = ("psi", "tau0", "mu", "nu", "theta", *SI_KEYS)
FLAGS = ("log_psi", "period", "physical")


def query_value(raw: str | bytes | list) -> str:
    """One URL query value as text: the last of repeated values (as
    `pn.state.session_args` lists them), bytes decoded, blanks stripped."""
    if isinstance(raw, list):
        raw = raw[-1] if raw else ""
    if isinstance(raw, bytes):
        raw = raw.decode("utf-8", "replace")
    return str(raw).strip()


def parse_query(query: Mapping[str, str | bytes | list]) -> tuple[dict, list[str]]:
    """Validate URL query values by applying them to a scratch `ExplorerState`.

    `query` maps names to strings (or bytes, or lists of them as in
    `pn.state.session_args`).  Returns `(values, messages)`: the accepted values as
    parameter updates for `ExplorerState` (the scratch state's value of each parameter
    the link set, or that follows from what it set), and one human-readable message per
    rejected value (whose default is then kept).  Unknown names are reported too.

    The order: a `preset` (`ExplorerState.apply_preset`; the link's own physical flag
    decides), then a `material` (`ExplorerState.apply_material`: G, nu, mu and
    physical = 1), then the drive, the numbers (`NUMBERS`, each against its domain) and
    the flags (`read_values`: explicit values override the preset's and the
    material's), all three in one batch of the state's watchers (its corrections, and
    leaving the preset or the material if they differ from its values, see them all
    at once), then what follows from them by the state's rules (`follow_drive`,
    `follow_physical`: with drive = angle psi follows from theta, mu and nu, eq 23;
    with physical = 1 psi and tau0 follow from R, G, H, u0, h, omega, mu and nu, and
    physical inputs core refuses together, e.g. |h| >= H, are reported and physical is
    left off), then tau, inside the contact they make (`apply_tau`).
    """
    flat = {key: query_value(raw) for key, raw in query.items()}
    messages = [f"unknown parameter {key!r} ignored (known: {', '.join(QUERY_KEYS)})"
                for key in flat if key not in QUERY_KEYS]
    scratch, touched = ExplorerState(), set()
    with param.parameterized.batch_call_watchers(scratch):  # (the state's rules see all)
        for step, key in ((apply_preset, "preset"), (apply_material, "material")):
            try:
                touched |= step(scratch, flat.get(key))
            except ValueError as err:
                messages.append(str(err))
        link = read_values(flat, messages)
        scratch.param.update(**link)
    touched |= set(link)
    for rule in (follow_drive, follow_physical, apply_tau):
        rule(scratch, flat, link, touched, messages)
    return {k: getattr(scratch, k) for k in QUERY_KEYS if k in touched}, messages


def apply_preset(scratch: ExplorerState, name: str | None) -> set[str]:
    """Preset `name` (if any) applied to `scratch`: the parameters it sets (but the
    physical inputs' flag, which the link's own decides); ValueError (the message to
    show) if it is unknown."""
    if name is None:
        return set()
    if name not in PRESETS:
        raise ValueError(f"preset = {name!r} is unknown (known: {', '.join(PRESETS)})")
    scratch.apply_preset(name)
    return set(PRESETS[name].values(name)) - {"physical"}


def apply_material(scratch: ExplorerState, name: str | None) -> set[str]:
    """Material `name` (if any) applied to `scratch` (G, nu, mu and physical = 1;
    'custom' names none): the parameters it sets; ValueError (the message) if unknown."""
    if name is None:
        return set()
    if name == "custom":
        scratch.material = name
        return {"material"}
    if name not in DRY_MU:
        raise ValueError(f"material = {name!r} is unknown "
                         f"(known: {', '.join(DRY_MU)}, custom)")
    scratch.apply_material(name)
    return set(material_values(name))


def read_values(flat: dict[str, str], messages: list[str]) -> dict:
    """The drive, numbers (`NUMBERS`, each against its domain) and flags (`FLAGS`) of
    the link's texts `flat` that are valid; the message of each refused one appended
    to `messages`."""
    values: dict = {}
    if "drive" in flat and flat["drive"] not in DRIVES:
        messages.append(f"drive = {flat['drive']!r} is unknown (known: {', '.join(DRIVES)})")
    elif "drive" in flat:
        values["drive"] = flat["drive"]
    for key in (k for k in (*NUMBERS, *FLAGS) if k in flat):
        try:
            values[key] = (parse_flag if key in FLAGS else parse_value)(key, flat[key])
        except ValueError as err:
            messages.append(str(err))
    return values


def follow_drive(scratch: ExplorerState, flat: dict[str, str], link: dict,
                 touched: set[str], messages: list[str]) -> None:
    """The drive's angle: a link's theta is ignored (said) unless drive = angle; with
    drive = angle (and no physical inputs) the state's psi follows from theta, mu and
    nu (`ExplorerState.drive_psi`, eq 23; a link's psi that does not give theta is
    ignored, said), or, when that psi is outside its domain, the drive angle is not
    applied (said) and the drive is psi again."""
    if "theta" in link and scratch.drive != "angle":
        messages.append(f"theta = {flat['theta']!r} ignored: it sets the drive only with "
                        f"drive = angle")
        touched.discard("theta")
    elif scratch.drive == "angle" and not scratch.physical:
        try:
            parse_value("psi", repr(scratch.drive_psi()))
        except ValueError as err:
            messages.append(f"the drive angle is not applied: {err}")
            scratch.drive = "psi"
            touched.discard("theta")
            return
        if "psi" in link and scratch.psi != link["psi"]:
            messages.append(f"psi = {flat['psi']!r} ignored: with drive = angle it "
                            f"follows from theta, mu and nu")
        touched |= {"psi", "theta"}


def follow_physical(scratch: ExplorerState, flat: dict[str, str], link: dict,
                    touched: set[str], messages: list[str]) -> None:
    """With physical = 1, psi and tau0 follow from the physical inputs (a link's psi or
    tau0 is ignored, said); inputs core refuses together are said and physical is left
    off (and the link's preset kept if it is still the state's contact)."""
    if not scratch.physical:
        return
    try:
        scratch.contact()
    except ValueError as err:
        messages.append(f"the physical inputs are not applied: {err}")
        # (a preset the physical inputs left is the state's again if its contact is)
        preset = flat["preset"] if "preset" in touched else scratch.preset
        scratch.param.update(physical=False, preset=preset)
        return
    for key in ("psi", "tau0"):
        if key in link:
            messages.append(f"{key} = {flat[key]!r} ignored: with physical = 1 it "
                            f"follows from {', '.join(SI_KEYS)}, mu and nu")
    touched |= {"psi", "tau0"}


def apply_tau(scratch: ExplorerState, flat: dict[str, str], link: dict,
              touched: set[str], messages: list[str]) -> None:
    """The link's tau, inside the contact of the state's tau0 (or with period = 1 the
    whole period: `parse_tau`); else, when the link moved tau0 but set no tau, pi / 2
    (inside every contact [tau0, pi - tau0])."""
    if "tau" in flat:
        try:
            scratch.tau = parse_tau(flat["tau"], Contact(1.0, scratch.tau0),
                                    period=scratch.period)
        except ValueError as err:
            messages.append(str(err))
            return
        touched.add("tau")
    elif "tau0" in touched and "tau" not in touched:
        scratch.tau = math.pi / 2
        touched.add("tau")
