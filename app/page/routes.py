"""A handler of our own in place of Panel's on one of Bokeh's per-application routes."""

from __future__ import annotations


def replace_route(path: str, handler: type) -> None:
    """Serve Bokeh's per-application route `path` (e.g. r"/?", the page; r"/ws", the
    websocket) with `handler`, a subclass of the handler there now (call before the
    server is made; calling it again changes nothing); LookupError if there is none."""
    from bokeh.server.urls import per_app_patterns

    for i, (route, current, *rest) in enumerate(per_app_patterns):
        if route == path and issubclass(handler, current):
            per_app_patterns[i] = (route, handler, *rest)
            return
    raise LookupError(f"no route {path!r} of Panel's among Bokeh's per-application patterns"
                      f" that {handler.__name__} extends")
