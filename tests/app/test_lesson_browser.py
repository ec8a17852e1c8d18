"""The lesson file in headless Chromium: downloaded from the explorer, then opened from
a file with the network off, it plays, pauses, steps and draws every figure."""

from __future__ import annotations

import pytest
from explorer_browser import open_explorer

from app.contact.lesson import MAX_BYTES

pytestmark = pytest.mark.browser

#: JavaScript: the tau of the spheres' forces (the frame on screen).
JS_TAU = "() => Bokeh.documents[0].get_model_by_name('spheres_forces').data.tau[0]"
#: JavaScript: the figures painted, each with a canvas of some size.
JS_PAINTED = """() => [...Bokeh.index.query((v) => v.model.type === "Figure")].map(
  (v) => v.canvas_view.bbox.width * v.canvas_view.bbox.height > 0)"""


def test_the_downloaded_lesson_plays_offline_from_a_file(browser, url, tmp_path) -> None:
    page, _ = open_explorer(browser, url)
    with page.expect_download(timeout=60_000) as got:
        page.get_by_text("Download this lesson").click()
    path = tmp_path / got.value.suggested_filename
    got.value.save_as(path)
    assert path.suffix == ".html" and path.stat().st_size <= MAX_BYTES
    page.close()

    offline = browser.new_context(offline=True, viewport={"width": 1400, "height": 1000})
    asked: list[str] = []

    def route(r) -> None:
        if r.request.url.startswith("file:"):
            r.continue_()
        else:
            asked.append(r.request.url)
            r.abort()

    offline.route("**/*", route)
    lesson = offline.new_page()
    problems: list[str] = []
    lesson.on("pageerror", lambda e: problems.append(str(e)))
    lesson.on("requestfailed", lambda r: problems.append(f"failed: {r.url}"))
    lesson.goto(path.as_uri())
    lesson.wait_for_function("() => window.Bokeh && Bokeh.documents.length === 1",
                             timeout=30_000)
    lesson.wait_for_function(f"() => ({JS_PAINTED})().length >= 11", timeout=30_000)
    assert all(lesson.evaluate(JS_PAINTED))  # the scenes and Fig. 6's six panels
    still = lesson.evaluate(JS_TAU)
    lesson.get_by_role("button", name="▶ Play").click()
    lesson.wait_for_function("(t) => (" + JS_TAU + ")() !== t", arg=still, timeout=10_000)
    lesson.get_by_role("button", name="❚❚ Pause").click()
    paused = lesson.evaluate(JS_TAU)
    lesson.wait_for_timeout(300)  # (a paused player must not move on: nothing to wait for)
    assert lesson.evaluate(JS_TAU) == paused
    lesson.get_by_role("button", name="Step").click()
    lesson.wait_for_function("(t) => (" + JS_TAU + ")() > t", arg=paused, timeout=10_000)
    assert asked == [] and problems == []
    offline.close()
