"""The base of the app's scenes: one Bokeh figure fed by one named `ColumnDataSource`.

The figure is built once (with `app.kit.figures`) and only its data changes
(`source.data = ...`), so that a slider move sends numbers, not models.  Sources are
named after their scene, so that tests and the browser find them with
`get_model_by_name`.  A scene follows a state's contact and time by one watcher,
`Scene.follow`.
"""

from __future__ import annotations

import numpy as np
import param
from bokeh.models import ColumnDataSource

from app.kit.batch import held
from core import Contact


class Scene:
    """Base: a figure, its named source, and the two update hooks.

    A scene follows a state's contact (`current`) and time (`tau`) by `follow`, a
    watcher the feature subscribes (`app.contact.view.connect`)."""

    name: str = ""
    #: the tau0 (`float.hex`) of what the scene drew that depends on tau0 alone
    _drawn_tau0: str | None = None

    #: not on the page (a closed tab): it computes nothing and is `stale`
    hidden: bool = False
    #: it missed a change while hidden: drawn in full when shown again
    stale: bool = False
    #: the tau it last drew (None: nothing yet)
    drawn_tau: float | None = None

    def __init__(self, data: dict) -> None:
        self.source = ColumnDataSource(data=data, name=self.name)

    def note_tau0(self, c: Contact) -> bool:
        """Note `c`'s tau0 as the one drawn, and say whether it differs from the one noted
        before, bit for bit (-0.0 is not 0.0; True on the first call): what depends on
        tau0 alone is drawn again only then."""
        key = c.tau0.hex()
        if key == self._drawn_tau0:
            return False
        self._drawn_tau0 = key
        return True

    def follow(self, *events: param.parameterized.Event) -> None:
        """Draw `events`, changes of a state's `current` and `tau`
        (`app.contact.state.ExplorerState`; a watcher `app.contact.view.connect`
        subscribes): `update_contact` when the contact changed (or the scene is `stale`),
        then `update_tau`.  Nothing when the scene is `hidden` (it is then marked
        `stale`) or when only tau moved while the browser plays the frames (the scene
        draws the tau the pause lands on: `app.contact.animation`).  The tau drawn is
        noted as `drawn_tau`.  It draws inside `held`: a change that reaches the state
        from Panel's handling of a browser event (Enter in a text box, a click, with a
        change of a widget's value pending) comes without Bokeh's document lock."""
        state = events[0].obj
        new = self.stale or any(e.name == "current" for e in events)
        if self.hidden:
            self.stale = True
            return
        if state.playing and not new:
            return
        self.stale = False
        self.drawn_tau = tau = state.tau
        with held():
            if new:
                self.update_contact(state.current)
            self.update_tau(state.current, tau)

    def update_contact(self, c: Contact) -> None:
        """Recompute what depends on the parameters (default: nothing)."""

    def update_tau(self, c: Contact, tau: float) -> None:
        """Recompute what depends on the current tau (default: nothing)."""

    def table(self) -> dict[str, np.ndarray]:
        """The data shown, for the CSV download."""
        return {k: np.asarray(v) for k, v in self.source.data.items()}
