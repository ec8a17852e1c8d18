"""How each contact phase looks: one table for every title, colour, disc and key.

The phases and their names are `core.Phase` and `core.PHASE_NAMES`; which phase holds at
a time is always `Contact.phase` (one rule, phase boundaries included).
"""

from __future__ import annotations

from dataclasses import dataclass

from core import PHASE_NAMES, Phase


@dataclass(frozen=True)
class PhaseStyle:
    """The look of one phase: its name and colour (the traction plot's phase label, the
    disc's key), and the name and colour of the disc's ring outside the stick disc (the
    whole disc slips or counter-slips outside it)."""

    name: str
    color: str
    ring: str
    ring_color: str


#: Okabe-Ito hues (colour-blind safe), darkened where needed for a contrast of at least
#: 3:1 on white (WCAG, for the phase name drawn in its colour); the stick disc is always
#: the full-stick green.
_GREY, _GREEN, _ORANGE, _SKY, _BLUE = "#767676", "#009E73", "#C26A00", "#2E86C1", "#0072B2"

STYLES: dict[Phase, PhaseStyle] = {
    Phase.NO_CONTACT: PhaseStyle(PHASE_NAMES[Phase.NO_CONTACT], _GREY, "slip", _GREY),
    Phase.FULL_STICK: PhaseStyle(PHASE_NAMES[Phase.FULL_STICK], _GREEN, "slip", _GREEN),
    Phase.SLIP: PhaseStyle(PHASE_NAMES[Phase.SLIP], _ORANGE, "slip", _ORANGE),
    Phase.PARTIAL_STICK: PhaseStyle(PHASE_NAMES[Phase.PARTIAL_STICK], _SKY, "counter-slip",
                                    _BLUE),
    Phase.COUNTER_SLIP: PhaseStyle(PHASE_NAMES[Phase.COUNTER_SLIP], _BLUE, "counter-slip",
                                   _BLUE),
}

#: Colour of the stick disc.
STICK_COLOR = STYLES[Phase.FULL_STICK].color


def style(phase: int) -> PhaseStyle:
    """The style of phase code `phase` (an int or a 0-d array from `Contact.phase`)."""
    return STYLES[Phase(int(phase))]
