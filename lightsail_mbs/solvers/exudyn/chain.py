"""Exudyn solver: the sail as a chain of rigid slices integrated by one of Exudyn's integrators.

Model (paper Sec. III.A–C; details in solvers.exudyn.tree): n planar rigid slices (m = ρhWl,
J = ml²/12) joined by revolute joints, as ONE Exudyn ``ObjectKinematicTree`` in the paper's
own minimal coordinates q = [X, Y, θ₁, (z₁), φ₂, …] (Eqs 13–14, 30–31).
torsion: torsional spring-dampers k_T = EI/l on θ_{k+1} − θ_k; rigid: none; tnt: k_T per
params.bending, each hinge also slides along the preceding slice (spring-damper k_s, pre-stretched
to T/k_s) and the follower tension T acts at both ends along the end slices (Eq. 32); with
params.axial_springs=False the slides are rigid (plain revolute joints + end tension).
The frame accelerates at g₀: every slice carries −m g₀ ŷ, inside the net slice force of the shared
load model (the physics terms, model/terms), and x, y are slice centres in that frame.
Supports and a tip load (params.boundary, params.tip_load: the classic validations of Appendices
A–B) are added as Exudyn constraints and loads by solvers.exudyn.supports; the sail itself is free.

Why this formulation:

- in minimal coordinates the TnT spring extension z is itself a coordinate, exact to relative
  machine precision; in a redundant form (one rigid body per slice plus joints) it is a difference
  of hinge coordinates of order 1 m, and its Newton residual sits on a round-off floor;
- springs and dampers are C++ (joint P/D control); the state-dependent net load is one compiled
  force user function for the whole chain, evaluated at every Newton iterate or explicit stage, so
  the load is exact, not lagged;
- Exudyn 1.13.6 symbolic user functions abort on symbolic vectors of 8 or more entries, so the
  tree's force vector (n + 2 entries) cannot be recorded symbolically.

Integrators, chosen per case (``method="auto"``, the choice and its reason in Result.info):

1. The stiffness number ω_max t_c: the chain's highest frequency (top_frequency: the zig-zag mode of
   the bending and tension springs, ω² = 4k_T/J + T l/J; the axial springs of the extensible TnT chain,
   2√(k_s/m)) times the instability's time scale t_c = 1/(k√(g₀a₀)) (model.theory.time_scale).
2. Non-stiff free chains (ω_max t_c ≤ STIFF_LIMIT: rigid, soft torsion, soft inextensible TnT):
   Exudyn's explicit DOPRI5 with automatic step size. Its error control uses one absolute tolerance
   for every coordinate and rate, atol = rtol × the smallest state scale (angles: the defect slope
   2πνa₀/L; rates: that over t_c), and no relative part (Exudyn's relative tolerance scales with the
   signed, not the absolute, state values, so negative angles would get none). The largest step is
   t_final/EXPLICIT_MIN_STEPS.
3. Stiff chains (stable torsion, tensioned or extensible TnT) and chains with supports (constraints):
   generalized-α (implicit, second order, ρ∞ = 0.9, modified Newton) with the fixed step
   h = min(GA_STEP_FACTOR √(L/g₀), t_c/GA_STEPS_PER_TC) · √(rtol/DEFAULT_RTOL) (2 ms for the paper's
   torsion case at the default rtol: its error falls as h², so as rtol), made to divide the output
   interval when shorter than it. Newton at the default rtol: relative 1e-8, absolute
   DEFAULT_RTOL · f₀ · 2πνa₀/L (the load and the frame force cancel on a flat slice; what deforms the sail
   is f₀ times the defect slope); both × (rtol/DEFAULT_RTOL)², so that a tighter rtol makes the
   nonlinear solve's error fall far faster than the step's. The modified Newton's error does not fall
   smoothly with its tolerance (it jumps when one more iteration or a Jacobian update happens), and on an
   extensible chain it can dominate: a seeded survivor (validation/accuracy.md, case 50) is 1.2e-5
   (relative) off at the default tolerances and step h, 1.6e-5 with both tolerances / 10 at h, and
   3e-7 with both / 1000 (python validation/accuracy.py --probe-case 50).
   The whole run is one ``SolveSteps`` call: restarting it in chunks would perturb the generalized-α
   state at every restart.

Sampling and the stop rule (the run skeleton's, solvers.skeleton): a post-step function
(solvers.exudyn.sampler) keeps q, q̇, q̈ after every step and interpolates the output samples t_k = k·Δt
that the steps passed by the quintic Hermite polynomial of the two ends of each one's step (exact at a
step end; the generalized-α steps divide the output interval when shorter than it). Every
SAMPLES_PER_CHECK samples — sooner when the amplitude's growth since the last check predicts failure
before the next one, so that no time is spent integrating the crumpling sail past failure — or after
sampler.STEPS_PER_CHECK steps (an explosively crumpling chain shrinks the explicit steps faster than any
prediction from the samples), and at the end, it asks the skeleton's FailureMonitor for the first sample
at or above the limit; the run stops there and keeps that sample.
stop_at_failure=False runs on. A Newton failure, a too small step, an Exudyn error or a non-finite
state is recorded in Result.error with the samples up to there.
"""

from __future__ import annotations

import functools
import math
import time as _time

import numpy as np

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import failure, shapes, theory, world_line
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.exudyn.console import solve_steps
from lightsail_mbs.solvers.exudyn.sampler import Sampler
from lightsail_mbs.solvers.exudyn.supports import add_supports
from lightsail_mbs.solvers.exudyn.tree import ChainLayout, generalized_force, tree_arguments
from lightsail_mbs.solvers.exudyn.world_line import add_world_line, beam_factor_reader
from lightsail_mbs.solvers.progress import Progress
from lightsail_mbs.solvers.skeleton import FailureMonitor

METHODS = ("auto", "DOPRI5", "generalized-alpha")
DEFAULT_RTOL = 1e-7  # relative accuracy asked of a run (module docstring: what it sets in each method)
# Chains whose fastest oscillation is slower than this many radians per instability time t_c run on the
# explicit DOPRI5 (the paper's soft torsion sail: ω_max t_c = 5; the stable one: 494, the stable TnT: 250).
STIFF_LIMIT = 50.0
EXPLICIT_MIN_STEPS = 20  # DOPRI5: largest step t_final / EXPLICIT_MIN_STEPS
# Generalized-α step h = min(GA_STEP_FACTOR·sqrt(L/g₀), t_c/GA_STEPS_PER_TC) at the default rtol: the load
# sets the time scale (paper torsion case: sqrt(1 m / 667 m/s²) = 38.7 ms, h = 2 ms); large defects
# (a₀/L ~ 1e-3) move on t_c, which the step must resolve.
GA_STEP_FACTOR = 0.052
GA_STEPS_PER_TC = 500
NEWTON_REL_TOL = 1e-8  # residual reduction per step at the default rtol (Exudyn's default), ∝ rtol²
SPECTRAL_RADIUS = 0.9  # generalized-α numerical damping of the highest frequencies
SAMPLES_PER_CHECK = 50  # failure check (and progress) after this many output samples
OPTIONS = ("method", "rtol", "step_size", "newton_rel_tol", "newton_abs_tol", "spectral_radius")
OPTIONS += ("samples_per_check", "perturbation")


def defect_slope(p: SailParameters) -> float:
    """2πνa₀/L: the slope of the defect (rad), the scale of the angles; 1e-6 for a flat sail."""
    slope = 2.0 * math.pi * p.defect_mode * p.displacement_scale / p.length
    return slope if p.defect_amplitude > 0 else 1e-6


def instability_time(p: SailParameters) -> float:
    """t_c = 1/(k√(g₀a₀)) (s), or inf for a flat or unlit sail (nothing grows)."""
    if p.defect_amplitude <= 0 or p.nominal_acceleration <= 0:
        return math.inf
    return theory.time_scale(p)


def top_frequency(p: SailParameters) -> float:
    """The chain's highest angular frequency (rad/s): the zig-zag mode of the bending springs and the
    tension, ω² = 4k_T/J + T l/J (exact for the straight chain, chain_theory), or the axial springs of the
    extensible TnT chain, about 2√(k_s/m), whichever is higher; 0 for the rigid chain."""
    omega2 = (4.0 * p.torsional_stiffness + p.tension * p.slice_length) / p.slice_inertia
    if p.extensible:
        omega2 = max(omega2, 4.0 * p.axial_stiffness / p.slice_mass)
    return math.sqrt(omega2)


def choose_method(p: SailParameters) -> tuple[str, str]:
    """(method, reason): DOPRI5 for a free chain with ω_max t_c ≤ STIFF_LIMIT, else generalized-α."""
    if p.boundary != "free" or p.tip_load:
        return "generalized-alpha", "supports and tip loads are constraints (a DAE): implicit integrator"
    omega, tc = top_frequency(p), instability_time(p)
    if p.extensible:
        return "generalized-alpha", f"extensible chain: axial springs at ω ≈ {omega:.3g} rad/s are stiff"
    stiffness = omega * tc if omega > 0 else 0.0
    if stiffness <= STIFF_LIMIT:
        return "DOPRI5", f"non-stiff: ω_max t_c = {stiffness:.3g} ≤ {STIFF_LIMIT:g}"
    return "generalized-alpha", f"stiff: ω_max t_c = {stiffness:.3g} > {STIFF_LIMIT:g}"


def default_step_size(p: SailParameters, settings: RunSettings, rtol: float = DEFAULT_RTOL) -> float:
    """The generalized-α step: min(GA_STEP_FACTOR·sqrt(L/g₀), t_c/GA_STEPS_PER_TC) · sqrt(rtol/DEFAULT_RTOL);
    the output interval for an unlit sail (nothing sets a time scale but the springs, which the caller
    resolves by its choice of output interval or step). A step below the output interval is then made
    to divide it (step_in_grid), so that the samples fall on steps."""
    g0 = p.nominal_acceleration
    if g0 <= 0:
        return settings.sample_interval
    h = min(GA_STEP_FACTOR * math.sqrt(p.length / g0), instability_time(p) / GA_STEPS_PER_TC)
    return h * math.sqrt(rtol / DEFAULT_RTOL)


def step_in_grid(h: float, dt: float) -> float:
    """h made to divide the output interval dt when h < dt (samples on steps), else h itself."""
    return dt / math.ceil(dt / h * (1 - 1e-12)) if h < dt else h


def default_abs_tol(p: SailParameters, rtol: float = DEFAULT_RTOL) -> float:
    """Absolute Newton tolerance (N per coordinate): rtol × f₀ × 2πνa₀/L (or m·1 m/s² for f₀).

    The load and the frame force cancel on a flat slice; what drives the deformation is f₀ times the
    slope of the defect. A tolerance on f₀ alone let thin sails (g₀ = 6.7e4 m/s², h = 10 nm) drift by
    1.6e-5 rad in 0.3 s from the reduced solution; scaled by the slope they agree to 5e-10 rad."""
    scale = p.flat_force if p.flat_force > 0 else p.slice_mass
    return rtol * scale * defect_slope(p)


def explicit_abs_tol(p: SailParameters, rtol: float = DEFAULT_RTOL) -> float:
    """DOPRI5's one absolute tolerance: rtol × the smaller of the angle scale (the defect slope) and the
    rate scale (the slope over t_c, or over 1 s for a chain with nothing growing)."""
    slope = defect_slope(p)
    tc = instability_time(p)
    return rtol * slope * min(1.0, 1.0 / tc if math.isfinite(tc) else 1.0)


def build(p: SailParameters, initial: shapes.ChainState | None = None):
    """The assembled Exudyn system starting at rest in `initial` (default shapes.initial_state(p)):
    (SystemContainer, mbs, layout, node, force function)."""
    import exudyn as exu
    from exudyn.itemInterface import NodeGenericODE2, ObjectKinematicTree

    layout = ChainLayout.of(p)
    q0 = layout.coordinates(initial or shapes.initial_state(p))
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
    factor = None  # the sail's world line after the tree's coordinates (integrated_trajectory)
    if p.integrated_trajectory:
        factor = beam_factor_reader(mbs, add_world_line(p, mbs))
    load = generalized_force(p, layout, factor)
    tree = mbs.AddObject(
        ObjectKinematicTree(
            nodeNumber=node,
            forceUserFunction=lambda mbs, t, i, q, q_t: load(q, q_t, t),
            **tree_arguments(p, layout, exu),
        )
    )
    add_supports(p, mbs, node, tree, layout, q0)  # supports and tip load (validations; none for a sail)
    mbs.Assemble()
    return SC, mbs, layout, node, load


def simulation_settings(
    t_final: float, step_size: float, rel_tol: float, abs_tol: float, spectral_radius: float = SPECTRAL_RADIUS
):
    """Exudyn's SimulationSettings for one generalized-α run of fixed step up to t_final (a whole number
    of steps, the last one at or past t_final)."""
    import exudyn as exu

    s = exu.SimulationSettings()
    ti = s.timeIntegration
    steps = max(1, int(math.ceil(t_final / step_size * (1 - 1e-12))))
    ti.endTime = steps * step_size
    ti.numberOfSteps = steps
    ti.newton.relativeTolerance = rel_tol
    ti.newton.absoluteTolerance = abs_tol
    ti.generalizedAlpha.spectralRadius = spectral_radius
    ti.minimumStepSize = step_size * 1e-4
    ti.verboseMode = 0
    s.solution.file.write = False
    s.linearSolver.solverType = exu.LinearSolverType.EXUdense
    return s


def explicit_settings(t_final: float, abs_tol: float, initial_step: float, fixed_step: float | None = None):
    """Exudyn's SimulationSettings for one DOPRI5 run to t_final: automatic steps (absolute tolerance
    only, largest step t_final/EXPLICIT_MIN_STEPS) or, with fixed_step, a fixed step."""
    import exudyn as exu

    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.endTime = t_final
    ti.solverType = exu.DynamicSolverType.DOPRI5
    ti.explicit.useLieGroupIntegration = False
    ti.explicit.computeEndOfStepAccelerations = True
    if fixed_step is None:
        ti.automaticStepSize = True
        ti.numberOfSteps = EXPLICIT_MIN_STEPS
        ti.relativeTolerance = 0.0
        ti.absoluteTolerance = abs_tol
        ti.initialStepSize = min(initial_step, t_final / EXPLICIT_MIN_STEPS)
        ti.minimumStepSize = 1e-14 * t_final
    else:
        ti.automaticStepSize = False
        ti.numberOfSteps = max(1, int(math.ceil(t_final / fixed_step * (1 - 1e-12))))
    ti.verboseMode = 0
    s.solution.file.write = False
    s.linearSolver.solverType = exu.LinearSolverType.EigenDense  # refactorised every stage: 2x faster than EXUdense
    return s


def run(
    params: SailParameters,
    settings: RunSettings,
    *,
    progress: bool = False,
    method: str = "auto",
    rtol: float | None = None,
    step_size: float | None = None,
    newton_rel_tol: float | None = None,
    newton_abs_tol: float | None = None,
    spectral_radius: float = SPECTRAL_RADIUS,
    samples_per_check: int = SAMPLES_PER_CHECK,
    perturbation: float = 0.0,
    **options,
) -> Result:
    """Integrate one case to t_final or to failure; see the module docstring.

    method: "auto" (choose_method), "DOPRI5" or "generalized-alpha"; rtol: the run's relative accuracy
    (default DEFAULT_RTOL; sets DOPRI5's tolerance and the generalized-α step); step_size: a fixed step
    (generalized-α, or fixed-step DOPRI5), overriding rtol's; perturbation: amplitude (m) of the seeded
    roughness shapes.initial_state adds to the start (the conditioning probe of solvers.uncertainty).
    """
    if options:
        raise ParameterError(f"options={sorted(options)} are invalid: the exudyn solver accepts {', '.join(OPTIONS)}")
    p = params
    rtol = DEFAULT_RTOL if rtol is None else rtol
    _check_options(method, rtol, step_size, spectral_radius, perturbation)
    method, reason = _method(p, method, step_size, newton_rel_tol, newton_abs_tol)
    newton_scale = (rtol / DEFAULT_RTOL) ** 2  # the Newton tolerances ∝ rtol², the step ∝ √rtol (docstring)
    rel_tol = NEWTON_REL_TOL * newton_scale if newton_rel_tol is None else float(newton_rel_tol)
    abs_tol = default_abs_tol(p) * newton_scale if newton_abs_tol is None else float(newton_abs_tol)
    for name, v in (("newton_rel_tol", rel_tol), ("newton_abs_tol", abs_tol)):
        if not (v >= 0 and math.isfinite(v)):
            raise ParameterError(f"{name}={v!r} is invalid: allowed a finite value ≥ 0")

    start = _time.perf_counter()
    initial = shapes.initial_state(p, perturbation=perturbation)
    monitor = FailureMonitor(failure.amplitude(initial.x, initial.y), settings)
    SC, mbs, layout, _, _ = build(p, initial)
    info = {"method": method, "method_reason": reason, "rtol": rtol, "top_frequency": top_frequency(p)}
    if method == "generalized-alpha":
        h = step_in_grid(
            default_step_size(p, settings, rtol) if step_size is None else float(step_size), settings.sample_interval
        )
        s = simulation_settings(settings.t_final, h, rel_tol, abs_tol, spectral_radius)
        info.update(step_size=h, newton_rel_tol=rel_tol, newton_abs_tol=abs_tol, spectral_radius=spectral_radius)
    else:
        atol = explicit_abs_tol(p, rtol)
        h0 = default_step_size(p, settings, rtol)
        s = explicit_settings(settings.t_final, atol, h0, None if step_size is None else float(step_size))
        info.update(atol=atol, step_size=None if step_size is None else float(step_size))
    if perturbation:
        info["perturbation"] = perturbation
    bar = Progress(settings.t_final, progress, label=f"exudyn {p.model} n={p.n}")
    sample = functools.partial(Sampler, mbs, settings.sample_times(), layout, monitor, samples_per_check, bar)
    solver, sampler, error = _solve(mbs, s, method, sample, bar)
    wall = _time.perf_counter() - start
    time, q, q_t = _samples(sampler, error, layout.coordinates(initial))
    if q.shape[1] > layout.size:  # the sail's world line (model/world_line.py) after the tree's coordinates
        info["world_line"] = world_line.record(q[:, layout.size :], q_t[:, layout.size :])
    x, y, theta, z = layout.positions(q)
    vx, vy, omega, z_rate = layout.velocities(q, q_t)
    info.update(
        steps=int(sampler.steps if sampler else 0),
        rejected_steps=int(getattr(solver.it, "rejectedAutomaticStepSizeSteps", 0)),
        newton_iterations=int(solver.it.newtonStepsCount),
        njev=int(solver.it.newtonJacobiCount),
        coordinates=layout.size,
        formulation="ObjectKinematicTree (minimal coordinates), net slice load compiled",
    )
    return Result.from_trajectory(
        p,
        "exudyn",
        time,
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


def _check_options(method, rtol, step_size, spectral_radius, perturbation) -> None:
    """ParameterError for a method or option value out of its range."""
    if method not in METHODS:
        raise ParameterError(f"method={method!r} is invalid: allowed one of {', '.join(METHODS)}")
    if not (isinstance(rtol, (int, float)) and 0 < rtol < 1):
        raise ParameterError(f"rtol={rtol!r} is invalid: allowed 0 < rtol < 1")
    if step_size is not None and not (step_size > 0 and math.isfinite(step_size)):
        raise ParameterError(f"step_size={step_size!r} is invalid: allowed a finite step > 0 (s)")
    if not 0 <= spectral_radius <= 1:
        raise ParameterError(f"spectral_radius={spectral_radius!r} is invalid: allowed 0 ≤ ρ∞ ≤ 1")
    if not (perturbation >= 0 and math.isfinite(perturbation)):
        raise ParameterError(f"perturbation={perturbation!r} is invalid: allowed a finite value ≥ 0 (m)")


def _method(p: SailParameters, method: str, step_size, newton_rel_tol, newton_abs_tol) -> tuple[str, str]:
    """(method, reason) of a run: choose_method's for "auto" unless generalized-α options are given."""
    chosen, reason = choose_method(p)
    implicit_only = [
        name
        for name, v in (
            ("step_size", step_size),
            ("newton_rel_tol", newton_rel_tol),
            ("newton_abs_tol", newton_abs_tol),
        )
        if v is not None
    ]
    if method == "auto":
        method = "generalized-alpha" if implicit_only else chosen
        if implicit_only:
            reason = f"generalized-α options given ({', '.join(implicit_only)})"
    else:
        reason = "asked for"
    if method == "DOPRI5" and (p.boundary != "free" or p.tip_load):
        raise ParameterError("method='DOPRI5' is invalid with supports or a tip load: allowed 'generalized-alpha'")
    return method, reason


def _solve(mbs, s, method: str, sample, bar):
    """Run Exudyn's solver of `method` with the post-step sampler that sample() makes once the solver is
    initialised (it reads the initial accelerations): (solver, sampler or None if the run failed before
    it, error or None)."""
    import exudyn as exu

    solver = exu.MainSolverImplicitSecondOrder() if method == "generalized-alpha" else exu.MainSolverExplicit()
    made = []

    def start_sampling():
        made.append(sample())
        mbs.SetPostStepUserFunction(made[0])

    error = solve_steps(
        solver,
        mbs,
        s,
        bar,
        failure=f"{method} failed",
        stopped=lambda: made[0].failed_at is not None,
        initialised=start_sampling,
    )
    return solver, (made[0] if made else None), error


def _samples(sampler: Sampler | None, error: str | None, q0: np.ndarray):
    """(time, q, q̇) of the run's samples; after an error only those with a finite state; the initial
    coordinates q0 at rest when the run failed before its first step (no sampler)."""
    if sampler is None:
        return np.zeros(1), q0[None, :], np.zeros_like(q0[None, :])
    sampler.check(final=error is None)
    time, q, q_t = sampler.arrays()
    if error is not None:  # keep the samples with a finite state
        finite = np.all(np.isfinite(q), axis=1) & np.all(np.isfinite(q_t), axis=1)
        keep = int(np.argmin(finite)) if not finite.all() else finite.size
        time, q, q_t = time[: max(keep, 1)], q[: max(keep, 1)], q_t[: max(keep, 1)]
    return time, q, q_t
