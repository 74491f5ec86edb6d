"""One solver interface: ``solve(params, solver, settings) -> Result``.

How to run a case:

1. Describe the sail: ``params = SailParameters(model="torsion", youngs_modulus=4.5e9)`` (or
   ``paper_case("torsion-soft")``).
2. Say how the run is watched: ``settings = RunSettings(t_final=6.0)`` (duration, output interval,
   stop rule; ``paper_settings(name)`` for the paper's cases).
3. ``result = solve(params, "reduced", settings)`` (or ``"exudyn"``), with the solver's own options
   as keywords (Exudyn: ``step_size``, ``newton_rel_tol``, …; reduced: ``rtol``, ``method``, …).
4. Read the :class:`~lightsail_mbs.result.Result`: ``result.failure_time``, its
   ``result.failure_time_uncertainty`` and ``result.well_conditioned`` (twin runs, on by default:
   :mod:`lightsail_mbs.solvers.uncertainty`), ``result.summary()``, ``result.save("run.npz")``.

The chain and the sheet are dispatched by ``params.model`` (``SOLVERS``, ``SHEET_SOLVERS``). Each
solver is a module exposing
``run(params, settings, *, progress=False, **options)`` that keeps the contract of
:mod:`lightsail_mbs.solvers.skeleton` (sampling, stop rule, errors as results). A third solver is a
new folder here and one line in ``SOLVERS``.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers.settings import paper_settings
from lightsail_mbs.solvers.skeleton import interrupts_propagate

if TYPE_CHECKING:
    from lightsail_mbs.result import Result

SOLVERS = {"exudyn": "exudyn.chain", "reduced": "reduced.solver"}
# the same solvers for the sheet (model "sheet"): Exudyn's rigid tiles and the in-house tile solver
SHEET_SOLVERS = {"exudyn": "exudyn.sheet", "reduced": "reduced.sheet"}

__all__ = ["SHEET_SOLVERS", "SOLVERS", "RunSettings", "paper_settings", "solve", "solver_module"]


def solver_module(params: SailParameters, solver: str) -> str:
    """The module (relative to this package) that runs `solver` for the model family of `params`."""
    return (SHEET_SOLVERS if params.model == "sheet" else SOLVERS)[solver]


def solve(
    params: SailParameters,
    solver: str = "exudyn",
    settings: RunSettings | None = None,
    *,
    progress: bool = False,
    uncertainty: bool = True,
    **options,
) -> Result:
    """Run one case with the named solver and return its Result.

    Parameters
    ----------
    params : SailParameters
        The physical case.
    solver : {"exudyn", "reduced"}
        The engine: Exudyn's KinematicTree chain or the in-house reduced-Lagrangian chain; for
        model "sheet", Exudyn's rigid tiles (solvers.exudyn.sheet) or the in-house tile solver
        (solvers.reduced.sheet).
    settings : RunSettings, optional
        Duration, output interval and stop rule (default ``RunSettings()``: 6 s, stop at failure).
    progress : bool
        Show a progress bar on stderr.
    uncertainty : bool
        Estimate the answer's uncertainty and conditioning from twin runs (tolerances tightened; start
        perturbed at round-off level), stored in ``Result.uncertainty``; the Result returned is then the
        tightest run's (:mod:`lightsail_mbs.solvers.uncertainty`). Costs about 2–7 more runs. Sweeps
        turn it off.
    **options
        The solver's own numerical options (see its module); an unknown one raises ParameterError.
    """
    if solver not in SOLVERS:
        raise ParameterError(f"solver={solver!r} is invalid: allowed one of {', '.join(SOLVERS)}")
    if settings is None:
        settings = RunSettings()
    if not isinstance(settings, RunSettings):
        raise ParameterError(f"settings={settings!r} is invalid: allowed a RunSettings")
    module = importlib.import_module(f".{solver_module(params, solver)}", __name__)
    with interrupts_propagate():
        result = module.run(params, settings, progress=progress, **options)
        if uncertainty:
            from lightsail_mbs.solvers import uncertainty as estimate

            result = estimate.assess(module, params, settings, options, result)
    return result
