"""The two spheres over a whole period, in headless Chromium: under the period strip the
pictograms show the spheres apart outside the contact (a gap that follows tau0) and
touching inside it.

Runs against EXPLORER_URL when set, else against a `python -m app.serve` started here
(fixtures in conftest.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from explorer_browser import column, open_explorer

from app.contact import pictograms
from app.contact.spheres import SpheresScene
from core import Contact

pytestmark = pytest.mark.browser

#: JavaScript: CSS px per scene unit of the spheres' plot (its frame over its y range).
JS_SCALE = """() => {
  const v = __views((v) => v.model != null && v.model.type === "Figure"
                    && v.model.title.text === "Two spheres in section")[0];
  const y = v.model.y_range;
  return v.frame.bbox.height / (y.end - y.start);
}"""

DRIVE = pictograms.PICTOGRAM_DRIVE * pictograms.RADIUS  # the pictograms' drawn H


def drawn(page) -> dict[str, np.ndarray]:
    """The pictograms' columns as the browser holds them (once they arrived)."""
    page.wait_for_function("() => (__col('spheres_pictograms', 'tau') || []).length === 6",
                           timeout=20_000)
    return {k: np.array(column(page, "spheres_pictograms", k))
            for k in ("tau", "yu", "yl", "xu", "xl", "r")}


def check_period(d: dict[str, np.ndarray], tau0: float) -> np.ndarray:
    """Assert the pictograms of a contact starting at tau0 show the spheres apart outside
    it and touching inside it; their surfaces' separations."""
    assert np.array_equal(d["xu"], d["xl"])  # one above the other
    gap = (d["yu"] - d["yl"]) - 2 * d["r"]  # centres' distance less the radii
    inside = (d["tau"] >= tau0) & (d["tau"] <= math.pi - tau0)
    assert inside.sum() == 3 and (~inside).sum() == 3  # touch, contact, release
    s0 = math.sin(tau0)
    # the gap H (sin tau0 - sin tau) outside (eqs 3, 4), the approach inside (eq 8)
    np.testing.assert_allclose(gap, DRIVE * (s0 - np.sin(d["tau"])), atol=1e-12)
    assert np.all(gap[~inside] > 0)
    assert np.all(gap[inside] <= 1e-12)
    return gap


def test_the_spheres_are_drawn_apart_outside_the_contact(browser, url) -> None:
    """The scene drew the spheres only in contact: the gap of the intermittent contact
    was never seen.  The default page (tau0 = pi/6): a gap of 1.5 H at tau = -pi/2."""
    page, _ = open_explorer(browser, url)
    d = drawn(page)
    gap = check_period(d, math.pi / 6)
    assert d["tau"][0] == pytest.approx(-math.pi / 2)
    assert gap[0] == pytest.approx(1.5 * DRIVE)
    assert gap[0] * page.evaluate(JS_SCALE) > 8  # px: the gap is seen
    page.close()


def test_the_gap_follows_tau0(browser, url) -> None:
    """A preload (tau0 < 0, h < 0) gives a shorter gap and a longer contact."""
    page, _ = open_explorer(browser, url + "?psi=2.414&tau0=-0.5&tau=1.0")
    d = drawn(page)
    gap = check_period(d, -0.5)
    assert gap[0] == pytest.approx(DRIVE * (1 + math.sin(-0.5)))
    assert 0 < gap[0] < 1.5 * DRIVE / 2
    page.close()


def test_the_pictograms_are_static_per_contact() -> None:
    """They are no part of a frame: the player's frames hold the spheres, not them."""
    assert "spheres_pictograms" not in SpheresScene.drawing(Contact(2.414, 0.5),
                                                            np.array([1.0, 2.0]))


#: JavaScript: the painted ends (CSS px) of the segments of the named source, per row:
#: [[sx0, sy0, sx1, sy1], ...] of its first solid Segment renderer.
JS_PAINTED = """(name) => {
  const v = __renderers().find((r) => r.model.data_source.name === name
      && r.model.glyph.type === "Segment"
      && JSON.stringify(r.model.glyph.line_dash.value) === "[]");
  const g = v.glyph;
  return [...Array(g.sx0.length).keys()].map((i) => [g.sx0[i], g.sy0[i], g.sx1[i], g.sy1[i]]);
}"""


def test_the_forces_are_painted_to_one_scale_with_their_coulomb_bound(browser, url) -> None:
    """Slipping (psi = 2.414, tau = 1.2 rad), the friction arrow is painted a fifth of the
    normal one (T = mu P, mu = 0.2) and ends on the tick of the bound +mu P; its label is
    there however short the arrow.  (P / P0 and T / T0 were painted on one scale, the
    friction arrow as long as the normal one.)"""
    page, _ = open_explorer(browser, url + "?psi=2.414&tau=1.2")
    page.wait_for_function("() => (__col('spheres_bound', 'x0') || []).length === 2",
                           timeout=20_000)
    (P, T) = page.evaluate(JS_PAINTED, "spheres_forces")
    ticks = page.evaluate(JS_PAINTED, "spheres_bound")
    normal, friction = abs(P[3] - P[1]), T[2] - T[0]
    c = Contact(2.414, math.pi / 6)
    assert int(c.phase(1.2)) == 2  # slip
    assert friction == pytest.approx(0.2 * normal, abs=0.5)
    assert T[2] == pytest.approx(ticks[1][0], abs=0.5)  # on the +mu P tick
    assert T[0] == pytest.approx((ticks[0][0] + ticks[1][0]) / 2, abs=0.5)
    labels = column(page, "spheres_forces", "label")
    assert labels == [f"P = {float(c.normal_force(1.2)):.3g} P₀",
                      f"T = {float(c.tangential_force(1.2)):+.3g} T₀"]
    page.close()


def test_the_whole_period_plays_the_spheres_approaching_and_parting(browser, url) -> None:
    """The animation looped over the contact only: the spheres never parted in motion.
    With the whole period ticked, Play shows frames in the gap, the spheres apart (the
    lower one's top below the upper one's bottom), and frames of the contact."""
    page, _ = open_explorer(browser, url)
    page.get_by_label("Play the whole period: approach, contact, parting").check()
    page.wait_for_function("() => __slider('tau').start < -1.5", timeout=20_000)
    page.get_by_role("button", name="▶ Play").click()
    c = Contact(math.sqrt(2) + 1, math.pi / 6)
    apart = ("(t0) => { const t = __col('spheres_forces', 'tau')[0];"
             " const lo = Math.max(...__col('spheres_lower', 'y'));"
             " const up = Math.min(...__col('spheres_upper', 'y'));"
             " return t < t0 && lo < up; }")
    page.wait_for_function(apart, arg=c.tau0, timeout=20_000)
    page.wait_for_function("([a, b]) => { const t = __col('spheres_forces', 'tau')[0];"
                           " return a < t && t < b; }", arg=[c.tau0, c.tau_end],
                           timeout=20_000)
    page.close()
