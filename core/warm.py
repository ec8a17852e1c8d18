"""Load (or, in a fresh environment, compile) every compiled kernel of the closed form.

numba compiles a kernel on its first call and caches it on disk (``NUMBA_CACHE_DIR``, or
``__pycache__`` next to the sources): a few seconds the first time, tens of ms from the
cache. ``warm()`` makes that first call with tiny inputs, so that a server can do it in
the background at start-up and an image can do it at build time.
"""

from __future__ import annotations

from core import batch
from core.contact import Contact, curve, impulse_ratio


def warm() -> None:
    """One tiny call of each entry point of the closed form (every kernel it compiles)."""
    curve(2.0, 0.3, 8)
    impulse_ratio([0.5, 2.0], [0.3, -0.9])
    batch.phase(2.0, 0.3, [1.0])
    c = Contact(2.0, 0.3)
    line = c.at([1.0, 2.0])
    for name in ("clock", "phase", "approach", "contact_radius", "stick_radius",
                 "normal_force", "tangential_force", "centre_displacement"):
        getattr(line, name)
    c.traction([0.1], [1.0])
    float(c.F0)


if __name__ == "__main__":
    warm()
