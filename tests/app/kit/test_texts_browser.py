"""app.kit.texts in Chromium: the texts are set as text, never read as markup, and follow
their data model's changes."""

from __future__ import annotations

import panel as pn
import pytest
from explorer_browser import free_port, wait_until

from app.kit.texts import Description, TextTable

pytestmark = pytest.mark.browser

#: JavaScript: the table's caption, its header cells' scopes and its rows as text, and
#: the figure's name, described-by target and text.
JS_READ = """() => {
  const all = [];
  const walk = (root) => { for (const el of root.querySelectorAll("*")) {
    all.push(el); if (el.shadowRoot) walk(el.shadowRoot); } };
  walk(document);
  const t = all.find((el) => el.tagName === "TABLE");
  const f = all.find((el) => el.getAttribute && el.getAttribute("role") === "figure");
  if (!t || !f) return null;
  const d = f.querySelector("#" + f.getAttribute("aria-describedby"));
  return {caption: t.caption.textContent, cls: t.className,
          scopes: [...t.querySelectorAll("th")].map((th) => th.getAttribute("scope")),
          rows: [...t.tBodies[0].rows].map((r) => [r.cells[0].textContent,
                                                   r.cells[1].textContent]),
          elements: t.querySelectorAll("b, script").length,
          name: f.getAttribute("aria-label"), text: d && d.textContent};
}"""


def test_texts_are_text_and_follow_their_model(browser) -> None:
    rows = [["<b>q</b> & co", "<script>alert(1)</script>"], ["ψ", "1 < 2"]]
    table = TextTable(caption="Derived <i>quantities</i>", rows=rows)
    figure = Description(label="The <b>two</b> spheres", description="at τ = 1 rad: T = -0.046 T0")
    port = free_port()
    server = pn.serve(pn.Column(table, figure), port=port, threaded=True, show=False,
                      start=True)
    page = browser.new_page()
    try:
        page.goto(f"http://127.0.0.1:{port}/")
        got = wait_until(lambda: page.evaluate(JS_READ), timeout=30, what="the table")
        assert got == {"caption": "Derived <i>quantities</i>", "cls": "readout",
                       "scopes": ["col", "col", "row", "row"], "rows": rows, "elements": 0,
                       "name": "The <b>two</b> spheres", "text": "at τ = 1 rad: T = -0.046 T0"}
        table.write(rows=[["a", "1"]])
        figure.description = "at τ = 2 rad"
        # (two changes made outside the server's thread: each reaches the page in its
        # own message, in either order)
        got = wait_until(lambda: (g := page.evaluate(JS_READ))["rows"] == [["a", "1"]]
                         and g["text"] == "at τ = 2 rad" and g,
                         timeout=20, what="the new rows and description")
        assert got["scopes"] == ["col", "col", "row"] and got["elements"] == 0
    finally:
        page.close()
        server.stop()
