"""The "Physical inputs" card: the SI inputs of `core.Contact.from_physical` in the units
people think in.

The state (`app.contact.state.ExplorerState`) keeps R, G, H, u0, h in SI units and the angular
frequency omega in rad/s; the boxes show and take R in mm, G in GPa, H, u0 and h in µm
and the frequency f = omega / (2 pi) in kHz.  `FIELDS` is the one table of the boxes:
unit and the advisory sensible range of each.  The pure functions below
convert between the two (`to_si`, `to_user`, `display`), check a typed value against
core's allowed range (`parse_entry`, the range from `core.DOMAIN` via
`app.contact.state.domain`, written in the box's unit) and word the advisory warning
(`warning`) and core's refusal of the inputs taken together (`refusal`).

A box is a text box and takes any number: a text that is not a number, or a value
outside core's range, is refused with that range in the box's unit under it and the box
shows the last good value again (the browser's own limits of a number box would put the
old value back without a word).  A value outside its
sensible range is used and a warning under the box says so.  What the core refuses of
the inputs together (e.g. |h| >= H) is shown under the boxes in core's words.

A material (G and nu of `core.MATERIALS`, mu of `core.DRY_MU`) sets G, nu and mu and
switches the physical inputs on: choosing one is asking for that physical contact, so it
never changes mu and nu of a dimensionless contact unseen.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from decimal import Decimal

import panel as pn
import param

import core
from app.contact.state import SI_KEYS, ExplorerState, domain
from app.kit.a11y import expandable_card
from app.kit.widgets import ERROR_STYLE, LabelledCheckbox, show_later, text_html, typed_value
from core import Interval

#: Style of an advisory warning under a box (dark amber on white: 8.5:1 contrast).
WARNING_STYLE = {"color": "#664d03", "font-size": "0.9em", "margin-top": "0"}

#: Style of the line under the material menu (10:1 on white).
NOTE_STYLE = {"color": "#444444", "font-size": "0.9em", "margin-top": "0"}

#: What the card says before core's refusal of the inputs together.
REFUSED = "Refused by core (in SI units: m, Pa, rad/s): "

#: Significant digits a box's value is read and shown to: every decimal of up to 15
#: digits is one float, so what a person types is kept as typed, and the float noise
#: of a unit conversion (2.3e-6 m / 1e-6 = 2.3000000000000003 µm) is dropped.
DIGITS = 15


@dataclass(frozen=True)
class Field:
    """One box of the card.

    `name`: the `ExplorerState` parameter it sets (SI units: m, Pa, rad/s); `symbol`,
    `unit` and `label` title the box, `symbol (unit): label`; one `unit` is
    `factor * 10**decade` SI units (mm: 1e-3 m; kHz of f: 2 pi 1e3 rad/s); `sensible`:
    the advisory range (lo, hi), in `unit`, outside which a warning shows.
    """

    name: str
    symbol: str
    label: str
    unit: str
    decade: int
    sensible: tuple[float, float]
    factor: float = 1.0

    @property
    def title(self) -> str:
        """The box's title, with its unit."""
        return f"{self.symbol} ({self.unit}): {self.label}"


#: The boxes of the card, in order: units and sensible ranges.
#:
#: The sensible ranges are advisory: they bound the contacts this model is usually
#: applied to (millimetre to metre spheres of gels to diamond, drive amplitudes up to a
#: millimetre, 1 Hz to 10 MHz), so a value outside them is most likely a slip of the
#: unit.  Such a value is still used, with a warning under its box; what the core
#: accepts is `core.DOMAIN`, far wider.
FIELDS: dict[str, Field] = {f.name: f for f in (
    Field("R", "R", "sphere radius", "mm", -3, (0.1, 1000.0)),
    Field("G", "G", "shear modulus", "GPa", 9, (0.1, 1000.0)),
    Field("H", "H", "normal amplitude", "µm", -6, (0.001, 1000.0)),
    Field("u0", "u₀", "tangential amplitude", "µm", -6, (0.0, 1000.0)),
    Field("h", "h", "gap at t = 0, < H (< 0: a preload)", "µm", -6, (-1000.0, 1000.0)),
    Field("omega", "f", "frequency, ω = 2πf", "kHz", 3, (0.001, 10000.0),
          factor=2 * math.pi),
)}
assert tuple(FIELDS) == SI_KEYS


def shift(value: float, decade: int) -> float:
    """`value * 10**decade`, the float nearest to the shortest decimal of `value` with its
    point moved: 2.1 µm is 2.1e-06 m, the float a person typing "2.1e-6" gets."""
    return float(Decimal(repr(float(value))).scaleb(decade))


def to_si(field: Field, value: float) -> float:
    """`value` in `field.unit` as the state's SI value (m, Pa or rad/s): the decimal
    point moved (`shift`), then times `field.factor` (2 pi for f), each one rounding."""
    return shift(value, field.decade) * field.factor


def to_user(field: Field, si: float) -> float:
    """The SI value `si` (m, Pa or rad/s) in `field.unit`; the inverse of `to_si` (exact
    for the units that are powers of ten)."""
    return shift(si / field.factor, -field.decade)


def rounded(value: float) -> float:
    """`value` to `DIGITS` significant digits (non-finite values as they are)."""
    return float(f"{value:.{DIGITS}g}") if math.isfinite(value) else value


def display(field: Field, si: float) -> float:
    """The number the box of `field` shows for the SI value `si`, in `field.unit`."""
    return rounded(to_user(field, si))


def box_text(field: Field, si: float) -> str:
    """The text the box of `field` shows for the SI value `si`: `display`'s number, in
    its shortest form ("5", "79.3", "-0.5", "2e-06")."""
    return f"{display(field, si):.{DIGITS}g}"


def limits(field: Field) -> Interval:
    """Core's allowed range of `field` (`core.DOMAIN` via `app.contact.state.domain`), in
    `field.unit`."""
    d = domain(field.name)
    lo = None if d.lo is None else display(field, d.lo)
    hi = None if d.hi is None else display(field, d.hi)
    return Interval(lo, hi, d.lo_open, d.hi_open)


def parse_entry(field: Field, value: object) -> float:
    """The SI value (m, Pa or rad/s) of `value` (a number, or the text typed) in
    `field.unit`; ValueError naming the box, the value and core's allowed range in
    `field.unit` if it is not a number or core refuses it."""
    if isinstance(value, str):
        try:
            value = float(value)
        except ValueError:
            pass  # refused below, with the text as typed
    if isinstance(value, float | int) and not isinstance(value, bool):
        value = rounded(float(value))
        si = to_si(field, value)
        if domain(field.name).contains(si):
            return si
    limits(field).check(f"{field.symbol} ({field.unit})", value)  # raises, in the unit
    return domain(field.name).check(field.name, to_si(field, value))  # an edge's rounding


def warning(field: Field, si: float) -> str:
    """The advisory warning for the SI value `si` of `field` outside its sensible range,
    '' inside it."""
    v, (lo, hi) = display(field, si), field.sensible
    if lo <= v <= hi:
        return ""
    side = "above" if v > hi else "below"
    return (f"{field.symbol} = {v:g} {field.unit} is {side} the sensible range {lo:g} … "
            f"{hi:g} {field.unit}: is the unit right? (a warning only: the value is used)")


def refusal(state: ExplorerState) -> str:
    """Why core refuses the state's SI inputs taken together (with its mu and nu), e.g.
    |h| >= H, in core's words after a line naming the SI units; '' when it accepts them."""
    try:
        core.PhysicalInputs(**{k: getattr(state, k) for k in (*SI_KEYS, "mu", "nu")})
    except ValueError as err:
        return f"{REFUSED}{err}"
    return ""


class PhysicalInputs(pn.viewable.Viewer):
    """The "Physical inputs" card of `state` (`__panel__`): the check box that defines
    the contact by these inputs, the material menu, one text box per `FIELDS` row with
    its message under it, and core's refusal of the inputs together under them.

    The boxes and the menu follow the state whichever side changes; `errors` holds, per
    field, why its last typed value was refused ('' if it was not).
    """

    errors = param.Dict(default={}, doc="field name -> why its last entry was refused")

    def __init__(self, state: ExplorerState) -> None:
        super().__init__()
        self.state = state
        self.physical_box = LabelledCheckbox.from_param(
            state.param.physical, label="Use physical inputs")
        self.material_select = pn.widgets.Select(
            label="Material", options=list(state.param.material.objects),
            value=state.material, sizing_mode="stretch_width")
        self.material_note = pn.pane.HTML(
            text_html("A material sets G, ν and μ and switches the physical inputs on."),
            styles=NOTE_STYLE, sizing_mode="stretch_width", margin=(0, 10))
        self.boxes: dict[str, pn.widgets.TextInput] = {}
        self.notes: dict[str, pn.pane.HTML] = {}
        for f in FIELDS.values():
            box = pn.widgets.TextInput(
                label=f.title, value=box_text(f, getattr(state, f.name)),
                sizing_mode="stretch_width", css_classes=[f"si-{f.name}"])
            box.param.watch(lambda e, f=f: self._on_entry(f, e.new), "value")
            self.boxes[f.name] = box
            self.notes[f.name] = pn.pane.HTML("", visible=False, sizing_mode="stretch_width",
                                              margin=(0, 10))
        self.refusal = pn.pane.HTML("", visible=False, styles=ERROR_STYLE,
                                    sizing_mode="stretch_width", margin=(0, 10))
        self.material_select.param.watch(self._on_material_select, "value")
        state.param.watch(self._on_material, "material")
        state.param.watch(self._on_state, [*SI_KEYS, "mu", "nu"])
        for f in FIELDS.values():
            self._show_note(f)
        self._show_refusal()
        self.card = expandable_card(
            self.physical_box, self.material_select, self.material_note,
            *(w for name in FIELDS for w in (self.boxes[name], self.notes[name])),
            self.refusal, title="Physical inputs", collapsed=not state.physical,
            sizing_mode="stretch_width")

    def __panel__(self) -> pn.Card:
        return self.card

    # ----------------------------------------------------------------- boxes

    def _on_entry(self, field: Field, text: str) -> None:
        """A text typed in the box of `field` (a number in `field.unit`)."""
        current, box = getattr(self.state, field.name), self.boxes[field.name]
        try:
            si = typed_value(box, text, box_text(field, current),
                             lambda t: parse_entry(field, t))
        except ValueError as err:  # (the box shows the last good value again)
            self.errors = {**self.errors, field.name: str(err)}
            self._show_note(field)
            return
        if si is None:
            return  # the box shows the state's value (set from here, or reverted)
        self.errors = {**self.errors, field.name: ""}
        if si == current:  # e.g. "2.50" for 2.5: the state does not change
            self._show_note(field)
            show_later(box, box_text(field, si))
            return
        setattr(self.state, field.name, si)  # `_on_state` shows it

    def _on_state(self, *events: param.parameterized.Event) -> None:
        for e in events:
            if e.name in FIELDS:
                field = FIELDS[e.name]
                if self.errors.get(e.name):  # a new value: the refused entry is past
                    self.errors = {**self.errors, e.name: ""}
                self._show_note(field)
                box, text = self.boxes[e.name], box_text(field, e.new)
                if box.value != text:
                    show_later(box, text)
        self._show_refusal()

    def _show_note(self, field: Field) -> None:
        """Under the box of `field`: why its last entry was refused, else the advisory
        warning of the state's value, else nothing."""
        error = self.errors.get(field.name, "")
        text = error or warning(field, getattr(self.state, field.name))
        self.notes[field.name].param.update(object=text_html(text), visible=bool(text),
                                           styles=ERROR_STYLE if error else WARNING_STYLE)

    def _show_refusal(self) -> None:
        text = refusal(self.state)
        if text_html(text) != self.refusal.object or self.refusal.visible != bool(text):
            self.refusal.param.update(object=text_html(text), visible=bool(text))

    # -------------------------------------------------------------- material

    def _on_material_select(self, event: param.parameterized.Event) -> None:
        if event.new == self.state.material:
            return
        if event.new == "custom":
            self.state.material = "custom"
        else:
            self.state.apply_material(event.new)

    def _on_material(self, event: param.parameterized.Event) -> None:
        self.material_select.value = event.new
