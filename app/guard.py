"""Every page build guarded: whatever a link holds, the visitor gets a page.

`build_page` builds one session's explorer from the page's URL and, if anything raises
while reading the URL or building a scene, builds the default explorer instead with a
message saying why; the server logs one line (no traceback per request).

The URL is read through `SafeLocation`, Panel's `Location` whose query parser takes any
text: Panel's own fails on some links that a browser sends as they are (a doubled
``??``, an integer of more than 4,300 digits), and before the page exists.
"""

from __future__ import annotations

import logging
import reprlib
from collections.abc import Mapping
from typing import Any

import panel as pn
from panel.io.location import Location

from app.explorer import Explorer

log = logging.getLogger(__name__)

#: How much of a text from the URL a message or a log line quotes (characters).
QUOTE_CHARS = 120

_quote = reprlib.Repr(maxstring=QUOTE_CHARS, maxother=QUOTE_CHARS)


def quoted(value: Any) -> str:
    """`value` as a short text for a message or a log line (long texts cut in the
    middle with '...')."""
    return _quote.repr(value)


class SafeLocation(Location):
    """Panel's `Location` (the page's URL, read and written) whose `query_params` never
    raise: a query Panel cannot parse reads as empty (the explorer reads the query
    itself, from the request's arguments, and writes it whole)."""

    @property
    def query_params(self) -> dict[str, Any]:
        try:
            return super().query_params
        except ValueError:
            return {}


def location_of(request: Any) -> SafeLocation:
    """The page's location from its HTTP request (Bokeh's session request); an empty one
    (the explorer then writes the URL afresh) when Panel cannot split the URL."""
    try:
        return SafeLocation.from_request(request)
    except ValueError as err:
        log.info("unreadable URL %s (%s): written afresh", quoted(getattr(request, "uri", "")),
                 err)
        return SafeLocation()


def build_page(query: Mapping[str, Any], location: SafeLocation | None
               ) -> tuple[Explorer, pn.Column]:
    """The explorer for URL `query` (as `pn.state.session_args` gives it) and its page;
    if building them raises, the default explorer with a message naming what failed."""
    try:
        explorer = Explorer(query=dict(query), location=location)
        return explorer, explorer.view()
    except Exception as err:
        log.warning("page build failed for %s: %s: %s (the defaults are shown)",
                    quoted(dict(query)), type(err).__name__, quoted(str(err)))
        explorer = Explorer(location=location)
        explorer.show_messages([f"This link could not be shown ({type(err).__name__}: "
                                f"{err}); the default contact is shown instead."])
        return explorer, explorer.view()


def serve_page() -> pn.Column:
    """Build the page of the session being created (the application script's one call)
    from its URL, guarded as `build_page` says, and mark it servable."""
    request = pn.state.curdoc.session_context.request
    explorer, page = build_page(pn.state.session_args, location_of(request))
    return explorer.servable(page)
