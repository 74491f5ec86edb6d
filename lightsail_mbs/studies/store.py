"""The on-disk case store of a sweep: one JSON record per finished case, named by the case key.

A record is written atomically (temporary file, then ``os.replace``), so a file either holds a
whole record or does not exist: its presence marks the case as finished, whatever killed the sweep.
Optional full Results go to ``results/<key>.npz`` (and its ``.json`` summary) and are written
*before* the record, so a record never points at a missing Result.
"""
from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

import numpy as np


def to_json(value) -> str:
    """Canonical JSON (sorted keys) of records and case descriptions; numpy scalars and arrays allowed."""
    return json.dumps(value, sort_keys=True, default=_jsonable)


def _jsonable(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, Path):
        return str(value)
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")


def _jsonable_or_repr(value):
    """For records: an odd solver statistic is kept as its repr rather than losing the case."""
    try:
        return _jsonable(value)
    except TypeError:
        return repr(value)


class CaseStore:
    """A directory of finished cases: ``<key>.json`` records and optional ``results/<key>.npz``."""

    def __init__(self, directory):
        self.directory = Path(directory)
        self.directory.mkdir(parents=True, exist_ok=True)

    def record_path(self, key: str) -> Path:
        return self.directory / f"{key}.json"

    def result_path(self, key: str) -> Path:
        return self.directory / "results" / f"{key}.npz"

    def has(self, key: str, with_result: bool = False) -> bool:
        """True when the case is finished (and, if asked, its full Result was saved)."""
        if not self.record_path(key).exists():
            return False
        return not with_result or self.result_path(key).exists()

    def load(self, key: str) -> dict:
        return json.loads(self.record_path(key).read_text())

    def keys(self) -> list[str]:
        return sorted(p.stem for p in self.directory.glob("*.json"))

    def records(self) -> list[dict]:
        """Every finished case in the store (e.g. to plot a map without rerunning anything)."""
        return [self.load(key) for key in self.keys()]

    def write(self, key: str, record: dict) -> Path:
        """Write the record atomically: a reader sees the old file, or the whole new one."""
        path = self.record_path(key)
        text = json.dumps(record, indent=1, sort_keys=True, default=_jsonable_or_repr) + "\n"
        fd, tmp = tempfile.mkstemp(dir=self.directory, prefix=f".{key}.", suffix=".tmp")
        try:
            with os.fdopen(fd, "w") as handle:
                handle.write(text)
                handle.flush()
                os.fsync(handle.fileno())
            os.replace(tmp, path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
        return path

    def save_result(self, key: str, result) -> Path:
        """Save a full Result (arrays) next to the records; returns the .npz path."""
        return result.save(self.result_path(key))
