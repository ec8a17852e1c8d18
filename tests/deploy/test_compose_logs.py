"""Every container of the shipped compose files keeps a bounded log: Docker's json-file
driver with max-size and max-file (its default keeps every line it is given)."""

from __future__ import annotations

import re
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]

#: Docker's sizes: a number and a unit (k, m, g).
SIZE = re.compile(r"^(\d+)([kmg])$")


def default(value: str) -> str:
    """The default of a compose variable (``${NAME:-default}``), or `value` itself."""
    m = re.fullmatch(r"\$\{\w+:-([^}]*)\}", value)
    return m.group(1) if m else value


def test_every_service_logs_to_bounded_json_files():
    services = yaml.safe_load((ROOT / "docker" / "compose.yaml").read_text())["services"]
    assert {"app1", "app2", "balancer"} <= set(services)
    for name, service in services.items():
        logging = service.get("logging")
        assert logging and logging["driver"] == "json-file", name
        size = SIZE.match(default(logging["options"]["max-size"]))
        files = int(default(logging["options"]["max-file"]))
        assert size and int(size.group(1)) > 0 and 1 <= files <= 10, (name, logging)
        bound = int(size.group(1)) * {"k": 2**10, "m": 2**20, "g": 2**30}[size.group(2)] * files
        assert bound <= 2**30, f"{name} may keep {bound} bytes of log"  # at most 1 GiB


def test_the_tls_overlay_keeps_the_bounds():
    """compose.tls.yaml is merged over compose.yaml: it sets no logging of its own."""
    overlay = yaml.safe_load((ROOT / "docker" / "compose.tls.yaml").read_text())["services"]
    assert all("logging" not in s for s in overlay.values())
