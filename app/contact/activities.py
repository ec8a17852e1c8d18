"""Three guided activities for a class: a contact to look at, a question, and a check of
the student's answer against `core`.

Each activity sets a contact (`Activity.values`, parameters of `ExplorerState`), asks
one question whose answer the student finds by playing or scrubbing the animation, and
checks the answer typed (`Activity.check`): right within `Activity.tolerance`, or a hint
that says where to look, never the answer itself.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from scipy.optimize import brentq

from app.contact.state import SQRT2_1, TAU0, drive_ratio, number_text
from core import Contact


def sign_change(c: Contact) -> float:
    """The time tau (rad) at which T changes sign during unloading (eqs 38, 39: from +
    to -, found by bracketing between pi/2, where T > 0, and the end of the contact,
    where T < 0 for psi > 1)."""
    hi = math.nextafter(c.tau_end, 0.0)
    return brentq(lambda t: float(c.tangential_force(t)), math.pi / 2, hi, xtol=1e-12)


def larger_mu(c: Contact, mu: float) -> str:
    """What friction `mu` does to contact `c` with its drive's angle theta held (eq 23):
    'stick' if the contact sticks at first touch then and did not (psi falls to 1 or
    below), 'slip' if the reverse, else 'same'."""
    psi = drive_ratio(math.degrees(c.theta), mu, c.nu)
    before, after = c.psi <= 1.0, psi <= 1.0
    return "same" if before == after else "stick" if after else "slip"


@dataclass(frozen=True)
class Activity:
    """A contact (`values`), a question, the answer `core` gives (`answer(contact)`, a
    time in rad or a choice) and how close a typed answer must be (`tolerance`, rad; 0
    for a choice), a hint for a wrong answer and what the right answer shows."""

    title: str
    values: dict[str, object]
    question: str
    answer: Callable[[Contact], float | str]
    hint: str
    explain: str
    tolerance: float = 0.0
    choices: tuple[str, ...] = field(default=())

    def contact(self) -> Contact:
        """The activity's contact (its psi, tau0, mu, nu)."""
        v = self.values
        return Contact(float(v["psi"]), float(v["tau0"]), mu=float(v["mu"]),
                       nu=float(v["nu"]))

    def check(self, typed: str) -> tuple[bool, str]:
        """Whether `typed` answers the question, and what to tell the student."""
        right = self.answer(self.contact())
        if self.choices:
            ok = typed.strip().lower() == str(right).lower()
            return ok, (f"Right: {self.explain}" if ok else f"Not quite. {self.hint}")
        value = number_text(typed.strip())
        if not isinstance(value, float) or not math.isfinite(value):
            return False, "Type a time in radians, e.g. 2.3 or 3pi/4."
        if abs(value - float(right)) <= self.tolerance:
            return True, f"Right: τ = {float(right):.3f} rad. {self.explain}"
        return False, f"Not quite. {self.hint}"


#: The paper's contact (Figs. 4, 6, 9): psi = sqrt 2 + 1, tau0 = pi / 6.
PAPER = {"psi": SQRT2_1, "tau0": TAU0, "mu": 0.2, "nu": 0.3, "drive": "psi"}

ACTIVITIES: dict[str, Activity] = {
    "stick_ends": Activity(
        title="Find where stick ends",
        values={**PAPER, "tau": math.pi / 2},
        question="Play, or move the time τ, until the green stick disc in the middle of "
                 "the contact disappears. At what τ (rad) does it disappear?",
        answer=lambda c: c.tau1,
        tolerance=0.05,
        hint="Watch the traction plot's green band while unloading (after τ = π/2): it "
             "shrinks to nothing. Step frame by frame near the end of the contact.",
        explain="This is τ₁ = 3π/4 for ψ = 1 + √2: after it the whole contact slips "
                "back (counter-slip)."),
    "sign": Activity(
        title="When does T change sign",
        values={**PAPER, "tau": math.pi / 2},
        question="The friction force T pushes along the drive while the spheres press "
                 "together. At what time τ (rad) does T change sign, from + to −?",
        answer=sign_change,
        tolerance=0.05,
        hint="Look at the T(τ) plot: find where the black curve crosses zero after "
             "τ = π/2, or watch the arrow T turn round on the spheres.",
        explain="While unloading, the rim slips back and the friction there pulls the "
                "other way; when it outweighs the stuck centre, T turns negative."),
    "larger_mu": Activity(
        title="What does a larger μ do",
        values={**PAPER, "drive": "angle", "tau": math.pi / 3},
        question="The drive's angle θ is held. Raise the friction μ from 0.2 to 0.5 and "
                 "watch the start of the contact. Does the contact now slip more, stick "
                 "more, or behave the same? (type: slip, stick or same)",
        answer=lambda c: larger_mu(c, 0.5),
        choices=("slip", "stick", "same"),
        hint="With θ held, a larger μ makes ψ = tan θ / tan θ₀ smaller: compare ψ in the "
             "table before and after.",
        explain="ψ falls below 1 (tan θ₀ grows with μ), so the contact sticks at first "
                "touch instead of slipping (full stick)."),
}
