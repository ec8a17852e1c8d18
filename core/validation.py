"""Validation at the boundary of the core API: one table, ``DOMAIN``, of the allowed range of
every parameter and input, and the two checks that use it (``check_param`` for one number,
``as_reals`` for arrays). The app derives its limits from the same table.

Messages are written to be shown to users as they are: they name the parameter, its value
and the allowed range, e.g. ``psi = -1 is outside the allowed range [0, 1e+12]`` or
``psi must be a real number in [0, 1e+12], got 'abc'``.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

PSI_MAX = 1e12
MU_MAX = 1e3
H_MAX = 1e3


def _as_float(value: object) -> float | None:
    """value as a float if it is a real number, else None. Booleans and numpy timedeltas
    (which numpy registers as integers) are not real numbers here; ints and fractions
    beyond the float range become +-inf."""
    if isinstance(value, bool | np.bool_ | np.timedelta64) or not isinstance(
        value, numbers.Real
    ):
        return None
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def shown(value: object) -> str:
    """A short text for value in a message: numbers with as few digits as identify them
    ("-1", "2e+12", "0.1", "-1.5707963267948966"), anything else by its repr, cut short."""
    v = _as_float(value)
    if v is not None and math.isfinite(v):
        short = f"{v:g}"
        return short if float(short) == v else repr(v)
    if isinstance(value, numbers.Integral) and v is not None:  # an int beyond the floats
        return f"{'-' if value < 0 else ''}~1e+{round(abs(value).bit_length() * 0.30103)}"
    text = str(value) if v is not None else repr(value)
    return text if len(text) <= 24 else text[:21] + "..."


@dataclass(frozen=True)
class Interval:
    """An interval of the real line. ``lo`` or ``hi`` None is an infinite end; infinities
    and nan are never inside (every allowed value is finite)."""

    lo: float | None
    hi: float | None
    lo_open: bool = False
    hi_open: bool = False

    def _holds(self, x: ArrayLike) -> np.bool_ | NDArray[np.bool_]:
        """Element-wise: x (floats) is finite and inside."""
        ok = np.isfinite(x)
        if self.lo is not None:
            ok &= np.greater(x, self.lo) if self.lo_open else np.greater_equal(x, self.lo)
        if self.hi is not None:
            ok &= np.less(x, self.hi) if self.hi_open else np.less_equal(x, self.hi)
        return ok

    @cached_property
    def closed_bounds(self) -> tuple[float, float]:
        """(lo, hi) such that a float x is inside exactly when lo <= x <= hi: open ends
        moved inward by one ulp, infinite ends as -inf, inf (then also check finiteness)."""
        lo = -math.inf if self.lo is None else (
            math.nextafter(self.lo, math.inf) if self.lo_open else self.lo)
        hi = math.inf if self.hi is None else (
            math.nextafter(self.hi, -math.inf) if self.hi_open else self.hi)
        return lo, hi

    def _holds_float(self, v: float) -> bool:
        """``_holds`` of one float, compared with ``closed_bounds`` in plain floats (the
        same answer without numpy's calls on one number)."""
        lo, hi = self.closed_bounds
        return math.isfinite(v) and lo <= v <= hi

    def contains(self, x: float) -> bool:
        """True when x is a real number (not a bool) inside the interval."""
        v = _as_float(x)
        return v is not None and self._holds_float(v)

    def describe(self) -> str:
        """Interval notation, e.g. '(-1, 0.5]', '(0, inf)', '(-inf, inf)'."""
        left = "(-inf" if self.lo is None else ("(" if self.lo_open else "[") + f"{self.lo:g}"
        right = "inf)" if self.hi is None else f"{self.hi:g}" + (")" if self.hi_open else "]")
        return f"{left}, {right}"

    def check(self, name: str, value: object) -> float:
        """value as a float if it is a real number inside the interval; ValueError naming
        the parameter, its value and the allowed range otherwise (strings, booleans, nan,
        inf and out-of-range numbers alike)."""
        v = _as_float(value)
        if v is not None and self._holds_float(v):
            return v
        where = "" if self.lo is None and self.hi is None else f" in {self.describe()}"
        if v is None:
            raise ValueError(f"{name} must be a real number{where}, got {shown(value)}")
        if isinstance(value, float | np.floating) and not np.isfinite(value):
            raise ValueError(f"{name} must be a finite number{where}, got {shown(value)}")
        raise ValueError(f"{name} = {shown(value)} is outside the allowed range"
                         f" {self.describe()}")


#: The allowed range of every parameter and input of the core API, the one table the
#: checks below and the app's limits are derived from.
#:
#: Dimensionless (``Contact``): psi, tau0 (rad), mu, nu. mu <= 1e3 is far above any real
#: friction coefficient (dry pairs are below ~10); the bound keeps T0 = mu P0 and the
#: traction scale mu p* finite for every SI input below. tau (rad) and r (units of a*):
#: any finite number. upper_share: the upper body's share of the relative tangential
#: displacement (``core.physical.upper_share``), 1/2 for the paper's identical spheres.
#:
#: SI (``Contact.from_physical``): R (m), G (Pa), H, u0, h (m), omega (rad/s). The ranges
#: span every realistic contact (nanometre to kilometre spheres, 1 Pa gels to beyond
#: diamond, 1e-9 to 1e12 rad/s) and are what keeps every derived scale finite: over the
#: whole box P0 < 2e19 N, T0 < 2e22 N, p* < 3e19 Pa, mu p* < 3e22 Pa, impulses < 2e29 N s,
#: period < 7e9 s (tests/core/test_physical.py checks every corner). Inputs also checked
#: together (``PhysicalInputs``): h must lie in (-H, H) (the "h" row is its widest
#: extent, H <= 1e3), and psi of u0 / H, mu and nu in [0, 1e12].
DOMAIN: dict[str, Interval] = {
    "psi": Interval(0.0, PSI_MAX),
    "tau0": Interval(-math.pi / 2, math.pi / 2, lo_open=True, hi_open=True),
    "mu": Interval(0.0, MU_MAX, lo_open=True),
    "nu": Interval(-1.0, 0.5, lo_open=True),
    "upper_share": Interval(0.0, 1.0, lo_open=True, hi_open=True),
    "tau": Interval(None, None),
    "r": Interval(None, None),
    "R": Interval(1e-9, 1e3),
    "G": Interval(1.0, 1e13),
    "H": Interval(1e-15, H_MAX),
    "u0": Interval(0.0, H_MAX),
    "h": Interval(-H_MAX, H_MAX, lo_open=True, hi_open=True),
    "omega": Interval(1e-9, 1e12),
}


#: Smallest load factor Phi = F(tau0) at the rod's centre (``core.motor.balance``): below
#: it the contact only grazes (tau0 within 1.2e-6 of pi/2 at Phi = 1e-24, and rounding to
#: pi/2 below ~1e-62, where the balance cannot be solved).
PHI_MIN = 1e-24
#: Fewest and most springs and time steps of one MDR contact, their largest product
#: (1e8 spring-steps), and the largest work of one call (speeds x springs x steps).
MDR_WORK_MAX = 10**8
CALL_WORK_MAX = 10**9

#: The allowed range of every parameter of ``core.motor`` (SI: m, Hz, N, kg, Pa), beside
#: ``DOMAIN`` (which holds R, G, nu, mu of the rotor and of the rod's contact point:
#: rod_R, rod_G, rod_nu take the rows R, G, nu, and rod_R also inf, a flat face). Lengths
#: from a micrometre rod to a 100 m one, amplitudes up to 10 cm, frequencies 1 mHz to
#: 1 GHz, preloads and loads up to 1 MN: every drive amplitude, psi and Phi is then finite
#: (tests/core/test_motor_fuzz.py). Rod and Motor also check one joint condition: Phi at
#: the rod's centre (its smallest value) is at least PHI_MIN, so that the preload balance
#: has a root inside core's tau0 range wherever the contact opens. The resolution rows
#: (springs, steps, n: integers) and xtol are those of the moving rotor
#: (``core.motor.moving_rotor``); v is its dimensionless speed V / (omega u0), and
#: psi_moving the smallest psi it takes (its full-slip speed (1 + 1/psi) cos tau0 must lie
#: in v's range). load_ratio is a load over the largest thrust mu N; wear_coefficient is
#: Archard's k (dimensionless) and hardness the softer body's (Pa).
MOTOR_DOMAIN: dict[str, Interval] = {
    "half_length": Interval(1e-6, 1e2),
    "thickness": Interval(1e-9, 1e2),
    "nu_rod": DOMAIN["nu"],
    "amplitude": Interval(1e-12, 1e-1),
    "frequency": Interval(1e-3, 1e9),
    "preload": Interval(1e-12, 1e6),
    "load_factor": Interval(PHI_MIN, None),
    "load": Interval(0.0, 1e6),
    "load_ratio": Interval(0.0, 1.0),
    "mass": Interval(1e-9, 1e6),
    "wear_coefficient": Interval(0.0, 1.0),
    "hardness": Interval(1e3, 1e12),
    "springs": Interval(2, 10**6),
    "steps": Interval(4, 10**7),
    "n": Interval(2, 10**4),
    "xtol": Interval(1e-12, 1e-2),
    "v": Interval(0.0, 1e6),
    "psi_moving": Interval(1e-5, PSI_MAX),
    "periods": Interval(1.0, 1e9),
}


def is_flat(value: object) -> bool:
    """value is the float +inf: a radius of a flat face (rod_R, R2)."""
    return isinstance(value, float | np.floating) and value == math.inf


def check_param(name: str, value: object) -> float:
    """value as a float if it is inside ``DOMAIN[name]``; ValueError (see
    ``Interval.check``) otherwise."""
    return DOMAIN[name].check(name, value)


def as_reals(x: ArrayLike, name: str) -> NDArray[np.float64]:
    """x as a float64 array (the same array if it is one) with every element inside
    ``DOMAIN[name]``: the boundary check of every function of time, radius or psi array.

    Accepts Python and numpy ints and floats, alone, in lists or in arrays of any integer
    or float dtype. TypeError naming the argument and its dtype for any other (bool,
    complex, str, bytes, object, datetime, ...); ValueError naming the first offending
    element for nan, inf or a value outside the domain. Cost on a valid float64 array:
    one min and one max (an interval holds every element when it holds the least and the
    greatest; nan propagates into both).
    """
    try:
        a = np.asarray(x)
    except (ValueError, TypeError) as err:  # e.g. ragged nested lists, undecodable bytes
        kind = TypeError if isinstance(err, TypeError) else ValueError
        raise kind(f"{name} must be an array of real numbers: {err}") from err
    if a.dtype.kind not in "iuf":
        raise TypeError(f"{name} must be real numbers (int or float), got dtype {a.dtype}")
    if a.dtype != np.float64:
        with np.errstate(over="ignore"):  # long double beyond float64: inf, refused below
            a = a.astype(np.float64)
    domain = DOMAIN[name]
    if a.ndim == 0:
        if not domain.contains(a[()]):
            domain.check(name, a[()])
        return a
    if a.size and not (domain.contains(a.min()) and domain.contains(a.max())):
        first = np.unravel_index(np.flatnonzero(~domain._holds(a))[0], a.shape)
        domain.check(f"{name}[{', '.join(str(int(i)) for i in first)}]", a[first])
    return a


def common_shape(**arrays: NDArray) -> tuple[int, ...]:
    """The shape the named arrays broadcast to; ValueError naming each with its shape if
    they do not broadcast together."""
    try:
        return np.broadcast_shapes(*(a.shape for a in arrays.values()))
    except ValueError:
        listed = ", ".join(f"{name} {a.shape}" for name, a in arrays.items())
        raise ValueError(f"the shapes of {listed} do not broadcast together") from None
