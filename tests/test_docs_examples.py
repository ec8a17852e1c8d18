"""The Python examples of README.md and docs/ run as written and give the numbers their
text states (a README whose example fails, or whose figures drift from the code, is a
defect the reader finds first)."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCUMENTS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def python_blocks(path: Path) -> list[str]:
    return re.findall(r"```python\n(.*?)```", path.read_text(), re.S)


def run_blocks(path: Path) -> dict:
    """Every Python block of `path`, in order, in one namespace (later blocks may use
    what earlier ones defined)."""
    namespace: dict = {}
    for block in python_blocks(path):
        exec(compile(block, str(path), "exec"), namespace)
    return namespace


EXAMPLES = [p for p in DOCUMENTS if python_blocks(p)]


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_every_python_example_runs_as_written(path: Path) -> None:
    run_blocks(path)


def test_the_readme_api_example_gives_the_numbers_it_states() -> None:
    ns = run_blocks(ROOT / "README.md")
    c = ns["c"]
    assert c.tau1 == pytest.approx(2.3562, abs=5e-5)  # "2.3562 (3 pi/4)"
    assert math.degrees(c.theta0) == pytest.approx(13.65, abs=5e-3)
    assert ns["coulomb_certificate"](c).worst < 1e-13  # "~1e-14"
    assert ns["s"].scales.T0 > 0  # the SI example's scales
    # (the Motor example's figures: tests/core/test_moving_rotor.py)
    # the traction and pressure examples broadcast r against tau
    assert ns["c"].traction(ns["r"][:, None], ns["tau"]).shape == (ns["r"].size,
                                                                   ns["tau"].size)
