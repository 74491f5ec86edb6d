"""lightsail-mbs: does a laser-driven lightsail keep its shape under the beam, or crumple?

Data flows one way: case (SailParameters) → initial shape → solver (exudyn | reduced, with RunSettings)
→ Result → analysis → studies, reports, figures, frames.

The public names below are imported on first use (PEP 562), so ``import lightsail_mbs.cli`` or
``lightsail_mbs.model`` pays only for what it uses.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

from lightsail_mbs.base.constants import VERSION

# public name -> module that defines it
_PUBLIC = {
    "ParameterError": "lightsail_mbs.base.validation",
    "SailParameters": "lightsail_mbs.model.parameters",
    "paper_case": "lightsail_mbs.model.parameters",
    "RunSettings": "lightsail_mbs.base.settings",
    "paper_settings": "lightsail_mbs.solvers.settings",
    "Result": "lightsail_mbs.result",
    "solve": "lightsail_mbs.solvers",
}
_SUBMODULES = ("analysis", "base", "model", "paper", "result", "solvers", "studies", "viz", "cli")

if TYPE_CHECKING:
    from lightsail_mbs.base.settings import RunSettings
    from lightsail_mbs.base.validation import ParameterError
    from lightsail_mbs.model.parameters import SailParameters, paper_case
    from lightsail_mbs.result import Result
    from lightsail_mbs.solvers import solve
    from lightsail_mbs.solvers.settings import paper_settings

# the package's files that hold numba kernels compiled with cache=True (tests/test_package.py checks the list)
KERNEL_SOURCES = (
    "model/loads.py",
    "model/optics.py",
    "solvers/exudyn/tree.py",
    "solvers/reduced/dop853.py",
    "solvers/reduced/dynamics.py",
    "solvers/reduced/newton.py",
    "solvers/reduced/radau.py",
    "solvers/reduced/sampling.py",
    "solvers/reduced/sheet.py",
)


def _drop_stale_kernels() -> None:
    """Keep numba's cached machine code only while every kernel source is the one it was compiled from.

    numba keys each cached function on its own file's time stamp and size, but a kernel inlines the kernels
    it calls from other files (an integrator inlines the right-hand side), so after an edit of one file the
    others would load machine code built from the old source. ``__pycache__/numba-kernel-sources`` records
    the size, time stamp (ns) and SHA-256 of every kernel source at compilation:

    * all sizes and time stamps as recorded: nothing to do (every import after the first);
    * a source with another time stamp but the recorded content (an install: pip writes the files anew,
      after the kernels were compiled into the wheel at build time): its recorded time stamp is restored,
      so numba's own check accepts the cache;
    * any content changed: every ``*.nbi``/``*.nbc`` of the kernel sources is removed and the record
      rewritten; numba compiles afresh.

    A read-only install is left as it is."""
    import hashlib
    import os
    from pathlib import Path

    root = Path(__file__).parent
    record = root / "__pycache__" / "numba-kernel-sources"
    try:
        stats = {name: (root / name).stat() for name in KERNEL_SOURCES}
        recorded = {}
        for line in record.read_text().splitlines() if record.is_file() else ():
            fields = line.split()
            if len(fields) == 4 and fields[1].isdigit() and fields[2].isdigit():
                recorded[fields[0]] = (int(fields[1]), int(fields[2]), fields[3])
        if all(recorded.get(n, (None, None))[:2] == (st.st_size, st.st_mtime_ns) for n, st in stats.items()):
            return
        digests = {name: hashlib.sha256((root / name).read_bytes()).hexdigest() for name in KERNEL_SOURCES}
        if all(recorded.get(n, (0, 0, None))[2] == d for n, d in digests.items()):
            for name, st in stats.items():
                os.utime(root / name, ns=(st.st_atime_ns, recorded[name][1]))
            return
        for name in KERNEL_SOURCES:
            source = root / name
            for cached in (source.parent / "__pycache__").glob(f"{source.stem}.*.nb[ic]"):
                cached.unlink(missing_ok=True)
        record.parent.mkdir(exist_ok=True)
        lines = (f"{n} {st.st_size} {st.st_mtime_ns} {digests[n]}" for n, st in stats.items())
        record.write_text("\n".join(lines))
    except OSError:
        pass


_drop_stale_kernels()

__all__ = ["ParameterError", "SailParameters", "RunSettings", "paper_case", "paper_settings", "Result", "solve"]
__version__ = VERSION


def __getattr__(name: str):
    if name in _PUBLIC:
        value = getattr(importlib.import_module(_PUBLIC[name]), name)
        globals()[name] = value
        return value
    if name in _SUBMODULES:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_PUBLIC) | set(_SUBMODULES))
