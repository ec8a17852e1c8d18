"""Fuzz of the public core API (hypothesis): on any input, every call either returns
finite numbers of the right shape or raises ValueError / TypeError naming the offending
argument. No other exception, no warning, no floating-point error (np.errstate raise;
only underflow is let through: a subnormal or zero result such as T = psi a^3 for
psi = 5e-324 is the correctly rounded value, and numpy ignores it by default)."""

import math
import os
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from decimal import Decimal
from fractions import Fraction
from functools import partial

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from core import Contact, impulse_ratio

#: examples per random test; FUZZ_EXAMPLES=20000 for a long run
FUZZ = settings(max_examples=int(os.environ.get("FUZZ_EXAMPLES", "250")), deadline=None)

SPECIAL: list[object] = [
    0, 1, -1, 0.0, -0.0, 0.5, 1.0, 2.0, 5e-324, -5e-324, 2.2250738585072014e-308,
    1e-300, 1e-12, 1e12, 1e300, 1e308, -1e308, 1.7976931348623157e308, math.nan, -math.nan,
    math.inf, -math.inf, 10**400, -(10**400), 2**63, 2**64, -(2**63) - 1, 10**12 + 1,
    True, False, "1", "abc", "", b"1", b"", bytearray(b"1"), 1j, 1 + 0j, None, [], (),
    {}, object(), Fraction(1, 3), Fraction(10**400, 3), Decimal("0.5"), Decimal("nan"),
    np.bool_(True), np.bytes_(b"1"), np.str_("1"), np.longdouble("1e400"),
    np.longdouble("-1e-400"), np.float16(65504), np.float32(3.4e38), np.float64(math.nan),
    np.int64(-1), np.uint64(2**64 - 1), np.int8(-128), np.complex64(1),
    np.datetime64(1, "s"), np.timedelta64(1, "s"), np.array(0.5), np.array([np.nan]),
    np.array([np.longdouble("1e400")]), np.array([1, 2], dtype=object),
]  # (not np.ma.masked: numpy itself warns when it turns a masked element into nan)

_shapes = hnp.array_shapes(min_dims=0, max_dims=2, min_side=0, max_side=3)
_dtypes = st.one_of(hnp.scalar_dtypes(), hnp.byte_string_dtypes(max_len=3),
                    hnp.unicode_string_dtypes(max_len=3),
                    st.just(np.dtype(np.longdouble)))
numpy_scalars = hnp.scalar_dtypes().flatmap(hnp.from_dtype)
scalars = st.one_of(
    st.sampled_from(SPECIAL), st.floats(), st.integers(), st.booleans(),
    st.text(max_size=3), st.binary(max_size=3), st.complex_numbers(), numpy_scalars,
)
arrays = st.one_of(
    hnp.arrays(_dtypes, _shapes),
    hnp.arrays(np.float64, _shapes, elements=st.floats(-10.0, 10.0)),
    hnp.arrays(np.dtype(object), _shapes, elements=scalars),
    st.lists(scalars, max_size=3),
)
#: anything that might be passed where times, radii or a psi array are expected
array_like = st.one_of(scalars, arrays, st.floats(-10.0, 10.0))

CONTACTS = [
    Contact(0.0, 0.5),
    Contact(0.4, math.pi / 6),
    Contact(1.0 + 2**-52, 0.0, mu=1e-3, nu=0.5),
    Contact(math.sqrt(2) + 1, math.pi / 6),
    Contact(1e6, -0.9, nu=-0.99),
    Contact(1e12, math.pi / 2 - 1e-8),
    Contact(5e-324, -math.pi / 2 + 1e-8, mu=5e-324),
]
TIME_METHODS = ("phase", "approach", "normal_force", "tangential_force", "contact_radius",
                "stick_radius", "centre_displacement", "centre_velocity",
                "drive_displacement", "drive_velocity")
TIMELINE = ("clock", "phase", "approach", "contact_radius", "stick_radius", "normal_force",
            "tangential_force", "centre_displacement", "centre_velocity")
SI_NAMES = ("R", "G", "nu", "mu", "H", "u0", "h", "omega")


@contextmanager
def strict() -> Iterator[None]:
    """Every warning an error, every floating-point event but underflow an error."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with np.errstate(all="raise", under="ignore"):
            yield


def attempt(f: Callable[[], object], names: tuple[str, ...]) -> object | None:
    """f(), or None if it refused its input with a ValueError or TypeError whose message
    names one of ``names`` (any other exception or any warning fails the test)."""
    try:
        with strict():
            return f()
    except (ValueError, TypeError) as err:
        assert any(name in str(err) for name in names), f"unclear message: {err!r}"
        return None


def assert_numbers(out: object, shape: tuple[int, ...], kind: str = "f") -> None:
    a = np.asarray(out)
    assert a.shape == shape
    assert a.dtype.kind == kind, a.dtype
    assert np.isfinite(a).all(), a


def check_contact(c: Contact) -> None:
    assert isinstance(c, Contact)
    with strict():
        for name in ("psi", "tau0", "mu", "nu", "F0", "impulse_ratio", "theta", "theta0",
                     "tau_end"):
            value = getattr(c, name)
            assert type(value) is float and math.isfinite(value), (name, value)
        assert math.isnan(c.tau1) if c.psi <= 1.0 else math.isfinite(c.tau1)
        grid = c.tau_grid(40)
    assert_numbers(grid, grid.shape)
    assert (np.diff(grid) >= 0).all()


def check_physical(c: Contact) -> None:
    check_contact(c)
    s = c.scales
    for name in ("T0", "P0", "a_star", "p_star", "traction_star", "alpha_star", "u0",
                 "v_star", "normal_impulse", "tangential_impulse", "period"):
        value = getattr(s, name)
        assert type(value) is float and math.isfinite(value) and value >= 0, (name, value)


PARAMS = {  # valid values of the dimensionless parameters
    "psi": st.floats(0.0, 1e12),
    "tau0": st.floats(-1.5707963, 1.5707963),
    "mu": st.floats(1e-3, 2.0),
    "nu": st.floats(-0.99, 0.5),
}
SI = {  # typical SI inputs (h in units of H, see ``call_physical``)
    "R": st.floats(1e-4, 1.0),
    "G": st.floats(1e6, 1e12),
    "nu": st.floats(-0.99, 0.5),
    "mu": st.floats(1e-3, 2.0),
    "H": st.floats(1e-9, 1e-3),
    "u0": st.floats(0.0, 1e-3),
    "h": st.one_of(st.floats(-1.0, 1.0), st.sampled_from([-1 + 2**-53, 1 - 2**-53])),
    "omega": st.floats(1.0, 1e7),
}
#: a value anywhere in the floats, by decade
anywhere = st.floats(-323.0, 308.0).map(lambda e: 10.0**e)


@st.composite
def mutated(draw: st.DrawFn, valid: dict[str, st.SearchStrategy],
            weird: st.SearchStrategy) -> dict[str, object]:
    """Valid arguments with one or two of them replaced by weird values."""
    args = {name: draw(s) for name, s in valid.items()}
    for name in draw(st.sets(st.sampled_from(sorted(valid)), min_size=1, max_size=2)):
        args[name] = draw(weird)
    return args


def call_physical(args: dict[str, object]) -> Contact:
    """from_physical, with a float h taken in units of a float H (else as drawn)."""
    h, H = args["h"], args["H"]
    if type(h) is float and type(H) is float and abs(h) <= 1.0:
        args = {**args, "h": h * H}
    return Contact.from_physical(**args)


# ---- every special value in every argument -------------------------------------------
def test_special_values_in_the_constructor() -> None:
    for name in PARAMS:
        for value in SPECIAL:
            args = {"psi": 2.0, "tau0": 0.5, "mu": 0.2, "nu": 0.3, name: value}
            c = attempt(lambda args=args: Contact(**args), (name,))
            if c is not None:
                check_contact(c)


def test_special_values_in_from_physical() -> None:
    base = {"R": 5e-3, "G": 79.3e9, "nu": 0.29, "mu": 0.2, "H": 1e-6, "u0": 0.8e-6,
            "h": 0.5e-6, "omega": 2.5e5}
    for name in base:
        for value in SPECIAL:
            c = attempt(lambda name=name, value=value: Contact.from_physical(
                **{**base, name: value}), (name,))
            if c is not None:
                check_physical(c)


def test_special_values_in_impulse_ratio() -> None:
    for name in PARAMS:
        for value in SPECIAL:
            args = {"psi": [0.5, 2.0], "tau0": 0.5, "mu": 0.2, "nu": 0.3, name: value}
            out = attempt(lambda args=args: impulse_ratio(**args), (name,))
            if out is not None:
                assert_numbers(out, np.shape(args["psi"]))


def test_special_values_in_the_functions_of_time() -> None:
    for c in CONTACTS:
        for value in SPECIAL:
            for method in TIME_METHODS:
                out = attempt(partial(getattr(c, method), value), ("tau",))
                if out is not None:
                    assert_numbers(out, np.shape(value), "i" if method == "phase" else "f")
            for method in ("traction", "pressure"):
                for r, tau in ((value, 1.0), (0.5, value)):
                    out = attempt(partial(getattr(c, method), r, tau), ("r", "tau"))
                    if out is not None:
                        assert_numbers(out, np.broadcast_shapes(np.shape(r), np.shape(tau)))


# ---- random ----------------------------------------------------------------------------
@FUZZ
@given(args=mutated(PARAMS, scalars | anywhere))
def test_constructor(args: dict[str, object]) -> None:
    c = attempt(lambda: Contact(**args), tuple(PARAMS))
    if c is not None:
        check_contact(c)


@FUZZ
@given(args=mutated(SI, scalars | anywhere | anywhere.map(lambda x: -x)))
def test_from_physical(args: dict[str, object]) -> None:
    c = attempt(lambda: call_physical(args), tuple(SI))
    if c is not None:
        check_physical(c)


@FUZZ
@given(args=mutated({**PARAMS, "psi": hnp.arrays(np.float64, _shapes,
                                                  elements=PARAMS["psi"])},
                    array_like | anywhere))
def test_impulse_ratio(args: dict[str, object]) -> None:
    out = attempt(lambda: impulse_ratio(**args), tuple(PARAMS))
    if out is None:
        return
    assert_numbers(out, np.broadcast_shapes(*(np.shape(args[name]) for name in PARAMS)))
    assert ((0.0 <= out) & (out <= 1.0 + 1e-15)).all()


@FUZZ
@given(c=st.sampled_from(CONTACTS), tau=array_like, method=st.sampled_from(TIME_METHODS))
def test_functions_of_time(c: Contact, tau: object, method: str) -> None:
    out = attempt(lambda: getattr(c, method)(tau), ("tau",))
    if out is not None:
        assert_numbers(out, np.shape(tau), "i" if method == "phase" else "f")


@FUZZ
@given(c=st.sampled_from(CONTACTS), tau=array_like)
def test_at(c: Contact, tau: object) -> None:
    line = attempt(lambda: c.at(tau), ("tau",))
    if line is None:
        return
    with strict():
        for name in TIMELINE:
            assert_numbers(getattr(line, name), np.shape(tau), "i" if name == "phase" else "f")


@FUZZ
@given(c=st.sampled_from(CONTACTS), r=array_like, tau=array_like,
       method=st.sampled_from(("traction", "pressure")))
def test_functions_of_radius_and_time(c: Contact, r: object, tau: object, method: str) -> None:
    out = attempt(lambda: getattr(c, method)(r, tau), ("r", "tau"))
    if out is not None:
        assert_numbers(out, np.broadcast_shapes(np.shape(r), np.shape(tau)))


@FUZZ
@given(c=st.sampled_from(CONTACTS), n=scalars | st.integers(-5, 2000))
def test_tau_grid(c: Contact, n: object) -> None:
    if (isinstance(n, int | np.integer) and not isinstance(n, bool | np.timedelta64)
            and 2000 < n <= 10**8):
        return  # valid but slow to build
    grid = attempt(lambda: c.tau_grid(n), ("n",))
    if grid is not None:
        assert_numbers(grid, grid.shape)
        assert grid[0] == c.tau0 and grid[-1] == c.tau_end
