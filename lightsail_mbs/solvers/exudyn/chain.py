"""Exudyn solver: the sail as a chain of rigid slices integrated by one of Exudyn's integrators.

Model (paper Sec. III.A–C; details in solvers.exudyn.tree): n planar rigid slices (m = ρhWl,
J = ml²/12) joined by revolute joints, as ONE Exudyn ``ObjectKinematicTree`` in the paper's
own minimal coordinates q = [X, Y, θ₁, (z₁), φ₂, …] (Eqs 13–14, 30–31).
torsion: torsional spring-dampers k_T = EI/l on θ_{k+1} − θ_k; rigid: none; tnt: k_T per
params.bending, each hinge also slides along the preceding slice (spring-damper k_s, pre-stretched
to T/k_s) and the follower tension T acts at both ends along the end slices (Eq. 32); with
params.axial_springs=False the slides are rigid (plain revolute joints + end tension).
The frame accelerates at g₀: every slice carries −m g₀ ŷ, inside the net slice force of the shared
load model (loads.applied_forces), and x, y are slice centres in that frame.
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

Sampling and the stop rule (the run skeleton's, solvers.skeleton): a post-step function keeps q, q̇,
q̈ after every step and interpolates the output samples t_k = k·Δt that the steps passed by the quintic
Hermite polynomial of the two ends of each one's step (exact at a step end; the generalized-α steps
divide the output interval when shorter than it). Every SAMPLES_PER_CHECK samples — sooner when the
amplitude's growth since the last check predicts failure before the next one, so that no time is spent
integrating the crumpling sail past failure — or after STEPS_PER_CHECK steps (an explosively crumpling
chain shrinks the explicit steps faster than any prediction from the samples), and at the end, it asks
the skeleton's FailureMonitor for the first sample at or above the limit; the run stops there and keeps that sample.
stop_at_failure=False runs on. A Newton failure, a too small step, an Exudyn error or a non-finite
state is recorded in Result.error with the samples up to there.
"""

from __future__ import annotations

import math
import time as _time

import numpy as np

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import failure, shapes, theory
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.exudyn.console import silenced
from lightsail_mbs.solvers.exudyn.supports import add_supports
from lightsail_mbs.solvers.exudyn.tree import ChainLayout, generalized_force, tree_arguments
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
STEPS_PER_CHECK = 100  # ... or after this many steps: a crumpling sail (steps shrinking) stops soon after failure
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


class Sampler:
    """The post-step function of a run: samples the output grid from the steps and applies the stop rule.

    After every step it keeps t, q, q̇, q̈; every ``check_every`` output samples (and at the end) it
    interpolates the samples the new steps passed, by the quintic Hermite polynomial through both ends
    of the step that holds each (exact at a step end), and asks the monitor for the first sample at or
    above the limit; it keeps the samples up to and including that one and returns False (stop).
    """

    def __init__(self, mbs, times: np.ndarray, layout: ChainLayout, monitor: FailureMonitor, check_every: int, bar):
        self.times, self.layout, self.monitor, self.bar = times, layout, monitor, bar
        self.check_every = max(1, int(check_every))
        data = mbs.systemData
        q0 = np.array(data.GetODE2Coordinates())
        self.steps_t = [0.0]
        self.steps_q = [q0]
        self.steps_v = [np.array(data.GetODE2Coordinates_t())]
        self.steps_a = [np.array(data.GetODE2Coordinates_tt())]
        self.q, self.v = [q0], [self.steps_v[0]]  # samples (rows)
        self.failed_at = None  # index of the first sample at or above the limit
        self.steps = 0
        self._next_check = min(self.check_every, times.size - 1)
        x, y, _, _ = layout.positions(q0)
        self._last = (0.0, failure.amplitude(x, y))  # time and amplitude of the last checked sample

    def __call__(self, mbs, t) -> bool:
        self.steps += 1
        data = mbs.systemData
        self.steps_t.append(float(t))
        self.steps_q.append(np.array(data.GetODE2Coordinates()))
        self.steps_v.append(np.array(data.GetODE2Coordinates_t()))
        self.steps_a.append(np.array(data.GetODE2Coordinates_tt()))
        if self.steps_t[-1] >= self.times[self._next_check] * (1 - 1e-13) or len(self.steps_t) > STEPS_PER_CHECK:
            self.bar.update(self.steps_t[-1])
            return not self.check()
        return True

    def _sample(self) -> None:
        """Interpolate the output times passed by the kept steps (then forget all but the last step)."""
        t = np.asarray(self.steps_t)
        k0 = len(self.q)
        k1 = int(np.searchsorted(self.times, t[-1] * (1 + 1e-13) + 1e-300, side="right"))
        if k1 > k0:
            times = self.times[k0:k1]
            step = np.clip(np.searchsorted(t, times * (1 - 1e-13), side="left"), 1, t.size - 1)
            q, v = hermite(
                (t[step - 1], *(np.asarray(a)[step - 1] for a in (self.steps_q, self.steps_v, self.steps_a))),
                (t[step], *(np.asarray(a)[step] for a in (self.steps_q, self.steps_v, self.steps_a))),
                times,
            )
            self.q.extend(q)
            self.v.extend(v)
        for kept in (self.steps_t, self.steps_q, self.steps_v, self.steps_a):
            del kept[:-1]

    def check(self) -> bool:
        """Sample, then check the new samples; True (and the samples cut after it) at the first one at or
        above the limit."""
        if self.failed_at is not None:
            return True
        checked = len(self.q)
        self._sample()
        every = self.check_every
        if self.monitor.active and len(self.q) > checked:
            x, y, _, _ = self.layout.positions(np.asarray(self.q[checked:]))
            amplitude = np.atleast_1d(failure.amplitude(x, y))
            over = self.monitor.first_failure(amplitude)
            if over is not None:
                self.failed_at = checked + over
                del self.q[self.failed_at + 1 :]
                del self.v[self.failed_at + 1 :]
                return True
            every = self._samples_to_next_check(self.times[len(self.q) - 1], float(amplitude[-1]))
        self._next_check = min(len(self.q) - 1 + every, self.times.size - 1)
        return False

    def _samples_to_next_check(self, t: float, amplitude: float) -> int:
        """check_every, or fewer when the amplitude, growing exponentially at the rate measured since the
        last check, would reach the limit within twice that many samples: then half the predicted time to
        the limit (at least one sample), so the run stops within a few steps of failure instead of
        integrating the crumpling sail past it."""
        t_last, a_last = self._last
        self._last = (t, amplitude)
        if not (amplitude > a_last > 0 and t > t_last):
            return self.check_every
        rate = math.log(amplitude / a_last) / (t - t_last)
        to_limit = math.log(self.monitor.limit / amplitude) / rate
        dt = self.times[1] - self.times[0] if self.times.size > 1 else to_limit
        return int(max(1, min(self.check_every, math.floor(0.5 * to_limit / dt))))

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(time, q, q̇) of the samples taken."""
        rows = len(self.q)
        return self.times[:rows], np.asarray(self.q), np.asarray(self.v)


def hermite(start, end, times) -> tuple[np.ndarray, np.ndarray]:
    """q and q̇ at `times` within the step [t₀, t₁] from (t, q, q̇, q̈) at both ends: the quintic Hermite
    polynomial and its derivative (error O(h⁶) in q, O(h⁵) in q̇)."""
    t0, q0, v0, a0 = start
    t1, q1, v1, a1 = end
    h = np.asarray(t1 - t0, float).reshape(-1, 1)
    s = np.clip((np.asarray(times) - np.asarray(t0).reshape(-1)) / h[:, 0], 0.0, 1.0)[:, None]
    s2, s3 = s * s, s * s * s
    s4, s5 = s3 * s, s3 * s2
    q = (
        (1 - 10 * s3 + 15 * s4 - 6 * s5) * q0
        + (s - 6 * s3 + 8 * s4 - 3 * s5) * (h * v0)
        + 0.5 * (s2 - 3 * s3 + 3 * s4 - s5) * (h * h * a0)
        + (10 * s3 - 15 * s4 + 6 * s5) * q1
        + (-4 * s3 + 7 * s4 - 3 * s5) * (h * v1)
        + 0.5 * (s3 - 2 * s4 + s5) * (h * h * a1)
    )
    v = (
        (-30 * s2 + 60 * s3 - 30 * s4) * ((q0 - q1) / h)
        + (1 - 18 * s2 + 32 * s3 - 15 * s4) * v0
        + 0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4) * (h * a0)
        + (-12 * s2 + 28 * s3 - 15 * s4) * v1
        + 0.5 * (3 * s2 - 8 * s3 + 5 * s4) * (h * a1)
    )
    return list(q), list(v)


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
    import exudyn as exu

    if options:
        raise ParameterError(f"options={sorted(options)} are invalid: the exudyn solver accepts {', '.join(OPTIONS)}")
    p = params
    dt = settings.sample_interval
    if method not in METHODS:
        raise ParameterError(f"method={method!r} is invalid: allowed one of {', '.join(METHODS)}")
    rtol = DEFAULT_RTOL if rtol is None else rtol
    if not (isinstance(rtol, (int, float)) and 0 < rtol < 1):
        raise ParameterError(f"rtol={rtol!r} is invalid: allowed 0 < rtol < 1")
    if step_size is not None and not (step_size > 0 and math.isfinite(step_size)):
        raise ParameterError(f"step_size={step_size!r} is invalid: allowed a finite step > 0 (s)")
    if not 0 <= spectral_radius <= 1:
        raise ParameterError(f"spectral_radius={spectral_radius!r} is invalid: allowed 0 ≤ ρ∞ ≤ 1")
    if not (perturbation >= 0 and math.isfinite(perturbation)):
        raise ParameterError(f"perturbation={perturbation!r} is invalid: allowed a finite value ≥ 0 (m)")
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
        h = step_in_grid(default_step_size(p, settings, rtol) if step_size is None else float(step_size), dt)
        s = simulation_settings(settings.t_final, h, rel_tol, abs_tol, spectral_radius)
        solver = exu.MainSolverImplicitSecondOrder()
        info.update(step_size=h, newton_rel_tol=rel_tol, newton_abs_tol=abs_tol, spectral_radius=spectral_radius)
    else:
        atol = explicit_abs_tol(p, rtol)
        h0 = default_step_size(p, settings, rtol)
        s = explicit_settings(settings.t_final, atol, h0, None if step_size is None else float(step_size))
        solver = exu.MainSolverExplicit()
        info.update(atol=atol, step_size=None if step_size is None else float(step_size))
    if perturbation:
        info["perturbation"] = perturbation
    bar = Progress(settings.t_final, progress, label=f"exudyn {p.model} n={p.n}")
    error = None
    sampler = None
    try:
        with silenced():
            solver.InitializeSolver(mbs, s)
            sampler = Sampler(mbs, settings.sample_times(), layout, monitor, samples_per_check, bar)
            mbs.SetPostStepUserFunction(sampler)
            ok = solver.SolveSteps(mbs, s)
            if not ok and sampler.failed_at is None:
                error = f"{method} failed at t = {solver.it.currentTime:.9g} s (exudyn: {solver.GetErrorString()})"
            elif not np.all(np.isfinite(mbs.systemData.GetODE2Coordinates())):
                error = f"non-finite state at t = {solver.it.currentTime:.9g} s"
            solver.FinalizeSolver(mbs, s)
    except exu.ExudynError as exc:  # solver failures are results, not crashes
        error = f"exudyn: {exc}".strip()
    finally:
        bar.update(solver.it.currentTime)
        bar.close()
    wall = _time.perf_counter() - start
    if sampler is None:  # failed before the first step
        time = np.zeros(1)
        q = layout.coordinates(initial)[None, :]
        q_t = np.zeros_like(q)
    else:
        sampler.check()
        time, q, q_t = sampler.arrays()
        if error is not None:  # keep the samples with a finite state
            finite = np.all(np.isfinite(q), axis=1) & np.all(np.isfinite(q_t), axis=1)
            keep = int(np.argmin(finite)) if not finite.all() else finite.size
            time, q, q_t = time[: max(keep, 1)], q[: max(keep, 1)], q_t[: max(keep, 1)]
    x, y, theta, z = layout.positions(q)
    vx, vy, omega, z_rate = layout.velocities(q, q_t)
    info.update(
        steps=int(sampler.steps if sampler else 0),
        rejected_steps=int(getattr(solver.it, "rejectedAutomaticStepSizeSteps", 0)),
        newton_iterations=int(solver.it.newtonStepsCount),
        jacobian_evaluations=int(solver.it.newtonJacobiCount),
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
