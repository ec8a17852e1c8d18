"""The lesson file without a browser: what it holds (`app.contact.lesson`)."""

from __future__ import annotations

import math

import numpy as np
from bokeh.models import ColumnDataSource

from app.contact.lesson import MAX_BYTES, lesson_html, lesson_layout
from app.contact.player import frame_taus
from app.contact.state import ExplorerState
from core import Contact


def test_the_lesson_holds_the_contacts_frames_in_cores_numbers() -> None:
    state = ExplorerState(psi=3.0, tau0=0.4, mu=0.25, preset="")
    layout = lesson_layout(state)
    sources = {m.name: m for m in layout.references() if isinstance(m, ColumnDataSource)}
    c = Contact(3.0, 0.4, mu=0.25, nu=0.3)
    taus = frame_taus(c)
    frames = sources["frames"].data
    np.testing.assert_array_equal(frames["tau"], taus)
    np.testing.assert_array_equal(frames["b"], c.stick_radius(taus))
    profiles = sources["frame_profiles"].data
    n = profiles["r"].size // taus.size
    r = np.asarray(profiles["r"]).reshape(taus.size, n)
    np.testing.assert_allclose(np.asarray(profiles["traction"]).reshape(taus.size, n),
                               c.traction(r, taus[:, None]), rtol=0, atol=1e-15)
    assert state.playing is False and state.psi == 3.0  # (the state is left alone)


def test_the_lesson_file_needs_no_network_and_fits_a_learning_platform() -> None:
    text = lesson_html(ExplorerState())
    assert len(text.encode()) <= MAX_BYTES
    assert "<script src" not in text and "<link" not in text  # everything inline
    assert "BEGIN bokeh.min.js" in text
    assert f"{math.pi / 6:.4g}" in text  # (the heading names the contact)
