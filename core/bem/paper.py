"""The paper's intermittent oblique contact solved by the boundary-element model, and its
comparison with the closed form (``core.Contact``).

The march starts unloaded at tau0 (no history: a new contact), steps the approach and the
shift of ``core.bem.loading`` through the contact, and records per time the tangential and
normal forces (T / T0, P / P0, as ``Contact.tangential_force`` and ``normal_force``), the
equal-area stick radius (units a*) and the friction work. The dissipation is the friction
work summed over the contact, in units T0 u0 as ``Contact.dissipated_energy``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from core.bem.cases import hertz_gap
from core.bem.convolution import Operators
from core.bem.grid import Grid, check_across
from core.bem.loading import PaperLoading
from core.bem.march import DEFAULT, State, StepSettings, step
from core.bem.pair import Pair
from core.contact import Contact
from core.tangential import Phase

Array = NDArray[np.float64]


@dataclass(frozen=True)
class PaperRun:
    """The referee's contact: times ``tau``, forces T / T0 (``T``, along the drive;
    ``Ty`` transverse) and P / P0 (``P``), stick radius b / a* (``stick``, equal-area),
    contact radius a / a* (``radius``, equal-area), the drive's work int T du_x0 per
    contact in T0 u0 (``dissipation``: all of it is dissipated, the elastic energy being 0
    at both ends; trapezoid rule), the friction work summed element by element
    (``friction_work``, -sum q . s dA over the steps: equal to ``dissipation`` as the step
    shrinks, the energy balance), the closed form (``closed``: a ``core.Contact`` of the pair's
    effective nu), the snapshots requested (tau -> State), the wall and CPU times (s)."""

    tau: Array
    T: Array
    Ty: Array
    P: Array
    stick: Array
    radius: Array
    dissipation: float
    friction_work: float
    closed: Contact
    grid: Grid
    snapshots: dict
    seconds: float
    cpu_seconds: float

    @property
    def worst_T_error(self) -> float:
        """max over the times of |T - T_closed| / T0."""
        return float(np.abs(self.T - self.closed.tangential_force(self.tau)).max())

    @property
    def impulse_ratio(self) -> float:
        """T_imp / (mu P_imp) of the referee (trapezoid rule on its times)."""
        return float(np.trapezoid(self.T, self.tau) / np.trapezoid(self.P, self.tau))

    @property
    def impulse_ratio_closed(self) -> float:
        """eq 41 (``Contact.impulse_ratio``)."""
        return self.closed.impulse_ratio

    @property
    def dissipation_ratio(self) -> float:
        """Referee's friction work over ``Contact.dissipated_energy``; nan when the
        closed form dissipates nothing (psi <= 1)."""
        d = self.closed.dissipated_energy
        return self.dissipation / d if d > 0.0 else math.nan

    @property
    def worst_stick_error(self) -> float:
        """max |b - b_closed| / a* over the closed form's partial-stick times (phase 3),
        or over full stick (b = a) for psi <= 1; 0 if there are none."""
        phase = self.closed.phase(self.tau)
        mask = (phase == Phase.PARTIAL_STICK) | (phase == Phase.FULL_STICK)
        if not mask.any():
            return 0.0
        closed = self.closed.stick_radius(self.tau)
        return float(np.abs(self.stick[mask] - closed[mask]).max())


def run_paper(psi: float, tau0: float, nu: float, *, beta: float = 0.0, mu: float = 0.2,
              grid: int = 64, steps: int = 200, snapshots: tuple[float, ...] = (),
              settings: StepSettings = DEFAULT) -> PaperRun:
    """One contact of the paper's loading by the boundary-element model.

    Parameters
    ----------
    psi, tau0, mu : float
        As ``core.Contact`` (eq 23; eq 4, rad).
    nu : float
        The pair's effective Poisson ratio, in [0, 0.5).
    beta : float
        Dundurs' beta, in (-0.5, 0.5); 0 for identical bodies.
    grid : int
        Elements across the largest contact diameter 2 a*.
    steps : int
        Equal time steps over the contact (even).
    snapshots : tuple of float
        Times (rad) whose full state to keep (the nearest step).

    Returns
    -------
    PaperRun
    """
    pair = Pair(nu, beta)
    load = PaperLoading(psi, tau0, mu, pair, steps)
    g = Grid(check_across(grid))
    t0, c0 = time.perf_counter(), time.process_time()
    op = Operators(g, pair.nu, pair.beta)
    h0 = hertz_gap(g)
    tau = load.tau
    alpha = load.approach(tau)
    shift = load.shift(tau)
    n = len(tau)
    T, Ty, P = np.zeros(n), np.zeros(n), np.zeros(n)
    stick, radius = np.zeros(n), np.zeros(n)
    keep = {int(np.argmin(np.abs(tau - s))): s for s in snapshots}
    kept: dict[float, State] = {}
    state = State.unloaded(h0.shape)
    area = g.area
    T0 = mu * load.P0
    for k in range(1, n):
        if alpha[k] <= 0.0:
            state = State(*(np.zeros_like(h0) for _ in range(7)), work=state.work)
            continue
        state = step(op, h0, state, mu, (shift[k] - shift[k - 1], 0.0),
                     approach=float(alpha[k]), settings=settings)
        T[k] = float(state.qx.sum()) * area / T0
        Ty[k] = float(state.qy.sum()) * area / T0
        P[k] = float(state.p.sum()) * area / load.P0
        contact = state.p > 0.0
        slip = np.hypot(state.sx, state.sy)
        thr = max(10.0 * settings.slip_tol, 1e-6 * float(slip.max()))
        radius[k] = math.sqrt(contact.sum() * area / math.pi)
        stick[k] = math.sqrt((contact & (slip <= thr)).sum() * area / math.pi)
        if k in keep:
            kept[keep[k]] = state
    friction_work = state.work / (T0 * load.u0)
    # the drive's work int T du_x0 (trapezoid rule, second order in the step): all of it
    # is dissipated over a contact (the elastic energy is zero at both ends)
    dissipation = float(np.sum(0.5 * (T[1:] + T[:-1]) * np.diff(shift))) / load.u0
    closed = Contact(psi=load.psi, tau0=load.tau0, mu=load.mu, nu=pair.nu)
    return PaperRun(tau, T, Ty, P, stick, radius, dissipation, friction_work, closed, g,
                    kept, time.perf_counter() - t0, time.process_time() - c0)
