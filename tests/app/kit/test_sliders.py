"""app.kit.sliders without a browser: the range an `ExactSlider` shows."""

from __future__ import annotations

from app.kit.sliders import ExactSlider


def psi_slider() -> ExactSlider:
    return ExactSlider(label="ψ", value=2.0, start=0.05, end=30.0, step=0.01, parse=float)


def test_a_typed_value_beyond_the_range_widens_it_and_a_drag_back_keeps_it() -> None:
    """Above psi = 30 the slider's end shrank to the value after each move, so the thumb
    jumped to the right end under the pointer: a move of the slider only widens the
    range; a value typed or set inside the slider's own range restores it."""
    s = psi_slider()
    s.value = 50.0  # typed in the box (or from a link)
    assert (s.start, s.end) == (0.05, 50.0)
    s.model.value = 40.0  # the browser's slider, dragged back
    assert (s.start, s.end) == (0.05, 50.0) and s.value == 40.0
    s.model.value = 20.0
    assert (s.start, s.end) == (0.05, 50.0)
    s.value = 10.0  # typed: the slider's own range again
    assert (s.start, s.end) == (0.05, 30.0)


def test_a_move_of_the_slider_never_narrows_what_it_shows() -> None:
    s = psi_slider()
    s.model.value = 5.0
    assert (s.start, s.end) == (0.05, 30.0)
    s.value = 0.01  # below the range: widened downwards
    assert (s.start, s.end) == (0.01, 30.0)
    s.model.value = 0.02
    assert s.start == 0.01
