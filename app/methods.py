"""Methods scene (placeholder until core.numerics lands)."""

from __future__ import annotations

import panel as pn

from core import Contact


class MethodsScene:
    """Numerical methods against the closed form."""

    def update_contact(self, c: Contact) -> None:
        """Recompute for new parameters."""

    def update_tau(self, c: Contact, tau: float) -> None:
        """Nothing depends on tau here."""

    def view(self) -> pn.viewable.Viewable:
        """The scene's layout."""
        return pn.pane.Markdown("Methods: coming soon.")
