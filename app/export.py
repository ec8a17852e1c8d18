"""CSV exports of what the explorer shows: tables of named columns, as text.

The curves table joins the T(tau), radii and motion scenes on their common tau grid and,
when the contact has SI scales (physical inputs), adds each quantity in SI units.
"""

from __future__ import annotations

import io
import math

import numpy as np

from app.scenes import Scene
from core import Contact
from core.physical import Scales


def curves_table(force: Scene, radii: Scene, motion: Scene,
                 scales: Scales | None) -> dict[str, np.ndarray]:
    """T/T0 and +-mu P/T0, approach, a, b and the centre's motion on one tau grid, plus
    SI columns (t_s, T_N, ...) when `scales` is given."""
    table = force.table()
    for scene in (radii, motion):
        extra = scene.table()
        if not np.array_equal(extra.pop("tau"), table["tau"]):
            raise ValueError(f"the {scene.name} scene is on another tau grid than T(tau)")
        table.update(extra)
    if scales is not None:
        sc = scales
        table.update(t_s=table["tau"] * sc.period / (2 * math.pi), T_N=table["T"] * sc.T0,
                     muP_N=table["muP"] * sc.T0, a_m=table["a"] * sc.a_star,
                     b_m=table["b"] * sc.a_star, approach_m=table["approach"] * sc.alpha_star,
                     u2_m=table["u2"] * sc.u0, v2_m_per_s=table["v2"] * sc.v_star)
    return table


def csv_text(table: dict[str, np.ndarray]) -> str:
    """The table as CSV: a header of column names, 10 significant digits (a negative
    zero is written 0)."""
    names = list(table)
    body = np.column_stack([np.asarray(table[n], float) for n in names]) + 0.0
    out = io.StringIO()
    np.savetxt(out, body, delimiter=",", header=",".join(names), comments="", fmt="%.10g")
    return out.getvalue()


def file_name(key: str, c: Contact) -> str:
    """The CSV file's name, after the parameters it holds."""
    return f"zharii_{key}_psi{c.psi:.4g}_tau0_{c.tau0:.4g}_mu{c.mu:g}_nu{c.nu:g}.csv"
