"""The elastic operators of two half-spaces on a grid, applied by discrete-convolution FFT
(DC-FFT; Liu, Wang & Liu, Wear 243 (2000) 101-111).

The influence coefficients of every offset (``core.bem.influence``) are laid out in
wrap-around order on a grid of at least 2M - 1 points per side (the next fast FFT size),
the tractions are zero-padded to that size, and one product of spectra gives the
aperiodic convolution exactly (no periodic images): N log N per application, N = M^2. The
kernels' spectra are computed once per grid and material pair and reused by every
application.

Units: tractions in p* (the peak Hertz pressure), lengths in the radius (a* or a),
displacements in a^2 / R_e (R_e the effective radius, a^2 / R_e the Hertz approach at that
radius): the displacement per unit traction is then (2 / pi^2) times the kernel integral,
since p* / E* = 2 a / (pi R_e).

    normal gap part      u_n = c [ K * p + beta (C_x * q_x + C_y * q_y) ]
    relative tangential  u_x = c [ (K + n K_xx) * q_x + n K_xy * q_y - beta C_x * p ]
                         u_y = c [ n K_xy * q_x + (K + n K_yy) * q_y - beta C_y * p ]

with c = 2 / pi^2, K = 1/r, n = nu / (1 - nu), q the traction on body 1 (the upper, held
body), u_t the displacement of body 1's surface relative to body 2's. The operator is
symmetric positive definite (it is the elastic energy's Hessian).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.fft as sfft
from numpy.typing import NDArray

from core.bem.grid import Grid
from core.bem.influence import coefficients

#: Displacement per unit traction times the kernel integral (see module docstring).
SCALE = 2.0 / math.pi**2

Array = NDArray[np.float64]


def wrap(kernel: Array, length: int) -> Array:
    """A (2M - 1) x (2M - 1) array of offsets -(M - 1) .. M - 1 (offset 0 at its centre)
    laid out in wrap-around order on a length x length grid (negative offsets at the end)."""
    m = (kernel.shape[0] + 1) // 2
    out = np.zeros((length, length))
    idx = np.r_[0:m, length - m + 1:length]
    src = np.r_[m - 1:2 * m - 1, 0:m - 1]
    out[np.ix_(idx, idx)] = kernel[np.ix_(src, src)]
    return out


@dataclass(frozen=True)
class Operators:
    """The elastic operators of a material pair on a grid (module docstring).

    Parameters
    ----------
    grid : Grid
    nu : float
        The pair's effective Poisson ratio (identical bodies: their nu), in [0, 0.5).
    beta : float
        Dundurs' second constant, in (-0.5, 0.5).
    """

    grid: Grid
    nu: float
    beta: float
    _spectra: dict[str, Array] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        m = self.grid.size
        length = sfft.next_fast_len(2 * m - 1, real=True)
        k = coefficients(m, self.grid.h)
        n = self.nu / (1.0 - self.nu)
        parts = {
            "nn": k["inv_r"],
            "xx": k["inv_r"] + n * k["xx"],
            "yy": k["inv_r"] + n * k["yy"],
            "xy": n * k["xy"],
            "cx": self.beta * k["cx"],
            "cy": self.beta * k["cy"],
        }
        spectra = {name: sfft.rfft2(SCALE * wrap(a, length)) for name, a in parts.items()}
        object.__setattr__(self, "_spectra", spectra)
        object.__setattr__(self, "_length", length)

    @property
    def coupled(self) -> bool:
        """True when beta != 0 (normal and tangential problems interact)."""
        return self.beta != 0.0

    def _fwd(self, f: Array) -> Array:
        """The spectrum of f (..., M, M) zero-padded to the FFT size."""
        return sfft.rfft2(f, s=(self._length, self._length))

    def _back(self, s: Array) -> Array:
        """The first M x M values of the inverse of a spectrum (..., L, L // 2 + 1)."""
        m = self.grid.size
        return sfft.irfft2(s, s=(self._length, self._length))[..., :m, :m]

    def normal(self, p: Array) -> Array:
        """u_n of a pressure field p alone (c K * p)."""
        return self._back(self._spectra["nn"] * self._fwd(p))

    def tangential(self, qx: Array, qy: Array) -> tuple[Array, Array]:
        """(u_x, u_y) of shear tractions alone (both components in one batched forward
        and one batched inverse FFT)."""
        s = self._spectra
        f = self._fwd(np.stack((qx, qy)))
        fx, fy = f[0], f[1]
        u = self._back(np.stack((s["xx"] * fx + s["xy"] * fy, s["xy"] * fx + s["yy"] * fy)))
        return u[0], u[1]

    def normal_from_shear(self, qx: Array, qy: Array) -> Array:
        """The coupling part of u_n: c beta (C_x * q_x + C_y * q_y); zeros when beta = 0."""
        if not self.coupled:
            return np.zeros_like(qx)
        s = self._spectra
        return self._back(s["cx"] * self._fwd(qx) + s["cy"] * self._fwd(qy))

    def shear_from_normal(self, p: Array) -> tuple[Array, Array]:
        """The coupling part of (u_x, u_y): -c beta (C_x * p, C_y * p); zeros when
        beta = 0."""
        if not self.coupled:
            z = np.zeros_like(p)
            return z, z.copy()
        s = self._spectra
        fp = self._fwd(p)
        return -self._back(s["cx"] * fp), -self._back(s["cy"] * fp)

    @cached_property
    def tangential_bound(self) -> float:
        """An upper bound of the tangential operator's largest eigenvalue: the largest
        eigenvalue of the circulant embedding's 2 x 2 symbols (Cauchy interlacing)."""
        s = self._spectra
        a, b, c = s["xx"].real, s["yy"].real, s["xy"].real
        lam = 0.5 * (a + b) + np.sqrt(0.25 * (a - b) ** 2 + c * c)
        return float(lam.max())

    @cached_property
    def normal_bound(self) -> float:
        """Largest eigenvalue bound of the normal operator (as ``tangential_bound``)."""
        return float(self._spectra["nn"].real.max())
