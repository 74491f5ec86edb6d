"""``solve`` as users call it (``lightsail_mbs.solve``): a run of the solver template with the verdicts
analysis makes of its case.

:func:`lightsail_mbs.solvers.solve` runs a case (failure located by event, the uncertainty twins); this
adds what only analysis can say, from the case's linear growth-rate spectrum: whether the answer has a
continuum limit in n (:mod:`lightsail_mbs.analysis.resolvedness`), recorded in ``Result.info`` and, when
the case is ill-posed in n, one line in ``Result.warnings``; where it is well posed and the uncertainty is
estimated, the error in n from a twin at n/2, added to the ± (:mod:`lightsail_mbs.analysis.n_error`). Sweeps
call the template alone.
"""

from __future__ import annotations

import time

from lightsail_mbs import solvers
from lightsail_mbs.analysis import n_error, resolvedness
from lightsail_mbs.solvers import twin_workers


def solve(
    params, solver: str = "exudyn", settings=None, *, progress: bool = False, uncertainty: bool = True, **options
):
    """:func:`lightsail_mbs.solvers.solve` (same arguments), then the resolvedness verdict of the case and, with
    the uncertainty estimated, the n-error folded into its ± (:mod:`lightsail_mbs.analysis.n_error`). The n-twins
    run in the same session of twin workers as the uncertainty's (:mod:`lightsail_mbs.solvers.twin_workers`): they
    start beside the base run, at the loose twin's options the solver declares, where the base run is long.
    ``Result.uncertainty["elapsed"]``: the wall time from the base run's start to the n-error's end."""
    start = time.perf_counter()
    with twin_workers.session(enabled=uncertainty) as twins:
        if uncertainty:
            twins.extra.append(lambda reference: n_error.jobs(params, solver, settings, reference, progress))
        result = solvers.solve(params, solver, settings, progress=progress, uncertainty=uncertainty, **options)
        resolvedness.annotate(params, result)
        if uncertainty:
            n_error.fold(params, solver, settings, options, result, progress=progress)
    if uncertainty and result.uncertainty:
        result.uncertainty["elapsed"] = time.perf_counter() - start
    return result
