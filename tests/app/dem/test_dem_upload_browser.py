"""The "Check a DEM code" card's upload on the served explorer (`python -m app.serve`,
its websocket message cap and Content-Security-Policy) in Chromium: a file over the
card's cap is refused by the browser in words under the upload box and the page goes on
(a psi move still updates the traction plot); a file of several pieces is scored."""

from __future__ import annotations

import numpy as np
import pytest
from explorer_browser import JS_HELPERS, JS_READY, column

from app.dem import data
from app.dem.upload import CHUNK_BYTES
from app.dem.view import TITLE
from app.serve import SESSION
from core.dem_check import CASES, exact

pytestmark = pytest.mark.browser

#: JavaScript: the length of a data column of the named source (0 if absent).
JS_LENGTH = """([name, col]) => {
  const m = window.Bokeh.documents[0].get_model_by_name(name);
  if (!m) return 0;
  const v = m.data instanceof Map ? m.data.get(col) : m.data[col];
  return v == null ? 0 : v.length;
}"""


def history_csv(points: int, T_factor: float) -> bytes:
    """The exact history of fig7_psi2.41 at about `points` times, T scaled by
    `T_factor`, every number with 17 digits (about 67 bytes a row)."""
    ref = exact(CASES["fig7_psi2.41"], points)
    rows = "\n".join(f"{a:.17g},{b:.17g},{c:.17g}" for a, b, c in
                     zip(ref.tau, T_factor * ref.T, ref.P, strict=True))
    return f"# code: mine\ntau,T,P\n{rows}\n".encode()


class Watched:
    """What a page did: its console's errors, the sizes of the websocket messages it
    sent (bytes or characters) and whether its websocket closed."""

    def __init__(self, page) -> None:
        self.errors: list[str] = []
        self.sent: list[int] = []
        self.closed = False
        page.on("console", lambda m: m.type == "error" and self.errors.append(m.text))
        page.on("pageerror", lambda e: self.errors.append(str(e)))
        page.on("websocket", self._socket)

    def _socket(self, ws) -> None:
        ws.on("framesent", lambda payload: self.sent.append(len(payload)))
        ws.on("close", lambda _: setattr(self, "closed", True))


def open_card(browser, url):
    """The explorer with the DEM card opened, watched from before it loads."""
    page = browser.new_page(viewport={"width": 1280, "height": 1000})
    watched = Watched(page)
    page.goto(url)
    page.wait_for_function(JS_READY, timeout=60_000)
    page.evaluate(JS_HELPERS)
    page.get_by_text(TITLE).click()
    page.wait_for_function(JS_LENGTH, arg=["dem_exact", "T"], timeout=30_000)
    return page, watched


def choose(page, name: str, content: bytes) -> None:
    page.locator("input[type=file]").set_input_files(
        files=[{"name": name, "mimeType": "text/csv", "buffer": content}])


def step_psi_updates_traction(page) -> None:
    """Press ArrowRight on the psi slider; wait until the traction plot's data change."""
    before = column(page, "traction", "traction")
    page.locator(".slider-psi input[type=range]").focus()
    page.keyboard.press("ArrowRight")
    page.wait_for_function(
        "([b]) => JSON.stringify(__col('traction', 'traction')) !== JSON.stringify(b)",
        arg=[before], timeout=20_000)


def test_a_file_over_the_cap_is_refused_and_the_page_goes_on(browser, url) -> None:
    """A file over about 390 KB closed the page's websocket (sent whole, base64-encoded,
    over the server's 512 KiB message cap) before the card could say anything."""
    page, watched = open_card(browser, url)
    watched.sent.clear()
    big = b"tau,T,P\n" + b"0,0,0\n" * ((data.MAX_UPLOAD_BYTES + 64 * 1024) // 6)
    assert len(big) > data.MAX_UPLOAD_BYTES + 64 * 1024
    choose(page, "big.csv", big)
    page.get_by_text(f"your file has {len(big):,} bytes, more than the "
                     f"{data.MAX_UPLOAD_BYTES:,} accepted").wait_for(state="visible",
                                                                      timeout=30_000)
    assert page.get_by_text("big.csv: not sent").is_visible()
    step_psi_updates_traction(page)
    assert max(watched.sent) < 4096  # the file itself never left the browser
    assert not watched.closed and watched.errors == []
    page.close()


def test_a_file_of_several_pieces_is_scored(browser, url) -> None:
    page, watched = open_card(browser, url)
    content = history_csv(6000, 1.02)  # about 400 KB: two pieces
    assert CHUNK_BYTES < len(content) < data.MAX_UPLOAD_BYTES
    choose(page, "mine.csv", content)
    page.get_by_text("Your file against fig7_psi2.41").wait_for(state="visible",
                                                              timeout=30_000)
    worst = float(np.max(np.abs(0.02 * exact(CASES["fig7_psi2.41"], 6000).T)))
    assert page.get_by_text(f"{worst:.3e} T₀ at τ = ").is_visible()
    assert page.evaluate(JS_LENGTH, ["dem_upload", "T"]) > 0
    assert page.get_by_text("mine.csv: sent").is_visible()
    pieces = [n for n in watched.sent if n > 64 * 1024]  # the rest: a few hundred bytes
    assert len(pieces) == 2 and 4 * CHUNK_BYTES / 3 < max(pieces) < SESSION[
        "websocket_max_message_size"]
    # a larger one, sent in more pieces, replaces it
    content = history_csv(24_000, 0.99)
    assert len(content) > 4 * CHUNK_BYTES
    choose(page, "mine2.csv", content)
    worst = float(np.max(np.abs(0.01 * exact(CASES["fig7_psi2.41"], 24_000).T)))
    page.get_by_text(f"{worst:.3e} T₀ at τ = ").wait_for(state="visible", timeout=30_000)
    step_psi_updates_traction(page)
    assert not watched.closed and watched.errors == []
    page.close()
