"""Bad input raises ValueError naming the parameter, its value and the allowed range."""

import math

import numpy as np
import pytest

from core import Contact, impulse_ratio

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
        ({"psi": 2e12}, "psi", "2000000000000.0"),
        ({"tau0": math.pi / 2}, "tau0", "(-1.5708, 1.5708)"),
        ({"tau0": -math.pi / 2}, "tau0", "-1.57"),
        ({"tau0": 3.0}, "tau0", "3.0"),
        ({"mu": 0.0}, "mu", "(0, inf)"),
        ({"mu": -0.1}, "mu", "-0.1"),
        ({"nu": 0.51}, "nu", "(-1, 0.5]"),
        ({"nu": -1.0}, "nu", "-1.0"),
        ({"psi": "2"}, "psi", "'2'"),
        ({"psi": True}, "psi", "True"),
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
        ({"u0": 1.0, "H": 1e-14, "h": 0.0}, "psi"),
    ],
)
def test_from_physical_rejects_bad_inputs(bad: dict, name: str) -> None:
    with pytest.raises(ValueError, match=rf"\b{name}\b"):
        Contact.from_physical(**{**GOOD, **bad})


def test_impulse_ratio_validates_psi_and_tau0() -> None:
    with pytest.raises(ValueError, match=r"psi = -2\.0"):
        impulse_ratio(np.array([1.0, -2.0]), 0.5)
    with pytest.raises(ValueError, match="psi = nan"):
        impulse_ratio([np.nan], 0.5)
    with pytest.raises(ValueError, match="tau0"):
        impulse_ratio([1.0], 2.0)


@pytest.mark.parametrize("n", [1, 0, -5, 2.5, "10", True, 10**9])
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
