"""app.dem.view.DemCard in a Bokeh document (no browser): built when first opened; the
case, the models and an upload update the named sources in place, the score table and
the message under the upload box."""

from __future__ import annotations

import base64
import math

import numpy as np
import pytest
from bokeh.document import Document

from app.dem import data
from app.dem.upload import CHUNK_BYTES
from app.dem.view import TITLE, DemCard
from core.dem_check import CASES, exact


def send(card: DemCard, content: bytes, serial: str = "s") -> None:
    """Send `content` to the card's upload box as the browser's script does: in pieces
    ("serial:index:count:size:base64"), each once the last is acknowledged."""
    count = max(1, math.ceil(len(content) / CHUNK_BYTES))
    for i in range(count):
        piece = base64.b64encode(content[i * CHUNK_BYTES:(i + 1) * CHUNK_BYTES]).decode()
        card.upload.chunk = f"{serial}:{i}:{count}:{len(content)}:{piece}"
        assert card.upload.ack == f"{serial}:{i}"


@pytest.fixture
def opened() -> tuple[DemCard, Document]:
    card = DemCard()
    doc = Document()
    doc.add_root(card.__panel__().get_root(doc))
    card.card.collapsed = False
    return card, doc


def test_the_card_is_collapsed_and_empty_until_opened() -> None:
    card = DemCard()
    doc = Document()
    doc.add_root(card.__panel__().get_root(doc))
    assert card.card.title == TITLE and card.card.collapsed and not card.built
    assert doc.select_one({"name": "dem_exact"}) is None
    card.card.collapsed = False
    assert card.built
    assert doc.select_one({"name": "dem_exact"}) is card.sources["exact"]


def test_choosing_a_case_updates_the_exact_source_in_place(opened) -> None:
    card, doc = opened
    source = doc.select_one({"name": "dem_exact"})
    np.testing.assert_array_equal(source.data["T"], exact(CASES["fig7_psi2.41"],
                                                          data.EXACT_POINTS).T)
    card.case_select.value = "preload"
    assert card.state.case == "preload"
    assert doc.select_one({"name": "dem_exact"}) is source
    ref = exact(CASES["preload"], data.EXACT_POINTS)
    np.testing.assert_array_equal(source.data["tau"], ref.tau)
    np.testing.assert_array_equal(source.data["T"], ref.T)
    assert card.figure.x_range.start < -0.5 and card.figure.x_range.end > ref.tau[-1]
    lmp = doc.select_one({"name": "dem_lammps"})
    assert lmp.data["label"] == ["LAMMPS mindlin", "LAMMPS mindlin/force"]
    assert lmp.data["xs"][0][0] == -0.5
    assert "ψ = 2, τ₀ = -0.5 rad" in card.case_note.object


def test_the_model_boxes_choose_the_overlays(opened) -> None:
    card, doc = opened
    card.model_boxes.value = ["mindlin_rescale", "linear_history"]
    assert card.state.models == ["mindlin_rescale", "linear_history"]
    lmp = doc.select_one({"name": "dem_lammps"})
    assert lmp.data["label"] == ["LAMMPS linear_history", "LAMMPS mindlin_rescale"]
    assert card.deck_button.label == "LAMMPS deck: linear_history"
    assert card.deck_button.filename == "fig7_psi2.41.mindlin.in"  # named when clicked
    assert card._deck_file().getvalue().count("variable model index linear_history") == 1
    assert card.deck_button.filename == "fig7_psi2.41.linear_history.in"


def test_an_upload_is_scored_and_drawn(opened) -> None:
    card, doc = opened
    ref = exact(CASES["fig7_psi2.41"], 6000)
    rows = "\n".join(f"{a:.17g},{b:.17g},{c:.17g}" for a, b, c in
                     zip(ref.tau, 1.01 * ref.T, ref.P, strict=True))
    content = f"tau,T,P\n{rows}\n".encode()
    assert CHUNK_BYTES < len(content) < 2 * CHUNK_BYTES  # two pieces
    send(card, content)
    np.testing.assert_array_equal(card.state.history.T, 1.01 * ref.T)
    table = card.score_table.object
    assert card.score_table.visible and not card.message.visible
    assert "<caption>Your file against fig7_psi2.41</caption>" in table
    worst = float(np.max(np.abs(0.01 * ref.T)))
    assert f"<td>{worst:.3e} T₀ at τ = " in table
    upload = doc.select_one({"name": "dem_upload"})
    np.testing.assert_array_equal(upload.data["T"], 1.01 * ref.T[::2])  # 4000 drawn


def test_a_refused_upload_says_why_under_the_box(opened) -> None:
    card, _ = opened
    send(card, b"tau,T,P\n0,0,0\n3,0,0\n", "a")  # scored, then replaced by:
    assert card.score_table.visible
    send(card, b"tau,T,P\n0,0,0\n1,<b>x</b>,0\n", "b")
    assert card.message.visible and not card.score_table.visible
    assert card.message.object == ("your file, line 3, column &#x27;T&#x27;: "
                                   "&#x27;&lt;b&gt;x&lt;/b&gt;&#x27; is not a number")
    assert len(card.sources["upload"].data["tau"]) == 0
    assert card.score_table.object == ""


def test_a_file_the_browser_refused_for_its_size_is_said_under_the_box(opened) -> None:
    card, _ = opened
    send(card, b"tau,T,P\n0,0,0\n3,0,0\n")
    assert card.score_table.visible
    card.upload.refused = f"big:{data.MAX_UPLOAD_BYTES + 1}"
    assert card.message.visible and not card.score_table.visible
    assert card.message.object == ("your file has 2,097,153 bytes, more than the "
                                   "2,097,152 accepted: keep every k-th step")
    assert len(card.sources["upload"].data["tau"]) == 0


def test_a_case_the_card_does_not_offer_is_refused(opened) -> None:
    card, _ = opened
    card.state.case = "critical"
    with pytest.raises(ValueError):
        card.state.case = "../../etc/passwd"
    assert card.case_select.value == "critical"


def test_the_test_vectors_download_is_the_cases_csv(opened) -> None:
    card, _ = opened
    card.state.case = "grazing"
    assert card._vectors_file().getvalue() == data.vectors_text("grazing")
    assert card.vectors_button.filename == "grazing.csv"
