"""The path of a slider move in the fast tier, without a browser: the value message a
browser's slider sends goes into the served explorer (`python -m app.serve`, the `url`
fixture) over Bokeh's websocket protocol (`bokeh_client.Tab`), and what comes back is
read as BokehJS reads it."""

from __future__ import annotations

import asyncio
import base64
import gzip
import json
import math

import numpy as np
from bokeh_client import Tab, named
from tornado.httpclient import AsyncHTTPClient

from core import Contact


def _columns(patches: list[str], source_id: str) -> dict[str, np.ndarray]:
    """The columns that `patches` (PATCH-DOC contents) send the source of id
    `source_id`, decoded as BokehJS decodes them (base64 of a gzip stream of float64)."""
    for content in patches:
        for event in json.loads(content)["events"]:
            if event.get("kind") == "ColumnDataChanged" and \
                    event["model"]["id"] == source_id:
                return {name: np.frombuffer(gzip.decompress(base64.b64decode(
                            rep["array"]["data"])), rep["dtype"]).reshape(rep["shape"])
                        for name, rep in event["data"]["entries"]}
    raise LookupError(f"no data of source {source_id} in the patches")


def test_a_browser_move_of_psi_reaches_the_traction_profile(url) -> None:
    """The whole path of a slider move, without a browser: the value message a browser's
    slider sends (`bokeh_client.Tab`, Bokeh's protocol) goes into the served document,
    and the message that comes back carries the traction profile of the new contact at
    the time shown, in core's numbers (eqs 18, 24, 33, 36: partial stick at psi = 3,
    tau = 17 pi / 24)."""
    async def move() -> tuple[list[str], str]:
        tab = Tab(url, AsyncHTTPClient())
        await tab.open()
        try:
            await tab.quiet(0.5)
            patches, _ = await tab.moved(3.0)
            (traction,) = named(tab.doc, "traction")
            return patches, traction
        finally:
            tab.close()

    patches, traction = asyncio.run(move())
    got = _columns(patches, traction)
    c, tau = Contact(3.0, math.pi / 6), 17 * math.pi / 24
    r = got["r"]
    b = float(c.stick_radius(tau))
    assert 0 < b < float(c.contact_radius(tau))  # (partial stick: the profile depends on psi)
    np.testing.assert_allclose(got["traction"], c.traction(r, tau), rtol=0, atol=1e-15)
    np.testing.assert_allclose(got["upper"], c.pressure(r, tau), rtol=0, atol=1e-15)
    np.testing.assert_array_equal(got["stick_hi"] > 0, np.abs(r) <= b)
    assert {-b, b} <= set(r.tolist())  # (the stick edges are points of the profile)
