"""What made a Result: the package's code_version and the provenance every Result records.

``code_version`` is the version of everything that decides a run's numbers and its stored record: a
hash of the source files in :data:`RESULT_SOURCES` (the leaf layer, the case and its physics, the solvers, the
Result, the failure rule and the energy of its summary, and the functions that turn a run into a sweep record:
studies/runners.py's, and studies/ride_maps.py's with the ride histories of analysis/ride3d.py)
together with the versions of the numerical libraries in :data:`LIBRARIES`. A change to any of them, and
only that, makes stored results stale (:mod:`lightsail_mbs.studies.store` recomputes them). Python and the
platform are recorded but not hashed: a numba-compiled loop may round differently on another CPU, which
moves numbers at the level of round-off, not of the physics.
"""

from __future__ import annotations

import functools
import hashlib
import platform
import subprocess
from datetime import datetime, timezone
from importlib import metadata
from pathlib import Path

from lightsail_mbs.base.constants import VERSION

PACKAGE = Path(__file__).resolve().parent.parent  # the lightsail_mbs folder
# what decides the numbers of a run and of its sweep record, relative to the package folder: folders (every
# .py file below them, at any depth) and single files
RESULT_SOURCES = (
    "base",
    "model",
    "solvers",
    "result.py",
    "studies/runners.py",
    "studies/ride_maps.py",
    "analysis/ride3d.py",
)
LIBRARIES = ("exudyn", "numpy", "scipy", "numba")  # their versions are part of code_version


@functools.cache
def code_version() -> str:
    """SHA-256 (first 16 hex digits) of the source files that decide a run's numbers and its record
    (RESULT_SOURCES) and of the versions of the numerical libraries (LIBRARIES)."""
    digest = hashlib.sha256()
    for path in result_source_files():
        digest.update(path.relative_to(PACKAGE).as_posix().encode())
        digest.update(path.read_bytes())
    for name in LIBRARIES:
        digest.update(f"{name}=={_library_version(name)}".encode())
    return digest.hexdigest()[:16]


def result_source_files() -> list[Path]:
    """The files code_version hashes: each file of RESULT_SOURCES and every .py file below each of its
    folders, however deep (a new subfolder is hashed as soon as it exists)."""
    files = []
    for entry in RESULT_SOURCES:
        path = PACKAGE / entry
        if path.is_dir():
            files += sorted(path.rglob("*.py"))
        elif path.is_file():
            files.append(path)
    return files


def _library_version(name: str) -> str | None:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return None


@functools.cache
def _static_provenance() -> dict:
    return {
        "package": "lightsail-mbs",
        "version": VERSION,
        "code_version": code_version(),
        **_git(),
        **{name: _library_version(name) for name in LIBRARIES},
        "python": platform.python_version(),
        "platform": platform.platform(),
    }


def _git() -> dict:
    """The commit (and whether the tree had uncommitted changes) when the package runs from a git checkout."""
    top = next((d for d in (PACKAGE, *PACKAGE.parents) if (d / ".git").exists()), None)
    if top is None:
        return {"git_commit": None, "git_dirty": None}
    try:
        run = functools.partial(subprocess.run, cwd=top, capture_output=True, text=True, timeout=5, check=True)
        commit = run(["git", "rev-parse", "HEAD"]).stdout.strip()
        dirty = bool(run(["git", "status", "--porcelain", "--untracked-files=no"]).stdout.strip())
    except (OSError, subprocess.SubprocessError):
        return {"git_commit": None, "git_dirty": None}
    return {"git_commit": commit, "git_dirty": dirty}


def provenance() -> dict:
    """What makes a Result now: versions, code_version, git commit, platform and the time (UTC)."""
    return {**_static_provenance(), "created": datetime.now(timezone.utc).isoformat(timespec="seconds")}
