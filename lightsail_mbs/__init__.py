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
    "paper_case": "lightsail_mbs.model.cases",
    "RunSettings": "lightsail_mbs.base.settings",
    "paper_settings": "lightsail_mbs.solvers.settings",
    "Result": "lightsail_mbs.result",
    "solve": "lightsail_mbs.analysis.runs",
}
_SUBMODULES = ("analysis", "base", "model", "paper", "result", "solvers", "studies", "viz", "cli")

if TYPE_CHECKING:
    from lightsail_mbs.analysis.runs import solve
    from lightsail_mbs.base.settings import RunSettings
    from lightsail_mbs.base.validation import ParameterError
    from lightsail_mbs.model.cases import paper_case
    from lightsail_mbs.model.parameters import SailParameters
    from lightsail_mbs.result import Result
    from lightsail_mbs.solvers.settings import paper_settings

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
