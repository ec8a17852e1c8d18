"""Fuzz of the public core.motor API (hypothesis), like tests/core/test_fuzz.py for core:
on any input every call returns finite numbers (nan only where a contact never opens) or
raises ValueError / TypeError naming the offending argument; never another exception, a
warning or a floating-point error. Also the bad inputs of issue 22, one by one."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from core.motor import (
    Motor,
    Rod,
    best_efficiency,
    full_slip_speed,
    moving_rotor,
    no_load_speed,
    operating_speed,
    thrust_speed_curve,
    wear_along_rod,
)
from tests.core.test_fuzz import SPECIAL, anywhere, attempt, strict

FUZZ = settings(max_examples=60, deadline=None)
ROD = {"half_length": 0.02, "thickness": 4e-3, "nu_rod": 0.3, "amplitude": 10e-6,
       "frequency": 40e3}
ROTOR = {"R": 5e-3, "G": 24e9, "nu": 0.31, "mu": 0.2, "preload": 0.05}
odd = st.one_of(st.sampled_from(SPECIAL), anywhere, anywhere.map(lambda x: -x),
                st.integers(-10, 80))


@pytest.mark.parametrize(("call", "name"), [
    (lambda: best_efficiency(2.414, 0.5236, steps=-3), "steps"),
    (lambda: no_load_speed(2.414, 0.5236, steps=0), "steps"),
    (lambda: no_load_speed(2.414, 0.5236, xtol=math.inf), "xtol"),
    (lambda: no_load_speed(2.414, 0.5236, springs=0), "springs"),
    (lambda: best_efficiency(2.414, 0.5236, springs=0), "springs"),
    (lambda: no_load_speed(2.414, 0.5236, steps=math.inf), "steps"),
    (lambda: no_load_speed(2.414, 0.5236, xtol=1j), "xtol"),
    (lambda: best_efficiency(2.414, 0.5236, springs=10**7), "springs"),
    (lambda: moving_rotor(2.414, 0.5236, 0.1, springs=10**6, steps=1000), "springs * steps"),
    (lambda: thrust_speed_curve(2.414, 0.5236, n=10**4, springs=2000, steps=600),
     "speeds x springs x steps"),
    (lambda: full_slip_speed(5e-324, 0.5), "psi"),
    (lambda: operating_speed(2.414, 0.5236, 1.5), "load_ratio"),
    (lambda: Rod(**{**ROD, "half_length": 5e-324}), "half_length"),
    (lambda: Rod(**{**ROD, "amplitude": 1e308}), "amplitude"),
    (lambda: Rod(**{**ROD, "thickness": 1e300}), "thickness"),
    (lambda: Motor(Rod(**ROD), **{**ROTOR, "preload": 5e-324}), "preload"),
    (lambda: Motor(Rod(**ROD), **{**ROTOR, "preload": 1e-300}), "preload"),
    (lambda: Motor(Rod(**{**ROD, "thickness": 100.0, "amplitude": 0.1,
                          "half_length": 1e-6}), **{**ROTOR, "preload": 1e-12}), "preload"),
])
def test_issue_22_bad_inputs_are_refused_by_name(call, name: str) -> None:
    with pytest.raises(ValueError) as err:
        call()
    assert str(err.value).startswith(name) or f" {name} " in str(err.value), err.value


def test_rod_at_the_ends_of_its_domain_is_finite() -> None:
    for L, d, A in [(1e-6, 1e-9, 1e-12), (1e2, 1e2, 1e-1), (1e-6, 1e2, 1e-1), (1e2, 1e-9, 1e-12)]:
        rod = Rod(half_length=L, thickness=d, nu_rod=0.5, amplitude=A, frequency=1e9)
        x = L * np.array([-1 + 1e-15, -0.5, 0.0, 0.5, 1 - 1e-15])
        with strict():
            assert np.isfinite(rod.u0(x)).all() and np.isfinite(rod.H(x)).all()


def check_motor(m: Motor) -> None:
    L = m.rod.half_length
    x = L * np.array([-(1 - 1e-9), -0.3, -1e-4, 0.0, 1e-3, 0.5, 1 - 1e-12])
    with strict():
        p = m.profile(x)
    assert np.isfinite(p.u0).all() and np.isfinite(p.H).all()
    ok = p.opens
    for name in ("tau0", "m0", "h", "impulse_ratio", "thrust_ratio", "stall_thrust"):
        value = getattr(p, name)
        assert np.isfinite(value[ok]).all() and np.isnan(value[~ok]).all(), name
    assert np.all(np.abs(p.tau0[ok]) < math.pi / 2)


@FUZZ
@given(**{k: odd for k in ("half_length", "thickness", "nu_rod", "amplitude", "frequency")})
def test_rod_and_motor_on_any_rod(**rod: object) -> None:
    r = attempt(lambda: Rod(**rod), tuple(rod))
    if r is not None:
        m = attempt(lambda: Motor(r, **ROTOR), ("preload",))
        if m is not None:
            check_motor(m)


@FUZZ
@given(R=odd, G=odd, nu=odd, mu=odd, preload=odd,
       rod_G=st.one_of(st.none(), odd), rod_nu=st.one_of(st.none(), odd),
       rod_R=st.one_of(st.none(), odd, st.just(math.inf)))
def test_motor_on_any_rotor(**kw: object) -> None:
    m = attempt(lambda: Motor(Rod(**ROD), **kw), tuple(kw))
    if m is not None:
        check_motor(m)
        w = attempt(lambda: wear_along_rod(m, [-0.01, 0.0, 0.01], 1e-6, 2e9), ("x0",))
        assert w is not None
        assert np.all(np.isfinite(w.volume_rate) | np.isnan(w.dissipated_energy))


@FUZZ
@given(psi=odd, tau0=odd, springs=odd, steps=odd, xtol=odd, n=odd)
def test_moving_rotor_functions_on_any_input(psi, tau0, springs, steps, xtol, n) -> None:
    small = dict(springs=springs, steps=steps)
    names = ("psi", "tau0", "springs", "steps", "xtol", "n")
    for f in (lambda: moving_rotor(psi, tau0, [0.0, 0.3], **small),
              lambda: thrust_speed_curve(psi, tau0, n, **small),
              lambda: full_slip_speed(psi, tau0),
              lambda: no_load_speed(psi, tau0, xtol=xtol, **small)):
        out = attempt(f, names)
        if out is None:
            continue
        values = [out] if isinstance(out, float) else [out.thrust_ratio, out.input_power,
                                                       out.friction_loss]
        for v in values:
            assert np.isfinite(v).all(), (f, v)
