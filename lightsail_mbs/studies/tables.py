"""The one place that writes tables: CSV files and Markdown tables (printed or returned as text)."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np


def write_csv(path, rows: list[dict]) -> Path:
    """Rows of dicts (same keys) to a CSV file; returns its path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]) if rows else [])
        writer.writeheader()
        writer.writerows(rows)
    return path


def series_csv(path, time: np.ndarray, columns: dict) -> Path:
    """A time series CSV: column 'time_s' and one column per entry of `columns` (same length)."""
    rows = [dict(time_s=t, **{k: v[i] for k, v in columns.items()}) for i, t in enumerate(time)]
    return write_csv(path, rows)


def fmt(value, spec: str = ".4g") -> str:
    """A table cell: numbers formatted with `spec` (default 4 significant digits), yes/no for booleans,
    '–' for None and nan."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(value)
    if isinstance(value, (float, np.floating)):
        return format(value, spec)
    return str(value)


def print_table(title: str, rows: list[dict]) -> None:
    """A Markdown table of the rows (keys as the header) under a title line."""
    print(f"\n{title}")
    if not rows:
        print("(no rows)")
        return
    keys = list(rows[0])
    print("| " + " | ".join(keys) + " |")
    print("|" + "---|" * len(keys))
    for row in rows:
        print("| " + " | ".join(fmt(row[k]) for k in keys) + " |")


def markdown_table(rows: list[dict], columns: dict | None = None) -> str:
    """A Markdown table of the rows; columns: {key: header} (default every key of the first row)."""
    columns = columns or {k: k for k in rows[0]} if rows else (columns or {})
    lines = ["| " + " | ".join(columns.values()) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(fmt(row.get(k)) for k in columns) + " |" for row in rows]
    return "\n".join(lines)
