"""The compiled kernels against the numpy-loop implementations they replaced.

``reference_numpy_loops.npz`` holds the outputs of ``mdr.run``, ``annulus.run`` and
``dem.integrate`` as they were at commit 744f4e8 (numpy, one Python iteration per time
step), on fixed grids for five cases (``cases``: psi <= 1, psi = 1, psi > 1, preload,
grazing) and on a grid that starts before and ends after contact. Where the arithmetic
is the same the results must be the same bit for bit (the MDR spring values, most DEM
rules); where it differs (summation order, LU against LAPACK, LAMMPS' rescaling
Fscrit / |F| instead of copysign), to 1e-14 of the largest |T|.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from core.numerics import annulus, dem, mdr
from core.numerics.loading import time_grid

REF = np.load(Path(__file__).with_name("reference_numpy_loops.npz"))
CASES = [tuple(c) for c in REF["cases"]]
TOL = 1e-14


def close(new, old):
    scale = max(float(np.max(np.abs(old))), 1e-300)
    assert np.max(np.abs(new - old)) <= TOL * scale


@pytest.mark.parametrize("i", range(len(CASES)))
def test_time_grids_are_the_same(i):
    psi, tau0 = CASES[i]
    np.testing.assert_array_equal(time_grid(psi, tau0, 90), REF[f"grid_{i}"])
    np.testing.assert_array_equal(time_grid(psi, tau0, 48), REF[f"agrid_{i}"])


@pytest.mark.parametrize("i", range(len(CASES)))
def test_mdr_kernel(i):
    psi, tau0 = CASES[i]
    T, P, b, u = mdr.run(psi, tau0, REF[f"grid_{i}"], 37)
    np.testing.assert_array_equal(u, REF[f"mdr_u_{i}"])  # spring values: same arithmetic
    close(T, REF[f"mdr_T_{i}"])
    close(P, REF[f"mdr_P_{i}"])
    close(b, REF[f"mdr_b_{i}"])


@pytest.mark.parametrize("psi", [0.5, 3.0])
def test_mdr_kernel_across_the_contact_window(psi):
    T, _, b, _ = mdr.run(psi, 0.4, REF["outside_grid"], 100)
    close(T, REF[f"mdr_out_T_{psi}"])
    close(b, REF[f"mdr_out_b_{psi}"])


@pytest.mark.parametrize("i", range(len(CASES)))
def test_annulus_kernel(i):
    psi, tau0 = CASES[i]
    T, b = annulus.run(psi, tau0, REF[f"agrid_{i}"], 12)
    close(T, REF[f"ann_T_{i}"])
    np.testing.assert_array_equal(b, REF[f"ann_b_{i}"])  # the same stick sets


OLD_RULES = ["lammps_mindlin", "lammps_mindlin_force", "lammps_mindlin_rescale",
             "lammps_mindlin_rescale_force", "liggghts_history", "direnzo"]


@pytest.mark.parametrize("name", OLD_RULES)
@pytest.mark.parametrize("i", range(len(CASES)))
def test_dem_kernels(name, i):
    psi, tau0 = CASES[i]
    F = dem.forces(dem.MODELS[name], psi, tau0, dem.dem_time_grid(tau0, 300))[0]
    old = REF[f"dem_{name}_{i}"]
    if name == "direnzo":  # unchanged arithmetic
        np.testing.assert_array_equal(F, old)
    else:
        close(F, old)
