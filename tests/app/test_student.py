"""The student view and its activities without a browser (`app.page.student`,
`app.contact.activities`)."""

from __future__ import annotations

import math

import pytest
from bokeh.document import Document

from app.contact.activities import ACTIVITIES, sign_change
from app.contact.glossary import GLOSSARY
from app.contact.state import drive_ratio
from app.page.explorer import Explorer
from core import Contact


def test_the_activities_answers_are_cores() -> None:
    paper = Contact(math.sqrt(2) + 1, math.pi / 6)
    assert ACTIVITIES["stick_ends"].answer(paper) == paper.tau1  # 3 pi / 4 (eq 31)
    assert paper.tau1 == pytest.approx(3 * math.pi / 4, rel=1e-15)
    tau = sign_change(paper)
    assert abs(float(paper.tangential_force(tau))) < 1e-12
    assert paper.tangential_force(tau - 1e-3) > 0 > paper.tangential_force(tau + 1e-3)
    # theta held, mu 0.2 -> 0.5: psi falls from 2.41 to below 1 (eq 23)
    theta = math.degrees(paper.theta)
    assert drive_ratio(theta, 0.5, 0.3) < 1 < paper.psi
    assert ACTIVITIES["larger_mu"].answer(paper) == "stick"


@pytest.mark.parametrize(("key", "typed", "ok"), [
    ("stick_ends", "3pi/4", True), ("stick_ends", "2.33", True), ("stick_ends", "2.2", False),
    ("sign", "2.17", True), ("sign", "1.9", False), ("larger_mu", "Stick", True),
    ("larger_mu", "slip", False)])
def test_an_answer_is_checked_within_its_tolerance(key: str, typed: str, ok: bool) -> None:
    right, said = ACTIVITIES[key].check(typed)
    assert right is ok
    assert said.startswith("Right") if ok else said.startswith("Not quite")


def test_a_non_number_is_asked_again() -> None:
    right, said = ACTIVITIES["sign"].check("about two")
    assert not right and "radians" in said


def test_the_student_page_holds_the_scenes_activities_and_glossary_only() -> None:
    ex = Explorer(query={"view": "student", "psi": "3"})
    assert ex.view_name == "student" and ex.messages == []
    root = ex.view().get_root(Document())
    names = {m.name for m in root.references() if getattr(m, "name", None)}
    assert {"traction", "disc", "force", "spheres_forces"} <= names
    texts = " ".join(str(getattr(m, "text", "")) for m in root.references())
    assert all(term.split(" ")[0] in texts for term in GLOSSARY)
    assert "Methods" not in texts and "Motor" not in texts  # no expert card
    assert root.select_one({"tags": ["formulas"]}) is None  # no formulas


def test_an_activity_loads_its_contact_and_checks_the_answer() -> None:
    from app.page import student

    ex = Explorer(query={"view": "student"})
    ex.view()
    card = student.ActivityCard(ex.contact)
    card.choice.value = "larger_mu"
    assert ex.state.drive == "angle" and ex.state.mu == 0.2
    assert "0.2 to 0.5" in card.question.object
    card.answer.value = "stick"
    assert card.feedback.startswith("Right")
    card.choice.value = ""
    assert card.answer.disabled and card.feedback == ""
