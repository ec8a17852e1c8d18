"""The CSV files of benchmarks/results/: one row per run, numbers to 6 significant digits.

The explorer shows two of them (speed_accuracy.csv, stability_map.csv) from its own
copy, read with its own reader (``make bench-charts`` publishes them to ``app/results/``).
"""

from __future__ import annotations

import csv
from pathlib import Path

#: Columns read as text and as whole numbers (every other column is a float).
TEXT = {"method", "regime", "kind", "peer"}
INTEGER = {"resolution", "steps", "points", "peer_points", "cf_n", "cf_points"}


def write_csv(rows: list[dict], path: Path, fields: list[str]) -> None:
    """Write ``rows`` with the columns ``fields``."""
    with path.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=fields)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v)
                             for k, v in row.items()})


def read_csv(path: Path) -> list[dict]:
    """The rows of a results file, numbers back to int and float."""
    def value(key: str, text: str):
        return text if key in TEXT else int(text) if key in INTEGER else float(text)

    with path.open(newline="") as fh:
        return [{k: value(k, v) for k, v in row.items()} for row in csv.DictReader(fh)]
