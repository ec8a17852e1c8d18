"""Benchmarks of the served explorer (latency in a browser, load, abuse, memory, CPU per
move): ``python -m benchmarks.app.NAME`` from the repository root.  Their shared helpers
are in `benchmarks.app.common` (servers, processes, the browser, the machine's yardstick)
and `benchmarks.app.client` (a browser's side of Bokeh's websocket protocol)."""
