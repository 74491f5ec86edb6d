"""What the reduced solver's free and supported chains share around their integrators: the tolerance
scales of the state, the adapters that hand the run skeleton (solvers.skeleton.collect_samples) the
states at the output times, and the Result assembled from those states.

The per-sample work is compiled (numba) and done once per sample, as the samples arrive, so a run at n in
the thousands spends its time integrating: `Trajectory.fill` writes the centres (the joint recursion
r_{i+1} = r_i + a_i e_i + b e_{i+1} of Eqs 13–14, 30–31), their velocities, the angles (and extensions)
of each output sample into the (samples, n) arrays of the Result, and returns its amplitude
(analysis.amplitude: the spread of the centres' offsets from their total-least-squares line) for the
failure monitor. Tested against the numpy forms of kinematics.py and model.failure.
"""

from __future__ import annotations

import math
import time as clock

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model import world_line
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.progress import Progress
from lightsail_mbs.solvers.reduced.dop853 import FINISHED as DONE
from lightsail_mbs.solvers.reduced.dop853 import STATUS
from lightsail_mbs.solvers.reduced.kinematics import ChainModel
from lightsail_mbs.solvers.skeleton import FINISHED, FailureMonitor, collect_samples

# Output samples per call of a compiled integrator (failure check and progress in between): the run goes
# on for up to this many samples past failure, where a crumpling chain can take 1e5 steps (a 6 t_c
# extensible TnT run: 252 392 steps with 50, 134 with 10 or 20; long stable runs cost ~10 % more with 10).
CHUNK = 10
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


def world_scales(scales: np.ndarray) -> np.ndarray:
    """The state scales with the sail's world line appended (model/world_line.py): 1 s for its coordinates
    (t, x/c), 1 for its 4-velocity (γ, γβ)."""
    dof, w = scales.size // 2, world_line.COORDINATES
    return np.concatenate([scales[:dof], np.ones(w), scales[dof:], np.ones(w)])


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


class Trajectory:
    """The Result's arrays of a run, preallocated for every output sample and filled as samples arrive.

    x, y, theta, vx, vy, omega: (capacity, n); z, z_rate: (capacity, n−1), or (capacity, 0) when
    inextensible; amplitude: (capacity,); count: the samples filled so far.
    """

    def __init__(self, model: ChainModel, capacity: int, world: bool = False):
        self.model = model
        n, nz = model.n, (model.n - 1 if model.extensible else 0)
        self.x, self.y, self.theta, self.vx, self.vy, self.omega = (np.empty((capacity, n)) for _ in range(6))
        self.z, self.z_rate = np.empty((capacity, nz)), np.empty((capacity, nz))
        self.amplitude = np.empty(capacity)
        # the sail's world line (model/world_line.py): its coordinates and 4-velocity after the chain's in y
        self.world = np.empty((capacity, 2 * world_line.COORDINATES)) if world else None
        self.count = 0

    def fill(self, rows: np.ndarray) -> np.ndarray:
        """Append the states y = (q, q̇) in the rows of rows; returns their amplitudes."""
        first, m = self.count, self.model
        if self.world is not None:
            dof, w = rows.shape[1] // 2, world_line.COORDINATES
            self.world[first : first + rows.shape[0]] = np.concatenate(
                [rows[:, dof - w : dof], rows[:, 2 * dof - w :]], 1
            )
        _fill(
            np.ascontiguousarray(rows),
            first,
            m.n,
            m.half_length,
            m.extensible,
            self.x,
            self.y,
            self.theta,
            self.vx,
            self.vy,
            self.omega,
            self.z,
            self.z_rate,
            self.amplitude,
        )
        self.count += rows.shape[0]
        return self.amplitude[first : self.count]

    def truncate(self, count: int) -> None:
        """Keep the first count samples (the run stopped inside the last batch)."""
        self.count = count

    def arrays(self) -> dict:
        """The filled samples as arrays (views: the pages of samples never filled are never touched, so a
        run stopped early holds no memory for them)."""
        names = ("x", "y", "theta", "vx", "vy", "omega", "z", "z_rate", "amplitude")
        return {k: getattr(self, k)[: self.count] for k in names}

    def coordinates(self) -> np.ndarray:
        """q of the filled samples as columns (dof, count)."""
        c = self.count
        parts = [self.x[:c, :1], self.y[:c, :1], self.theta[:c]] + ([self.z[:c]] if self.model.extensible else [])
        return np.concatenate(parts, axis=1).T


@njit(cache=True)
def _fill(rows, first, n, b, extensible, x, y, th, vx, vy, om, z, zd, amp):
    """Centres, velocities, angles, extensions and amplitude of the states in rows into row first… of the
    output arrays (ṙ_{i+1} − ṙ_i = ż_i e_i + a_i θ̇_i p_i + b θ̇_{i+1} p_{i+1})."""
    dof = rows.shape[1] // 2
    for row in range(rows.shape[0]):
        t = first + row
        for i in range(n):
            th[t, i] = rows[row, 2 + i]
            om[t, i] = rows[row, dof + 2 + i]
        if extensible:
            for i in range(n - 1):
                z[t, i] = rows[row, n + 2 + i]
                zd[t, i] = rows[row, dof + n + 2 + i]
        x[t, 0], y[t, 0] = rows[row, 0], rows[row, 1]
        vx[t, 0], vy[t, 0] = rows[row, dof], rows[row, dof + 1]
        c_prev, s_prev = math.cos(th[t, 0]), math.sin(th[t, 0])
        mx, my = x[t, 0], y[t, 0]
        for i in range(1, n):
            c, s = math.cos(th[t, i]), math.sin(th[t, i])
            a = b + z[t, i - 1] if extensible else b
            rate = zd[t, i - 1] if extensible else 0.0
            x[t, i] = x[t, i - 1] + a * c_prev + b * c
            y[t, i] = y[t, i - 1] + a * s_prev + b * s
            vx[t, i] = vx[t, i - 1] + rate * c_prev - a * om[t, i - 1] * s_prev - b * om[t, i] * s
            vy[t, i] = vy[t, i - 1] + rate * s_prev + a * om[t, i - 1] * c_prev + b * om[t, i] * c
            mx += x[t, i]
            my += y[t, i]
            c_prev, s_prev = c, s
        mx /= n
        my /= n
        sxy = sxx = syy = 0.0
        for i in range(n):
            dx, dy = x[t, i] - mx, y[t, i] - my
            sxy += dx * dy
            sxx += dx * dx
            syy += dy * dy
        phi = 0.5 * math.atan2(2.0 * sxy, sxx - syy)
        sp, cp = math.sin(phi), math.cos(phi)
        lo, hi = math.inf, -math.inf
        for i in range(n):
            off = -sp * (x[t, i] - mx) + cp * (y[t, i] - my)
            lo = min(lo, off)
            hi = max(hi, off)
        amp[t] = 0.5 * (hi - lo)


def sampled_run(
    model: ChainModel,
    y0: np.ndarray,
    settings: RunSettings,
    advance,
    chunk: int,
    progress: bool,
):
    """Run the skeleton's sampling loop from y0 with the chain's failure monitor; returns (the
    Trajectory of the samples, error, wall time). The monitor's initial amplitude is the first sample's,
    computed as every later one (a sail flat to round-off is flat for both)."""
    start = clock.perf_counter()
    times = settings.sample_times()
    trajectory = Trajectory(model, times.size, world=y0.size > 2 * model.dof)
    monitor = FailureMonitor(float(trajectory.fill(y0[None, :])[0]), settings)

    def amplitude_of(batch):
        return trajectory.fill(batch.T)

    bar = Progress(settings.t_final, progress, label="reduced")
    try:
        states, error = collect_samples(advance, y0, times, monitor, amplitude_of, bar, chunk)
    finally:
        bar.close()
    trajectory.truncate(sum(batch.shape[1] for batch in states))
    return trajectory, error, clock.perf_counter() - start


def trajectory_result(
    model: ChainModel, settings: RunSettings, trajectory: Trajectory, *, wall_time: float, error: str | None, info: dict
) -> Result:
    """The Result of a run's Trajectory (samples on settings.sample_times())."""
    arrays = trajectory.arrays()
    amplitude = arrays.pop("amplitude")
    if trajectory.world is not None:
        w, world = world_line.COORDINATES, trajectory.world[: trajectory.count]
        info = {**info, "world_line": world_line.record(world[:, :w], world[:, w:])}
    z, z_rate = arrays.pop("z"), arrays.pop("z_rate")
    return Result.from_trajectory(
        model.params,
        "reduced",
        settings.sample_times()[: trajectory.count],
        **arrays,
        z=z if model.extensible else None,
        z_rate=z_rate if model.extensible else None,
        wall_time=wall_time,
        error=error,
        info=info,
        settings=settings,
        amplitude=amplitude,
    )
