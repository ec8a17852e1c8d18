"""The explorer's state: the parameters a user controls, and nothing of the view.

`ExplorerState` holds the four dimensionless numbers of the problem (psi, tau0, mu,
nu), the current time tau, the animation settings and the optional physical inputs (SI
units: R, H, u0, h in m, G in Pa, omega in rad/s; `app.contact.physical_inputs` shows them in
mm, GPa, µm and kHz).  It turns them into a `core.Contact` (the only place the app
builds one) and knows how to read and write them as a URL query string.  All physics
lives in `core`.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import param

from core import DOMAIN, DRY_MU, MATERIALS, Contact
from core.validation import Interval

SQRT2_1 = math.sqrt(2.0) + 1.0  # psi of the paper's Figs. 4, 6 and 9 (tau1 = 3 pi / 4)
PI = math.pi
TAU0 = PI / 6  # all the paper's figures: H = 2 h


#: The app's own settings, beside core's parameters (whose ranges are core.DOMAIN):
#: the animation speed, in contacts per 4 s, the time shown, tau (rad), which lies in
#: one contact [tau0, pi - tau0] (core takes any real tau, modulo 2 pi), and the drive's
#: angle of incidence theta = arctan(u0 / H) in degrees (eq 23).
APP_DOMAIN: dict[str, Interval] = {"speed": Interval(0.05, 10.0),
                                   "tau": Interval(-math.pi / 2, 3 * math.pi / 2),
                                   "theta": Interval(0.0, 90.0)}


def domain(name: str) -> Interval:
    """The allowed range of parameter `name`: core's, or the app's own for settings."""
    return APP_DOMAIN[name] if name in APP_DOMAIN else DOMAIN[name]


def bounds(name: str) -> dict:
    """`param.Number` keyword arguments (bounds, inclusive_bounds) of `domain(name)`."""
    d = domain(name)
    return {"bounds": (d.lo, d.hi), "inclusive_bounds": (not d.lo_open, not d.hi_open)}


#: A multiple of pi as people type it: "pi/2", "3pi/4", "3*pi/4", "-π/6", "2 pi".
PI_TEXT = re.compile(r"^\s*([+-]?(?:\d+(?:\.\d*)?|\.\d+)?)\s*\*?\s*(?:pi|π)"
                     r"\s*(?:/\s*(\d+(?:\.\d*)?))?\s*$", re.IGNORECASE)


def number_text(raw: str) -> float | str:
    """The number a text stands for: a float ("0.5", "1e-3"), or a multiple of pi as
    people write it (`PI_TEXT`: "pi/2" is pi / 2, rounded once); else the text itself
    (for the domain's check to refuse, quoting it)."""
    try:
        return float(raw)
    except ValueError:
        pass
    m = PI_TEXT.match(raw)
    if m is None:
        return raw
    factor = m.group(1)
    value = (-1.0 if factor == "-" else 1.0 if factor in ("", "+") else float(factor)) * PI
    return value / float(m.group(2)) if m.group(2) else value


def parse_value(name: str, raw: str) -> float:
    """The number a typed or URL text `raw` gives parameter `name` (`number_text`: a
    number, or a multiple of pi), checked against its domain; ValueError with the
    message to show (the same for the URL and the boxes).  A text that reads as an
    infinite float ("1e400") is refused as the text typed, too large."""
    value = number_text(raw)
    if isinstance(value, float) and math.isinf(value) and raw.strip().lstrip("+-").lower() \
            not in ("inf", "infinity"):
        raise ValueError(f"{name} = {raw.strip()} is too large: it is outside the allowed "
                         f"range {domain(name).describe()}")
    return domain(name).check(name, value)


def parse_tau(raw: str, c: Contact, period: bool = False) -> float:
    """A time tau (rad) inside the contact of `c`, [tau0, pi - tau0], or with `period`
    inside the whole period [-pi/2, 3 pi/2] (the animation plays it); ValueError else,
    quoting that range."""
    lo, hi = (APP_DOMAIN["tau"].lo, APP_DOMAIN["tau"].hi) if period else (c.tau0, c.tau_end)
    where = (f"the period [{lo:.4g}, {hi:.4g}]" if period else
             f"the contact [{lo:.4g}, {hi:.4g}] (tau0 = {c.tau0:.4g})")
    try:
        tau = parse_value("tau", raw)
    except ValueError:
        if isinstance(number_text(raw), str):  # (not a number at all: say so)
            raise ValueError(f"tau must be a real number in {where}, got {raw!r}") from None
        tau = math.inf
    if not lo <= tau <= hi:
        raise ValueError(f"tau = {raw} is outside {where}")
    return tau


def drive_angle(psi: float, mu: float, nu: float) -> float:
    """The angle of incidence theta (degrees) of drive ratio psi with friction mu and
    Poisson ratio nu: arctan(psi tan theta0), tan theta0 = mu (2 - nu) / (2 (1 - nu))
    (eq 23; `core.Contact.theta`)."""
    return math.degrees(math.atan(psi * _tan_theta0(mu, nu)))


def drive_ratio(theta: float, mu: float, nu: float) -> float:
    """The drive ratio psi = tan theta / tan theta0 (eq 23) of the angle of incidence
    theta (degrees) with friction mu and Poisson ratio nu."""
    return math.tan(math.radians(theta)) / _tan_theta0(mu, nu)


def _tan_theta0(mu: float, nu: float) -> float:
    """tan theta0 = mu (2 - nu) / (2 (1 - nu)), as `core.Contact.theta0` takes it."""
    return math.tan(math.atan(mu * (2.0 - nu) / (2.0 * (1.0 - nu))))


#: The ways of setting the drive: by its ratio psi (mu and nu then leave the
#: dimensionless plots unchanged), or by its angle theta (psi then follows from theta,
#: mu and nu).
DRIVES = ("psi", "angle")

#: The physical inputs, in SI units: R, H, u0, h (m), G (Pa), omega (rad/s).
SI_KEYS = ("R", "G", "H", "u0", "h", "omega")

#: The state's parameters that define the contact (`ExplorerState.contact`).
CONTACT_INPUTS = ("psi", "tau0", "mu", "nu", "drive", "theta", "physical", *SI_KEYS)

#: Query parameters written to / read from the URL, in this order.  With physical = 1
#: the URL holds the physical inputs (SI units), and psi and tau0 follow from them.
QUERY_KEYS = ("psi", "tau0", "mu", "nu", "tau", "log_psi", "period", "preset", "drive",
              "theta", "physical", "material", *SI_KEYS)


def parse_flag(name: str, raw: str) -> bool:
    """The boolean a URL text `raw` gives flag `name` (1/0, true/false, yes/no, on/off,
    '' for false); ValueError with the message to show otherwise."""
    text = raw.lower()
    if text in ("1", "true", "yes", "on"):
        return True
    if text in ("0", "false", "no", "off", ""):
        return False
    raise ValueError(f"{name} = {raw!r} must be 0 or 1")


@dataclass(frozen=True)
class Preset:
    """Parameters that reproduce one figure of Zharii (1996)."""

    label: str
    psi: float
    tau0: float
    tau: float
    log_psi: bool = False
    family: tuple[float, ...] = ()  # further psi values overlaid on T(tau) (Fig. 7)
    tab: str = "force"  # the curve tab that shows its figure (a scene's name)
    mu: float = 0.2  # friction and Poisson ratio of every figure of the paper
    nu: float = 0.3

    def values(self, name: str) -> dict:
        """The state's parameters this preset (named `name`) sets (`apply_preset`)."""
        return dict(physical=False, psi=self.psi, tau0=self.tau0, mu=self.mu, nu=self.nu,
                    tau=self.tau, theta=drive_angle(self.psi, self.mu, self.nu),
                    log_psi=self.log_psi, preset=name)


PRESETS: dict[str, Preset] = {
    "fig4": Preset("Fig. 4: approach, a, b (ψ = 2.414)", SQRT2_1, TAU0, 3 * PI / 5,
                   tab="radii"),
    "fig6a": Preset("Fig. 6a: loading, τ = π/4", SQRT2_1, TAU0, PI / 4),
    "fig6b": Preset("Fig. 6b: loading, τ = π/3", SQRT2_1, TAU0, PI / 3),
    "fig6c": Preset("Fig. 6c: end of loading, τ = π/2", SQRT2_1, TAU0, PI / 2),
    "fig6d": Preset("Fig. 6d: partial stick, τ = 7π/12", SQRT2_1, TAU0, 7 * PI / 12),
    "fig6e": Preset("Fig. 6e: partial stick, τ = 17π/24", SQRT2_1, TAU0, 17 * PI / 24),
    # tau1 = 3 pi/4 (the first float of counter-slip: 3 pi/4 rounded down is still in
    # partial stick, by a stick disc of 1.5e-8 a*)
    "fig6f": Preset("Fig. 6f: counter-slip, τ = 3π/4", SQRT2_1, TAU0,
                    Contact(SQRT2_1, TAU0).tau1),
    "fig7a": Preset("Fig. 7a: T(τ), ψ = 0.4, 0.8, 1", 0.8, TAU0, PI / 2,
                    family=(0.4, 0.8, 1.0)),
    "fig7b": Preset("Fig. 7b: T(τ), ψ = 2.41 to 28.35", 6.46, TAU0, PI / 2,
                    family=(2.41, 6.46, 28.35)),
    "fig8": Preset("Fig. 8: impulse, peak at ψ = 1", 1.0, TAU0, PI / 2, tab="impulse"),
    "fig9": Preset("Fig. 9: centre motion (ψ = 2.414)", SQRT2_1, TAU0,
                   2 * PI / 3, tab="motion"),
}

DEFAULT_PRESET = "fig6e"


def material_values(name: str) -> dict:
    """The state's parameters material `name` (a key of `core.DRY_MU`) sets: its G
    (Pa), nu and mu, the physical inputs on (`ExplorerState.apply_material`)."""
    m = MATERIALS[name]
    return dict(material=name, G=m.G, nu=m.nu, mu=DRY_MU[name], physical=True)


class ExplorerState(param.Parameterized):
    """Everything the user sets; the view watches it and asks `core` for numbers."""

    psi = param.Number(default=SQRT2_1, **bounds("psi"), doc="psi = tan(theta) / tan(theta0)")
    tau0 = param.Number(default=math.pi / 6, **bounds("tau0"), doc="start of contact (rad)")
    mu = param.Number(default=0.2, **bounds("mu"), doc="friction coefficient")
    nu = param.Number(default=0.3, **bounds("nu"), doc="Poisson ratio")
    tau = param.Number(default=17 * math.pi / 24, **bounds("tau"),
                       doc="current time omega t (rad)")
    log_psi = param.Boolean(default=False, doc="log psi axis on the impulse curve")
    playing = param.Boolean(default=False, doc="animation running")
    period = param.Boolean(default=False, doc=(
        "the animation plays the whole period (-pi/2 to 3 pi/2: the spheres approach, "
        "touch, part and separate), tau may lie outside the contact; else the contact"))
    speed = param.Number(default=1.0, **bounds("speed"), doc="contacts per 4 s")
    preset = param.String(default=DEFAULT_PRESET,
                          doc="name of the last preset loaded, '' once edited")
    drive = param.Selector(default="psi", objects=list(DRIVES),
                           doc="'psi': the drive is set by psi; 'angle': by theta, psi "
                               "following from theta, mu and nu")
    theta = param.Number(default=drive_angle(SQRT2_1, 0.2, 0.3), **bounds("theta"),
                         doc="angle of incidence arctan(u0 / H) (degrees, eq 23); it "
                             "follows psi unless drive = 'angle'")

    physical = param.Boolean(default=False, doc="define the contact by SI inputs")
    material = param.Selector(default="custom", objects=["custom", *DRY_MU],
                              doc="the core.DRY_MU material G, nu and mu are those of, "
                                  "'custom' once one of them differs")
    R = param.Number(default=0.01, **bounds("R"), doc="sphere radius (m)")
    G = param.Number(default=79e9, **bounds("G"), doc="shear modulus (Pa)")
    H = param.Number(default=2e-6, **bounds("H"), doc="normal amplitude (m)")
    u0 = param.Number(default=1e-6, **bounds("u0"), doc="tangential amplitude (m)")
    h = param.Number(default=1e-6, **bounds("h"), doc="gap at t = 0 (m), |h| < H")
    omega = param.Number(default=2 * math.pi * 40e3, **bounds("omega"), doc="rad/s")

    current = param.ClassSelector(class_=Contact, doc=(
        "the core.Contact the inputs define, derived by the state itself "
        "(`_follow_inputs`); the last one core accepted when it refuses the inputs"))

    def __init__(self, **params) -> None:
        super().__init__(**params)
        self._last_contact: tuple[tuple, Contact] | None = None
        try:
            self.current = self.contact()
        except ValueError:  # (a scratch state of refused inputs: `current` stays None)
            pass

    def contact(self) -> Contact:
        """The `core.Contact` the current parameters define: from the SI inputs, or from
        the drive's angle theta (drive = 'angle'), or from psi; ValueError if core
        refuses it.  The same parameters give the same object (the last one is kept:
        a move asks for it more than once, and a Contact keeps what it computed)."""
        if self.physical:
            si = {k: getattr(self, k) for k in (*SI_KEYS, "nu", "mu")}
            key: tuple = (True, *si.values())
        else:
            key = (False, self.drive_psi(), self.tau0, self.mu, self.nu)
        last = self._last_contact
        if last is not None and last[0] == key:
            return last[1]
        c = Contact.from_physical(**si) if self.physical else Contact(
            key[1], self.tau0, mu=self.mu, nu=self.nu)
        self._last_contact = (key, c)
        return c

    def corrections(self, c: Contact) -> dict[str, float]:
        """What the state must change for its values to be those of contact `c` (its
        `contact()`), each that differs: with SI inputs psi and tau0 follow from them;
        with drive = 'angle' psi follows from theta, mu and nu, else theta (degrees)
        from psi, mu and nu (eq 23); tau is kept inside the contact (unless the whole
        period plays: `period`)."""
        fixes = {"psi": c.psi, "tau0": c.tau0} if self.physical else {"psi": c.psi}
        if self.physical or self.drive == "psi":
            fixes["theta"] = drive_angle(c.psi, self.mu, self.nu)
        if not self.period:
            fixes["tau"] = min(max(self.tau, c.tau0), c.tau_end)
        return {k: v for k, v in fixes.items() if getattr(self, k) != v}

    @param.depends(*CONTACT_INPUTS, "tau", "period", watch=True)
    def _follow_inputs(self) -> None:
        """The state derives what follows from its inputs after any change of them or of
        tau (a slider, a link, a preset, SI inputs, the Motor card's contact): its
        `corrections` and `current`, the contact, set in one batch of watchers (not with
        `param.update`, which reads every parameter of the state first).  `current`
        changes only when the contact does (its scales included).  A combination core
        refuses changes nothing: `current` keeps the last contact core accepted (the
        physical inputs' card says why, under its boxes)."""
        try:
            c = self.contact()
        except ValueError:
            return
        fixes = self.corrections(c)
        last = self.current
        with param.parameterized.batch_call_watchers(self):
            for k, v in fixes.items():
                setattr(self, k, v)
            if last is None or (c, c.scales) != (last, last.scales):
                self.current = c

    def set_input(self, name: str, value: object) -> None:
        """Set parameter `name` to `value` and, in the same batch of watchers, what
        follows from it (`_follow_inputs`: the corrections and `current`): each watcher
        is called once, on the corrected state (a slider's move: each scene draws once;
        `_follow_inputs` called again then finds nothing to change).  ValueError,
        nothing changed, if the parameter refuses `value`."""
        if getattr(self, name) == value:
            return  # (a widget following the state: its value is the state's)
        with param.parameterized.batch_call_watchers(self):
            setattr(self, name, value)
            self._follow_inputs()

    def drive_psi(self) -> float:
        """The psi of the drive: the state's own, or with drive = 'angle' the one theta,
        mu and nu give (eq 23); psi is kept when it already gives theta (switching to
        'angle' or loading a preset leaves the contact as it is)."""
        if self.drive == "angle" and drive_angle(self.psi, self.mu, self.nu) != self.theta:
            return drive_ratio(self.theta, self.mu, self.nu)
        return self.psi

    def matches(self, name: str) -> bool:
        """Whether the contact on screen is preset `name`'s (at any time tau: the preset
        is kept while its contact plays, steps or is scrubbed)."""
        p = PRESETS[name]
        return not self.physical and (self.psi, self.tau0, self.mu, self.nu) == (
            p.psi, p.tau0, p.mu, p.nu)

    @param.depends("psi", "tau0", "mu", "nu", "physical", watch=True)
    def _leave_preset(self) -> None:
        """`preset` names the figure whose contact is on screen: any other value of a
        contact input (a slider, a typed value, SI inputs) leaves it; a change of tau (the
        animation, a step, the scrubber) does not."""
        if self.preset and not self.matches(self.preset):
            self.preset = ""

    def apply_preset(self, name: str) -> None:
        """Load the parameters of preset `name` (a key of PRESETS); KeyError if unknown."""
        self.param.update(**PRESETS[name].values(name))

    def reset(self) -> None:
        """Back to the defaults (the default preset, speed 1, the default physical inputs
        and material, switched off), animation stopped."""
        self.playing = False
        self.speed = self.param.speed.default
        self.drive = self.param.drive.default
        self.apply_preset(DEFAULT_PRESET)  # (switches the physical inputs off first)
        self.param.update(**{k: self.param[k].default for k in (*SI_KEYS, "material")})

    def apply_material(self, name: str) -> None:
        """Copy G (Pa), nu (`core.MATERIALS[name]`) and mu (`core.DRY_MU[name]`) into the
        state and switch the physical inputs on (a material is a physical contact's; it
        never changes mu and nu of a dimensionless one unseen); KeyError if unknown."""
        self.param.update(**material_values(name))

    @param.depends("G", "nu", "mu", watch=True)
    def _leave_material(self) -> None:
        """`material` names the material whose G, nu and mu are the state's: another
        value of one of them (a slider, a typed value, a preset) leaves it."""
        m = material_values(self.material) if self.material in DRY_MU else None
        if m is not None and (self.G, self.nu, self.mu) != (m["G"], m["nu"], m["mu"]):
            self.material = "custom"

    def query(self) -> dict[str, str]:
        """The shareable part of the state as URL query values (SI units for the
        physical inputs; with them on, psi and tau0 follow from them and are left out)."""
        # repr: the shortest text that reads back as the same float (a link restores the
        # very state, the preset included)
        # with drive = angle both psi and theta: theta sets the drive, psi (which gives
        # theta) restores the very float
        angle = self.drive == "angle"
        keys = ("mu", "nu", "tau") if self.physical else (
            "psi", *(("theta",) if angle else ()), "tau0", "mu", "nu", "tau")
        q = {k: repr(float(getattr(self, k))) for k in keys}
        if self.log_psi:
            q["log_psi"] = "1"
        if self.period:
            q["period"] = "1"
        if self.preset:
            q["preset"] = self.preset
        if angle:
            q["drive"] = "angle"
        if self.physical:
            q["physical"] = "1"
            if self.material != "custom":
                q["material"] = self.material
            q.update({k: repr(float(getattr(self, k))) for k in SI_KEYS})
        return q
