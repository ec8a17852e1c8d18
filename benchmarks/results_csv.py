"""The CSV files of benchmarks/results/: one row per run, numbers to 6 significant digits
(read back by ``app.benchmark_charts.read_rows``, which the explorer reads them with)."""

from __future__ import annotations

import csv
from pathlib import Path

from app.benchmark_charts import read_rows as read_csv

__all__ = ["read_csv", "write_csv"]


def write_csv(rows: list[dict], path: Path, fields: list[str]) -> None:
    """Write ``rows`` with the columns ``fields``."""
    with path.open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=fields)
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v)
                             for k, v in row.items()})
