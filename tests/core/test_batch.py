"""The batch API (``core.batch``, ``core.impulse_ratio`` over arrays of psi and tau0) and
the one-call contact (``core.curve``): against 60-digit mpmath references of the paper's
formulas, and bit for bit against ``Contact``, on every layout of the broadcast."""

import math

import numpy as np
import pytest

from core import Contact, batch, curve, impulse_ratio
from tests.core import reference as ref
from tests.core.cases import PSIS, TAU0S

TOL = 1e-13
QUANTITIES = ("tangential_force", "normal_force", "contact_radius", "stick_radius", "phase")


def _contacts() -> tuple[np.ndarray, np.ndarray]:
    pairs = [(p, t) for p in PSIS for t in TAU0S]
    return np.array([p for p, _ in pairs]), np.array([t for _, t in pairs])


def test_tangential_force_of_many_contacts_matches_reference() -> None:
    psi, tau0 = _contacts()
    tau = np.linspace(-0.3, 3.4, 23)
    T = batch.tangential_force(psi[:, None], tau0[:, None], tau)
    assert T.shape == (psi.size, tau.size)
    worst = 0.0
    for i in range(0, psi.size, 3):  # every third contact: mpmath is slow
        for j, t in enumerate(tau):
            exact = ref.tangential_force(psi[i], t, tau0[i])
            worst = max(worst, abs(float(exact) - T[i, j]))
    assert worst < TOL  # T0 is the natural scale: |T| <= 1


@pytest.mark.parametrize("name", QUANTITIES)
def test_every_layout_gives_the_values_of_contact(name: str) -> None:
    psi, tau0 = _contacts()
    tau = np.linspace(-1.0, 4.0, 31)
    f = getattr(batch, name)
    rows = f(psi[:, None], tau0[:, None], tau)  # contacts along rows
    cols = f(psi, tau0, tau[:, None])  # contacts along the last axis
    flat = f(psi, tau0, 1.3)  # one time
    for i in range(psi.size):
        alone = getattr(Contact(psi[i], tau0[i]), name)(tau)
        np.testing.assert_array_equal(rows[i], alone)
        np.testing.assert_array_equal(cols[:, i], alone)
        np.testing.assert_array_equal(flat[i], getattr(Contact(psi[i], tau0[i]), name)(1.3))
    # per-contact times (tau with one row per contact) and mu, nu widening the shape
    taus = np.linspace(0.2, 2.9, psi.size * 4).reshape(psi.size, 4)
    own = f(psi[:, None], tau0[:, None], taus, mu=np.array([0.1, 0.5])[:, None, None])
    assert own.shape == (2, psi.size, 4)
    for i in range(psi.size):
        np.testing.assert_array_equal(own[1, i], getattr(Contact(psi[i], tau0[i]), name)(taus[i]))
    assert f(2.0, 0.3, 1.0).shape == ()
    assert f(2.0, 0.3, np.empty((0, 3))).shape == (0, 3)


def test_batch_validates_every_argument() -> None:
    with pytest.raises(ValueError, match=r"psi\[1\]"):
        batch.tangential_force([1.0, -1.0], 0.3, 1.0)
    with pytest.raises(ValueError, match=r"tau0\[0\]"):
        batch.tangential_force(1.0, [2.0], 1.0)
    with pytest.raises(ValueError, match="nu"):
        batch.stick_radius(1.0, 0.3, 1.0, nu=0.7)
    with pytest.raises(TypeError, match="tau"):
        batch.phase(1.0, 0.3, ["a"])
    with pytest.raises(ValueError, match=r"psi \(2,\), tau0 \(3,\)"):
        batch.normal_force([1.0, 2.0], [0.1, 0.2, 0.3], 1.0)


def test_impulse_ratio_over_arrays_of_psi_and_tau0() -> None:
    psi, tau0 = _contacts()
    got = impulse_ratio(psi, tau0)
    assert got.shape == psi.shape
    for p, t, g in zip(psi, tau0, got, strict=True):
        assert g == Contact(p, t).impulse_ratio
        exact = ref.impulse_ratio(p, t)
        assert abs(g - float(exact)) <= TOL * float(exact)
    grid = impulse_ratio(psi[:, None], tau0[None, :])
    assert grid.shape == (psi.size, tau0.size)
    np.testing.assert_array_equal(np.diag(grid), got)


@pytest.mark.parametrize("tau0", [math.pi / 6, 0.6435, -0.9, -1.5, 1.5, 1.5 - 1e-9])
def test_impulse_ratio_of_many_psi_is_that_of_contact(tau0: float) -> None:
    """One tau0, many psi (two compiled passes: the series of J for all, then the
    elliptic form where k^2 m0 >= 0.2, i.e. 1 < psi < 10 m0 - 1): bit for bit the scalar
    formula, on both sides of that edge and in any order."""
    m0 = (1.0 - math.sin(tau0)) / 2.0
    edge = 10.0 * m0 - 1.0  # k^2 m0 = 0.2
    psi = np.concatenate([np.linspace(0.0, 30.0, 301), [1.0, 1 + 1e-12, 1e6, 1e12],
                          edge * np.array([1 - 1e-9, 1.0, 1 + 1e-9]) if edge > 1 else []])
    psi = np.random.default_rng(3).permutation(psi)
    got = impulse_ratio(psi, tau0)
    for p, g in zip(psi, got, strict=True):
        assert g == Contact(p, tau0).impulse_ratio
    grid = impulse_ratio(psi.reshape(-1, 1), tau0)  # any shape
    np.testing.assert_array_equal(grid.ravel(), got)


def _grid_as_documented(c: Contact, n: int) -> list[float]:
    """``Contact.tau_grid(n)`` by its documented rule, in plain Python: pieces
    [tau0, pi/2), [pi/2, tau1), [tau1, pi - tau0) (or [pi/2, pi - tau0) for psi <= 1) of
    n/2, the partial-stick share plus max(n/8, 8), and the rest; piece [a, b) of k points
    is a + i (b - a)/k; a piece of zero length gets no point, any other at least one;
    then pi - tau0."""
    half, end = n // 2, math.pi - c.tau0
    if c.psi <= 1:
        pieces = [(c.tau0, math.pi / 2, half), (math.pi / 2, end, n - half)]
    else:
        share = round((c.tau1 - math.pi / 2) / (end - math.pi / 2) * (n - half))
        pieces = [(c.tau0, math.pi / 2, half), (math.pi / 2, c.tau1, share + max(n // 8, 8)),
                  (c.tau1, end, n - half - share)]
    out = []
    for a, b, k in pieces:
        k = max(k, 1) if b > a else 0
        out += [i * ((b - a) / k) + a for i in range(k)]
    return [*out, end]


@pytest.mark.parametrize("n", [2, 3, 9, 200, 1001])
def test_tau_grid_is_the_documented_rule(n: int) -> None:
    for psi in PSIS:
        for tau0 in TAU0S:
            c = Contact(psi, tau0)
            grid = c.tau_grid(n)
            assert grid.tolist() == _grid_as_documented(c, n), (psi, tau0)
            assert (np.diff(grid) >= 0).all()
            assert curve(psi, tau0, n)[0][0].tolist() == grid.tolist()


@pytest.mark.parametrize(("psi", "tau0"), [(0.4, math.pi / 6), (1.0, -0.9), (2.414, 1.5),
                                           (1e6, -1.5707), (1 + 1e-12, 1.5)])
def test_curve_is_contact_in_one_call(psi: float, tau0: float) -> None:
    c = Contact(psi, tau0)
    for n in (2, 9, 200):
        rows, ratio = curve(psi, tau0, n)
        tau = c.tau_grid(n)
        np.testing.assert_array_equal(rows[0], tau)
        line = c.at(tau)
        np.testing.assert_array_equal(rows[1], line.tangential_force)
        np.testing.assert_array_equal(rows[2], line.stick_radius)
        assert ratio == c.impulse_ratio
    # any real number is accepted as in Contact; anything else refused the same way
    np.testing.assert_array_equal(curve(np.float32(2), 0, np.int16(20))[0],
                                  curve(2.0, 0.0, 20)[0])
    for bad in (math.nan, -1.0, True, "1"):
        with pytest.raises(ValueError, match="psi"):
            curve(bad, 0.3)
    with pytest.raises(ValueError, match="tau0"):
        curve(1.0, math.pi / 2)
    with pytest.raises(ValueError, match="n must be"):
        curve(1.0, 0.3, 1)
