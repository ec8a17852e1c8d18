"""The presentation view's document (no browser): the curve under the traction profile
follows the preset, the projector box restyles the plots and back, the CSS sizes."""

from __future__ import annotations

import panel as pn
import pytest

from app.kit.a11y import Landmark
from app.page import present_css, projector
from app.page.explorer import Explorer


def select(page: pn.viewable.Viewable, kind: type) -> list:
    """The components of type `kind` in `page`, inside its landmarks too (Panel's
    `select` does not look into a `Landmark`'s object)."""
    found = list(page.select(kind))
    for landmark in page.select(Landmark):
        found += select(landmark.object, kind)
    return found


def slot_titles(page: pn.viewable.Viewable) -> list[str]:
    """The titles of the plots under the traction profile."""
    (slot,) = [r for r in select(page, pn.Row) if "pp-bottom" in r.css_classes]
    return [p.object.title.text for p in slot.objects]


def test_the_presets_figure_shows_and_t_of_tau_comes_back_when_the_preset_is_left() -> None:
    ex = Explorer(query={"view": "present", "preset": "fig8"})
    page = ex.view()
    assert slot_titles(page) == ["Tangential impulse T_imp / (μ P_imp)"]
    ex.state.psi = 3.0  # the preset is left
    assert ex.state.preset == ""
    assert slot_titles(page) == ["Tangential force T / T₀"]
    assert len(ex.contact.force.source.data["T"]) > 300  # caught up: its data are shown
    ex.state.apply_preset("fig9")
    assert slot_titles(page) == ["Contact-centre velocity (Fig. 9a)",
                                 "Contact-centre displacement (Fig. 9b)"]
    ex.state.apply_preset("fig6e")
    assert slot_titles(page) == ["Tangential force T / T₀"]


def test_the_projector_box_scales_type_and_lines_and_restores_them() -> None:
    ex = Explorer(query={"view": "present"})
    page = ex.view()
    force = ex.contact.force.figure
    axis, line = force.yaxis[0], force.select_one({"name": "force_T"}).glyph
    assert (axis.major_label_text_font_size, line.line_width) == ("12pt", 3)
    box = next(o for o in select(page, pn.widgets.CheckBoxGroup)
               if o.options == [projector.LABEL])
    box.value = [projector.LABEL]
    assert axis.major_label_text_font_size == "18pt"  # 24 px
    assert line.line_width == pytest.approx(3 * projector.LINE_SCALE)
    box.value = []
    assert (axis.major_label_text_font_size, line.line_width) == ("12pt", 3)


def test_scaled_sizes() -> None:
    assert projector.scaled_size("12pt", 1.5) == "18pt"
    assert projector.scaled_size("1.2em", 2) == "2.4em"
    assert projector.scaled("x", 2) == "x"  # (a column name: unchanged)
    assert projector.scaled({"value": 2}, 1.5) == {"value": 3.0}


def test_equal_scales_box_css() -> None:
    """The box whose frame (box less rim) has the aspect: width from height and back."""
    assert present_css.height_for_width(0.5, (10, 30), 240) == 490
    css = present_css.box_for_height(0.5, (10, 30), "400px")
    assert "width: calc((400px - 30px) * 0.5 + 10px)" in css
