"""The CSV downloads stand alone: named columns with units, the parameters in comment
lines, and every value what `core` computes for the explorer's state."""

from __future__ import annotations

import io
import math
import re
from importlib.metadata import version

import numpy as np
import pandas as pd
import pytest
from explorer_browser import wait_until

from app.contact.impulse import ImpulseScene
from app.contact.player import frame_taus
from app.contact.state import SQRT2_1
from app.kit.figures import CURVE_POINTS, PROFILE_POINTS
from app.page.explorer import Explorer
from core import Contact, impulse_ratio

#: 10 significant digits are written: a value read back is within half a unit of the
#: tenth digit (zeros are written exactly)
RTOL = 5e-10

CURVE_NAMES = ["tau (rad)", "T/T0", "mu P/T0", "-mu P/T0", "alpha/(H-h)", "a/a*", "b/a*",
               "v2/(omega u0)", "u2/u0", "(du_x0/dt)/(omega u0)", "u_x0/u0"]
CURVE_SI_NAMES = ["t (s)", "T (N)", "mu P (N)", "alpha (m)", "a (m)", "b (m)", "v2 (m/s)",
                  "u2 (m)"]
TRACTION_NAMES = ["r/a*", "tau_u/(mu p*)", "p/p*", "stick"]
TRACTION_SI_NAMES = ["r (m)", "tau_u (Pa)", "p (Pa)"]
SI_INPUTS = {"R": "m", "G": "Pa", "H": "m", "u0": "m", "h": "m", "omega": "rad/s"}


class Csv:
    """A CSV download read back: its comment lines, parameters, column names and columns."""

    def __init__(self, text: str) -> None:
        lines = text.splitlines()
        self.comments = [line[2:] for line in lines if line.startswith("# ")]
        assert all(line.startswith("# ") for line in lines[:len(self.comments)])
        self.names = lines[len(self.comments)].split(",")
        body = np.genfromtxt(io.StringIO(text), delimiter=",", comments="#",
                             skip_header=len(self.comments) + 1, ndmin=2)
        assert body.shape[1] == len(self.names)
        self.columns = {n: body[:, i] for i, n in enumerate(self.names)}
        #: 'name = value' lines: name -> (unit, value)
        self.parameters = {}
        for line in self.comments:
            m = re.fullmatch(r"(\w+)(?: \(([^)]+)\))? = (\S+)", line)
            if m:
                self.parameters[m[1]] = (m[2] or "", float(m[3]))
        #: the column descriptions after the 'columns:' line
        described = self.comments[self.comments.index("columns:") + 1:]
        self.descriptions = dict(line.strip().split(": ", 1) for line in described)
        assert not re.search(r"(^|,)-0(,|$)", text, re.MULTILINE)  # no negative zero
        # a general reader takes the file as it is
        assert list(pd.read_csv(io.StringIO(text), comment="#").columns) == self.names

    def value(self, name: str) -> float:
        return self.parameters[name][1]


def written(actual, expected) -> None:
    """`actual` (read from the file) is `expected` written to 10 significant digits."""
    np.testing.assert_allclose(actual, np.asarray(expected, float), rtol=RTOL, atol=0)


@pytest.fixture
def ex() -> Explorer:
    return Explorer()


def contact_of(ex: Explorer) -> Contact:
    s = ex.state
    if s.physical:
        return Contact.from_physical(R=s.R, G=s.G, nu=s.nu, mu=s.mu, H=s.H, u0=s.u0, h=s.h,
                                     omega=s.omega)
    return Contact(s.psi, s.tau0, mu=s.mu, nu=s.nu)


def use_physical_inputs(ex: Explorer) -> None:
    ex.state.param.update(R=0.005, G=26.0e9, nu=0.33, mu=0.3, H=2e-6, u0=3e-6, h=-1e-7,
                          omega=2 * math.pi * 30e3)
    ex.state.physical = True


def assert_parameters(csv: Csv, ex: Explorer) -> None:
    """The comment lines name the source, the version and the state's parameters (the
    very floats), and the SI inputs exactly when the contact was defined by them."""
    s = ex.state
    assert any("Zharii" in line and "(1996)" in line for line in csv.comments)
    assert f"app: zharii-contact {version('zharii-contact')}" in csv.comments
    units = {"psi": "", "tau0": "rad", "mu": "", "nu": ""}
    for name, unit in units.items():
        assert csv.parameters[name] == (unit, getattr(s, name))
    if s.physical:
        for name, unit in SI_INPUTS.items():
            assert csv.parameters[name] == (unit, getattr(s, name))
    else:
        assert not set(SI_INPUTS) & set(csv.parameters)


# ------------------------------------------------------------------------ curves


def test_curves_are_named_with_units_and_equal_core(ex: Explorer) -> None:
    ex.state.param.update(psi=6.46, tau0=0.3, mu=0.35, nu=0.25, tau=1.2)
    csv = Csv(ex.contact.csv_text("curves"))
    assert csv.names == CURVE_NAMES
    assert_parameters(csv, ex)
    assert "tau" not in csv.parameters  # the curves are over the whole contact
    c = Contact(6.46, 0.3, mu=0.35, nu=0.25)
    tau = c.tau_grid(CURVE_POINTS)
    got = csv.columns
    written(got["tau (rad)"], tau)
    written(got["T/T0"], c.tangential_force(tau))
    written(got["mu P/T0"], c.normal_force(tau))
    written(got["-mu P/T0"], -c.normal_force(tau))
    written(got["alpha/(H-h)"], c.approach(tau))
    written(got["a/a*"], c.contact_radius(tau))
    written(got["b/a*"], c.stick_radius(tau))
    written(got["v2/(omega u0)"], c.centre_velocity(tau))
    written(got["u2/u0"], c.centre_displacement(tau))
    written(got["(du_x0/dt)/(omega u0)"], np.cos(tau))
    written(got["u_x0/u0"], np.sin(tau))
    # each column says what it is and where the paper gives it
    assert list(csv.descriptions) == CURVE_NAMES
    assert "eqs 38, 39" in csv.descriptions["T/T0"]
    assert "eq 9" in csv.descriptions["mu P/T0"]
    assert "eqs 30, 36" in csv.descriptions["b/a*"]
    assert "eq 42" in csv.descriptions["v2/(omega u0)"]


def test_curves_of_physical_inputs_add_si_columns_and_the_inputs(ex: Explorer) -> None:
    use_physical_inputs(ex)
    csv = Csv(ex.contact.csv_text("curves"))
    assert csv.names == CURVE_NAMES + CURVE_SI_NAMES
    assert_parameters(csv, ex)
    c = contact_of(ex)
    sc, s = c.scales, ex.state
    tau = c.tau_grid(CURVE_POINTS)
    got = csv.columns
    written(got["t (s)"], tau / s.omega)
    written(got["T (N)"], c.tangential_force(tau) * sc.T0)
    written(got["mu P (N)"], c.normal_force(tau) * s.mu * sc.P0)
    written(got["alpha (m)"], c.approach(tau) * (s.H - s.h))
    written(got["a (m)"], c.contact_radius(tau) * math.sqrt(s.R * (s.H - s.h) / 2))
    written(got["b (m)"], c.stick_radius(tau) * sc.a_star)
    written(got["v2 (m/s)"], c.centre_velocity(tau) * s.omega * s.u0)
    written(got["u2 (m)"], c.centre_displacement(tau) * s.u0)
    written(got["T/T0"], c.tangential_force(tau))


# ---------------------------------------------------------------------- traction


def profile_grid(c: Contact, tau: float) -> np.ndarray:
    """The points across the diameter: PROFILE_POINTS over 1.05 times the largest contact
    radius, with -a, a, -b, b at tau."""
    A = float(c.contact_radius(math.pi / 2))
    a, b = float(c.contact_radius(tau)), float(c.stick_radius(tau))
    return np.sort(np.concatenate([np.linspace(-1.05 * A, 1.05 * A, PROFILE_POINTS),
                                   [-a, a, -b, b]]))


def assert_profile(csv: Csv, c: Contact, tau: float) -> None:
    r = profile_grid(c, tau)
    got = csv.columns
    written(got["r/a*"], r)
    written(got["tau_u/(mu p*)"], c.traction(r, tau))
    written(got["p/p*"], c.pressure(r, tau))
    b = float(c.stick_radius(tau))
    np.testing.assert_array_equal(got["stick"], (np.abs(r) <= b) & (b > 0))


@pytest.mark.parametrize(("psi", "tau0", "tau"), [
    (SQRT2_1, math.pi / 6, 17 * math.pi / 24),  # partial stick (Fig. 6e)
    (0.5, 0.2, 1.1),  # full stick
    (5.0, -0.3, 2.9),  # counter-slip, preloaded
])
def test_traction_profile_records_its_tau_and_equals_core(ex: Explorer, psi, tau0,
                                                          tau) -> None:
    ex.state.param.update(psi=psi, tau0=tau0, mu=0.25, nu=0.2, tau=tau)
    csv = Csv(ex.contact.csv_text("traction"))
    assert csv.names == TRACTION_NAMES
    assert_parameters(csv, ex)
    assert csv.parameters["tau"] == ("rad", tau)
    c = Contact(psi, tau0, mu=0.25, nu=0.2)
    assert_profile(csv, c, tau)
    assert "eqs 18, 24, 33, 36" in csv.descriptions["tau_u/(mu p*)"]
    assert "eq 6" in csv.descriptions["p/p*"]
    assert ex.contact.csv_filename("traction").endswith(f"_tau{tau:.4g}.csv")


def test_traction_of_physical_inputs_adds_si_columns(ex: Explorer) -> None:
    use_physical_inputs(ex)
    ex.state.tau = 1.9
    csv = Csv(ex.contact.csv_text("traction"))
    assert csv.names == TRACTION_NAMES + TRACTION_SI_NAMES
    assert_parameters(csv, ex)
    c = contact_of(ex)
    assert_profile(csv, c, 1.9)
    sc, r = c.scales, profile_grid(c, 1.9)
    got = csv.columns
    written(got["r (m)"], r * sc.a_star)
    written(got["tau_u (Pa)"], c.traction(r, 1.9) * ex.state.mu * sc.p_star)
    written(got["p (Pa)"], c.pressure(r, 1.9) * sc.p_star)


def test_a_download_while_playing_is_the_profile_at_the_frame_shown(ex: Explorer) -> None:
    """While playing, the profile downloaded is the one of the browser's frame, and its
    tau is in the file and in the file's name."""
    ex.state.playing = True
    try:
        wait_until(lambda: ex.contact.animation.clock_tau() != ex.state.tau, 5,
                   what="the player to move on from the state's tau")
        text = ex.contact.csv_file("traction").getvalue()
        name = ex.contact.controls.downloads["traction"].filename
        state_tau = ex.state.tau
    finally:
        ex.state.playing = False
    csv = Csv(text)
    tau = csv.value("tau")
    c = contact_of(ex)
    assert tau in frame_taus(c) and tau != state_tau
    assert name.endswith(f"_tau{tau:.4g}.csv")
    assert_profile(csv, c, tau)


def test_a_download_when_paused_is_the_profile_at_the_state_tau(ex: Explorer) -> None:
    ex.state.tau = 2.0
    text = ex.contact.csv_file("traction").getvalue()
    assert text == ex.contact.csv_text("traction")
    assert Csv(text).parameters["tau"] == ("rad", 2.0)
    assert ex.contact.controls.downloads["traction"].filename == ex.contact.csv_filename("traction")


# ----------------------------------------------------------------------- impulse


@pytest.mark.parametrize("log_psi", [False, True])
def test_impulse_curve_is_named_and_equals_core(ex: Explorer, log_psi: bool) -> None:
    ex.state.param.update(psi=40.0, tau0=-0.4, mu=0.15, nu=0.35, log_psi=log_psi)
    csv = Csv(ex.contact.csv_text("impulse"))
    assert csv.names == ["psi", "T_imp/(mu P_imp)"]
    assert_parameters(csv, ex)
    if log_psi:
        lo, hi = ImpulseScene.LOG_RANGE
        grid = np.geomspace(lo, hi, CURVE_POINTS)
    else:
        grid = np.linspace(0.0, 1.1 * 40.0, CURVE_POINTS)  # reaching psi beyond 30
    psi = np.unique(np.concatenate([grid, [1.0]]))
    written(csv.columns["psi"], psi)
    written(csv.columns["T_imp/(mu P_imp)"], impulse_ratio(psi, -0.4))
    assert "eq 41" in csv.descriptions["T_imp/(mu P_imp)"]


# -------------------------------------------------------------------- file names


def test_file_names_hold_the_parameters_and_the_profile_its_tau(ex: Explorer) -> None:
    ex.state.param.update(psi=2.5, tau0=-0.25, mu=0.3, nu=0.25, tau=1.5)
    params = "psi2.5_tau0_-0.25_mu0.3_nu0.25"
    assert ex.contact.csv_filename("curves") == f"zharii_curves_{params}.csv"
    assert ex.contact.csv_filename("impulse") == f"zharii_impulse_{params}.csv"
    assert ex.contact.csv_filename("traction") == f"zharii_traction_{params}_tau1.5.csv"
    for key in ("curves", "traction", "impulse"):
        ex.contact.csv_file(key)  # what a click does
        assert ex.contact.controls.downloads[key].filename == ex.contact.csv_filename(key)
