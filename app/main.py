"""Entry point of `panel serve app/main.py`: one explorer per browser session."""

import panel as pn

from app.explorer import build_explorer

pn.extension("katex", notifications=False)

build_explorer().servable()
