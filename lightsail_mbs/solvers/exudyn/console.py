"""Exudyn prints to stdout by default; the commands print JSON there. One switch for every Exudyn call, the
one way a run drives Exudyn's solver silently with its failures recorded, not raised, and the size of
system it can take."""

from __future__ import annotations

from collections.abc import Callable
from contextlib import contextmanager

import numpy as np

from lightsail_mbs.base.validation import ParameterError

# Exudyn 1.13 ends the process with a segmentation fault in SolveSteps, at the first step, on a system of
# more second-order coordinates than this: measured on the sheet (6 per tile), 7722 tiles (46,332) run and
# 7728 tiles (46,368) crash, where n² of the n coordinates passes 2³¹ − 1 (a 32-bit index).
MAX_COORDINATES = 46_340


@contextmanager
def silenced():
    """Turn Exudyn's console output off for the duration of the block (restored afterwards)."""
    import exudyn as exu

    printing = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        yield
    finally:
        exu.config.printToConsole = printing


def solve_steps(
    solver, mbs, settings, bar, *, failure: str, stopped: Callable[[], bool], initialised: Callable | None = None
) -> str | None:
    """Initialise, run and finalise Exudyn's `solver` on `mbs`, silenced; returns the run's error or None.

    initialised(): called once the solver is initialised, before the first step. A solve that fails
    when not stopped() (the post-step function's stop rule) is the error "<failure> at t = … s (exudyn:
    …)"; a non-finite state and an Exudyn exception are errors too. The progress bar ends at the time
    reached."""
    import exudyn as exu

    error = None
    try:
        with silenced():
            solver.InitializeSolver(mbs, settings)
            if initialised is not None:
                initialised()
            ok = solver.SolveSteps(mbs, settings)
            if not ok and not stopped():
                error = f"{failure} at t = {solver.it.currentTime:.9g} s (exudyn: {solver.GetErrorString()})"
            elif not np.all(np.isfinite(mbs.systemData.GetODE2Coordinates())):
                error = f"non-finite state at t = {solver.it.currentTime:.9g} s"
            solver.FinalizeSolver(mbs, settings)
    except exu.ExudynError as exc:  # solver failures are results, not crashes
        error = f"exudyn: {exc}".strip()
    finally:
        bar.update(float(solver.it.currentTime))
        bar.close()
    return error


def check_size(coordinates: int, bodies: str, per_body: int) -> None:
    """One line, before building the system, for a case larger than Exudyn can integrate (MAX_COORDINATES);
    `bodies` names the case's bodies (e.g. "7744 tiles"), each with `per_body` coordinates."""
    if coordinates > MAX_COORDINATES:
        raise ParameterError(
            f"{bodies} ({coordinates} coordinates) is too large for Exudyn: allowed ≤ {MAX_COORDINATES} coordinates "
            f"(about {MAX_COORDINATES // per_body} bodies; Exudyn 1.13 crashes beyond); use --solver reduced"
        )
