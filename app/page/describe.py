"""What a screen reader hears of the plots: each plot's name and a short description of
what it shows (numbers from core), and a polite live region announcing a change of phase.

`Describer` writes them for the contact and time shown (`app.contact.view.ContactView`),
when the contact, tau or the open curve tab change; while the animation plays nothing is
written (the browser plays the frames; the server learns the time at the pause), and the
pause writes them once.  The page puts them beside the plots (`app.page.layout`).
"""

from __future__ import annotations

import math

from app.contact.state import ExplorerState
from app.contact.view import TAB_TITLES, ContactView
from app.kit.a11y import LiveText
from app.kit.style import VISUALLY_HIDDEN_CSS
from app.kit.texts import Description
from core import PHASE_NAMES, Contact, Phase

#: The plots' accessible names (their cards' titles), by the key of their description.
PLOT_NAMES = {"spheres": "The two spheres (Fig. 2)", "traction": "Traction profile (Fig. 6)",
              "disc": "Contact disc", "curves": "Curves over the contact"}


def phase_start(c: Contact, tau: float) -> float:
    """When the phase of `c` at time `tau` (rad) began, from core's phase boundaries
    (``core.tangential.phase``): full stick and slip at tau0 (the contact's start),
    partial stick at pi/2 (the end of loading), counter-slip at tau1 (eq 31); nan
    outside the contact."""
    starts = {Phase.FULL_STICK: c.tau0, Phase.SLIP: c.tau0,
              Phase.PARTIAL_STICK: math.pi / 2, Phase.COUNTER_SLIP: c.tau1}
    return starts.get(int(c.phase(tau)), math.nan)


def announcement(c: Contact, tau: float) -> str:
    """What the live region says of the phase at time `tau`: 'Partial stick from
    τ = 1.571 rad'."""
    return f"{PHASE_NAMES[int(c.phase(tau))].capitalize()} from τ = {phase_start(c, tau):.3f} rad"


def descriptions(c: Contact, tau: float, tab: int) -> dict[str, str]:
    """A short text of what each plot (`PLOT_NAMES`) shows at time `tau` (rad), the
    curve tab `tab` open: the numbers are core's."""
    line = c.at(tau)  # (one evaluation of core for every quantity at tau)
    phase = PHASE_NAMES[int(line.phase)]
    T, P = float(line.tangential_force), float(line.normal_force)
    a, b = float(line.contact_radius), float(line.stick_radius)
    at = f"at τ = {tau:.3f} rad"
    span = f"over the contact, τ from {c.tau0:.3f} to {c.tau_end:.3f} rad"
    curves = (
        f"T(τ): the tangential force T/T0 {span}; {at}, T = {T:+.3f} T0",
        f"Impulse: the impulse ratio over ψ; at this contact's ψ = {c.psi:.4g}, "
        f"{c.impulse_ratio:.3f}",
        f"Radii: the contact radius a and the stick radius b {span}; {at}, "
        f"a = {a:.3f} a*, b = {b:.3f} a*",
        f"Centre motion: the displacement and velocity of the driven sphere's centre and "
        f"of the drive {span}",
    )
    return {
        "spheres": f"The two spheres {at}: {phase}; forces on the upper sphere "
                   f"P = {P:.3f} P0, T = {T:+.3f} T0",
        "traction": f"Traction profile {at}: {phase}, stick radius {b:.2f} a*, "
                    f"T = {T:+.3f} T0",
        "disc": f"Contact disc {at}: {phase}, contact radius {a:.3f} a*, "
                f"stick radius {b:.3f} a*",
        "curves": f"{TAB_TITLES[tab]}. {curves[tab]}",
    }


#: The description's text clipped to nothing too (its own box keeps its natural width,
#: beyond the 1 px of its hidden host).
HIDDEN_TEXT_CSS = "p { margin: 0; overflow: hidden; clip-path: inset(50%); white-space: nowrap; }"


class Describer:
    """The plots' descriptions and the live region of one page."""

    def __init__(self, contact: ContactView, state: ExplorerState) -> None:
        self.contact, self.state = contact, state
        #: each plot's name and description (by `PLOT_NAMES`' keys)
        self.descriptions = {
            key: Description(label=PLOT_NAMES[key],
                             stylesheets=[VISUALLY_HIDDEN_CSS, HIDDEN_TEXT_CSS],
                             name=f"{key}_description")
            for key in PLOT_NAMES}
        #: the polite live region announcing a change of phase
        self.announcer = LiveText(name="phase_announcement")
        self._announced = int(state.current.phase(state.tau))
        self.describe()
        contact.tabs.param.watch(lambda *_: self.describe(), "active")
        state.param.watch(lambda *_: self.describe(), ["current", "tau", "playing"])

    def describe(self) -> None:
        """Write each plot's description, and announce a new phase, for the contact and
        time shown.  While playing nothing is written (the browser plays the frames; the
        server learns the time at the pause): the pause writes them once."""
        if self.state.playing:
            return
        c = self.state.current
        tau = min(max(self.state.tau, c.tau0), c.tau_end)  # (before the state's clamp)
        tab = self.contact.tabs.active
        if tab not in range(len(TAB_TITLES)):
            return
        for key, text in descriptions(c, tau, tab).items():
            self.descriptions[key].write(description=text)
        phase = int(c.phase(tau))
        if phase != self._announced and phase != Phase.NO_CONTACT:
            self._announced = phase
            self.announcer.write(text=announcement(c, tau))
