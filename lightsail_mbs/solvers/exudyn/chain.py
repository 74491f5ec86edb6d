"""Exudyn solver: the sail as a chain of rigid slices integrated by Exudyn's implicit solver.

Model (paper Sec. III.A–C; details in solvers.exudyn.tree): n planar rigid slices (m = ρhWl,
J = ml²/12) joined by revolute joints, as ONE Exudyn ``ObjectKinematicTree`` in the paper's
own minimal coordinates q = [X, Y, θ₁, (z₁), φ₂, …] (Eqs 13–14, 30–31).
torsion: torsional spring-dampers k_T = EI/l on θ_{k+1} − θ_k; rigid: none; tnt: k_T per
params.bending, each hinge also slides along the preceding slice (spring-damper k_s, pre-stretched
to T/k_s) and the follower tension T acts at both ends along the end slices (Eq. 32); with
params.axial_springs=False the slides are rigid (plain revolute joints + end tension).
The frame accelerates at g₀: every slice carries −m g₀ ŷ (the tree's gravity), and x, y are
slice centres in that frame.
Supports and a tip load (params.boundary, params.tip_load: the classic validations of Appendices
A–B) are added as Exudyn constraints and loads by solvers.exudyn.supports; the sail itself is free.

Why this formulation:
- in minimal coordinates the TnT spring extension z is itself a coordinate, exact to relative
  machine precision; in a redundant form (one rigid body per slice plus joints) it is a difference
  of hinge coordinates of order 1 m, and its Newton residual sits on a round-off floor;
- springs, dampers and the frame force are C++ (joint P/D control, gravity); only the
  state-dependent load is Python: one vectorised force user function for the whole chain,
  evaluated at every Newton iterate, so the load is exact, not lagged;
- Exudyn 1.13.6 symbolic user functions abort on symbolic vectors of 8 or more entries, so the
  tree's force vector (n + 2 entries) cannot be recorded symbolically; per-slice symbolic loads
  cannot read the state, and one Python function per slice is several times slower.

Solver: Exudyn generalized-α (implicit, second order, ρ∞ = 0.9), modified Newton, one fixed step
h that divides the output interval, one ``SolveSteps`` call for the whole run (restarting it in
chunks would perturb the generalized-α state at every restart). A post-step function checks, every
SAMPLES_PER_CHECK output samples, the amplitude of every step since the last check and stops the
solver at failure (amplitude ≥ failure_ratio × initial); the Result ends at the first output sample
past failure; stop_at_failure=False runs on. A Newton failure, an Exudyn error or a non-finite state
is recorded in Result.error with the trajectory up to there.

Step: h = STEP_FACTOR·sqrt(L/g₀) (1 ms for the paper's torsion case), divided by
EXTENSIBLE_STEP_DIVISOR for the extensible TnT chain (its unresolved axial springs start out of
balance with the load's axial components and ring) and by RIGID_STEP_DIVISOR for the rigid chain;
Newton relTol 1e-8 and absTol 1e-8 f₀ × defect slope. The convergence study behind these numbers
(`python validation/benchmark.py --convergence`) is in the documentation's solver page.
"""

from __future__ import annotations

import math
import time as _time

import numpy as np

from lightsail_mbs import analysis
from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import ParameterError, SailParameters
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.exudyn.console import silenced
from lightsail_mbs.solvers.exudyn.supports import add_supports
from lightsail_mbs.solvers.exudyn.tree import ChainLayout, generalized_force, tree_arguments
from lightsail_mbs.solvers.progress import Progress
from lightsail_mbs.solvers.settings import RunSettings
from lightsail_mbs.solvers.skeleton import FailureMonitor

# Step size h = STEP_FACTOR · sqrt(L / g₀) (capped by the output interval): the radiation
# load sets the time scale of the instability (paper torsion case: sqrt(1 m / 667 m/s²) = 38.7 ms,
# h = 1 ms; paper rigid case: 1.22 ms, h capped to the 10 µs output interval).
STEP_FACTOR = 0.026
# Extensible TnT: the axial springs (never resolved) start out of balance with the load's axial
# components and ring; the failure time converges to 1 % only at h/4.
EXTENSIBLE_STEP_DIVISOR = 4
# Rigid chains (no bending springs): the failure time converges to 0.3 % at h/6.
RIGID_STEP_DIVISOR = 6
NEWTON_REL_TOL = 1e-8  # residual reduction per step (Exudyn default)
NEWTON_ABS_FACTOR = 1e-8  # absolute residual tolerance as a fraction of f₀ × defect slope (see default_abs_tol)
SPECTRAL_RADIUS = 0.9  # generalized-α numerical damping of the highest frequencies
SAMPLES_PER_CHECK = 50  # failure check (and progress) after this many output samples


def default_step_size(p: SailParameters, settings: RunSettings) -> float:
    """h = STEP_FACTOR · sqrt(L/g₀) (/ EXTENSIBLE_STEP_DIVISOR for extensible TnT, / RIGID_STEP_DIVISOR
    for the rigid model), at most the output interval (which it then divides)."""
    g0 = p.nominal_acceleration
    h = STEP_FACTOR * math.sqrt(p.length / g0) if g0 > 0 else math.inf
    if p.extensible:
        h /= EXTENSIBLE_STEP_DIVISOR
    elif p.model == "rigid":
        h /= RIGID_STEP_DIVISOR
    return min(h, settings.sample_interval)


def default_abs_tol(p: SailParameters) -> float:
    """Absolute Newton tolerance (N per coordinate): NEWTON_ABS_FACTOR × f₀ × 2πνa₀/L (or m·1 m/s² for f₀).

    The load and the frame force cancel on a flat slice; what drives the deformation is f₀ times the
    slope of the defect, 2πνa₀/L (1 for a flat sail). A tolerance on f₀ alone let thin sails
    (g₀ = 6.7e4 m/s², h = 10 nm) drift by 1.6e-5 rad in 0.3 s from the reduced solution; scaled by the
    slope they agree to 5e-10 rad, for +35–55 % Newton iterations on the paper cases."""
    scale = p.flat_force if p.flat_force > 0 else p.slice_mass
    slope = 2.0 * math.pi * p.defect_mode * p.defect_amplitude / p.length
    return NEWTON_ABS_FACTOR * scale * (slope if slope > 0 else 1.0)


def build(p: SailParameters, initial: shapes.ChainState | None = None):
    """The assembled Exudyn system starting at rest in `initial` (default shapes.initial_state(p)):
    (SystemContainer, mbs, layout, sensors (q, q̇), force function)."""
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectKinematicTree, SensorNode

    layout = ChainLayout.of(p)
    q0 = layout.coordinates(initial or shapes.initial_state(p))
    load = generalized_force(p, layout)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    node = mbs.AddNode(
        NodeGenericODE2(
            referenceCoordinates=[0.0] * layout.size,
            initialCoordinates=q0,
            initialCoordinates_t=[0.0] * layout.size,
            numberOfODE2Coordinates=layout.size,
        )
    )
    tree = mbs.AddObject(
        ObjectKinematicTree(
            nodeNumber=node, forceUserFunction=lambda mbs, t, i, q, q_t: load(q), **tree_arguments(p, layout, exu)
        )
    )
    add_supports(p, mbs, node, tree, layout, q0)  # supports and tip load (validations; none for a sail)
    sensors = [
        mbs.AddSensor(SensorNode(nodeNumber=node, storeInternal=True, writeToFile=False, outputVariableType=kind))
        for kind in (exu.OutputVariableType.Coordinates, exu.OutputVariableType.Coordinates_t)
    ]
    mbs.Assemble()
    return SC, mbs, layout, sensors, load


def simulation_settings(
    t_final: float, step_size: float, rel_tol: float, abs_tol: float, spectral_radius: float = SPECTRAL_RADIUS
):
    """Exudyn's SimulationSettings for one generalized-α run of fixed step to t_final."""
    import exudyn as exu

    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.endTime = t_final
    ti.numberOfSteps = max(1, int(round(t_final / step_size)))
    ti.newton.relativeTolerance = rel_tol
    ti.newton.absoluteTolerance = abs_tol
    ti.generalizedAlpha.spectralRadius = spectral_radius
    ti.minimumStepSize = step_size * 1e-4
    ti.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 0.5 * step_size  # every step; _samples keeps the output grid
    s.linearSolver.solverType = exu.LinearSolverType.EXUdense
    return s


def run(
    params: SailParameters,
    settings: RunSettings,
    *,
    progress: bool = False,
    step_size: float | None = None,
    newton_rel_tol: float | None = None,
    newton_abs_tol: float | None = None,
    spectral_radius: float = SPECTRAL_RADIUS,
    samples_per_check: int = SAMPLES_PER_CHECK,
    **options,
) -> Result:
    """Integrate one case to t_final or to failure; see the module docstring."""
    import exudyn as exu

    if options:
        raise ParameterError(
            f"options={sorted(options)} are invalid: the exudyn solver accepts step_size, "
            "newton_rel_tol, newton_abs_tol, spectral_radius, samples_per_check"
        )
    p = params
    dt = settings.sample_interval
    h = default_step_size(p, settings) if step_size is None else float(step_size)
    if not (h > 0 and math.isfinite(h)):
        raise ParameterError(f"step_size={step_size!r} is invalid: allowed 0 < step_size ≤ output interval {dt:g}")
    h = dt / math.ceil(dt / h * (1 - 1e-12))  # whole steps per output sample
    rel_tol = NEWTON_REL_TOL if newton_rel_tol is None else float(newton_rel_tol)
    abs_tol = default_abs_tol(p) if newton_abs_tol is None else float(newton_abs_tol)
    if not 0 <= spectral_radius <= 1:
        raise ParameterError(f"spectral_radius={spectral_radius!r} is invalid: allowed 0 ≤ ρ∞ ≤ 1")
    for name, v in (("newton_rel_tol", rel_tol), ("newton_abs_tol", abs_tol)):
        if not (v >= 0 and math.isfinite(v)):
            raise ParameterError(f"{name}={v!r} is invalid: allowed a finite value ≥ 0")

    start = _time.perf_counter()
    initial = shapes.initial_state(p)
    monitor = FailureMonitor(analysis.amplitude(initial.x, initial.y), settings)
    SC, mbs, layout, sensors, _ = build(p, initial)
    s = simulation_settings(settings.t_final, h, rel_tol, abs_tol, spectral_radius)
    steps_per_sample = int(round(dt / h))
    bar = Progress(settings.t_final, progress, label=f"exudyn {p.model} n={p.n}")
    check_steps = max(1, int(samples_per_check)) * steps_per_sample
    watch = {"steps": 0, "failed": False}

    def after_step(mbs, t) -> bool:
        """Every check_steps steps: progress, and the amplitude of the new rows; False stops."""
        watch["steps"] += 1
        if watch["steps"] % check_steps:
            return True
        bar.update(t)
        if monitor.active:
            q = mbs.GetSensorStoredData(sensors[0])[-(check_steps + 1) :]
            if monitor.first_failure(analysis.amplitude(*layout.positions(q[:, 1:])[:2])) is not None:
                watch["failed"] = True
                return False
        return True

    mbs.SetPostStepUserFunction(after_step)
    solver = exu.MainSolverImplicitSecondOrder()
    error = None
    try:
        with silenced():
            solver.InitializeSolver(mbs, s)
            ok = solver.SolveSteps(mbs, s)
            if not ok:
                error = (
                    f"Newton did not converge at t = {solver.it.currentTime:.9g} s (exudyn: {solver.GetErrorString()})"
                )
            elif not np.all(np.isfinite(mbs.systemData.GetODE2Coordinates())):
                error = f"non-finite state at t = {solver.it.currentTime:.9g} s"
            solver.FinalizeSolver(mbs, s)
    except exu.ExudynError as exc:  # solver failures are results, not crashes
        error = f"exudyn: {exc}".strip()
    finally:
        bar.update(solver.it.currentTime)
        bar.close()
    wall = _time.perf_counter() - start

    q, q_t = (_samples(mbs.GetSensorStoredData(sn), dt, h) for sn in sensors)
    t_now = float(solver.it.currentTime)
    if error is None and len(q) and t_now > q[-1, 0] + 0.5 * dt:  # a final sample the sensor
        q = np.vstack((q, np.concatenate(([t_now], mbs.systemData.GetODE2Coordinates()))))  # skipped
        q_t = np.vstack((q_t, np.concatenate(([t_now], mbs.systemData.GetODE2Coordinates_t()))))
    rows = min(len(q), len(q_t))
    if rows == 0:  # failed before the first sample
        q = np.concatenate(([0.0], layout.coordinates(initial)))[None, :]
        q_t = np.zeros_like(q)
        rows = 1
    q, q_t = q[:rows], q_t[:rows]
    x, y, theta, z = layout.positions(q[:, 1:])
    vx, vy, omega, z_rate = layout.velocities(q[:, 1:], q_t[:, 1:])
    over = monitor.first_failure(analysis.amplitude(x, y))
    if over is not None:  # end at the first sample past failure
        cut = over + 1
        q, x, y, theta, z, vx, vy, omega, z_rate = (a[:cut] for a in (q, x, y, theta, z, vx, vy, omega, z_rate))
    info = {
        "formulation": "ObjectKinematicTree (minimal coordinates), generalized-alpha",
        "step_size": h,
        "newton_rel_tol": rel_tol,
        "newton_abs_tol": abs_tol,
        "spectral_radius": spectral_radius,
        "steps": int(round((q[-1, 0] if len(q) else 0.0) / h)),
        "newton_iterations": int(solver.it.newtonStepsCount),
        "jacobian_evaluations": int(solver.it.newtonJacobiCount),
        "steps_per_sample": steps_per_sample,
        "coordinates": layout.size,
    }
    return Result.from_trajectory(
        p,
        "exudyn",
        q[:, 0],
        x,
        y,
        theta,
        vx,
        vy,
        omega,
        z=z if z.shape[-1] else None,
        z_rate=z_rate if z.shape[-1] else None,
        wall_time=wall,
        error=error,
        info=info,
        settings=settings,
    )


def _samples(data: np.ndarray, dt: float, h: float) -> np.ndarray:
    """The stored rows (one per step of size h) that lie on the output grid k·dt, once each."""
    data = np.asarray(data, float)
    if data.ndim != 2 or not len(data):
        return np.zeros((0, 0))
    index = np.round(data[:, 0] / dt)
    on_grid = np.abs(data[:, 0] - index * dt) < 0.25 * h
    data, index = data[on_grid], index[on_grid]
    keep = np.concatenate(([True], np.diff(index) > 0))
    return data[keep]
