"""Load (or, in a fresh environment, compile) every compiled kernel the explorer runs.

numba compiles a kernel on its first call and caches it on disk (``NUMBA_CACHE_DIR``, or
``__pycache__`` next to the sources): seconds the first time, far less from the cache
(time ``python -m core.warm`` with an empty ``NUMBA_CACHE_DIR``, then again).
``warm()`` makes that first call with tiny inputs for the closed form, ``warm_methods()``
for the methods of ``core.numerics``, the moving rotor of ``core.motor`` and its batched
design kernel (the Methods and Motor cards), so that a server can load the closed form
before it takes its first page and the methods in another process meanwhile, and an image
can do both at build time
(``python -m core.warm [closed-form | methods]``: both by default).
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


def warm_methods() -> None:
    """One tiny run of each method of ``core.numerics``, of the moving rotor and of the
    batched design kernel (the Motor card's design map)."""
    from core import numerics
    from core.motor.designs import contact_merits
    from core.motor.moving_rotor import moving_rotor

    c = Contact(2.0, 0.3)
    for name in numerics.METHODS:
        numerics.solve(name, c, 8)
    moving_rotor(2.0, 0.3, [0.0, 0.1], springs=8, steps=16)
    contact_merits([2.0], [0.3], [0.1], springs=8, steps=16)


def warm_all() -> None:
    """The closed form first (every page needs it), then the methods."""
    warm()
    warm_methods()


if __name__ == "__main__":  # python -m core.warm [closed-form | methods]: both by default
    import sys

    parts = {"closed-form": warm, "methods": warm_methods}
    for part in sys.argv[1:] or parts:
        parts[part]()
