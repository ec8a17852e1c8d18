"""Bad input raises ValueError naming the parameter, its value and the allowed range."""

import math
import warnings

import numpy as np
import pytest

from core import DOMAIN, Contact, Interval, impulse_ratio
from core.validation import check_param

GOOD = {
    "R": 0.01,
    "G": 80e9,
    "nu": 0.3,
    "mu": 0.2,
    "H": 1e-6,
    "u0": 1e-6,
    "h": 5e-7,
    "omega": 2 * math.pi * 40e3,
}


@pytest.mark.parametrize(
    ("kwargs", "name", "shown"),
    [
        ({"psi": -1.0}, "psi", "[0, 1e+12]"),
        ({"psi": math.nan}, "psi", "nan"),
        ({"psi": math.inf}, "psi", "inf"),
        ({"psi": 2e12}, "psi", "psi = 2e+12 is outside the allowed range [0, 1e+12]"),
        ({"psi": -1}, "psi", "psi = -1 is outside the allowed range [0, 1e+12]"),
        ({"psi": 10**400}, "psi", "psi = ~1e+400 is outside"),
        ({"tau0": math.pi / 2}, "tau0", "(-1.5708, 1.5708)"),
        ({"tau0": -math.pi / 2}, "tau0", "-1.57"),
        ({"tau0": 3.0}, "tau0", "tau0 = 3 is outside"),
        ({"mu": 0.0}, "mu", "(0, 1000]"),
        ({"mu": 1e308}, "mu", "mu = 1e+308 is outside the allowed range (0, 1000]"),
        ({"mu": -0.1}, "mu", "-0.1"),
        ({"nu": 0.51}, "nu", "(-1, 0.5]"),
        ({"nu": -1.0}, "nu", "nu = -1 is outside"),
        ({"psi": "2"}, "psi", "psi must be a real number in [0, 1e+12], got '2'"),
        ({"psi": True}, "psi", "True"),
        ({"psi": np.timedelta64(1, "s")}, "psi", "must be a real number"),
        ({"nu": 1j}, "nu", "nu must be a real number in (-1, 0.5], got 1j"),
    ],
)
def test_contact_rejects_bad_parameters(kwargs: dict, name: str, shown: str) -> None:
    args = {"psi": 1.0, "tau0": 0.5, **kwargs}
    with pytest.raises(ValueError, match=name) as err:
        Contact(**args)
    assert shown in str(err.value)


def test_contact_accepts_the_domain_edges() -> None:
    for psi in (0.0, 1e12):
        for tau0 in (-math.pi / 2 + 1e-8, math.pi / 2 - 1e-8):
            c = Contact(psi, tau0, mu=1e-3, nu=0.5)
            assert np.isfinite(c.tangential_force(c.tau_grid(50))).all()
    assert Contact(np.float64(2.0), np.float32(0.5)).psi == 2.0


@pytest.mark.parametrize(
    ("bad", "name"),
    [
        ({"R": -1.0}, "R"),
        ({"G": 0.0}, "G"),
        ({"H": -1e-6}, "H"),
        ({"omega": 0.0}, "omega"),
        ({"h": 1e-6}, "h"),
        ({"h": 2e-6}, "h"),
        ({"h": -1e-6}, "h"),
        ({"u0": -1e-9}, "u0"),
        ({"nu": 0.7}, "nu"),
        ({"mu": 0.0}, "mu"),
        ({"R": math.nan}, "R"),
        ({"G": math.inf}, "G"),
        ({"u0": 1.0, "H": 1e-12, "h": 0.0}, "psi"),
        ({"omega": 5e-324}, "omega"),
        ({"mu": 1e308}, "mu"),
        ({"mu": 5e-324}, "psi"),
        ({"R": 1e300}, "R"),
        ({"H": 1e-300, "h": 0.0}, "H"),
        ({"G": 10**400}, "G"),
        ({"H": 2.0**-20, "h": math.nextafter(-(2.0**-20), 0.0)}, "h"),  # h / H rounds to -1
    ],
)
def test_from_physical_rejects_bad_inputs(bad: dict, name: str) -> None:
    with pytest.raises(ValueError, match=rf"\b{name}\b"):
        Contact.from_physical(**{**GOOD, **bad})


def test_impulse_ratio_validates_psi_and_tau0() -> None:
    with pytest.raises(ValueError, match=r"psi\[1\] = -2 is outside the allowed range"):
        impulse_ratio(np.array([1.0, -2.0]), 0.5)
    with pytest.raises(ValueError, match=r"psi\[0\] must be a finite number .*got nan"):
        impulse_ratio([np.nan], 0.5)
    with pytest.raises(ValueError, match=r"psi = 1e\+13 is outside"):
        impulse_ratio(1e13, 0.5)
    with pytest.raises(ValueError, match="tau0"):
        impulse_ratio([1.0], 2.0)
    for psi in (True, "1", [True], b"1", 1j, [1, None]):
        with pytest.raises(TypeError, match="psi must be real numbers"):
            impulse_ratio(psi, 0.5)


@pytest.mark.parametrize("n", [1, 0, -5, 2.5, "10", True, 10**9, np.timedelta64(5, "s")])
def test_tau_grid_rejects_bad_sizes(n: object) -> None:
    with pytest.raises(ValueError, match="n must be an integer"):
        Contact(2.0, 0.5).tau_grid(n)


def test_outside_contact_everything_is_zero_never_nan() -> None:
    c = Contact(2.414, math.pi / 6)
    tau = np.array([0.0, 0.3, 3.0, 4.0, 6.0, -1.0])
    assert (c.phase(tau) == 0).all()
    for f in (
        c.tangential_force,
        c.normal_force,
        c.contact_radius,
        c.stick_radius,
        c.approach,
        c.centre_displacement,
        c.centre_velocity,
    ):
        np.testing.assert_array_equal(f(tau), 0.0)
    np.testing.assert_array_equal(c.traction(np.linspace(-1, 1, 5), tau[:, None]), 0.0)
    np.testing.assert_array_equal(c.pressure(0.0, tau), 0.0)


def test_scalars_and_shapes_broadcast() -> None:
    c = Contact(2.414, math.pi / 6)
    assert c.tangential_force(1.0).shape == ()
    assert c.traction(np.zeros(3), np.ones((4, 1))).shape == (4, 3)
    assert c.traction(0.5, 1.0).shape == ()
    assert c.phase(np.ones((2, 3))).shape == (2, 3)


# ---- the domain table ------------------------------------------------------------------
def test_domain_covers_every_parameter_and_input() -> None:
    assert set(DOMAIN) == {"psi", "tau0", "mu", "nu", "upper_share", "tau", "r", "R", "G",
                           "H", "u0", "h", "omega"}
    assert DOMAIN["upper_share"].describe() == "(0, 1)"
    assert DOMAIN["psi"] == Interval(0.0, 1e12)
    assert (DOMAIN["psi"].lo, DOMAIN["psi"].hi) == (0.0, 1e12)
    assert DOMAIN["nu"].describe() == "(-1, 0.5]"
    assert DOMAIN["mu"].describe() == "(0, 1000]"
    assert DOMAIN["tau"].describe() == "(-inf, inf)"
    assert Interval(0.0, None, lo_open=True).describe() == "(0, inf)"


@pytest.mark.parametrize(
    ("name", "inside", "outside"),
    [
        ("psi", [0, 0.0, 1e12, np.float32(2.5), np.int64(7)], [-5e-324, 1e12 + 1e-3, 10**400]),
        ("tau0", [0.0, -1.5707963267948963], [math.pi / 2, -math.pi / 2]),
        ("mu", [5e-324, 1e3], [0.0, 1000.0001, 1e308]),
        ("nu", [0.5, -0.999], [-1.0, 0.5000001]),
        ("tau", [1e308, -1e308, 0], [math.inf, math.nan]),
    ],
)
def test_interval_contains(name: str, inside: list, outside: list) -> None:
    domain = DOMAIN[name]
    assert all(domain.contains(x) for x in inside)
    assert not any(domain.contains(x) for x in outside)
    for x in (True, np.True_, "1", b"1", 1j, None, np.timedelta64(1, "s"), math.nan):
        assert not domain.contains(x)


def test_contains_is_the_element_wise_check_at_every_edge() -> None:
    """``contains`` and ``check`` (plain float comparisons with ``closed_bounds``) answer
    as the numpy element-wise check does, at each end of every interval and one ulp
    either side."""
    for name, domain in DOMAIN.items():
        values = [0.0, 1.0, -1.0, math.inf, -math.inf, math.nan, 1e308, -1e308]
        for end in (domain.lo, domain.hi):
            if end is not None:
                values += [end, math.nextafter(end, math.inf), math.nextafter(end, -math.inf)]
        for x in values:
            inside = bool(domain._holds(x))
            assert domain.contains(x) == inside, (name, x)
            if inside:
                assert domain.check(name, x) == x
            else:
                with pytest.raises(ValueError, match=name):
                    domain.check(name, x)


def test_check_param_returns_floats_and_short_messages() -> None:
    assert check_param("psi", 3) == 3.0 and type(check_param("psi", np.int8(3))) is float
    cases = [
        ("psi", -1, "psi = -1 is outside the allowed range [0, 1e+12]"),
        ("psi", "abc", "psi must be a real number in [0, 1e+12], got 'abc'"),
        ("psi", math.inf, "psi must be a finite number in [0, 1e+12], got inf"),
        ("psi", np.longdouble("1e400"), "psi = 1e+400 is outside the allowed range [0, 1e+12]"),
        ("nu", np.float32("nan"), "nu must be a finite number in (-1, 0.5], got nan"),
        ("tau0", -math.pi / 2,
         "tau0 = -1.5707963267948966 is outside the allowed range (-1.5708, 1.5708)"),
        ("mu", 0.1 + 1e3, "mu = 1000.1 is outside the allowed range (0, 1000]"),
        ("tau", math.nan, "tau must be a finite number, got nan"),
        ("omega", 5e-324, "omega = 4.94066e-324 is outside the allowed range [1e-09, 1e+12]"),
        ("R", "x" * 100, "R must be a real number in [1e-09, 1000], got 'xxxxxxxxxxxxxxxxxxxx..."),
    ]
    for name, value, message in cases:
        with pytest.raises(ValueError) as err:
            check_param(name, value)
        assert str(err.value) == message


# ---- arrays of times, radii and psi ---------------------------------------------------------
FUNCTIONS_OF_TIME = ("phase", "approach", "normal_force", "tangential_force", "contact_radius",
                     "stick_radius", "centre_displacement", "centre_velocity",
                     "drive_displacement", "drive_velocity", "at")


@pytest.mark.parametrize("method", FUNCTIONS_OF_TIME)
@pytest.mark.parametrize(
    ("tau", "dtype"),
    [
        (True, "bool"),
        (np.array([True, False]), "bool"),
        ([1.0, 2j], "complex128"),
        (np.bytes_(b"1"), "|S1"),
        ([b"1", b"2"], "|S1"),
        ("1", "<U1"),
        (np.array([1.0, 2.0], dtype=object), "object"),
        ([1.0, None], "object"),
        ([10**400], "object"),
        (np.array(["2026-01-01"], dtype="datetime64[D]"), "datetime64[D]"),
        (np.timedelta64(1, "s"), "timedelta64[s]"),
    ],
)
def test_times_of_bad_dtypes_raise_type_error(method: str, tau: object, dtype: str) -> None:
    c = Contact(2.414, math.pi / 6)
    with pytest.raises(TypeError) as err:
        getattr(c, method)(tau)
    assert str(err.value) == f"tau must be real numbers (int or float), got dtype {dtype}"


@pytest.mark.parametrize("method", FUNCTIONS_OF_TIME)
def test_nan_and_inf_times_raise_value_error_naming_the_element(method: str) -> None:
    c = Contact(2.414, math.pi / 6)
    with warnings.catch_warnings(), np.errstate(all="raise"):
        warnings.simplefilter("error")
        for tau, where, shown in [
            (np.array([1.0, np.nan, np.inf]), "tau[1]", "nan"),
            ([[0.0, 1.0], [-np.inf, 2.0]], "tau[1, 0]", "-inf"),
            (math.inf, "tau", "inf"),
            (np.array([np.longdouble("1e400")]), "tau[0]", "inf"),
        ]:
            with pytest.raises(ValueError) as err:
                getattr(c, method)(tau)
            assert str(err.value) == f"{where} must be a finite number, got {shown}"


def test_radii_are_validated_and_huge_radii_give_zero() -> None:
    c = Contact(2.414, math.pi / 6)
    for f in (c.traction, c.pressure):
        with pytest.raises(TypeError, match="r must be real numbers"):
            f(np.array([True]), 1.0)
        with pytest.raises(ValueError, match=r"r\[0\] must be a finite number, got nan"):
            f([math.nan], 1.0)
        with pytest.raises(ValueError, match="tau must be a finite number"):
            f(0.5, math.nan)
        with np.errstate(all="raise"):
            np.testing.assert_array_equal(f([1e300, -1.7e308, 1e20], math.pi / 2), 0.0)


def test_any_real_dtype_gives_the_float64_answer() -> None:
    c = Contact(2.414, math.pi / 6)
    expected = c.tangential_force(np.array([1.0, 2.0]))
    for tau in ([1, 2], (1.0, 2.0), np.array([1, 2], dtype=np.int8),
                np.array([1, 2], dtype=np.uint64), np.array([1, 2], dtype=np.float16),
                np.array([1, 2], dtype=np.float32), np.array([1, 2], dtype=np.longdouble)):
        np.testing.assert_array_equal(c.tangential_force(tau), expected)
    assert c.tangential_force(np.float32(1.0)) == expected[0]
    assert c.normal_force([]).shape == (0,)
