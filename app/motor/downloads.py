"""The Motor card's CSV files in the explorer's style (`app.contact.export`): a header block with
the source, the app's version and the inputs in SI (the floats core computed with),
columns named with their units, file names carrying the inputs in display units.

'thrust': the rod on the points of the stall-thrust plot; 'speed': the thrust-speed
curve at x0 (its header block says why there are no rows where there is no curve).
"""

from __future__ import annotations

import numpy as np

from app.contact import export
from app.motor.data import KEY_DIGITS, AtX0, scales
from app.motor.fields import FIELDS, ROD_FIELDS, ROTOR_FIELDS, SI_UNITS
from app.motor.state import MotorState
from core.motor import Motor, MotorProfile

SPEED_NAMES = ("V/(omega u0)", "F/(mu N)", "eta", "P_out/(mu N omega u0)",
               "P_in/(mu N omega u0)", "P_loss/(mu N omega u0)", "V (m/s)", "F (N)",
               "P_out (W)", "P_in (W)", "P_loss (W)")


def thrust_table(p: MotorProfile) -> dict[str, np.ndarray]:
    """The rod on the points of `p`: x0, drive, psi, Phi, tau0, stall thrust."""
    return {"x0 (m)": p.x0, "u0 (m)": p.u0, "H (m)": p.H, "psi": p.psi,
            "Phi": p.load_factor, "opens": p.opens.astype(float), "tau0 (rad)": p.tau0,
            "F_x/(mu N)": p.thrust_ratio, "F_x (N)": p.stall_thrust}


def speed_table(motor: Motor, x0: float, at: AtX0 | None) -> dict[str, np.ndarray]:
    """The thrust-speed curve at x0, dimensionless then SI (no rows without a curve)."""
    if at is None or at.curve is None:
        return {name: np.empty(0) for name in SPEED_NAMES}
    speed, force, power = scales(motor, x0)
    c = at.curve.curve
    return dict(zip(SPEED_NAMES, (c.v, c.thrust_ratio, c.efficiency, c.output_power,
                                  c.input_power, c.friction_loss, c.v * speed,
                                  c.thrust_ratio * force, c.output_power * power,
                                  c.input_power * power, c.friction_loss * power),
                    strict=True))


def header(key: str, motor: Motor, x0: float, at: AtX0 | None) -> list[str]:
    """The comment lines of CSV `key`: the rod's and the rotor's inputs in SI, the rod's
    contact layer where it is not the rotor's, and for 'speed' x0 and the contact."""
    names = (*ROD_FIELDS, *ROTOR_FIELDS, *(("x0",) if key == "speed" else ()))
    lines: list[export.Line] = [
        "inputs in SI (the rod: L half-length, delta thickness, nu_rod Poisson ratio,"
        " A amplitude at x = L, f frequency; the rotor: R radius, G shear modulus,"
        " nu Poisson ratio, mu friction coefficient, N preload"
        f"{'; x0 the contact point' if key == 'speed' else ''}):"]
    lines += [(n, SI_UNITS[FIELDS[n].unit],
               x0 if n == "x0" else getattr(motor.rod if n in ROD_FIELDS else motor,
                                            FIELDS[n].core))
              for n in names]
    if motor.rod_G is not None or motor.rod_R is not None:
        lines.append("the rod's contact point (Goodman's equivalent pair; None: the "
                     "rotor's value):")
        lines += [(n, u, getattr(motor, n)) for n, u in
                  (("rod_G", "Pa"), ("rod_nu", ""), ("rod_R", "m"))
                  if getattr(motor, n) is not None]
    if key == "speed":
        if at is None or at.curve is None:
            p = motor.profile(x0)
            lines.append("no curve: " + ("the contact never opens at x0" if not p.opens
                                         else "no tangential drive at x0"))
        else:
            lines.append("the contact at x0 (the curve is computed at these values,"
                         f" rounded to {KEY_DIGITS} significant digits):")
            lines += [(n, u, v) for (n, u), v in zip(export.PARAMETERS, at.key, strict=True)]
    return export.comments(f"motor_{key}", lines)


def filename(key: str, state: MotorState) -> str:
    """The CSV's file name (`app.contact.export.named`): what it holds and the inputs in display
    units (to 6 significant digits), x0 for the curve at x0."""
    names = (*ROD_FIELDS, *ROTOR_FIELDS, *(("x0",) if key == "speed" else ()))
    return export.named(f"motor_{key}", [
        (n, getattr(state, n), "g", FIELDS[n].unit.replace("µ", "u")) for n in names])
