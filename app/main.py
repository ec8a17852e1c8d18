"""Entry point of `panel serve app/main.py`: one explorer per browser session."""

import sys
from pathlib import Path

# `panel serve` puts app/ (not the repository) on sys.path; make `core` and `app`
# importable as the regular packages of this checkout even without an install.
_ROOT = str(Path(__file__).resolve().parent.parent)
if _ROOT not in sys.path:
    sys.path.insert(0, _ROOT)

import panel as pn  # noqa: E402

from app.explorer import build_explorer  # noqa: E402

pn.extension("katex", notifications=False)

build_explorer().servable()
