"""The snapshot journey's rows kept on disk as they are made, so that a rerun resumes (docs/journey.md).

**The file.** ``DIR/journey_rows.jsonl``: a first line ``{"key": K, "snapshots": n}``, then one line per finished
snapshot ``{"index": i, "beta": β_i, "row": {...}}`` in order, each written and flushed when its snapshot (and its
shape run) is done. K is the SHA-256 of the case's and the settings' fields (JSON, keys sorted): two journeys with
the same K compute the same snapshots at the same speeds, so a rerun reads the finished rows and computes only the
rest. Floats are written by ``json`` as their shortest repr, which reads back to the same double (NaN as ``NaN``):
a resumed journey's rows equal the uninterrupted one's exactly.

**What is not resumed.** A file whose key differs (another case or other settings) is started afresh, and the
report's ``resume`` entry says so. A last line cut short by an interruption, or a row whose index or speed does not
follow the previous one, ends what is read: the snapshots from there on are computed again.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

ROWS_FILE = "journey_rows.jsonl"


def key_of(case: dict, settings: dict) -> str:
    """K: the SHA-256 of the case's and the settings' fields (the journey's identity)."""
    text = json.dumps({"case": case, "settings": settings}, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()


class RowStore:
    """The rows of one journey (key) in folder/ROWS_FILE: :meth:`done` reads the finished ones, :meth:`add`
    appends one. ``resumed``: how many rows were read; ``discarded``: why a file's rows were not (None when
    there was nothing to discard)."""

    def __init__(self, folder, key: str, betas):
        self.path = Path(folder) / ROWS_FILE
        self.key, self.betas = key, [float(b) for b in betas]
        self.resumed, self.discarded = 0, None

    def done(self) -> list[dict]:
        """The finished rows of this journey, in order; a file of another journey is started afresh."""
        if not self.path.exists():
            self._start()
            return []
        lines = self.path.read_text(encoding="utf-8").splitlines()
        head = _parse(lines[0]) if lines else None
        if head is None or head.get("key") != self.key:
            self.discarded = f"{self.path} held another case's or other settings' rows: started afresh"
            self._start()
            return []
        rows = []
        for line in lines[1:]:
            entry = _parse(line)
            k = len(rows)
            if entry is None or entry.get("index") != k or k >= len(self.betas) or entry.get("beta") != self.betas[k]:
                break
            rows.append(entry["row"])
        self._start(rows)
        self.resumed = len(rows)
        return rows

    def add(self, row: dict) -> None:
        """Append the next finished snapshot's row (flushed at once)."""
        index = self._count
        with self.path.open("a", encoding="utf-8") as handle:
            handle.write(json.dumps({"index": index, "beta": self.betas[index], "row": row}) + "\n")
        self._count += 1

    def report(self) -> dict:
        """The report's ``resume`` entry: the file, the rows read from it, and why a file was started afresh."""
        return {"file": str(self.path), "resumed": self.resumed, "discarded": self.discarded}

    def _start(self, rows=()) -> None:
        """Rewrite the file: the header and the rows kept (dropping a cut-short or stray tail)."""
        self.path.parent.mkdir(parents=True, exist_ok=True)
        lines = [json.dumps({"key": self.key, "snapshots": len(self.betas)})]
        lines += [json.dumps({"index": i, "beta": self.betas[i], "row": row}) for i, row in enumerate(rows)]
        self.path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        self._count = len(rows)


def _parse(line: str):
    try:
        value = json.loads(line)
    except ValueError:
        return None
    return value if isinstance(value, dict) else None
