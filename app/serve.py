"""Serve the explorer: `python -m app.serve [options]` (what `make serve` and the image run).

A `panel serve app/main.py` with the settings a deployment needs fixed in one place:

- **Security headers on every HTML page.** A Content-Security-Policy with a fresh nonce
  per response: the page's own inline scripts carry the nonce, so a script injected into
  the page (e.g. an ``<img onerror=...>`` smuggled through a URL) does not run.  BokehJS
  evaluates the app's `CustomJS` callbacks with ``new Function``, hence
  ``'unsafe-eval'``; its components set inline styles, hence ``'unsafe-inline'`` for
  styles only.  Plus ``nosniff``, no referrer, and no framing by other sites.
- **Websocket origins refused unless listed** (``--allow-websocket-origin``, repeatable;
  default: the address the server is reached at on this machine,
  ``localhost:PORT`` and ``127.0.0.1:PORT``).  ``*`` must be asked for and is logged.
- **Session lifetimes** (see ``SESSION``): a page load whose websocket never connects
  (a link preview, a crawler) is discarded after 20 s; connections are pinged every
  10 s so that proxies keep idle classroom sessions open.
- **Message size cap**: a client's websocket message above 512 KiB closes its
  connection (the explorer's own messages are a few hundred bytes).
- **No admin page** unless ``--admin``, and then only behind HTTP basic auth
  (``--basic-auth``: a password, or a file holding user:password lines).

The security headers are a Tornado output transform (``tornado.web.OutputTransform``,
passed to the Tornado application through Bokeh's ``Server`` keyword arguments).
"""

from __future__ import annotations

import argparse
import gc
import logging
import re
import secrets
import sys
import threading
from pathlib import Path

from tornado.web import GZipContentEncoding, OutputTransform

MAIN = Path(__file__).with_name("main.py")

#: Session lifetimes and limits, in the units Bokeh's `Server` takes.
SESSION = {
    # a session created by a GET whose websocket has not connected is discarded after
    # this long: long enough for a slow classroom network to load the page's scripts
    "unused_session_lifetime_milliseconds": 20_000,
    "check_unused_sessions_milliseconds": 5_000,
    # ping every connection this often (proxies drop websockets idle for ~60 s)
    "keep_alive_milliseconds": 10_000,
    # a client's message above this closes its connection
    "websocket_max_message_size": 512 * 1024,
}

#: The Content-Security-Policy of every HTML page; {nonce} is fresh per response.
CSP = "; ".join([
    "default-src 'self'",
    "script-src 'self' 'nonce-{nonce}' 'unsafe-eval'",
    "style-src 'self' 'unsafe-inline'",
    "img-src 'self' data: blob:",
    "font-src 'self' data:",
    "connect-src 'self'",
    "object-src 'none'",
    "base-uri 'none'",
    "form-action 'self'",
    "frame-ancestors 'self'",
])

_SCRIPT_TAG = re.compile(rb"<script(?=[\s>])")


class SecurityHeaders(OutputTransform):
    """Adds the security headers to every response and the CSP nonce to HTML pages.

    The server's HTML pages are rendered from its own templates in one chunk; every
    ``<script`` tag in them is the server's own (user values reach the page through the
    websocket, never through the HTML), so each gets the response's nonce.
    """

    def transform_first_chunk(self, status_code, headers, chunk, finishing):
        headers["X-Content-Type-Options"] = "nosniff"
        headers["Referrer-Policy"] = "no-referrer"
        if headers.get("Content-Type", "").startswith("text/html"):
            nonce = secrets.token_urlsafe(18)
            chunk = _SCRIPT_TAG.sub(f'<script nonce="{nonce}"'.encode(), chunk)
            headers["Content-Security-Policy"] = CSP.format(nonce=nonce)
            headers["X-Frame-Options"] = "SAMEORIGIN"
            if "Content-Length" in headers:
                headers["Content-Length"] = str(len(chunk))
        return status_code, headers, chunk


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    """The command line (see the module docstring)."""
    p = argparse.ArgumentParser(prog="python -m app.serve", description=__doc__.split("\n")[0])
    p.add_argument("--port", type=int, default=5006)
    p.add_argument("--address", default="127.0.0.1",
                   help="address to listen on (0.0.0.0: every interface)")
    p.add_argument("--num-procs", type=int, default=1,
                   help="server processes (0: one per CPU); each session lives in one")
    p.add_argument("--allow-websocket-origin", action="append", default=None,
                   metavar="HOST[:PORT]",
                   help="an origin allowed to open the websocket (repeatable); default "
                        "localhost:PORT and 127.0.0.1:PORT; '*' allows any (opt-in)")
    p.add_argument("--prefix", default="", help="URL prefix, e.g. /explorer")
    p.add_argument("--admin", action="store_true",
                   help="serve Panel's /admin page (requires --basic-auth)")
    p.add_argument("--basic-auth", default=None,
                   help="password, or file of user:password lines, for every page")
    args = p.parse_args(argv)
    if args.admin and not args.basic_auth:
        p.error("--admin needs --basic-auth: the admin page shows every session")
    if args.num_procs < 0:
        p.error("--num-procs must be >= 0")
    if not args.allow_websocket_origin:
        args.allow_websocket_origin = [f"localhost:{args.port}", f"127.0.0.1:{args.port}"]
    return args


def server_options(args: argparse.Namespace) -> dict:
    """Keyword arguments of `panel.io.server.get_server` for `args`."""
    opts = dict(
        port=args.port, address=args.address, num_procs=args.num_procs,
        websocket_origin=args.allow_websocket_origin, prefix=args.prefix,
        liveness=True, index=None, admin=args.admin,
        transforms=[SecurityHeaders, GZipContentEncoding],
        **SESSION,
    )
    if args.basic_auth:
        opts.update(basic_auth=args.basic_auth, cookie_secret=secrets.token_urlsafe(32))
    return opts


def main(argv: list[str] | None = None) -> None:
    """Serve the explorer at /main (and / redirecting there) until interrupted."""
    from panel.io.server import get_server

    from core.warm import warm_all

    args = parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(levelname)s %(message)s")
    log = logging.getLogger("app.serve")
    if "*" in args.allow_websocket_origin:
        log.warning("websocket origin '*': any web page may open sessions on this server")
    import app.explorer  # noqa: F401  (what every session's script imports)
    gc.freeze()  # the modules' objects: out of every later garbage collection's walk
    server = get_server({"main": str(MAIN)}, start=False, **server_options(args))
    log.info("explorer at http://%s:%d%s/main (websocket origins: %s)", args.address,
             args.port, args.prefix, ", ".join(args.allow_websocket_origin))
    server.start()
    # load the compiled kernels (core.warm: the closed form first, then the Methods and
    # Motor cards' methods) without delaying the first page
    threading.Thread(target=warm_all, name="warm-kernels", daemon=True).start()
    server.io_loop.start()


if __name__ == "__main__":
    sys.exit(main())
