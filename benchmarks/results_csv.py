"""The CSV files of benchmarks/results/: one row per run, numbers to 6 significant digits."""

from __future__ import annotations

import csv
from pathlib import Path

TEXT = {"method", "regime", "kind", "peer"}
INTEGER = {"resolution", "steps", "points", "peer_points", "cf_n", "cf_points"}


def _value(key: str, text: str):
    if key in TEXT:
        return text
    if key in INTEGER:
        return int(text)
    return float(text)


def read_csv(path: Path) -> list[dict]:
    """Rows written by ``write_csv`` (numbers back to int / float)."""
    with path.open() as fh:
        return [{k: _value(k, v) for k, v in row.items()} for row in csv.DictReader(fh)]


def write_csv(rows: list[dict], path: Path, fields: list[str]) -> None:
    """Write ``rows`` with the columns ``fields``."""
    with path.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=fields)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v)
                             for k, v in row.items()})
