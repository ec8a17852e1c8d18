"""A collapsed card whose content is built on its first opening: `LazyCard`.

A card of the page that computes or draws anything (the Methods, DEM and BEM cards)
starts collapsed with nothing in it: no model of its content is made or sent until the
user opens it.  Its header button says whether it is open (`aria-expanded`:
`app.kit.a11y.expandable_card`).
"""

from __future__ import annotations

from collections.abc import Callable

import panel as pn
import param

from app.kit.a11y import expandable_card
from app.kit.batch import held


class LazyCard:
    """A collapsed Panel card (`card`, an `expandable_card`) titled `title`, whose
    objects `build()` returns on its first opening; `on_open(first)` (if given) runs
    after it on every opening, with whether it was the first.  Both run in one `held`
    batch: what the opening builds and shows reaches the browser in one message.
    `params` go to the card (default: the column's width, a margin of 6 px)."""

    def __init__(self, title: str, build: Callable[[], list],
                 on_open: Callable[[bool], None] | None = None, **params) -> None:
        self._build = build
        self._on_open = on_open
        params = {"sizing_mode": "stretch_width", "margin": 6} | params
        self.card = expandable_card(title=title, collapsed=True, **params)
        self.card.param.watch(self._on_collapsed, "collapsed")

    def __panel__(self) -> pn.Card:
        return self.card

    @property
    def built(self) -> bool:
        """Whether the card's content exists (it has been opened)."""
        return bool(self.card.objects)

    @property
    def opened(self) -> bool:
        """Whether the card is open."""
        return not self.card.collapsed

    def _on_collapsed(self, event: param.parameterized.Event) -> None:
        if event.new:
            return
        first = not self.built
        with held():
            if first:
                self.card.objects = list(self._build())
            if self._on_open is not None:
                self._on_open(first)
