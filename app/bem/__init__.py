"""The "How exact is the model?" card: the explorer's contact solved by the 3D
boundary-element referee (`core.bem`) beside the closed form, and the closed form's
error mapped over nu and beta (docs/bem.md).

`data` holds the numbers (no Bokeh, no Panel: the referee's runs, their cache, the
fields and curves drawn, the error map), `view` the card (`BemCard`).
"""

from app.bem.view import BemCard

__all__ = ["BemCard"]
