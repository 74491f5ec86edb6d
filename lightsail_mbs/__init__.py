"""lightsail-mbs: does a laser-driven lightsail keep its shape under the beam, or crumple?

Data flows one way: case (SailParameters) → initial shape → solver (exudyn | reduced, with RunSettings)
→ Result → analysis → studies, reports, figures, frames.

The public names below are imported on first use (PEP 562), so ``import lightsail_mbs.cli`` or
``lightsail_mbs.model`` pays only for what it uses.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

# public name -> module that defines it
_PUBLIC = {
    "ParameterError": "lightsail_mbs.model.parameters",
    "SailParameters": "lightsail_mbs.model.parameters",
    "paper_case": "lightsail_mbs.model.parameters",
    "RunSettings": "lightsail_mbs.solvers.settings",
    "paper_settings": "lightsail_mbs.solvers.settings",
    "Result": "lightsail_mbs.result",
    "solve": "lightsail_mbs.solvers",
}
_SUBMODULES = ("analysis", "model", "paper", "result", "solvers", "studies", "viz", "cli")

if TYPE_CHECKING:
    from lightsail_mbs.model.parameters import ParameterError, SailParameters, paper_case
    from lightsail_mbs.result import Result
    from lightsail_mbs.solvers import solve
    from lightsail_mbs.solvers.settings import RunSettings, paper_settings

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
    """Delete numba's cached machine code of every kernel when any kernel source changed since it was cached.

    numba keys each cached function on its own file's time stamp and size only, but a kernel inlines the kernels it
    calls from other files (an integrator inlines the right-hand side), so after an edit of one file the
    others would load machine code built from the old source. The sizes and time stamps of all kernel
    sources are kept in ``__pycache__/numba-kernel-sources``; when they differ, every ``*.nbi``/``*.nbc`` of
    those files is removed and numba compiles afresh. A read-only install is left as it is."""
    from pathlib import Path

    root = Path(__file__).parent
    try:
        stamp = "\n".join(
            f"{name} {(root / name).stat().st_size} {(root / name).stat().st_mtime!r}" for name in KERNEL_SOURCES
        )
        record = root / "__pycache__" / "numba-kernel-sources"
        if record.is_file() and record.read_text() == stamp:
            return
        for name in KERNEL_SOURCES:
            source = root / name
            for cached in (source.parent / "__pycache__").glob(f"{source.stem}.*.nb[ic]"):
                cached.unlink(missing_ok=True)
        record.parent.mkdir(exist_ok=True)
        record.write_text(stamp)
    except OSError:
        pass


_drop_stale_kernels()

__all__ = ["ParameterError", "SailParameters", "RunSettings", "paper_case", "paper_settings", "Result", "solve"]
__version__ = "0.1.0"


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
