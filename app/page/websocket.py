"""The explorer's websocket handler: Panel's, with one whole-document pull per connection,
session tokens checked before the handshake and each close told to the page gate.

BokehJS sends exactly one ``PULL-DOC-REQ`` per websocket, right after the server's
``ACK``; each asks for the session's whole document, all its models serialized.
`OnePullHandler` closes a connection that sends a second one (one log line per client
per burst: `app.page.limits.quiet_closed_connections`), before Bokeh reads it.  Pulls
over new connections to one session are still bounded by the session's bucket
(`app.page.pulls`).

It also refuses, with 403 before the websocket handshake, a websocket whose session
token is not signed with the server's key (Bokeh would accept the connection, then log
an error and raise from ``open``): the refusal is one access-log line like any other
(`app.page.limits.log_request`), counted per client.

Each close names its session to `app.page.gate.THROWN`, which counts a page closed while
its explorer was built, or right after it was sent, against its client.

Public APIs only: Panel installs its handler (``panel.io.server.WSHandler``, a subclass
of Bokeh's) as the ``/ws`` route of Bokeh's per-application URL patterns
(``bokeh.server.urls.per_app_patterns``) when it is imported; `install` puts
`OnePullHandler` in its place the same way.  Tornado's ``prepare``, ``on_message`` and
``on_close`` are overridden; each message's fragments are counted from its header (Bokeh's wire
format: header, metadata, content, then two fragments per buffer).
"""

from __future__ import annotations

import json
import logging
from typing import Any

from bokeh.util.token import check_token_signature, get_session_id
from panel.io.server import WSHandler

from app.page import gate
from app.page.limits import WEBSOCKET_LOGGER
from app.page.routes import replace_route

log = logging.getLogger(WEBSOCKET_LOGGER)

#: Whole-document pulls a connection may send (BokehJS: one).
PULLS_PER_CONNECTION = 1

#: The websocket close code and reason of a connection closed for a second pull
#: (1008: policy violation, RFC 6455).
CLOSE_CODE, CLOSE_REASON = 1008, "one PULL-DOC per connection"

#: The longest text fragment read as a message header (Bokeh's are ~100 bytes).
HEADER_CHARS = 4096


def header_of(fragment: str | bytes) -> dict | None:
    """`fragment` read as a Bokeh message header (a JSON object naming its ``msgtype``),
    or None if it is not one."""
    if not isinstance(fragment, str) or len(fragment) > HEADER_CHARS:
        return None
    try:
        header = json.loads(fragment)
    except ValueError:
        return None
    return header if isinstance(header, dict) and "msgtype" in header else None


def fragments_after(header: dict) -> int:
    """How many fragments follow a message's `header`: its metadata and content, and two
    per buffer (``num_buffers``)."""
    buffers = header.get("num_buffers", 0)
    return 2 + 2 * (buffers if isinstance(buffers, int) and buffers > 0 else 0)


def token_of(subprotocols: str | None) -> str | None:
    """The session token of a ``Sec-WebSocket-Protocol`` header (``bokeh, TOKEN``), or
    None if the header is not of that form (Bokeh then refuses the connection itself)."""
    parts = [p.strip() for p in (subprotocols or "").split(",")]
    return parts[1] if len(parts) == 2 and parts[0] == "bokeh" and parts[1] else None


class OnePullHandler(WSHandler):
    """Panel's websocket handler, refusing tokens not signed with the server's key before
    the handshake, closing a connection at its second ``PULL-DOC-REQ`` and telling
    `app.page.gate.THROWN` of each close (see the module docstring)."""

    #: Fragments still to come of the message being received (0: a header is next).
    pending_fragments = 0
    #: ``PULL-DOC-REQ`` messages received on this connection.
    pulls = 0
    #: Whether this connection was closed for its pulls (what it sends after is dropped).
    refused = False

    async def prepare(self) -> None:
        token = token_of(self.request.headers.get("Sec-WebSocket-Protocol"))
        if token is not None and not check_token_signature(
                token, secret_key=self.application.secret_key,
                signed=self.application.sign_sessions):
            self.set_status(403)
            self.finish()
            return
        await super().prepare()

    def on_close(self) -> None:
        token = token_of(self.request.headers.get("Sec-WebSocket-Protocol"))
        if token is not None:
            try:
                gate.THROWN.closed(get_session_id(token))
            except (ValueError, KeyError, TypeError):  # (a token Bokeh refused itself)
                pass
        super().on_close()

    async def on_message(self, message: str | bytes) -> Any:
        if self.refused:
            return None
        if self.pending_fragments > 0:
            self.pending_fragments -= 1
        elif (header := header_of(message)) is not None:
            self.pending_fragments = fragments_after(header)
            if header["msgtype"] == "PULL-DOC-REQ":
                self.pulls += 1
                if self.pulls > PULLS_PER_CONNECTION:
                    self.refused = True
                    client = str(self.request.remote_ip)
                    log.warning("websocket of %s closed at its PULL-DOC number %d (BokehJS "
                                "sends %d per connection)", client, self.pulls,
                                PULLS_PER_CONNECTION, extra={"client": client})
                    self.close(CLOSE_CODE, CLOSE_REASON)
                    return None
        return await super().on_message(message)


def install() -> None:
    """Serve every application's websocket with `OnePullHandler`: it replaces Panel's
    handler in Bokeh's per-application URL patterns (call before the server is made;
    calling it again changes nothing)."""
    replace_route(r"/ws", OnePullHandler)
