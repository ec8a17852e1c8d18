"""CSV exports of what the explorer shows, each file readable on its own.

A file opens with a block of comment lines ('#'): what it holds and its source (Zharii
1996, with the equation of each column), the app's version, the parameters (for the
explorer's files the contact's psi, tau0, mu, nu, written with `repr`: they read back as
the very floats the explorer used), the SI inputs when the contact was defined by them,
and, for the traction profile, the time tau it is drawn at.  Parameters are written
`# name (unit) = value`.  Then one line of column names, each a quantity with its unit
(the dimensionless ones as the paper's ratios, T/T0, a/a*; SI ones as T (N), a (m)), and
the rows: 10 significant digits, a negative zero written 0.
`pandas.read_csv(f, comment="#")` reads it as it is.

The Motor scene's files (`app.motor`) are written by the same functions: `comments` for
the header block (the motor's inputs in SI), `csv_text` for the columns, `named` for the
file's name.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from importlib.metadata import PackageNotFoundError, version

import numpy as np

from app.contact.curves import ForceScene, MotionScene
from app.contact.radii import RadiiScene
from app.contact.traction import TractionScene
from core import Contact

SOURCE = ("O. Yu. Zharii, An exact solution of a time-dependent frictional contact problem"
          " for two elastic spheres, Int. J. Engng Sci. 34(5), 537-548 (1996)")

#: What each column holds, and where the paper gives it.
COLUMNS: dict[str, str] = {
    "tau (rad)": "time tau = omega t (Zharii 1996, eq 3)",
    "T/T0": "tangential force on the upper sphere, positive along the drive, in"
            " T0 (Zharii 1996, eqs 38, 39; T0 eq 37)",
    "mu P/T0": "Coulomb bound +mu P/T0 = P/P0 = (sin tau - sin tau0)^(3/2)"
               " (Zharii 1996, eq 9)",
    "-mu P/T0": "Coulomb bound -mu P/T0 (Zharii 1996, eq 9)",
    "alpha/(H-h)": "approach of the sphere centres (Zharii 1996, eq 8)",
    "a/a*": "contact radius, a* = sqrt(R (H - h) / 2) (Zharii 1996, eqs 7, 8)",
    "b/a*": "stick radius: a in full stick, 0 in slip (Zharii 1996, eqs 30, 36)",
    "v2/(omega u0)": "velocity of the contact centre of the upper sphere"
                     " (Zharii 1996, eq 42)",
    "u2/u0": "displacement of the contact centre of the upper sphere (Zharii 1996, eq 43)",
    "(du_x0/dt)/(omega u0)": "velocity of the drive, cos tau (Zharii 1996, eq 3)",
    "u_x0/u0": "displacement of the drive, sin tau (Zharii 1996, eq 3)",
    "t (s)": "time t = tau / omega",
    "T (N)": "tangential force T (Zharii 1996, eqs 37-39)",
    "mu P (N)": "Coulomb bound mu P (Zharii 1996, eq 9)",
    "alpha (m)": "approach of the sphere centres (Zharii 1996, eq 8)",
    "a (m)": "contact radius (Zharii 1996, eqs 7, 8)",
    "b (m)": "stick radius (Zharii 1996, eqs 30, 36)",
    "v2 (m/s)": "velocity of the contact centre of the upper sphere (Zharii 1996, eq 42)",
    "u2 (m)": "displacement of the contact centre of the upper sphere (Zharii 1996, eq 43)",
    "r/a*": "position along x through the contact centre (signed radius r)",
    "tau_u/(mu p*)": "tangential traction on the upper sphere, p* = 4 G a* / ((1 - nu) pi R)"
                     " (Zharii 1996, eqs 18, 24, 33, 36)",
    "p/p*": "contact pressure; also the Coulomb bound mu p in units of mu p*"
            " (Zharii 1996, eq 6)",
    "stick": "1 in the stick disc |r| <= b, 0 in slip and outside contact"
             " (Zharii 1996, eqs 30, 36)",
    "r (m)": "position along x through the contact centre",
    "tau_u (Pa)": "tangential traction on the upper sphere (Zharii 1996, eqs 18, 24, 33, 36)",
    "p (Pa)": "contact pressure (Zharii 1996, eq 6)",
    "psi": "drive ratio tan theta / tan theta0 (Zharii 1996, eq 23)",
    "T_imp/(mu P_imp)": "tangential impulse of one contact over mu times its normal"
                        " impulse, at the contact's tau0 (Zharii 1996, eq 41; T_imp eq 40,"
                        " P_imp eq 10)",
    # the Motor scene (docs/physics.md, section 10; x along the rod, x = 0 its centre)
    "x0 (m)": "contact point of the rotor on the rod (docs/physics.md 10.1)",
    "u0 (m)": "tangential drive amplitude at x0, signed: -A sin(pi x0 / (2 L))"
              " (Zharii 1996, eq 1; docs/physics.md 10.1)",
    "H (m)": "normal drive amplitude at x0: nu_rod pi delta A cos(pi x0 / (2 L)) / (4 L)"
             " (Zharii 1996, eq 2; docs/physics.md 10.1)",
    "Phi": "load factor 9 pi (1 - nu) N / (4 G R^(1/2) H^(3/2)), the F(tau0) the preload"
           " requires (Zharii 1996, eq 10); 8 or more: the contact never opens"
           " (docs/physics.md 10.2)",
    "opens": "1 where the contact opens once per period (Phi < 8), 0 where it never opens"
             " and the model does not apply (tau0 and the thrust are nan there)",
    "tau0 (rad)": "start of contact, fixed by the preload: F(tau0) = Phi"
                  " (Zharii 1996, eqs 10, 11; docs/physics.md 10.2)",
    "F_x/(mu N)": "stall thrust (rotor held) over mu N, signed: + along +x on the rotor's"
                  " bottom surface; T_imp/(mu P_imp) (Zharii 1996, eq 41) times sign u0"
                  " (docs/physics.md 10.3)",
    "F_x (N)": "stall thrust on the held rotor, signed: + along +x (docs/physics.md 10.3)",
    "V/(omega u0)": "rotor surface speed V over the rod's peak surface speed omega |u0(x0)|"
                    " (docs/physics.md 10.4)",
    "F/(mu N)": "mean thrust on the moving rotor along the drive over mu N:"
                " r = T_imp/(mu P_imp), eq 41 at V = 0 (docs/physics.md 10.4)",
    "eta": "efficiency P_out/P_in; nan beyond the no-load speed, where F < 0"
           " (docs/physics.md 10.4)",
    "P_out/(mu N omega u0)": "output power V F over mu N omega |u0| (docs/physics.md 10.4)",
    "P_in/(mu N omega u0)": "power the rod delivers through the contact over"
                            " mu N omega |u0| (docs/physics.md 10.4)",
    "P_loss/(mu N omega u0)": "power dissipated by slip over mu N omega |u0|"
                              " (docs/physics.md 10.4)",
    "V (m/s)": "rotor surface speed, along the drive (docs/physics.md 10.4)",
    "F (N)": "mean thrust on the moving rotor, along the drive (docs/physics.md 10.4)",
    "P_out (W)": "output power V F (docs/physics.md 10.4)",
    "P_in (W)": "power the rod delivers through the contact (docs/physics.md 10.4)",
    "P_loss (W)": "power dissipated by slip (docs/physics.md 10.4)",
}

#: What each file holds (its first comment line).
TITLES = {
    "curves": "the curves over one contact, on the tau grid of the T(tau) plot"
              " (Figs. 4b, 7, 9)",
    "traction": "the traction profile across the contact at one time tau (Fig. 6)",
    "impulse": "the impulse ratio against psi at the contact's tau0 (Fig. 8)",
    "motor_thrust": "the motor of Fig. 1 (docs/physics.md section 10, an extension of the"
                    " paper): the drive, tau0 and the stall thrust along the rod, on the"
                    " points of its plot",
    "motor_speed": "the motor of Fig. 1 (docs/physics.md section 10, an extension of the"
                   " paper): thrust, efficiency and powers against the rotor's speed at"
                   " the contact point x0 (moving-rotor MDR of core.motor)",
}

#: The contact's parameters and the SI inputs, with their units ('' dimensionless).
PARAMETERS = (("psi", ""), ("tau0", "rad"), ("mu", ""), ("nu", ""))
SI_INPUTS = (("R", "m"), ("G", "Pa"), ("H", "m"), ("u0", "m"), ("h", "m"),
             ("omega", "rad/s"))


def app_version() -> str:
    """The installed version of the zharii-contact package, or 'unknown'."""
    try:
        return version("zharii-contact")
    except PackageNotFoundError:
        return "unknown"


def curves_table(force: ForceScene, radii: RadiiScene, motion: MotionScene,
                 c: Contact) -> dict[str, np.ndarray]:
    """T/T0 and +-mu P/T0, the approach, a, b and the centre's motion on the tau grid
    (rad) of the T(tau) plot, the contact's, plus the same in SI units (t (s), T (N), ...)
    when `c` has SI scales.  A scene plotted at further times too (the motion, before and
    after the contact and beside its jumps) gives its rows at that grid."""
    table = force.table()
    tau = table["tau (rad)"]
    for scene in (radii, motion):
        extra = scene.table()
        times = extra.pop("tau (rad)")
        rows = np.isin(times, tau)
        if not np.array_equal(times[rows], tau):
            raise ValueError(f"the {scene.name} scene lacks times of the T(tau) grid")
        table.update({name: values[rows] for name, values in extra.items()})
    sc = c.scales
    if sc is not None:
        table.update({
            "t (s)": table["tau (rad)"] / sc.inputs.omega,
            "T (N)": table["T/T0"] * sc.T0, "mu P (N)": table["mu P/T0"] * sc.T0,
            "alpha (m)": table["alpha/(H-h)"] * sc.alpha_star,
            "a (m)": table["a/a*"] * sc.a_star, "b (m)": table["b/a*"] * sc.a_star,
            "v2 (m/s)": table["v2/(omega u0)"] * sc.v_star,
            "u2 (m)": table["u2/u0"] * sc.u0})
    return table


def traction_table(traction: TractionScene, c: Contact, tau: float) -> dict[str, np.ndarray]:
    """The traction profile of `c` at time tau (rad): r/a*, tau_u/(mu p*), p/p*, stick, plus
    r (m), tau_u (Pa) and p (Pa) when `c` has SI scales."""
    table = traction.table(c, tau)
    sc = c.scales
    if sc is not None:
        table.update({"r (m)": table["r/a*"] * sc.a_star,
                      "tau_u (Pa)": table["tau_u/(mu p*)"] * sc.traction_star,
                      "p (Pa)": table["p/p*"] * sc.p_star})
    return table


#: A line of a header block: a parameter (name, unit ('' if none), value) or a text.
Line = tuple[str, str, float] | str


def comments(key: str, lines: Sequence[Line] = ()) -> list[str]:
    """The comment lines of file `key` (a `TITLES` key), without the leading '# ': what it
    holds, the source, the app's version, then `lines`: a parameter written
    'name (unit) = value' (`repr`: it reads back as the same float), a text as it is."""
    out = [f"Zharii 1996 explorer: {TITLES[key]}",
           f"source: {SOURCE}",
           f"app: zharii-contact {app_version()}"]
    out += [line if isinstance(line, str) else _parameter(*line) for line in lines]
    return out


def header(key: str, c: Contact, tau: float | None = None) -> list[str]:
    """The comment lines of file `key` ('curves', 'traction', 'impulse') for contact `c`
    and, for a traction profile, its time tau (rad); without the leading '# '."""
    lines: list[Line] = [(name, unit, getattr(c, name)) for name, unit in PARAMETERS]
    if c.scales is not None:
        lines.append("defined by SI inputs (psi from u0/H, eq 23; tau0 from h/H, eq 4):")
        inputs = c.scales.inputs
        lines += [(name, unit, getattr(inputs, name)) for name, unit in SI_INPUTS]
    if tau is not None:
        lines.append(("tau", "rad", tau))
    return comments(key, lines)


def _parameter(name: str, unit: str, value: float) -> str:
    """'name (unit) = value' with the shortest text that reads back as the same float."""
    return f"{name}{f' ({unit})' if unit else ''} = {float(value) + 0.0!r}"


def csv_text(table: dict[str, np.ndarray], comments: Sequence[str] = ()) -> str:
    """The table as CSV: the `comments` and a description of each column (`COLUMNS`) as
    lines starting '# ', a line of column names, then the rows with 10 significant digits
    (a negative zero is written 0)."""
    names = list(table)
    lines = [*comments, "columns:", *(f"  {n}: {COLUMNS[n]}" for n in names)]
    body = np.column_stack([np.asarray(table[n], float) for n in names]) + 0.0
    out = io.StringIO()
    out.writelines(f"# {line}\n" for line in lines)
    np.savetxt(out, body, delimiter=",", header=",".join(names), comments="", fmt="%.10g")
    return out.getvalue()


def file_name(key: str, c: Contact, tau: float | None = None) -> str:
    """The CSV file's name, after the parameters it holds (psi, tau0 and tau to 4
    significant digits, mu and nu to 6; the file's comment lines have them in full) and,
    for a traction profile, its time tau (rad)."""
    parts = [("psi", c.psi, ".4g"), ("tau0", c.tau0, ".4g"), ("mu", c.mu, "g"),
             ("nu", c.nu, "g")]
    if tau is not None:
        parts.append(("tau", tau, ".4g"))
    return named(key, parts)


#: A part of a file's name: (name, value, format spec) or (name, value, spec, unit).
Part = tuple[str, float, str] | tuple[str, float, str, str]


def named(key: str, parts: Sequence[Part]) -> str:
    """'zharii_{key}' and each part as name, value (formatted by its spec, a negative
    zero written 0) and unit, joined by '_', with '.csv': e.g. 'psi2.5', 'tau0_0.5236'
    (a '_' after a name ending in a digit), 'x0_-5mm'."""
    words = [f"zharii_{key}"]
    for name, value, spec, *unit in parts:
        sep = "_" if name[-1].isdigit() else ""
        words.append(f"{name}{sep}{_short(value, spec)}{''.join(unit)}")
    return "_".join(words) + ".csv"


def _short(x: float, spec: str) -> str:
    """x formatted with `spec`; a negative zero written 0."""
    return format(float(x) + 0.0, spec)
