"""What the contact feature shows, as plain data from `core` (no Bokeh, no Panel).

`readout_rows` are the derived quantities of the readout card; `captions` the traction
plot's caption at each of K times (the player writes one per frame).  Units: the paper's
scales (T0, a*, p*; eqs 7, 37) and, for a contact built from SI inputs, SI values.
"""

from __future__ import annotations

import math

import numpy as np

from core import Contact


def readout_rows(c: Contact) -> list[tuple[str, str]]:
    """The derived quantities shown: (quantity, value) pairs."""
    rows = [
        ("θ (incidence angle)", f"{math.degrees(c.theta):.3f}°"),
        ("θ₀ (critical angle)", f"{math.degrees(c.theta0):.3f}°"),
        ("ψ", f"{c.psi:.6g}"),
        ("τ₀ … π − τ₀", f"{c.tau0:.4f} … {c.tau_end:.4f} rad"),
        ("τ₁ (stick disc vanishes)", "none (ψ ≤ 1)" if math.isnan(c.tau1)
         else f"{c.tau1:.4f} rad"),
        ("T_imp / (μ P_imp)", f"{c.impulse_ratio:.5g}"),  # (5 digits, at psi = 1e12 too)
    ]
    sc = c.scales
    if sc is not None:
        rows += [
            ("T₀ (force scale)", f"{sc.T0:.4g} N"),
            ("P₀ = T₀/μ", f"{sc.P0:.4g} N"),
            ("a* (largest contact radius)", f"{sc.a_star * 1e6:.4g} µm"),
            ("p* (peak pressure)", f"{sc.p_star / 1e6:.4g} MPa"),
            ("normal impulse", f"{sc.normal_impulse:.4g} N·s"),
            ("tangential impulse", f"{sc.tangential_impulse:.4g} N·s"),
            ("period 2π/ω", f"{sc.period * 1e6:.4g} µs"),
        ]
    return rows


def captions(c: Contact, taus: np.ndarray) -> list[str]:
    """The caption of the traction plot at each of the times `taus` (rad): tau, T/T0,
    a/a*, b/a* (and t, T, a, b in SI units for a contact built from SI inputs)."""
    line = c.at(taus)  # (one validation of taus for the three)
    T, a, b = line.tangential_force, line.contact_radius, line.stick_radius
    taus, T, a, b = (np.asarray(v, float).tolist() for v in (taus, T, a, b))
    texts = [f"τ = {t:.4f} rad  T/T₀ = {x:+.4f}\na/a* = {y:.4f}  b/a* = {z:.4f}"
             for t, x, y, z in zip(taus, T, a, b, strict=True)]
    sc = c.scales
    if sc is not None:
        texts = [text + (f"\nt = {t * sc.period / (2 * math.pi) * 1e6:.4g} µs"
                         f"  T = {x * sc.T0:.4g} N\n"
                         f"a = {y * sc.a_star * 1e6:.4g} µm  b = {z * sc.a_star * 1e6:.4g} µm")
                 for text, t, x, y, z in zip(texts, taus, T, a, b, strict=True)]
    return texts


def caption(c: Contact, tau: float) -> str:
    """The traction plot's caption at one time tau (rad)."""
    return captions(c, np.array([tau]))[0]
