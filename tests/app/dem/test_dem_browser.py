"""The "Check a DEM code" card in Chromium, served alone (`pn.serve`, with the app
server's websocket message cap): opened, an uploaded CSV is scored and drawn, and a
malformed one, or one over the card's size cap, is refused in words under the upload box."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

import numpy as np
import panel as pn
import pytest
from explorer_browser import free_port, wait_for_http

from app.dem import data
from app.dem.view import TITLE, DemCard
from app.serve import SESSION
from core.dem_check import CASES, exact

pytestmark = pytest.mark.browser

#: JavaScript: the length of a data column of the named source (0 if absent).
JS_LENGTH = """([name, col]) => {
  const d = window.Bokeh && window.Bokeh.documents && window.Bokeh.documents[0];
  const m = d && d.get_model_by_name(name);
  if (!m) return 0;
  const v = m.data instanceof Map ? m.data.get(col) : m.data[col];
  return v == null ? 0 : v.length;
}"""


@contextlib.contextmanager
def served_card() -> Iterator[str]:
    """The card alone on a Panel server in this process; yields its URL."""
    port = free_port()
    server = pn.serve(DemCard, port=port, address="127.0.0.1", show=False, threaded=True,
                      liveness=True, websocket_origin=[f"127.0.0.1:{port}"],
                      websocket_max_message_size=SESSION["websocket_max_message_size"])
    try:
        wait_for_http(f"http://127.0.0.1:{port}/liveness")
        yield f"http://127.0.0.1:{port}/"
    finally:
        server.stop()


@pytest.fixture(scope="module")
def card_url() -> Iterator[str]:
    with served_card() as url:
        yield url


def history_csv(T_factor: float = 1.0) -> bytes:
    ref = exact(CASES["fig7_psi2.41"])
    rows = "\n".join(f"{a:.17g},{b:.17g},{c:.17g}" for a, b, c in
                     zip(ref.tau, T_factor * ref.T, ref.P, strict=True))
    return f"# code: mine\ntau,T,P\n{rows}\n".encode()


def test_an_uploaded_csv_is_scored_and_drawn(browser, card_url) -> None:
    page = browser.new_page(viewport={"width": 1280, "height": 1000})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(card_url)
        page.get_by_text(TITLE).click()
        page.wait_for_function(JS_LENGTH, arg=["dem_exact", "T"], timeout=30_000)
        assert page.evaluate(JS_LENGTH, ["dem_lammps", "xs"]) == 2

        upload = page.locator("input[type=file]")
        upload.set_input_files(files=[{"name": "mine.csv", "mimeType": "text/csv",
                                       "buffer": history_csv(1.02)}])
        caption = page.get_by_text("Your file against fig7_psi2.41")
        caption.wait_for(state="visible", timeout=30_000)
        worst = float(np.max(np.abs(0.02 * exact(CASES["fig7_psi2.41"]).T)))
        assert page.get_by_text(f"{worst:.3e} T₀ at τ = ").is_visible()
        page.wait_for_function(JS_LENGTH, arg=["dem_upload", "T"], timeout=10_000)

        upload.set_input_files(files=[{"name": "bad.csv", "mimeType": "text/csv",
                                       "buffer": b"tau,T,P\n0,0,0\n1,oops,0\n"}])
        message = page.get_by_text("your file, line 3, column 'T': 'oops' is not a number")
        message.wait_for(state="visible", timeout=30_000)
        assert not caption.is_visible()

        # over the card's cap, under the server's message cap: refused in words
        big = b"tau,T,P\n" + b"0" * data.MAX_UPLOAD_BYTES
        upload.set_input_files(files=[{"name": "big.csv", "mimeType": "text/csv",
                                       "buffer": big}])
        page.get_by_text(f"your file has {len(big):,} bytes, more than the "
                         f"{data.MAX_UPLOAD_BYTES:,} accepted").wait_for(state="visible",
                                                                          timeout=30_000)
        assert errors == []
    finally:
        page.close()
