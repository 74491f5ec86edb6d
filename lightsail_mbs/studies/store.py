"""The on-disk case store of a sweep: one JSON record per finished case, named by the case key.

A record is written atomically (temporary file, then ``os.replace``), so a file either holds a
whole record or does not exist: its presence marks the case as finished, whatever killed the sweep.
Optional full Results go to ``results/<key>.npz`` (and its ``.json`` summary) and are written
*before* the record, so a record never points at a missing Result.

A record is served only while it is current: it carries the ``code_version`` of the code that made it
(:func:`lightsail_mbs.result.code_version`, a hash of the sources that decide a run's numbers and its
record and of the numerical libraries' versions), and a
record made by other code is *stale*; a record that does not parse, or lacks its key, status or code
version, is *corrupt*; a record whose saved Result is missing or unreadable is *incomplete*. All three
count as not finished: the sweep recomputes them. :meth:`CaseStore.audit` reports them without
recomputing (``lightsail-mbs store DIR``).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.result import code_version, write_atomically

REQUIRED = ("key", "status", "code_version")


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
        try:
            if self.directory.exists() and not self.directory.is_dir():
                raise NotADirectoryError(20, "a file, not a folder")
            self.directory.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise ParameterError(
                f"store_dir={str(directory)!r} is invalid: allowed a folder this process can create and write "
                f"({exc.strerror or exc})"
            ) from None

    def record_path(self, key: str) -> Path:
        return self.directory / f"{key}.json"

    def result_path(self, key: str) -> Path:
        return self.directory / "results" / f"{key}.npz"

    def state(self, key: str, with_result: bool = False) -> str:
        """ "current", "missing", "corrupt", "stale" or (a current record without its asked-for saved
        Result) "incomplete"."""
        path = self.record_path(key)
        if not path.exists():
            return "missing"
        record = self._read(path)
        if record is None or record.get("key") != key:
            return "corrupt"
        if record["code_version"] != code_version():
            return "stale"
        if with_result and not self._result_matches(key, record):
            return "incomplete"
        return "current"

    def has(self, key: str, with_result: bool = False) -> bool:
        """True when the case is finished by the current code (and, if asked, its full Result is there)."""
        return self.state(key, with_result) == "current"

    def load(self, key: str) -> dict:
        return json.loads(self.record_path(key).read_text())

    def keys(self) -> list[str]:
        return sorted(p.stem for p in self.directory.glob("*.json"))

    def records(self) -> list[dict]:
        """Every current record in the store (e.g. to plot a map without rerunning anything)."""
        return [self.load(key) for key in self.keys() if self.has(key)]

    def audit(self) -> dict:
        """Counts and keys of the records by state (current, stale, corrupt, incomplete: a record with a
        result_path whose Result is missing or unreadable)."""
        found = {"current": [], "stale": [], "corrupt": [], "incomplete": []}
        for key in self.keys():
            state = self.state(key)
            if state == "current" and "result_path" in (self._read(self.record_path(key)) or {}):
                state = self.state(key, with_result=True)
            found[state].append(key)
        return found

    def write(self, key: str, record: dict) -> dict:
        """Write the record, stamped with the current code_version, atomically (a reader sees the old
        file, or the whole new one); returns the stamped record."""
        path = self.record_path(key)
        record = {**record, "code_version": code_version()}
        text = json.dumps(record, indent=1, sort_keys=True, default=_jsonable_or_repr) + "\n"
        write_atomically(path, lambda handle: handle.write(text.encode()))
        return record

    def save_result(self, key: str, result) -> Path:
        """Save a full Result (arrays) next to the records; returns the .npz path."""
        return result.save(self.result_path(key))

    @staticmethod
    def _read(path: Path) -> dict | None:
        """The record at path, or None if it does not parse or lacks a required entry."""
        try:
            record = json.loads(path.read_text())
        except (OSError, ValueError):
            return None
        if not isinstance(record, dict) or any(name not in record for name in REQUIRED):
            return None
        return record

    def _result_matches(self, key: str, record: dict) -> bool:
        """The saved Result loads as a whole run (Result.load: archive intact, every entry and array there)
        and is the run of this record's case (the same parameters and settings)."""
        from lightsail_mbs.base.validation import ParameterError
        from lightsail_mbs.result import Result, RunFileError

        try:
            saved = Result.load(self.result_path(key))
        except (RunFileError, ParameterError):
            return False
        same = json.loads(to_json([saved.params.to_dict(), saved.settings.to_dict()]))
        return same == [record.get("parameters"), record.get("settings")]
