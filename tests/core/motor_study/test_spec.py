"""The declaration of a design study (core.motor.study.spec): axes and their grids
validated against MOTOR_DOMAIN with messages naming the axis, the TOML form, the chunk
layout and the key that names the store."""

import math
from pathlib import Path

import numpy as np
import pytest

from core.motor.study import Axis, BaseDesign, StudySpec, load_spec, spec_from_toml
from core.motor.study.chunks import chunk_grid, chunk_ids, chunk_slices, evaluate_chunk
from core.motor.study.spec import code_version

EXAMPLES = Path(__file__).resolve().parents[3] / "core" / "motor" / "study" / "examples"

TOML = """
[study]
name = "t"
block = 6

[design]
rotor_material = "alumina"
load = 1e-3

[axes.x0]
start = -0.01
stop = -0.001
num = 4

[axes.preload]
start = 0.01
stop = 1.0
num = 3
spacing = "log"

[axes.rod_material]
values = ["PZT-4", "rotor"]
"""


def test_a_toml_spec_and_its_python_object_are_the_same_study() -> None:
    spec = spec_from_toml(TOML)
    assert spec.shape == (4, 3, 2) and spec.size == 24
    assert spec.axis("preload").values == pytest.approx((0.01, 0.1, 1.0), rel=1e-15)
    assert spec.base.rotor_material == "alumina" and spec.base.load == 1e-3
    same = StudySpec("t", (Axis.grid("x0", -0.01, -0.001, 4),
                           Axis.grid("preload", 0.01, 1.0, 3, "log"),
                           Axis("rod_material", ("PZT-4", "rotor"))),
                     base=BaseDesign(rotor_material="alumina", load=1e-3), block=6)
    assert same == spec and same.key == spec.key
    assert StudySpec.from_dict(spec.to_dict()) == spec


def test_the_key_follows_the_declaration_and_the_code() -> None:
    spec = spec_from_toml(TOML)
    assert len(spec.key) == 16 and spec.key == spec_from_toml(TOML).key
    renamed = spec_from_toml(TOML.replace('name = "t"', 'name = "u"'))
    assert renamed.key == spec.key  # the name names the store, not the results
    assert renamed.store_path("/s").name == f"u-{spec.key}.zarr"
    for change in ("num = 4", "load = 2e-3", "block = 7"):
        old = {"num = 4": "num = 4", "load = 2e-3": "load = 1e-3", "block = 7": "block = 6"}
        other = spec_from_toml(TOML.replace(old[change], change if change != "num = 4"
                                            else "num = 5"))
        assert other.key != spec.key, change
    assert len(code_version()) == 16


def test_chunks_tile_the_grid() -> None:
    spec = spec_from_toml(TOML)
    assert spec.chunk_shape == (1, 3, 2)  # whole trailing axes while they fit in 6
    assert chunk_grid(spec) == (4, 1, 1)
    wide = StudySpec("w", (Axis.grid("x0", -0.01, -0.001, 7), Axis.grid("load", 0, 1e-3, 5)),
                     block=12)
    assert wide.chunk_shape == (2, 5) and chunk_grid(wide) == (4, 1)
    covered = np.zeros(wide.shape, dtype=int)
    for c in chunk_ids(wide):
        covered[chunk_slices(wide, c)] += 1
    assert (covered == 1).all()


@pytest.mark.parametrize(("text", "message"), [
    ("[axes.x0]\nvalues = [-0.01, 0.03]", r"axis x0: x0\[1\] = 0.03 is outside the allowed "
                                          r"range \(-0.02, 0.02\)"),
    ("[axes.preload]\nvalues = [0.1, -1.0]", r"axis preload: preload\[1\] = -1 is outside"),
    ("[axes.amplitude]\nvalues = [1.0]", r"axis amplitude: amplitude\[0\] = 1 is outside"),
    ("[axes.frequency]\nstart = 1e3\nstop = 2e9\nnum = 3",
     r"axis frequency: frequency\[1\] = 1000000500.0 is outside"),
    ("[axes.rotor_radius]\nvalues = [0.0]", r"axis rotor_radius: rotor_radius\[0\] = 0 is "),
    ("[axes.load]\nvalues = [2e6]", r"axis load: load\[0\] = 2e\+06 is outside"),
    ("[axes.rotor_material]\nvalues = ['steel', 'wood']",
     "axis rotor_material: rotor_material\\[1\\] = 'wood' is not a material"),
    ("[axes.speed]\nvalues = [1.0]", "axis 'speed' is not a study axis"),
    ("[axes.x0]\nstart = -0.01\nstop = 0.0\nnum = 0", "axis x0: num = 0 must be an integer"),
    ("[axes.preload]\nstart = 0.0\nstop = 1.0\nnum = 3\nspacing = 'log'",
     "axis preload: a log spacing needs"),
    ("[axes.x0]\nvalues = [0.001, 0.001]", "axis x0: a value is repeated"),
    ("[axes.x0]\nstart = 0.001\nnum = 3", "axis x0: needs 'values', or 'start'"),
    ("[design]\nwheels = 3\n[axes.x0]\nvalues = [0.001]", r"\[design\]: unknown key\(s\) wheels"),
    ("[design]\npreload = -1\n[axes.x0]\nvalues = [0.001]", "preload = -1 is outside"),
    ("[study]\nblock = 0\n[axes.x0]\nvalues = [0.001]", "block = 0 is outside"),
    ("[study]\nname = '../x'\n[axes.x0]\nvalues = [0.001]", "name = '../x' must be letters"),
    ("", "axes must be one Axis or more"),
    ("[axes.x0\n", "the spec is not valid TOML"),
])
def test_bad_specs_are_refused_naming_the_axis(text: str, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        spec_from_toml(text)


def test_a_chunk_is_the_batched_kernel_on_its_designs() -> None:
    """A chunk's variables are design_merits of its designs, and designs whose motor core
    refuses are nan."""
    from core.motor.designs import design_merits
    from core.motor.study.chunks import motor_of

    rod = {"thickness": 100.0, "amplitude": 0.1, "rotor_radius": 1e3}  # H ~ 118 m
    spec = StudySpec("c", (Axis("preload", (1e-12, 0.05)), Axis("x0", (-0.004, -0.001))),
                     base=BaseDesign(load=1e-4, **rod), springs=24, steps=64)
    got = evaluate_chunk(spec, (0, 0))
    assert np.isnan(got["stall_thrust"][0]).all()  # Phi < PHI_MIN: Motor refuses 1e-12 N
    assert np.isfinite(got["no_load_speed"][1]).all()
    m = motor_of(BaseDesign(preload=0.05, **rod))
    ref = design_merits(m, [-0.004, -0.001], 1e-4, 1e-6, 5e9, springs=24, steps=64)
    for name in ("stall_thrust", "no_load_speed", "wear_rate", "psi"):
        assert got[name][1].tobytes() == np.asarray(getattr(ref, name)).tobytes()


def test_the_example_specs_load() -> None:
    for path in sorted(EXAMPLES.glob("*.toml")):
        spec = load_spec(path)
        assert spec.size >= 1 and math.prod(spec.chunk_shape) <= spec.block


def test_the_scheduler_comes_from_the_argument_or_the_environment(monkeypatch) -> None:
    from core.motor.study.run import scheduler_address

    monkeypatch.delenv("DASK_SCHEDULER_ADDRESS", raising=False)
    assert scheduler_address(None) is None  # an embedded LocalCluster
    monkeypatch.setenv("DASK_SCHEDULER_ADDRESS", "tcp://10.0.0.5:8786")
    assert scheduler_address(None) == "tcp://10.0.0.5:8786"
    assert scheduler_address("tcp://127.0.0.1:9000") == "tcp://127.0.0.1:9000"
