"""The page's URL: one query for every feature, read once and written whole.

A query holds the contact's keys (`app.contact.state.QUERY_KEYS`), the Motor card's
(`motor_*`, `app.motor`) and the view (`view=present`).  `split` sorts a request's
arguments by feature; each feature validates its own part (every refused value becomes a
message, its default kept); `join` writes them back (`UrlWriter` puts them in the address
bar), so that a link restores the page exactly.  The URL writer never writes a value its
reader would refuse: every value comes from a feature's state, which holds accepted
values only.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import param

from app.contact.query import parse_query, query_value
from app.contact.state import ExplorerState
from app.kit.style import VISUALLY_HIDDEN_CSS
from app.kit.texts import WrittenHTML, pairs_json
from app.motor import PREFIX as MOTOR_PREFIX
from app.page.presentation import VIEW
from app.page.student import VIEW as STUDENT

#: The views a link may ask for: '' (the full page), the one-screen presentation and the
#: student view.
VIEWS = ("", VIEW, STUDENT)


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
    return "", [f"view = {raw!r} is unknown (known: {VIEW}, {STUDENT}); the full page is "
                "shown"]


def join(contact: dict[str, str], motor: dict[str, str], view: str) -> dict[str, str]:
    """One query of the features' parts and the view."""
    return {**contact, **motor, **({"view": view} if view else {})}



#: JavaScript of `UrlWriter`: `delay_ms` after the last change of the query, the address
#: bar shows it: the first time in place of the link the page was opened with (which a
#: refused value may have changed), then as a new history entry.
_WRITE_URL = """
if (state.timer != null) { clearTimeout(state.timer); }
state.timer = setTimeout(() => {
  state.timer = null;
  const pairs = JSON.parse(data.query);
  const search = pairs.length ? "?" + new URLSearchParams(pairs).toString() : "";
  if (window.location.search !== search) {
    const url = window.location.pathname + search + window.location.hash;
    if (state.written) { window.history.pushState({}, "", url); }
    else { window.history.replaceState(window.history.state, "", url); }
  }
  state.written = true;
}, data.delay_ms);
"""


class UrlWriter(WrittenHTML):
    """The page's URL query (`query`: its (key, value) pairs in order, as one JSON text,
    `app.kit.texts.pairs_json`), written into the browser's address bar `delay_ms` after
    its last change (`write(query=pairs)` changes it).

    Every change of the query is one property in the message of the change that made it
    (Panel's `Location` would send it in a message of its own, and the browser would
    send the new address back); a slider drag leaves one history entry, at its end.
    Nothing to see: out of sight, like a live region."""

    query = param.String(default="[]", allow_refs=False,
                         doc="the query's [key, value] pairs, in order, as JSON")
    delay_ms = param.Integer(default=400, bounds=(0, None))

    _template = '<div id="url"></div>'
    _scripts: ClassVar[dict[str, str]] = dict.fromkeys(("render", "query"), _WRITE_URL)

    def __init__(self, **params) -> None:
        params["stylesheets"] = [VISUALLY_HIDDEN_CSS, *params.get("stylesheets", [])]
        params.setdefault("margin", 0)
        super().__init__(**params)

    def write(self, **values) -> None:
        """`WrittenHTML.write`, `query` given as (key, value) pairs of str."""
        if "query" in values:
            values["query"] = pairs_json(values["query"], "query")
        super().write(**values)
