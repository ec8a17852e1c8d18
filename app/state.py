"""The explorer's state: the parameters a user controls, and nothing of the view.

`ExplorerState` holds the four dimensionless numbers of the problem (psi, tau0, mu,
nu), the current time tau, the animation settings and the optional physical inputs.
It turns them into a `core.Contact` (the only place the app builds one) and knows how
to read and write them as a URL query string.  All physics lives in `core`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import param

from core import MATERIALS, Contact

SQRT2_1 = math.sqrt(2.0) + 1.0  # psi of the paper's Figs. 4, 6 and 9 (tau1 = 3 pi / 4)
PI = math.pi
TAU0 = PI / 6  # all the paper's figures: H = 2 h


@dataclass(frozen=True)
class Limits:
    """Accepted range of one URL/query parameter (inclusive unless marked open)."""

    lo: float
    hi: float
    lo_open: bool = False
    hi_open: bool = False

    def contains(self, x: float) -> bool:
        """True when x lies in the range."""
        above = x > self.lo if self.lo_open else x >= self.lo
        below = x < self.hi if self.hi_open else x <= self.hi
        return above and below

    def describe(self) -> str:
        """The range in interval notation, e.g. '(0, 1e+06]'."""
        left = "(" if self.lo_open else "["
        right = ")" if self.hi_open else "]"
        return f"{left}{self.lo:g}, {self.hi:g}{right}"


#: Limits of every numeric query parameter.  tau is checked separately against
#: the contact interval [tau0, pi - tau0] implied by tau0.
LIMITS: dict[str, Limits] = {
    "psi": Limits(0.0, 1e6, lo_open=True),
    "tau0": Limits(-1.5, 1.5),
    "mu": Limits(0.0, 2.0, lo_open=True),
    "nu": Limits(0.0, 0.5, hi_open=True),
    "speed": Limits(0.05, 10.0),
}

#: Query parameters written to / read from the URL, in this order.
QUERY_KEYS = ("psi", "tau0", "mu", "nu", "tau", "log_psi", "preset")


@dataclass(frozen=True)
class Preset:
    """Parameters that reproduce one figure of Zharii (1996)."""

    label: str
    psi: float
    tau0: float
    tau: float
    log_psi: bool = False
    family: tuple[float, ...] = ()  # further psi values overlaid on T(tau) (Fig. 7)


PRESETS: dict[str, Preset] = {
    "fig4": Preset("Fig. 4: approach, a and b (psi = 2.414)", SQRT2_1, TAU0, 3 * PI / 5),
    "fig6a": Preset("Fig. 6a: loading, tau = pi/4", SQRT2_1, TAU0, PI / 4),
    "fig6b": Preset("Fig. 6b: loading, tau = pi/3", SQRT2_1, TAU0, PI / 3),
    "fig6c": Preset("Fig. 6c: end of loading, tau = pi/2", SQRT2_1, TAU0, PI / 2),
    "fig6d": Preset("Fig. 6d: partial stick, tau = 7pi/12", SQRT2_1, TAU0, 7 * PI / 12),
    "fig6e": Preset("Fig. 6e: partial stick, tau = 17pi/24", SQRT2_1, TAU0, 17 * PI / 24),
    "fig6f": Preset("Fig. 6f: counter-slip starts, tau = 3pi/4", SQRT2_1, TAU0, 3 * PI / 4),
    "fig7a": Preset("Fig. 7a: T(tau), psi = 0.4, 0.8, 1", 0.8, TAU0, PI / 2,
                    family=(0.4, 0.8, 1.0)),
    "fig7b": Preset("Fig. 7b: T(tau), psi = 2.41, 6.46, 28.35", 6.46, TAU0, PI / 2,
                    family=(2.41, 6.46, 28.35)),
    "fig8": Preset("Fig. 8: impulse vs psi (maximum at psi = 1)", 1.0, TAU0, PI / 2),
    "fig9": Preset("Fig. 9: contact-centre motion (psi = 2.414)", SQRT2_1, TAU0,
                   2 * PI / 3),
}

DEFAULT_PRESET = "fig6e"


class ExplorerState(param.Parameterized):
    """Everything the user sets; the view watches it and asks `core` for numbers."""

    psi = param.Number(default=SQRT2_1, bounds=(1e-6, 1e6), doc="psi = tan(theta) / tan(theta0)")
    tau0 = param.Number(default=math.pi / 6, bounds=(-1.5, 1.5), doc="start of contact (rad)")
    mu = param.Number(default=0.2, bounds=(1e-3, 2.0), doc="friction coefficient")
    nu = param.Number(default=0.3, bounds=(0.0, 0.499), doc="Poisson ratio")
    tau = param.Number(default=17 * math.pi / 24, doc="current time omega t (rad)")
    log_psi = param.Boolean(default=False, doc="log psi axis on the impulse curve")
    playing = param.Boolean(default=False, doc="animation running")
    speed = param.Number(default=1.0, bounds=(0.05, 10.0), doc="contacts per 4 s")
    preset = param.String(default=DEFAULT_PRESET,
                          doc="name of the last preset loaded, '' once edited")

    physical = param.Boolean(default=False, doc="define the contact by SI inputs")
    material = param.Selector(default="custom", objects=["custom", *MATERIALS])
    R = param.Number(default=0.01, bounds=(1e-9, None), doc="sphere radius (m)")
    G = param.Number(default=79e9, bounds=(1.0, None), doc="shear modulus (Pa)")
    H = param.Number(default=2e-6, bounds=(1e-15, None), doc="normal amplitude (m)")
    u0 = param.Number(default=1e-6, bounds=(0.0, None), doc="tangential amplitude (m)")
    h = param.Number(default=1e-6, bounds=(None, None), doc="gap at t = 0 (m)")
    omega = param.Number(default=2 * math.pi * 40e3, bounds=(1e-9, None), doc="rad/s")

    def contact(self) -> Contact:
        """The `core.Contact` the current parameters define."""
        if self.physical:
            return Contact.from_physical(R=self.R, G=self.G, nu=self.nu, mu=self.mu, H=self.H,
                                         u0=self.u0, h=self.h, omega=self.omega)
        return Contact(self.psi, self.tau0, mu=self.mu, nu=self.nu)

    def apply_preset(self, name: str) -> None:
        """Load the parameters of preset `name` (a key of PRESETS); KeyError if unknown."""
        p = PRESETS[name]
        self.param.update(physical=False, psi=p.psi, tau0=p.tau0, mu=0.2, nu=0.3, tau=p.tau,
                          log_psi=p.log_psi, preset=name)

    def reset(self) -> None:
        """Back to the defaults (the default preset), animation stopped."""
        self.playing = False
        self.apply_preset(DEFAULT_PRESET)

    def apply_material(self, name: str) -> None:
        """Copy G, nu and mu of `core.MATERIALS[name]` into the state."""
        m = MATERIALS[name]
        self.param.update(material=name, G=m["G"], nu=m["nu"], mu=m["mu"])

    def query(self) -> dict[str, str]:
        """The shareable part of the state as URL query values."""
        q = {k: f"{getattr(self, k):.10g}" for k in ("psi", "tau0", "mu", "nu", "tau")}
        if self.log_psi:
            q["log_psi"] = "1"
        if self.preset:
            q["preset"] = self.preset
        return q


def _number(key: str, raw: str) -> tuple[float | None, str | None]:
    try:
        x = float(raw)
    except ValueError:
        return None, f"{key}={raw!r} is not a number"
    if not math.isfinite(x):
        return None, f"{key}={raw!r} is not a finite number"
    lim = LIMITS.get(key)
    if lim is not None and not lim.contains(x):
        return None, f"{key}={raw} is out of range {lim.describe()}"
    return x, None


def parse_query(query: Mapping[str, str | bytes | list]) -> tuple[dict, list[str]]:
    """Validate URL query values.

    `query` maps names to strings (or bytes, or lists of them as in
    `pn.state.session_args`).  Returns `(values, messages)`: the accepted values as
    parameter updates for `ExplorerState`, and one human-readable message per
    rejected value (whose default is then kept).  Unknown names are reported too.
    A `preset` is applied first; explicit values then override it.
    """
    values: dict = {}
    messages: list[str] = []
    flat: dict[str, str] = {}
    for key, raw in query.items():
        if isinstance(raw, list):
            raw = raw[-1] if raw else ""
        if isinstance(raw, bytes):
            raw = raw.decode("utf-8", "replace")
        flat[key] = str(raw).strip()

    for key in flat:
        if key not in QUERY_KEYS:
            messages.append(f"unknown parameter {key!r} ignored "
                            f"(known: {', '.join(QUERY_KEYS)})")

    if "preset" in flat:
        name = flat["preset"]
        if name in PRESETS:
            p = PRESETS[name]
            values.update(psi=p.psi, tau0=p.tau0, mu=0.2, nu=0.3, tau=p.tau, log_psi=p.log_psi,
                          preset=name)
        else:
            messages.append(f"preset={name!r} is unknown (known: {', '.join(PRESETS)})")

    for key in ("psi", "tau0", "mu", "nu"):
        if key in flat:
            x, msg = _number(key, flat[key])
            if msg:
                messages.append(msg)
            else:
                values[key] = x
                values["preset"] = ""

    if "log_psi" in flat:
        raw = flat["log_psi"].lower()
        if raw in ("1", "true", "yes", "on"):
            values["log_psi"] = True
        elif raw in ("0", "false", "no", "off", ""):
            values["log_psi"] = False
        else:
            messages.append(f"log_psi={flat['log_psi']!r} must be 0 or 1")

    if "tau" in flat:
        x, msg = _number("tau", flat["tau"])
        tau0 = values.get("tau0", ExplorerState.param.tau0.default)
        if msg:
            messages.append(msg)
        elif not tau0 <= x <= math.pi - tau0:
            messages.append(f"tau={flat['tau']} is outside the contact "
                            f"[{tau0:.4g}, {math.pi - tau0:.4g}] (tau0 = {tau0:.4g})")
        else:
            values["tau"] = x
    elif "tau0" in values and "tau" not in values:
        values["tau"] = math.pi / 2  # inside every contact [tau0, pi - tau0]
    return values, messages
