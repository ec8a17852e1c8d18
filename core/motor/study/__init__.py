"""Design studies of the motor: declared axes swept over a base design, every figure of
merit of ``core.motor.designs`` computed on Dask distributed (an embedded LocalCluster
or an existing scheduler), written chunk by chunk into a Zarr store that a killed study
resumes (docs/study.md).

One concept per module:

- ``spec``: the declaration (``StudySpec``, ``Axis``, ``BaseDesign``; ``load_spec`` of a
  TOML file), validated against ``core.MOTOR_DOMAIN``, and its key.
- ``chunks``: the chunks of the grid and their evaluation (one task each).
- ``store``: the Zarr store (an xarray Dataset) and its finished chunks.
- ``run``: the run on Dask (``run_study``), bounded, with progress and cancel.
- ``summary``: best designs, Pareto fronts, CSV.
- ``__main__``: the command line, ``python -m core.motor.study``.

    from core.motor.study import Axis, StudySpec, run_study, open_study
    spec = StudySpec("x0-preload", (Axis.grid("x0", -0.0199, -0.0001, 200),
                                    Axis.grid("preload", 0.01, 1.0, 200, "log")))
    result = run_study(spec, "studies/")        # a LocalCluster of this machine's CPUs
    ds = open_study(result.path)                # xarray Dataset: ds.no_load_speed, ...
"""

from core.motor.study.chunks import SENSE, VARIABLES, evaluate_chunk
from core.motor.study.run import StudyRun, run_study
from core.motor.study.spec import AXES, Axis, BaseDesign, StudySpec, load_spec, spec_from_toml
from core.motor.study.store import open_study, spec_of
from core.motor.study.summary import best, export_csv, pareto

__all__ = [
    "AXES",
    "SENSE",
    "VARIABLES",
    "Axis",
    "BaseDesign",
    "StudyRun",
    "StudySpec",
    "best",
    "evaluate_chunk",
    "export_csv",
    "load_spec",
    "open_study",
    "pareto",
    "run_study",
    "spec_from_toml",
    "spec_of",
]
