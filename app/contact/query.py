"""A link's query read into the explorer's state: `parse_query` (and `query_value`).

The state writes its own query (`ExplorerState.query`); this module reads one back,
validating each value once against the domain (`app.contact.state.domain`) and telling
the user, value by value, what was refused and why.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

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


def query_value(raw: str | bytes | list) -> str:
    """One URL query value as text: the last of repeated values (as
    `pn.state.session_args` lists them), bytes decoded, blanks stripped."""
    if isinstance(raw, list):
        raw = raw[-1] if raw else ""
    if isinstance(raw, bytes):
        raw = raw.decode("utf-8", "replace")
    return str(raw).strip()


def parse_query(query: Mapping[str, str | bytes | list]) -> tuple[dict, list[str]]:
    """Validate URL query values.

    `query` maps names to strings (or bytes, or lists of them as in
    `pn.state.session_args`).  Returns `(values, messages)`: the accepted values as
    parameter updates for `ExplorerState`, and one human-readable message per
    rejected value (whose default is then kept).  Unknown names are reported too.
    With drive = angle the contact's drive is its angle theta (degrees) and psi follows
    from theta, mu and nu (eq 23).
    A `preset` is applied first, then a `material` (G, nu, mu, physical = 1); explicit
    values then override them (and the state leaves the preset or the material if they
    differ from its values).  With physical = 1, R, G, H, u0, h (m, Pa) and omega
    (rad/s) define the contact and psi and tau0 follow from them; physical inputs that
    core refuses together (e.g. |h| >= H) are reported and physical is left off.
    """
    values: dict = {}
    messages: list[str] = []
    flat = {key: query_value(raw) for key, raw in query.items()}

    for key in flat:
        if key not in QUERY_KEYS:
            messages.append(f"unknown parameter {key!r} ignored "
                            f"(known: {', '.join(QUERY_KEYS)})")

    if "preset" in flat:
        name = flat["preset"]
        if name in PRESETS:
            values.update(PRESETS[name].values(name))
            del values["physical"]  # (a link's own physical flag, if any, decides)
        else:
            messages.append(f"preset = {name!r} is unknown (known: {', '.join(PRESETS)})")

    if "material" in flat:
        name = flat["material"]
        if name in DRY_MU:
            values.update(material_values(name))
        elif name == "custom":
            values["material"] = name
        else:
            messages.append(f"material = {name!r} is unknown "
                            f"(known: {', '.join(DRY_MU)}, custom)")

    if "drive" in flat:
        if flat["drive"] in DRIVES:
            values["drive"] = flat["drive"]
        else:
            messages.append(f"drive = {flat['drive']!r} is unknown (known: {', '.join(DRIVES)})")

    explicit = set()
    for key in ("psi", "tau0", "mu", "nu", "theta", *SI_KEYS):
        if key in flat:
            try:
                values[key] = parse_value(key, flat[key])
                explicit.add(key)
            except ValueError as err:
                messages.append(str(err))

    for key in ("log_psi", "period", "physical"):
        if key in flat:
            try:
                values[key] = parse_flag(key, flat[key])
            except ValueError as err:
                messages.append(str(err))

    if "theta" in explicit and values.get("drive") != "angle":
        messages.append(f"theta = {flat['theta']!r} ignored: it sets the drive only with "
                        f"drive = angle")
        del values["theta"]
    elif values.get("drive") == "angle" and not values.get("physical"):
        scratch = ExplorerState(**{k: values[k] for k in ("psi", "theta", "mu", "nu")
                                   if k in values}, drive="angle")
        theta = scratch.theta
        if "psi" in values and scratch.drive_psi() == values["psi"]:
            values["theta"] = theta  # (psi gives theta: kept, as ExplorerState.drive_psi)
        else:
            try:
                psi = parse_value("psi", repr(scratch.drive_psi()))
            except ValueError as err:
                messages.append(f"the drive angle is not applied: {err}")
                values["drive"] = "psi"
                values.pop("theta", None)
            else:
                if "psi" in explicit:
                    messages.append(f"psi = {flat['psi']!r} ignored: with drive = angle it "
                                    f"follows from theta, mu and nu")
                values.update(psi=psi, theta=theta)

    if values.get("physical"):
        scratch = ExplorerState(**{k: values[k] for k in (*SI_KEYS, "mu", "nu")
                                   if k in values}, physical=True)
        try:
            c = scratch.contact()
        except ValueError as err:
            messages.append(f"the physical inputs are not applied: {err}")
            values["physical"] = False
        else:
            for key in ("psi", "tau0"):
                if key in explicit:
                    messages.append(f"{key} = {flat[key]!r} ignored: with physical = 1 it "
                                    f"follows from {', '.join(SI_KEYS)}, mu and nu")
            values.update(psi=c.psi, tau0=c.tau0)

    if "tau" in flat:
        tau0 = values.get("tau0", ExplorerState.param.tau0.default)
        try:
            values["tau"] = parse_tau(flat["tau"], Contact(1.0, tau0),
                                      period=bool(values.get("period")))
        except ValueError as err:
            messages.append(str(err))
    elif "tau0" in values and "tau" not in values:
        values["tau"] = math.pi / 2  # inside every contact [tau0, pi - tau0]
    return values, messages
