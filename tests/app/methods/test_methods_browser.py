"""The Methods card in a real browser (Debian's Chromium through Playwright): the
benchmark scripts are named as code, painted like the heading's text, not as links; the
table's times read in µs."""

from __future__ import annotations

import pytest
from explorer_browser import open_explorer
from test_browser import errors

pytestmark = pytest.mark.browser

CARD = "Methods: numerical schemes against the closed form"

#: JavaScript: every element matching `selector`, inside shadow roots too.
JS_DEEP = """(selector) => {
  const found = [];
  const walk = (root) => {
    found.push(...root.querySelectorAll(selector));
    for (const el of root.querySelectorAll('*')) if (el.shadowRoot) walk(el.shadowRoot);
  };
  walk(document);
  return found.map((el) => {
    const s = getComputedStyle(el), h = getComputedStyle(el.closest('h3'));
    return {text: el.textContent, link: el.closest('a') !== null, color: s.color,
            heading: h.color, cursor: s.cursor, underline: s.textDecorationLine};
  });
}"""


def test_the_benchmark_scripts_are_painted_as_code_not_as_links(browser, url) -> None:
    page, console = open_explorer(browser, url)
    page.get_by_text(CARD).click()
    page.wait_for_function(f"() => ({JS_DEEP})('h3 code').length == 2", timeout=60_000)
    shown = page.evaluate(JS_DEEP, "h3 code")
    assert [s["text"] for s in shown] == ["benchmarks/core/methods.py",
                                          "benchmarks/core/stability_map.py"]
    for s in shown:
        assert not s["link"] and s["cursor"] != "pointer" and s["underline"] == "none"
        assert s["color"] == s["heading"]
    assert errors(console) == []
    page.close()
