"""Serve the explorer: `python -m app.serve [options]` (what `make serve` and the image run).

A `panel serve app/main.py` with the settings a deployment needs fixed in one place:

- **Pages built off the event loop, and only for a browser.** A page's HTML holds a shell;
  the explorer is built into it once the browser has opened the page's websocket
  (`app.page.guard.serve_page`), on one of Bokeh's worker threads: a page build (the
  costliest work of a page load: ``python -m benchmarks.app.page_load`` times it) shares
  the interpreter with the sessions already open instead of stopping them, and a page
  fetched without its websocket builds nothing. A thread holds the interpreter for at
  most 0.5 ms while another waits (``SWITCH_INTERVAL_S``), so that their moves are not
  held up by it.
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
  10 s so that proxies keep idle classroom sessions open; one that answers no ping for
  10 s (e.g. a client stopped half-way through a frame) is closed.
- **Page loads and builds per client** (an IPv4 address, an IPv6 /64;
  ``--class-size N``, default 40): N pages built at once, then one every 4 s
  (`app.page.guard.BUILDS`), 3N page loads, then one a second, and N/16 pages thrown
  away (closed while their explorer was built or within 3 s of its being sent), then
  one every 30 s (`app.page.gate`): past any of them a page request is answered, before
  any session is made, with a short 429 page that opens its link again when it may.
- **Signed session ids** (``BOKEH_SECRET_KEY``, else a key drawn at start): a websocket
  or a page request naming a session id this server did not issue is refused (a
  websocket with 403, before its handshake: `app.page.websocket`), so no client can have
  documents built without loading a page.
- **One whole-document pull per websocket** (BokehJS sends one): a connection sending a
  second ``PULL-DOC-REQ`` is closed (`app.page.websocket.OnePullHandler`).
- **Logs bounded per client**: refusals are logged as one line per client address per
  burst, and the access log writes at most a dozen lines per address at once, then one
  every 20 s, the dropped ones counted (`app.page.limits.quiet_closed_connections`).
- **Message size cap**: a client's websocket message above 512 KiB closes its
  connection (the explorer's own messages are a few hundred bytes).
- **No autoload script**: Bokeh's ``/main/autoload.js`` (embedding in other sites'
  pages) answers 404.
- **No admin page** unless ``--admin``, and then only behind a login: the password in
  the environment (``BASIC_AUTH``: a password, or the path of a JSON file of user names
  to passwords) or ``--basic-auth-file PATH``, never on the command line.

The security headers and the autoload refusal are Tornado output transforms
(``tornado.web.OutputTransform``, passed to the Tornado application through Bokeh's
``Server`` keyword arguments); the websocket pings' settings are Tornado application
settings passed the same way.
"""

from __future__ import annotations

import argparse
import gc
import json
import logging
import os
import re
import secrets
import subprocess
import sys
import threading
import time
from pathlib import Path

from tornado.web import GZipContentEncoding, OutputTransform

from app.page.bucket import CLASS_SIZE

#: The environment variable holding the key session ids are signed with (Bokeh's own
#: name; at least 32 characters).  Unset, a key is drawn at start: every process of one
#: `--num-procs` server shares it; replicas behind a proxy need the same one only if a
#: page's websocket may reach another replica than its page (sticky sessions: not).
SECRET_KEY_ENV = "BOKEH_SECRET_KEY"

#: What loading the closed form's kernels takes on a fresh machine (they compile), s.
COMPILE_SECONDS = 20

#: How long the server waits, once the closed form is loaded, for the process loading
#: the Methods and Motor kernels (s): with numba's cache filled it is done by then.
METHODS_WAIT_S = 4.0

#: How long a thread may hold the interpreter while another waits for it (s; Python's
#: default is 0.005).  A psi move passes between the event loop and Bokeh's worker
#: threads a dozen times; beside a page build or a PULL-DOC reply being serialized
#: (pure Python, CPU-bound) each hand-off waited up to the whole interval, which
#: doubled the open sessions' latency (benchmarks/app/load_test.py --abuse, docs/deploy.md).
SWITCH_INTERVAL_S = 0.0005

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
    # Tornado's own pings (application settings, in seconds): a connection that has not
    # answered a ping within the timeout is closed, and dropped 5 s later if the client
    # does not answer the close either; a client that sends half a frame and stops can
    # answer nothing, so it is disconnected within interval + timeout + 5 = 25 s
    "websocket_ping_interval": 10,
    "websocket_ping_timeout": 10,
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


#: Bokeh's route of an app's autoload script (its pattern: "." matches any character).
_AUTOLOAD = re.compile(r"/autoload.js$")


class NoAutoload(OutputTransform):
    """Answers 404 with an empty body in place of Bokeh's ``/<app>/autoload.js``.

    That endpoint embeds a session in another site's page and writes its
    ``bokeh-autoload-element`` parameter, unescaped, into the JavaScript it serves from
    this origin; the explorer is served as a whole page and never uses it.  Bokeh's own
    routes come before any given to its ``Server`` (``extra_patterns``), so the
    response is refused here.
    """

    def __init__(self, request):
        super().__init__(request)
        self.refused = bool(_AUTOLOAD.search(request.path))

    def transform_first_chunk(self, status_code, headers, chunk, finishing):
        if not self.refused:
            return status_code, headers, chunk
        for name in ("Etag", "Access-Control-Allow-Origin", "Access-Control-Allow-Headers",
                     "Access-Control-Allow-Methods"):
            headers.pop(name, None)
        headers["Content-Type"] = "text/plain; charset=UTF-8"
        headers["Content-Length"] = "0"
        return 404, headers, b""

    def transform_chunk(self, chunk, finishing):
        return b"" if self.refused else chunk


def basic_auth(p: argparse.ArgumentParser, path: str | None, env: str | None) -> str | None:
    """Panel's ``basic_auth`` from ``--basic-auth-file`` or ``BASIC_AUTH``, checked.

    ``BASIC_AUTH`` is a password, or the path of a file (an absolute path naming no file
    is refused, rather than taken for the password); the file holds a JSON object of
    user names to passwords, as Panel reads it at each login.
    """
    if path and env:
        p.error("give either BASIC_AUTH or --basic-auth-file, not both")
    if not path and env and env.startswith("/"):
        path = env
    if not path:
        return env or None
    try:
        users = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as err:
        p.error(f"basic auth file {path}: {err.__class__.__name__}: not a readable JSON file")
    if not (isinstance(users, dict) and users
            and all(isinstance(v, str) and v for v in users.values())):
        p.error(f"basic auth file {path}: not a JSON object of user names to passwords")
    return path


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
    p.add_argument("--behind-proxy", action="store_true",
                   help="behind a reverse proxy (the shipped nginx): a client's address is "
                        "the last hop of X-Forwarded-For, which the proxy appends (the "
                        "page-build limit per address needs it; never set it without one)")
    p.add_argument("--class-size", type=int, default=CLASS_SIZE, metavar="N",
                   help="the most visitors behind one address (a school's NAT) opening the "
                        "page at once: each address may have N pages built at once, then one "
                        "every 4 s, 3N page loads, then one a second, and N/16 pages closed "
                        "as soon as they came, then one every 30 s (default %(default)s)")
    p.add_argument("--admin", action="store_true",
                   help="serve Panel's /admin page (requires BASIC_AUTH or --basic-auth-file)")
    p.add_argument("--basic-auth-file", default=None, metavar="PATH",
                   help="JSON file of {user: password} asked for on every page; or set "
                        "BASIC_AUTH in the environment to a password or such a file's path")
    # refused: a password on a command line is shown to every user of the machine (ps)
    p.add_argument("--basic-auth", default=None, help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.basic_auth is not None:
        p.error("--basic-auth would show the password to every user of the machine (ps): "
                "set BASIC_AUTH in the environment or use --basic-auth-file")
    args.basic_auth = basic_auth(p, args.basic_auth_file, os.environ.get("BASIC_AUTH"))
    if args.admin and not args.basic_auth:
        p.error("--admin needs BASIC_AUTH or --basic-auth-file: the admin page shows every session")
    if args.num_procs < 0:
        p.error("--num-procs must be >= 0")
    if not 1 <= args.class_size <= 100_000:
        p.error(f"--class-size must be between 1 and 100000, got {args.class_size}")
    if not args.allow_websocket_origin:
        args.allow_websocket_origin = [f"localhost:{args.port}", f"127.0.0.1:{args.port}"]
    return args


def server_options(args: argparse.Namespace) -> dict:
    """Keyword arguments of `panel.io.server.get_server` for `args`; the page and websocket
    handlers of every application set to `app.page.gate.GatedDocHandler` and
    `app.page.websocket.OnePullHandler`."""
    from app.page import gate, websocket
    from app.page.limits import log_request

    websocket.install()
    gate.install()

    opts = dict(
        port=args.port, address=args.address, num_procs=args.num_procs,
        websocket_origin=args.allow_websocket_origin, prefix=args.prefix,
        liveness=True, index=None, admin=args.admin,
        use_xheaders=args.behind_proxy,
        transforms=[NoAutoload, SecurityHeaders, GZipContentEncoding],
        log_function=log_request,  # (Tornado's access log, with each line's client)
        **SESSION,
    )
    if args.basic_auth:
        opts.update(basic_auth=args.basic_auth, cookie_secret=secrets.token_urlsafe(32))
    # session ids signed with this deployment's key: a websocket or a page request naming
    # a session id the server did not issue is refused before any document is built
    opts.update(sign_sessions=True, generate_session_ids=True,
                secret_key=(os.environ.get(SECRET_KEY_ENV) or secrets.token_urlsafe(32)).encode())
    return opts


def size_limits(class_size: int) -> None:
    """Size this process's page limits per client address for `class_size` visitors
    behind one address opening the page at once: that many page builds at once
    (`app.page.guard.BUILDS`), `app.page.gate.pages_burst` page loads
    (`app.page.gate.PAGES`) and `app.page.gate.thrown_burst` pages closed soon after
    their build (`app.page.gate.THROWN`); their rates stay."""
    from app.page import gate, guard

    guard.BUILDS.burst = float(class_size)
    gate.PAGES.burst = gate.pages_burst(class_size)
    gate.THROWN.limit.burst = gate.thrown_burst(class_size)


def applications() -> dict:
    """The server's one application, /main: each session's page served by
    `app.page.guard.serve_page` (what `panel serve app/main.py` runs as a script).

    Given as a function, not as the script: Bokeh runs a function application on a
    worker thread (a script on the event loop, since it runs with the process's globals
    patched)."""
    import panel as pn

    from app.page.guard import serve_page

    pn.extension("katex", notifications=False, lazy_resources=False)
    return {"main": serve_page}


def main(argv: list[str] | None = None) -> None:
    """Serve the explorer at /main (and / redirecting there) until interrupted."""
    from panel.io.server import get_server

    from app.page import memory
    from app.page.limits import quiet_closed_connections
    from core.warm import warm, warm_methods

    args = parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(levelname)s %(message)s")
    log = logging.getLogger("app.serve")
    quiet_closed_connections()  # (a closed client's queued messages: one line, no traceback)
    if "*" in args.allow_websocket_origin:
        log.warning("websocket origin '*': any web page may open sessions on this server")
    # the Methods and Motor cards' kernels: compiled into numba's disk cache by another
    # process (numba holds the GIL while it compiles: in this one, it would stall pages)
    methods = subprocess.Popen([sys.executable, "-m", "core.warm", "methods"],
                               stdin=subprocess.DEVNULL, stdout=subprocess.PIPE)
    # the closed form, which every page runs: loaded (compiled on a fresh machine) before
    # the first page is taken, so that it is not built behind the compiler
    log.info("loading the closed form's compiled kernels (a first run compiles them: "
             "~%d s on 2 cores)...", COMPILE_SECONDS)
    started = time.perf_counter()
    warm()
    from bokeh.document import Document

    import app.methods.data
    import app.page.explorer  # (what every session's page is built from)

    # one page built and dropped: what a first page would do once (Panel's and Bokeh's
    # lazy imports and caches) is done before a visitor waits for it
    app.page.explorer.Explorer().view().get_root(Document())
    log.info("closed form and a page ready in %.1f s", time.perf_counter() - started)
    def load_methods() -> None:  # from the cache the other process fills
        methods.stdout.read()  # (EOF when it ends, in every server process)
        methods.poll()  # (reaped, where this process started it)
        try:
            warm_methods()
            app.methods.data.prepare()
        except Exception as err:  # the cards then compile on first use; pages are served
            log.warning("the Methods and Motor cards' kernels did not load: %s: %s",
                        type(err).__name__, err)

    try:  # with a warm cache they are loaded in a second or two: before the address
        methods.wait(timeout=METHODS_WAIT_S)
        load_methods()  # (from the cache, holding the GIL: before any page)
    except subprocess.TimeoutExpired:
        log.info("the Methods and Motor cards' kernels compile in the background")
        threading.Thread(target=load_methods, name="warm-methods", daemon=True).start()
    size_limits(args.class_size)
    sys.setswitchinterval(SWITCH_INTERVAL_S)
    gc.freeze()  # the modules' objects: out of every later garbage collection's walk
    gc.set_threshold(*memory.THRESHOLDS)  # (and Python's own full collections rare)
    server = get_server(applications(), start=False, **server_options(args))
    server.start()
    log.info("explorer at http://%s:%d%s/main (websocket origins: %s)", args.address,
             args.port, args.prefix, ", ".join(args.allow_websocket_origin))
    server.io_loop.start()


if __name__ == "__main__":
    sys.exit(main())
