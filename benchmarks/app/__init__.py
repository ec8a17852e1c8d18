"""Benchmarks of the served explorer (latency in a browser, load, abuse, memory, CPU per
move): ``python -m benchmarks.app.NAME`` from the repository root.  Their shared helpers
are in `benchmarks.app.common` (servers, processes, the browser, the machine's yardstick);
a browser's side of Bokeh's websocket protocol is `docker.browser_client` (shared with the
replica smoke check, `docker/replicas.py`)."""
