"""Changes that reach the browser together: `held`, Panel's `hold` entered only where the
document does not hold its changes already."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import panel as pn
from panel.io import hold


@contextmanager
def held() -> Iterator[None]:
    """Hold the current document's changes (Panel's `hold()`) for the body, to go to the
    browser in one message, unless the document holds them already: inside Panel's
    handling of an event, a served slider's move (`ExactSlider`) or an outer `held`.

    Entering Panel's hold again there sends nothing sooner, yet costs: each exit of a
    nested hold walks every change held so far."""
    doc = pn.state.curdoc
    if doc is not None and doc.callbacks.hold_value:
        yield
    else:
        with hold():
            yield
