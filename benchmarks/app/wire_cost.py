"""What encoding a psi move's columns costs (app/wire.py): CPU and bytes per gzip level.

The columns a psi move sends that are float curves (T(τ) with its bounds on the
contact's grid, and the traction profile), encoded as `app.kit.wire.InlineColumn` does:
base64 of a gzip stream, at gzip levels 0 (stored), 1, 2 (Bokeh's default) and 6, and
the stored stream as `app.kit.wire.stored_gzip` writes it (the same bytes as level 0).

    .venv/bin/python -m benchmarks.app.wire_cost
"""

from __future__ import annotations

import base64
import gzip
import math
import sys
import time
from functools import partial

import numpy as np

from app.contact.traction import TractionScene
from app.kit.figures import CURVE_POINTS
from app.kit.wire import stored_gzip
from core import Contact


def columns() -> list[np.ndarray]:
    """The float columns of one psi move's T(τ) and traction updates."""
    c = Contact(2.4, math.pi / 6)
    tau = c.tau_grid(CURVE_POINTS)
    line = c.at(tau)
    cols = [tau, line.tangential_force, line.normal_force, -line.normal_force]
    scene = TractionScene()
    scene.update_contact(c)
    cols += [np.ascontiguousarray(v[0]) for v in scene.profiles(c, np.array([2.0])).values()]
    return cols


def main() -> int:
    cols = columns()
    raw = sum(x.nbytes for x in cols)
    print(f"{len(cols)} float64 columns, {raw} bytes")
    ways = {f"gzip level {level}": partial(gzip.compress, compresslevel=level, mtime=1)
            for level in (0, 1, 2, 6)}
    ways["stored_gzip"] = stored_gzip
    for name, compress in ways.items():
        best = math.inf
        for _ in range(5):
            t0 = time.perf_counter()
            for _ in range(100):
                out = [base64.b64encode(compress(x.tobytes())) for x in cols]
            best = min(best, (time.perf_counter() - t0) / 100)
        print(f"{name}: {best * 1e3:.3f} ms, {sum(map(len, out))} bytes of base64")
    return 0


if __name__ == "__main__":
    sys.exit(main())
