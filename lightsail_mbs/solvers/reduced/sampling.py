"""What the reduced solver's free and supported chains share around their integrators: the tolerance
scales of the state, the adapters that hand the run skeleton (solvers.skeleton.collect_samples) the
states at the output times, and the Result assembled from those states.
"""

from __future__ import annotations

import math
import time as clock

import numpy as np

from lightsail_mbs import analysis
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.progress import Progress
from lightsail_mbs.solvers.reduced.dop853 import FINISHED as DONE
from lightsail_mbs.solvers.reduced.dop853 import STATUS
from lightsail_mbs.solvers.reduced.kinematics import ChainModel, centre_velocities, centres
from lightsail_mbs.solvers.settings import RunSettings
from lightsail_mbs.solvers.skeleton import FINISHED, FailureMonitor, collect_samples

CHUNK = 50  # output samples per call of a compiled integrator (failure check and progress in between)
SOLVER_ERRORS = (np.linalg.LinAlgError, ValueError, FloatingPointError)


def state_scales(model: ChainModel, waves: float) -> np.ndarray:
    """Typical magnitudes of y = (q, q̇) for the absolute tolerances.

    Positions (x₁, y₁ and the extensions z, which therefore carry the same absolute accuracy as the
    transverse displacements: the stiff axial vibration at √(k_s/m) is then not resolved but damped by
    the L-stable implicit method, as in Exudyn's generalized-α): the defect amplitude a₀
    (p.displacement_scale: 1e-6 L for a flat sail), or the static tip deflection P₀L³/(3EI) if larger.
    Angles: the slope 2π·waves·position/L of a sine with `waves` wavelengths over L (the free sail:
    its defect's ν). Rates: those over the fastest bending, tension or axial time scale of the chain
    (floored by a 1 ms time scale).
    """
    p = model.params
    position = p.displacement_scale
    bending = p.youngs_modulus * p.second_moment_of_area if model.torsional_stiffness else 0.0
    if p.tip_load and bending:
        position = max(position, abs(p.tip_load) * p.length**3 / (3 * bending))
    rate = 1e3
    if model.torsional_stiffness:
        rate = max(rate, math.sqrt(model.torsional_stiffness / model.inertia))
    if model.tension:
        rate = max(rate, math.sqrt(model.tension / (model.mass * 2 * model.half_length)))
    scales = [position, position] + [2 * math.pi * waves * position / p.length] * p.n
    if model.extensible:
        scales += [position] * (p.n - 1)
        rate = max(rate, math.sqrt(model.axial_stiffness / model.mass))
    scales = np.array(scales)
    return np.concatenate([scales, scales * rate])


def compiled_advance(method: str, integrator):
    """Adapter of a compiled integrator (dop853.Dop853, radau.Radau) for collect_samples."""

    def advance(times):
        batch = integrator.advance(times)
        status = None
        if integrator.status in STATUS:
            status = f"{method} failed at t = {integrator.t:.6g} s: {STATUS[integrator.status]}"
        elif integrator.status == DONE:
            status = FINISHED
        return batch, integrator.t, status

    return advance


def stepper_advance(method: str, integrator, size: int):
    """Adapter of a scipy OdeSolver (one step per call; every output time passed is interpolated from
    its dense output) for collect_samples; counts the steps in integrator.steps."""
    integrator.steps = 0
    nothing = np.zeros((size, 0))

    def advance(times):
        try:
            message = integrator.step()
            integrator.steps += 1
            if integrator.status == "failed" or not np.all(np.isfinite(integrator.y)):
                return (
                    nothing,
                    integrator.t,
                    f"{method} failed at t = {integrator.t:.6g} s: {message or 'non-finite state'}",
                )
            stop = int(np.searchsorted(times, integrator.t, side="right"))
            batch = integrator.dense_output()(times[:stop]) if stop else nothing
        except SOLVER_ERRORS as exc:
            return nothing, integrator.t, f"{method} failed at t = {integrator.t:.6g} s: {exc}"
        return batch, integrator.t, FINISHED if integrator.status == "finished" else None

    return advance


def sampled_run(
    model: ChainModel,
    y0: np.ndarray,
    initial_amplitude: float,
    settings: RunSettings,
    advance,
    chunk: int,
    progress: bool,
):
    """Run the skeleton's sampling loop from y0 with the chain's failure monitor; returns
    (states (size, k), error, wall time)."""
    start = clock.perf_counter()
    monitor = FailureMonitor(initial_amplitude, settings)

    def amplitude_of(batch):
        x, y = centres(model, batch[: model.dof])
        return analysis.amplitude(x.T, y.T)

    bar = Progress(settings.t_final, progress, label="reduced")
    try:
        states, error = collect_samples(advance, y0, settings.sample_times(), monitor, amplitude_of, bar, chunk)
    finally:
        bar.close()
    return np.concatenate(states, axis=1), error, clock.perf_counter() - start


def trajectory_result(
    model: ChainModel, settings: RunSettings, states: np.ndarray, *, wall_time: float, error: str | None, info: dict
) -> Result:
    """The Result of sampled states y = (q, q̇) (columns on settings.sample_times())."""
    q, qd = states[: model.dof], states[model.dof :]
    x, y = centres(model, q)
    vx, vy = centre_velocities(model, q, qd)
    _, _, theta, z = model.split(q)
    _, _, omega, z_rate = model.split(qd)
    return Result.from_trajectory(
        model.params,
        "reduced",
        settings.sample_times()[: states.shape[1]],
        x.T,
        y.T,
        theta.T,
        vx.T,
        vy.T,
        omega.T,
        z=z.T if model.extensible else None,
        z_rate=z_rate.T if model.extensible else None,
        wall_time=wall_time,
        error=error,
        info=info,
        settings=settings,
    )
