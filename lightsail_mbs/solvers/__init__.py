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

Each solver is declared once per model family in :mod:`lightsail_mbs.solvers.registry`, under the
numbered contract of :mod:`lightsail_mbs.solvers.contract` (options schema checked before solving,
the hooks of the uncertainty estimate, capabilities); ``SOLVERS`` names them. A third solver is a new
folder here and its registration.
"""

from __future__ import annotations

import time
from typing import TYPE_CHECKING

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers import contract, events, registry, twin_workers  # noqa: F401 - registry: the declarations
from lightsail_mbs.solvers.settings import paper_settings
from lightsail_mbs.solvers.skeleton import interrupts_propagate

if TYPE_CHECKING:
    from lightsail_mbs.result import Result

SOLVERS = contract.names()  # the registered solver names

__all__ = ["SOLVERS", "RunSettings", "paper_settings", "solve"]


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
        A registered solver (``SOLVERS``): Exudyn's KinematicTree chain or the in-house reduced-Lagrangian
        chain; for model "sheet", Exudyn's rigid tiles (solvers.exudyn.sheet) or the in-house tile solver
        (solvers.reduced.sheet). A solver without the case's model family is refused in one line.
    settings : RunSettings, optional
        Duration, output interval and stop rule (default ``RunSettings()``: 6 s, stop at failure). An
        output interval left at None follows the case's fastest time scale, and a failure time found
        between coarse samples is located by reruns at finer intervals (:mod:`lightsail_mbs.solvers.events`);
        the Result keeps the settings asked for, and ``info["sampling"]`` the interval and end of the run
        it reports.
    progress : bool
        Show a progress bar on stderr.
    uncertainty : bool
        Estimate the answer's uncertainty and conditioning from twin runs (tolerances loosened; start
        perturbed at round-off level; a film), stored in ``Result.uncertainty``; the Result returned is the
        base run (a tightened twin where the loose twin finds the base run inaccurate:
        :mod:`lightsail_mbs.solvers.uncertainty`). Its twins cost 2–4 base runs of CPU; on more than one core
        they run in worker processes beside the base run (:mod:`lightsail_mbs.solvers.twin_workers`). Sweeps
        turn it off.
    **options
        The solver's own numerical options (its schema in :mod:`lightsail_mbs.solvers.registry`); an
        unknown option or a value outside its range raises ParameterError before anything is solved.
    """
    engine = contract.lookup(solver, params)
    if settings is None:
        settings = RunSettings()
    if not isinstance(settings, RunSettings):
        raise ParameterError(f"settings={settings!r} is invalid: allowed a RunSettings")
    engine.check_options(options)
    with interrupts_propagate(), twin_workers.session(enabled=uncertainty) as twins:
        start, start_wall = time.process_time(), time.perf_counter()
        if uncertainty:
            from lightsail_mbs.solvers import uncertainty as estimate

            twins.speculation = estimate.speculation(engine, params, options, progress)
        base = twins.watching(engine) if uncertainty else engine
        result, sampled = events.located_run(base, params, settings, options, progress=progress)
        twins.base_ended()
        if uncertainty:
            base_cpu = time.process_time() - start  # the base run's, its reruns that locate a failure included
            result = estimate.assess(engine, params, sampled, options, result, progress=progress, base_cpu=base_cpu)
            result.uncertainty["elapsed"] = time.perf_counter() - start_wall  # the twins' sum is wall_time
    result.settings = settings  # the run control asked for; info["sampling"] says how it was sampled
    return result
