"""The chunks of a design study and their evaluation: each chunk is a block of the
axes' grid (``StudySpec.chunk_shape``), one task, one region of the store; its figures
of merit come from one call of ``core.motor.designs.design_merits``.

A chunk's results depend only on the spec and the chunk (every design is evaluated on
its own: the same floats whichever worker, block or order), so a chunk computed twice
(a worker lost mid-task, its task run again) is written with the same bytes.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterator
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from core.materials import MATERIALS
from core.motor.designs import MERITS, design_merits
from core.motor.motor import Motor
from core.motor.rod import Rod
from core.motor.study.spec import ROTOR, BaseDesign, StudySpec

#: The variables of a study's Dataset: the figures of merit, then the contact of each
#: design (psi of eq 23, tau0 in rad), name -> (unit, description).
VARIABLES: dict[str, tuple[str, str]] = {
    **MERITS,
    "psi": ("1", "psi = tan theta / tan theta0 of the contact (eq 23)"),
    "tau0": ("rad", "start of contact tau0 (eq 10)"),
}
#: The greater the better (+1) or the smaller (-1), per figure of merit.
SENSE: dict[str, int] = {name: (-1 if name == "wear_rate" else 1) for name in MERITS}


def chunk_grid(spec: StudySpec) -> tuple[int, ...]:
    """Chunks along each axis."""
    return tuple(math.ceil(n / c) for n, c in zip(spec.shape, spec.chunk_shape, strict=True))


def chunk_ids(spec: StudySpec) -> Iterator[tuple[int, ...]]:
    """Every chunk's index on the chunk grid, in C order."""
    return itertools.product(*(range(g) for g in chunk_grid(spec)))


def chunk_slices(spec: StudySpec, chunk: tuple[int, ...]) -> tuple[slice, ...]:
    """The region of the grid that chunk covers."""
    return tuple(slice(i * c, min((i + 1) * c, n))
                 for i, c, n in zip(chunk, spec.chunk_shape, spec.shape, strict=True))


def chunk_name(chunk: tuple[int, ...]) -> str:
    """The chunk's id as text, '3.0' (its index on the chunk grid)."""
    return ".".join(str(i) for i in chunk)


def motor_of(design: BaseDesign) -> Motor:
    """The ``Motor`` of a design (ValueError if core refuses it)."""
    rod = Rod(half_length=design.half_length, thickness=design.thickness,
              nu_rod=design.nu_rod, amplitude=design.amplitude, frequency=design.frequency)
    rotor = MATERIALS[design.rotor_material]
    face = {}
    if design.rod_material != ROTOR:
        m = MATERIALS[design.rod_material]
        face = {"rod_G": m.G, "rod_nu": m.nu, "rod_R": design.rod_radius}
    return Motor(rod, R=design.rotor_radius, G=rotor.G, nu=rotor.nu, mu=design.mu,
                 preload=design.preload, **face)


def hardness_of(design: BaseDesign) -> float:
    """Archard's hardness of the design: its own, or the softer material's."""
    if design.hardness is not None:
        return design.hardness
    rotor = MATERIALS[design.rotor_material].hardness
    if design.rod_material == ROTOR:
        return rotor
    return min(rotor, MATERIALS[design.rod_material].hardness)


def evaluate_chunk(spec: StudySpec, chunk: tuple[int, ...]) -> dict[str, NDArray[np.float64]]:
    """Every variable of ``VARIABLES`` over the chunk's region (arrays of its shape).
    Designs whose motor core refuses (e.g. a preload too small for the rod: Phi below
    PHI_MIN at the centre) have every variable nan."""
    region = chunk_slices(spec, chunk)
    values = [a.values[s] for a, s in zip(spec.axes, region, strict=True)]
    shape = tuple(len(v) for v in values)
    names = [a.name for a in spec.axes]
    motors: list[Motor] = []
    x0, load, k, hard, index = [], [], [], [], []
    known: dict[BaseDesign, Motor | None] = {}
    for i, point in enumerate(itertools.product(*values)):
        design = replace(spec.base, **dict(zip(names, point, strict=True)))
        held = replace(design, x0=0.0, load=0.0)  # the motor: all but x0 and the load
        if held not in known:
            try:
                known[held] = motor_of(held)
            except ValueError:
                known[held] = None
        motor = known[held]
        if motor is None:
            continue
        motors.append(motor)
        x0.append(design.x0)
        load.append(design.load)
        k.append(design.wear_coefficient)
        hard.append(hardness_of(design))
        index.append(i)
    out = {name: np.full(math.prod(shape), np.nan) for name in VARIABLES}
    if index:
        got = design_merits(motors, np.array(x0), np.array(load), np.array(k),
                            np.array(hard), springs=spec.springs, steps=spec.steps)
        for name in VARIABLES:
            out[name][np.array(index)] = getattr(got, name)
    return {name: a.reshape(shape) for name, a in out.items()}
