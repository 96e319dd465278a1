"""Files an algorithm writes beside its layers (CSV tables, JSON, plots), with errors that name the output."""
from __future__ import annotations

import csv

from qgis.core import QgsProcessingException


def write_rows_csv(path, rows: list[dict]) -> None:
    """One CSV line per row dict (None written as an empty cell)."""
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]) if rows else [])
        writer.writeheader()
        writer.writerows({k: ("" if v is None else v) for k, v in r.items()} for r in rows)


def write_output(path, name: str, write) -> None:
    """Run ``write(path)``, turning a file-system error into a message naming the output."""
    try:
        write(path)
    except OSError as exc:
        raise QgsProcessingException(f"{name}: cannot write {path} ({exc})") from exc
