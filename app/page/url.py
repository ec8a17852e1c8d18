"""The page's URL: one query for every feature, read once and written whole.

A query holds the contact's keys (`app.contact.state.QUERY_KEYS`), the Motor card's
(`motor_*`, `app.motor`) and the view (`view=present`).  `split` sorts a request's
arguments by feature; each feature validates its own part (every refused value becomes a
message, its default kept); `join` and `encode` write them back, so that a link restores
the page exactly.  The URL writer never writes a value its reader would refuse: every
value comes from a feature's state, which holds accepted values only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from urllib.parse import urlencode

from app.contact.state import ExplorerState, parse_query, query_value
from app.motor import PREFIX as MOTOR_PREFIX
from app.page.presentation import VIEW

#: The views a link may ask for: '' (the full page) and the one-screen presentation.
VIEWS = ("", VIEW)


@dataclass
class Parts:
    """A URL query sorted by feature (raw values, as the request gave them)."""

    contact: dict = field(default_factory=dict)
    motor: dict = field(default_factory=dict)
    view: str = ""


def split(query: dict) -> Parts:
    """Sort `query` (names to values, as `pn.state.session_args` gives them) by feature."""
    parts = Parts(view=query_value(query.pop("view", "")))
    for key, raw in query.items():
        (parts.motor if key.startswith(MOTOR_PREFIX) else parts.contact)[key] = raw
    return parts


def apply_contact(state: ExplorerState, query: dict) -> list[str]:
    """Apply a URL query's validated contact values to `state`; returns the messages to
    show.  A combination core rejects falls back to the defaults of the values it gave."""
    if not query:
        return []
    values, messages = parse_query(query)
    defaults = {k: state.param[k].default for k in values}
    state.param.update(**values)
    try:
        state.contact()
    except ValueError as err:
        messages.append(f"these parameters are rejected ({err}); defaults used")
        state.param.update(**defaults)
    return messages


def view_of(raw: str) -> tuple[str, list[str]]:
    """The view a link asks for and, for an unknown one, the message saying so."""
    if raw in VIEWS:
        return raw, []
    return "", [f"view = {raw!r} is unknown (known: {VIEW}); the full page is shown"]


def join(contact: dict[str, str], motor: dict[str, str], view: str) -> dict[str, str]:
    """One query of the features' parts and the view."""
    return {**contact, **motor, **({"view": view} if view else {})}


def encode(query: dict[str, str]) -> str:
    """The query as the URL's search string (without the '?')."""
    return urlencode(query)
