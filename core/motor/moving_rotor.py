"""A rotor moving at a steady surface speed: thrust, powers, friction loss and efficiency
of one contact point of the motor (docs/physics.md, section 10.4; the paper's open problem).

The rotor's bottom surface moves at a steady speed V along the drive (V >= 0: with it;
v = V / (omega u0) is the speed over the rod's peak surface speed). During a contact the
tangential drive relative to the rotor is

    u_x0(tau) = u0 sin tau - (V / omega)(tau - tau0),       tau0 < tau < pi - tau0

while the normal problem (eqs 3-9) is unchanged, so each contact is still independent.
There is no closed form; the contact is solved by the method of dimensionality reduction
(``core.numerics.mdr.moving``, the same ``march`` kernel as for eq 3) on the time grid of
``core.numerics.loading.drive_grid``. The dimensionless results depend on psi, tau0 and
v only (mu and nu enter through psi, eq 23); mu and nu are accepted, and checked, for
symmetry with ``core.impulse_ratio``.

Per contact, with P_imp and T_imp the normal and tangential impulses and the powers as
means over one period, in units of mu N omega u0 (mu N = mu P_imp omega / (2 pi), the
mean Coulomb force; omega u0 the rod's peak surface speed):

    thrust ratio    r      = T_imp / (mu P_imp)                        (eq 41 at v = 0)
    output power    p_out  = v r                     (V T_imp per contact)
    input power     p_in   = int T d(u0 sin tau) / (mu P_imp omega u0)  (the rod's work)
    friction loss   p_loss = slip work of the springs (the dissipation), >= 0
    efficiency      eta    = p_out / p_in

The elastic tangential energy returns to zero when the contact opens, so
p_in = p_out + p_loss; the three are computed independently (T over the rod's drive,
T over the rotor's, and the springs' slip), and the residual of this balance measures
the discretisation error (``MovingRotor.energy_residual``).

    from core.motor import moving_rotor, thrust_speed_curve, no_load_speed
    res = moving_rotor(2.414, 0.5236, [0.0, 0.1, 0.2])   # r, powers, eta per speed
    curve = thrust_speed_curve(2.414, 0.5236)            # 40 speeds, 0 .. full counter-slip
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq, minimize_scalar

from core.frozen import freeze
from core.numerics import mdr
from core.numerics.loading import trapezoid
from core.numerics.result import check_resolution
from core.validation import (
    CALL_WORK_MAX,
    MDR_WORK_MAX,
    MOTOR_DOMAIN,
    PSI_MAX,
    Interval,
    check_param,
    shown,
)

#: Largest dimensionless speed v = V / (omega u0) accepted. Beyond full counter-slip
#: (``full_slip_speed``, at most 1 + 1 / psi) nothing changes but the scale.
V_MAX = 1e6
#: v: along the drive, from the held rotor (0) to V_MAX.
SPEED = Interval(0.0, V_MAX)
#: psi must be positive here: v = V / (omega u0) needs a tangential drive u0 > 0.
PSI = Interval(0.0, PSI_MAX, lo_open=True)

#: Springs of the MDR row (each half) and time steps per contact: the thrust-speed curve
#: is converged to 1e-4 in r with these (tests/core/test_moving_rotor.py measures it).
SPRINGS = 200
STEPS = 600


@dataclass(frozen=True)
class MovingRotor:
    """One contact point (psi, tau0) with the rotor moving at the speeds v (read-only
    arrays of v's shape; every quantity dimensionless).

    Attributes:
        psi, tau0: the contact (eq 23; rad).
        v: rotor surface speed V / (omega u0), >= 0 (along the drive).
        thrust_ratio: r = T_imp / (mu P_imp); the mean thrust is mu N r. r(v = 0) is
            eq 41; r = -1 from ``full_slip_speed`` on.
        output_power: v r, the rotor's mean mechanical power (V times the mean thrust)
            over mu N omega u0.
        input_power: the mean power the rod delivers through the contact,
            int T d(u0 sin tau) per contact, over mu N omega u0.
        friction_loss: the mean power dissipated by slip (the springs' slip work), over
            mu N omega u0; 0 for psi <= 1 at v = 0 (full stick).
        efficiency: output_power / input_power where the rotor delivers power (r > 0),
            evaluated as output_power / (output_power + friction_loss) (equal by the
            energy balance, and well conditioned where both vanish); at v = 0 its limit
            v -> 0+, 1 for psi <= 1 (full stick: the loss vanishes as v^2) and 0 for
            psi > 1; 0 where r = 0; nan beyond the no-load speed (r < 0: the rotor is
            braked, not driven, and has no efficiency).
        springs, steps: the MDR resolution used.
    """

    psi: float
    tau0: float
    v: NDArray[np.float64]
    thrust_ratio: NDArray[np.float64]
    output_power: NDArray[np.float64]
    input_power: NDArray[np.float64]
    friction_loss: NDArray[np.float64]
    efficiency: NDArray[np.float64]
    springs: int
    steps: int

    def __post_init__(self) -> None:
        freeze(self, arrays_only=True)

    @property
    def energy_residual(self) -> NDArray[np.float64]:
        """input_power - output_power - friction_loss: zero for the exact solution (the
        elastic energy returns to zero each contact); the discretisation error of the
        energy balance."""
        return self.input_power - self.output_power - self.friction_loss


# ---- checks --------------------------------------------------------------------------
def _check_speeds(v: ArrayLike) -> NDArray[np.float64]:
    """v as a float array with every element in SPEED; ValueError naming the first bad
    element, its value and the allowed range."""
    if isinstance(v, str | bytes):
        raise ValueError(f"v must be real numbers in {SPEED.describe()}, got {shown(v)}")
    try:
        raw = np.asarray(v)
    except (ValueError, TypeError) as err:
        raise ValueError(f"v must be real numbers in {SPEED.describe()}: {err}") from err
    if raw.dtype.kind not in "iuf" or raw.size == 0:
        what = f"dtype {raw.dtype}" if raw.size else "no value"
        raise ValueError(f"v must be real numbers in {SPEED.describe()}, got {what}")
    arr = raw.astype(np.float64)
    bad = ~((arr >= 0.0) & (arr <= V_MAX))  # also nan
    if bad.any():
        first = np.unravel_index(np.flatnonzero(bad)[0], arr.shape)
        label = "v" if arr.ndim == 0 else f"v[{', '.join(str(int(i)) for i in first)}]"
        SPEED.check(label, arr[first])  # raises, naming the value and the range
    return arr


def _check_contact(psi: object, tau0: object, mu: object, nu: object) -> tuple[float, float]:
    """(psi, tau0) checked: psi in (0, 1e12] and at least MOTOR_DOMAIN["psi_moving"]
    (1e-5: the full-slip speed must lie in v's range), tau0, mu, nu in core's domain."""
    psi_ = PSI.check("psi", psi)
    low = MOTOR_DOMAIN["psi_moving"]
    if not low.contains(psi_):
        raise ValueError(f"psi = {shown(psi_)} is outside the moving rotor's range "
                         f"{low.describe()}: its full-slip speed (1 + 1/psi) cos tau0 would "
                         f"exceed the largest speed v = {V_MAX:g}")
    tau0_ = check_param("tau0", tau0)
    check_param("mu", mu)
    check_param("nu", nu)
    return psi_, tau0_


def _count(name: str, value: object) -> int:
    """An integer in its MOTOR_DOMAIN row (springs, steps, n); ValueError naming it."""
    row = MOTOR_DOMAIN[name]
    return check_resolution(value, minimum=int(row.lo), maximum=int(row.hi), name=name)


def _resolution(springs: object, steps: object, calls: int = 1) -> tuple[int, int]:
    """(springs, steps) checked against MOTOR_DOMAIN, with springs * steps <= MDR_WORK_MAX
    and calls * springs * steps <= CALL_WORK_MAX (calls: contacts solved by one call)."""
    n, m = _count("springs", springs), _count("steps", steps)
    check_resolution(n * m, maximum=MDR_WORK_MAX, name="springs * steps")
    if calls * n * m > CALL_WORK_MAX:
        raise ValueError(f"speeds x springs x steps = {calls} x {n} x {m} is beyond the work "
                         f"of one call, {CALL_WORK_MAX:.0e}: fewer speeds or a coarser MDR")
    return n, m


def _xtol(value: object) -> float:
    """xtol in MOTOR_DOMAIN["xtol"]; ValueError naming it."""
    return MOTOR_DOMAIN["xtol"].check("xtol", value)


# ---- one contact ---------------------------------------------------------------------
def _one(psi: float, tau0: float, v: float, springs: int, steps: int
         ) -> tuple[float, float, float]:
    """(r, p_in, p_loss) of one contact at speed v by the MDR."""
    tau, T, P, S = mdr.moving(psi, tau0, v, springs, steps)
    impulse = trapezoid(P, tau)  # mu P_imp omega / T0
    mean_T = 0.5 * (T[1:] + T[:-1])
    work_in = float(np.dot(mean_T, np.diff(np.sin(tau))))  # int T d(sin tau), T0 u0
    return trapezoid(T, tau) / impulse, work_in / impulse, float(S.sum()) / impulse


def full_slip_speed(psi: float, tau0: float) -> float:
    """v above which the contact slides backwards at every point from the moment it
    touches: (1 + 1 / psi) cos(max(tau0, 0)) (docs/physics.md, section 10.4). There
    r = -1, p_in = 0, p_loss = v exactly. psi in [1e-5, 1e12] (so that the result is at
    most 1e5 + 1, inside v's range)."""
    psi, tau0 = _check_contact(psi, tau0, 0.2, 0.3)
    return (1.0 + 1.0 / psi) * math.cos(max(tau0, 0.0))


def moving_rotor(psi: float, tau0: float, v: ArrayLike, mu: float = 0.2, nu: float = 0.3,
                 *, springs: int = SPRINGS, steps: int = STEPS) -> MovingRotor:
    """Thrust ratio, powers, friction loss and efficiency of the contact (psi, tau0) with
    the rotor's surface moving at v = V / (omega u0) (scalar or array, each in
    [0, 1e6]; ``MovingRotor``). MDR with ``springs`` springs and about ``steps`` time
    steps per contact (the defaults converge r to 1e-4).

    Validated (ValueError naming the parameter, its value and the allowed range): psi in
    [1e-5, 1e12], tau0 in (-pi/2, pi/2), mu and nu in core's domain, every v, springs and
    steps (integers in [2, 1e6] and [4, 1e7], springs * steps <= 1e8, and speeds x
    springs x steps <= 1e9: ``core.validation.MOTOR_DOMAIN``).
    """
    psi, tau0 = _check_contact(psi, tau0, mu, nu)
    speeds = _check_speeds(v)
    n, m = _resolution(springs, steps, speeds.size)
    flat = speeds.reshape(-1)
    out = np.array([_one(psi, tau0, float(s), n, m) for s in flat]).reshape(-1, 3)
    r, p_in, loss = (out[:, i].reshape(speeds.shape) for i in range(3))
    p_out = speeds * r
    return MovingRotor(psi=psi, tau0=tau0, v=speeds, thrust_ratio=r, output_power=p_out,
                       input_power=p_in, friction_loss=loss,
                       efficiency=_efficiency(psi, speeds, p_out, loss), springs=n, steps=m)


def _efficiency(psi: float, v: NDArray[np.float64], p_out: NDArray[np.float64],
                loss: NDArray[np.float64]) -> NDArray[np.float64]:
    """eta = p_out / p_in, evaluated as p_out / (p_out + p_loss) (the energy balance),
    which stays well conditioned where both powers vanish; at v = 0 its limit v -> 0+:
    1 for psi <= 1 (full stick: the loss vanishes as v^2), 0 above (the loss of the held
    rotor is finite); 0 where r = 0 and nan where r < 0 (no power delivered)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        eta = np.where(p_out > 0.0, p_out / (p_out + loss), np.where(p_out == 0.0, 0.0, np.nan))
    return np.where(v == 0.0, 1.0 if psi <= 1.0 else 0.0, eta)


def thrust_speed_curve(psi: float, tau0: float, n: int = 40, v_max: float | None = None,
                       mu: float = 0.2, nu: float = 0.3, *, springs: int = SPRINGS,
                       steps: int = STEPS) -> MovingRotor:
    """``moving_rotor`` at n equally spaced speeds from 0 (stall) to v_max; v_max
    defaults to ``full_slip_speed`` (r = -1 there and beyond), so the curve passes the
    no-load speed (r = 0) and ends at full counter-slip."""
    psi, tau0 = _check_contact(psi, tau0, mu, nu)
    count = _count("n", n)
    _resolution(springs, steps, count)
    top = full_slip_speed(psi, tau0) if v_max is None else SPEED.check("v_max", v_max)
    return moving_rotor(psi, tau0, np.linspace(0.0, top, count), mu, nu,
                        springs=springs, steps=steps)


def no_load_speed(psi: float, tau0: float, mu: float = 0.2, nu: float = 0.3, *,
                  springs: int = SPRINGS, steps: int = STEPS, xtol: float = 1e-9) -> float:
    """The speed v0 at which the thrust vanishes, r(v0) = 0 (brentq on the MDR's r,
    bracketed by 0 and ``full_slip_speed``, where r = -1). Its error is that of r
    (1e-4 at the defaults) over the slope |dr/dv| there. xtol in [1e-12, 1e-2]; springs
    and steps as for ``moving_rotor``."""
    psi, tau0 = _check_contact(psi, tau0, mu, nu)
    springs, steps = _resolution(springs, steps)
    xtol = _xtol(xtol)

    def r(s: float) -> float:
        return _one(psi, tau0, s, springs, steps)[0]

    return float(brentq(r, 0.0, full_slip_speed(psi, tau0), xtol=xtol))


@dataclass(frozen=True)
class BestEfficiency:
    """The point of best efficiency on a thrust-speed curve: speed v, efficiency eta
    and thrust ratio r there (dimensionless)."""

    v: float
    efficiency: float
    thrust_ratio: float


def best_efficiency(psi: float, tau0: float, mu: float = 0.2, nu: float = 0.3, *,
                    springs: int = SPRINGS, steps: int = STEPS, xtol: float = 1e-6
                    ) -> BestEfficiency:
    """The point of largest efficiency between stall and the no-load speed.

    psi > 1: bounded scalar maximisation of eta(v) (``MovingRotor.efficiency``) over
    (0, v0), v0 the no-load speed; the held rotor already slips (eta(0) = 0). psi <= 1:
    the contact sticks fully at v = 0 and the loss vanishes as v^2, so eta -> 1 as
    v -> 0+: the supremum is the stall limit, returned as v = 0, efficiency 1 and
    r(0) = psi (eq 41), a point of no power. xtol (in v) in [1e-12, 1e-2]; springs and
    steps as for ``moving_rotor``."""
    psi, tau0 = _check_contact(psi, tau0, mu, nu)
    springs, steps = _resolution(springs, steps)
    xtol = _xtol(xtol)
    if psi <= 1.0:
        return BestEfficiency(v=0.0, efficiency=1.0,
                              thrust_ratio=_one(psi, tau0, 0.0, springs, steps)[0])
    v0 = no_load_speed(psi, tau0, springs=springs, steps=steps)

    def minus_eta(s: float) -> float:
        r, _, loss = _one(psi, tau0, s, springs, steps)
        return float(-_efficiency(psi, np.array(s), np.array(s * r), np.array(loss)))

    best = minimize_scalar(minus_eta, bounds=(0.0, v0), method="bounded",
                           options={"xatol": xtol})
    s = float(best.x)
    return BestEfficiency(v=s, efficiency=-float(best.fun),
                          thrust_ratio=_one(psi, tau0, s, springs, steps)[0])
