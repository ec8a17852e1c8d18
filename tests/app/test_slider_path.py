"""The path of a slider move in the fast tier, without a browser: the value message a
browser's slider sends goes into the served explorer (`python -m app.serve`, the `url`
fixture) over Bokeh's websocket protocol (`bokeh_client.Tab`), and what comes back is
read as BokehJS reads it; a run-time trace of a move checks docs/app.md's account of
the path."""

from __future__ import annotations

import asyncio
import base64
import gzip
import inspect
import json
import math
import re
from pathlib import Path

import numpy as np
from bokeh.document import Document
from bokeh_client import Tab, named
from tornado.httpclient import AsyncHTTPClient

from app.page.explorer import Explorer
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


#: docs/app.md's hops of a slider move: "N. `app/MODULE.py`: ... `Name.function` ...".
HOP = re.compile(r"^(\d)\. `(app/[\w/]+\.py)`: (.*)$")


def documented_path() -> list[tuple[str, list[str]]]:
    """docs/app.md's "How data flows" hops: (module, the functions it names), in order."""
    text = (Path(__file__).parents[2] / "docs" / "app.md").read_text()
    part = text.split("### How data flows", 1)[1].split("\n#", 1)[0]
    hops, lines = [], part.splitlines()
    for i, line in enumerate(lines):
        m = HOP.match(line)
        if m:
            body = [m.group(3)]
            for more in lines[i + 1:]:
                if not more.startswith("   "):
                    break
                body.append(more)
            names = re.findall(r"`(?:\w+\.)?(\w+)`", " ".join(body))
            hops.append((m.group(2), names))
    return hops


def test_the_path_of_a_move_is_the_one_docs_app_md_describes() -> None:
    """A run-time trace of one psi move, as Bokeh applies the browser's value to the
    slider's model: the app's frames on the stack when the traction source gets its data
    are, module by module, the hops docs/app.md lists (each naming the function the
    move enters it by), five at most over four modules at most; the URL is computed
    once; nothing is written back into the
    slider the move came from (the one change of its model is the browser's own)."""
    ex = Explorer()
    doc = Document()
    ex.view().server_doc(doc)
    slider = ex.contact.controls.psi_slider
    slider.value = 2.5  # (leaves the preset first: a move that does not)
    traction = doc.get_model_by_name("traction")
    stacks: list[list[tuple[str, str]]] = []

    def on_data(attr, old, new) -> None:
        root = str(Path(__file__).parents[2]) + "/"
        stacks.append([(f.filename.removeprefix(root), f.function)
                       for f in reversed(inspect.stack()) if f.filename.startswith(root + "app/")])

    traction.on_change("data", on_data)
    queries, query = [], ex.query
    ex.query = lambda: queries.append(1) or query()
    events: list = []
    doc.on_change(events.append)
    slider.model.value = 2.6  # (what Bokeh does with the browser's PATCH-DOC)
    (stack,) = stacks
    modules: list[str] = []
    for module, _ in stack:
        if not modules or modules[-1] != module:
            modules.append(module)
    hops = documented_path()
    assert modules == [module for module, _ in hops] and len(hops) <= 5
    assert len(set(modules)) <= 4  # (the widget, the state, the scenes' base, the scene)
    for module, names in hops:  # each hop names the function the move enters it by
        entry = next(function for m, function in stack if m == module)
        assert entry in names, (module, entry, names)
    assert len(queries) == 1
    assert [(e.attr, e.new) for e in events if getattr(e, "model", None) is slider.model] \
        == [("value", 2.6)]
    np.testing.assert_allclose(
        traction.data["traction"],
        Contact(2.6, math.pi / 6).traction(traction.data["r"], 17 * math.pi / 24),
        rtol=0, atol=1e-15)
