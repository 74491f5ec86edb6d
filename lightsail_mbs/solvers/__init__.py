"""One solver interface: solve(params, solver="exudyn" | "reduced") -> Result.

Each solver is a module of this package exposing ``run(params, *, progress=False, **options)``.
"""
from __future__ import annotations

import importlib

from lightsail_mbs.model.parameters import ParameterError, SailParameters
from lightsail_mbs.result import Result

SOLVERS = {"exudyn": "exudyn.chain", "reduced": "reduced.solver"}


def solve(params: SailParameters, solver: str = "exudyn", *, progress: bool = False, **options) -> Result:
    """Run one case with the named solver and return its Result."""
    if solver not in SOLVERS:
        raise ParameterError(f"solver={solver!r} is invalid: allowed one of {', '.join(SOLVERS)}")
    module = importlib.import_module(f".{SOLVERS[solver]}", __name__)
    return module.run(params, progress=progress, **options)
