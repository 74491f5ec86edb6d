"""What the reduced solver's free and supported chains share around their integrators: the tolerance
scales of the state, the adapters that hand the run skeleton (solvers.skeleton.collect_samples) the
states at the output times, and the Result assembled from those states.

The per-sample work is compiled (numba), so a run at n in the thousands spends its time integrating:
`amplitudes` (the failure monitor's analysis.amplitude of each output sample: centres by the joint
recursion r_{i+1} = r_i + a_i e_i + b e_{i+1} of Eqs 13–14, 30–31, then the spread of their offsets from
the total-least-squares line) and `trajectory_arrays` (centres, their velocities and the angles of
every sample, directly in the (samples, n) layout of the Result). Both are tested against the numpy
forms of kinematics.py and analysis.failure.
"""

from __future__ import annotations

import math
import time as clock

import numpy as np
from numba import njit

from lightsail_mbs.result import Result
from lightsail_mbs.solvers.progress import Progress
from lightsail_mbs.solvers.reduced.dop853 import FINISHED as DONE
from lightsail_mbs.solvers.reduced.dop853 import STATUS
from lightsail_mbs.solvers.reduced.kinematics import ChainModel
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
    (rows: the sampled states y = (q, q̇) as rows of a (k, size) array, error, wall time)."""
    start = clock.perf_counter()
    monitor = FailureMonitor(initial_amplitude, settings)

    def amplitude_of(batch):
        return amplitudes(np.ascontiguousarray(batch.T), model.n, model.half_length, model.extensible)

    bar = Progress(settings.t_final, progress, label="reduced")
    try:
        states, error = collect_samples(advance, y0, settings.sample_times(), monitor, amplitude_of, bar, chunk)
    finally:
        bar.close()
    return np.concatenate([batch.T for batch in states]), error, clock.perf_counter() - start


@njit(cache=True)
def _centres_into(state, n, b, extensible, x, y):
    """Slice centres of the state y = (q, q̇) into x, y."""
    x[0], y[0] = state[0], state[1]
    c_prev, s_prev = math.cos(state[2]), math.sin(state[2])
    for i in range(1, n):
        c, s = math.cos(state[2 + i]), math.sin(state[2 + i])
        a = b + state[n + 1 + i] if extensible else b
        x[i] = x[i - 1] + a * c_prev + b * c
        y[i] = y[i - 1] + a * s_prev + b * s
        c_prev, s_prev = c, s


@njit(cache=True)
def amplitudes(rows, n, b, extensible):
    """analysis.amplitude of the chain in every row of rows (states y = (q, q̇); n slices, half-length b)."""
    count = rows.shape[0]
    out = np.empty(count)
    x = np.empty(n)
    y = np.empty(n)
    for col in range(count):
        _centres_into(rows[col], n, b, extensible, x, y)
        mx, my = 0.0, 0.0
        for i in range(n):
            mx += x[i]
            my += y[i]
        mx /= n
        my /= n
        sxy = sxx = syy = 0.0
        for i in range(n):
            dx, dy = x[i] - mx, y[i] - my
            sxy += dx * dy
            sxx += dx * dx
            syy += dy * dy
        phi = 0.5 * math.atan2(2.0 * sxy, sxx - syy)
        sp, cp = math.sin(phi), math.cos(phi)
        lo, hi = math.inf, -math.inf
        for i in range(n):
            off = -sp * (x[i] - mx) + cp * (y[i] - my)
            lo = min(lo, off)
            hi = max(hi, off)
        out[col] = 0.5 * (hi - lo)
    return out


@njit(cache=True)
def trajectory_arrays(rows, n, b, extensible):
    """x, y, θ, ẋ, ẏ, θ̇ as (samples, n) arrays and z, ż as (samples, n−1) (or (samples, 0)) from the
    states y = (q, q̇) in the rows of rows: ṙ_{i+1} − ṙ_i = ż_i e_i + a_i θ̇_i p_i + b θ̇_{i+1} p_{i+1}."""
    dof = rows.shape[1] // 2
    count = rows.shape[0]
    nz = n - 1 if extensible else 0
    x = np.empty((count, n))
    y = np.empty((count, n))
    th = np.empty((count, n))
    vx = np.empty((count, n))
    vy = np.empty((count, n))
    om = np.empty((count, n))
    z = np.empty((count, nz))
    zd = np.empty((count, nz))
    for t in range(count):
        for i in range(n):
            th[t, i] = rows[t, 2 + i]
            om[t, i] = rows[t, dof + 2 + i]
        for i in range(nz):
            z[t, i] = rows[t, n + 2 + i]
            zd[t, i] = rows[t, dof + n + 2 + i]
        x[t, 0], y[t, 0] = rows[t, 0], rows[t, 1]
        vx[t, 0], vy[t, 0] = rows[t, dof], rows[t, dof + 1]
        c_prev, s_prev = math.cos(th[t, 0]), math.sin(th[t, 0])
        for i in range(1, n):
            c, s = math.cos(th[t, i]), math.sin(th[t, i])
            a = b + z[t, i - 1] if extensible else b
            rate = zd[t, i - 1] if extensible else 0.0
            x[t, i] = x[t, i - 1] + a * c_prev + b * c
            y[t, i] = y[t, i - 1] + a * s_prev + b * s
            vx[t, i] = vx[t, i - 1] + rate * c_prev - a * om[t, i - 1] * s_prev - b * om[t, i] * s
            vy[t, i] = vy[t, i - 1] + rate * s_prev + a * om[t, i - 1] * c_prev + b * om[t, i] * c
            c_prev, s_prev = c, s
    return x, y, th, vx, vy, om, z, zd


def trajectory_result(
    model: ChainModel, settings: RunSettings, rows: np.ndarray, *, wall_time: float, error: str | None, info: dict
) -> Result:
    """The Result of sampled states y = (q, q̇) (rows, on settings.sample_times())."""
    rows = np.ascontiguousarray(rows)
    shape = model.n, model.half_length, model.extensible
    x, y, theta, vx, vy, omega, z, z_rate = trajectory_arrays(rows, *shape)
    return Result.from_trajectory(
        model.params,
        "reduced",
        settings.sample_times()[: rows.shape[0]],
        x,
        y,
        theta,
        vx,
        vy,
        omega,
        z=z if model.extensible else None,
        z_rate=z_rate if model.extensible else None,
        wall_time=wall_time,
        error=error,
        info=info,
        settings=settings,
        amplitude=amplitudes(rows, *shape),
    )
