"""The in-house reduced-Lagrangian solver (`solve(params, "reduced")`), independent of Exudyn.

Minimal coordinates q = (x₁, y₁, θ₁…θₙ[, z₁…zₙ₋₁]) (paper Eqs 13–14, 30–31), equations of
motion M(q) q̈ = Q(q, q̇) − c(q, q̇) (Eq. 16, 39) solved for q̈ in O(n) by dynamics.py, and
integrated as the first-order system ẏ = (q̇, q̈) (Eq. 40) by one of two compiled integrators:

* DOP853 (dop853.py): explicit 8th-order Dormand–Prince, for chains whose fastest spring mode the
  accuracy-limited step resolves anyway;
* Radau (radau.py): implicit Radau IIA (order 5) with the O(n) Newton matrix of newton.py, for stiff
  chains: the bending springs of a finely cut torsion sail (top mode ∝ n²) and the axial springs of
  the extensible TnT chain (ω ~ √(k_s/m) ~ 10⁵–10⁶ rad/s).

Both run as numba-compiled step loops on the compiled right-hand side; RK45, BDF and LSODA use
scipy's steppers on the same right-hand side.

The method is chosen from the case's stiffness (`choose_method`) unless given. An explicit method's
step is bounded by stability, h ≲ c/ω_max, with ω_max the chain's fastest spring mode::

    bending:  ω_T = 2 √(k_T/J)   (zig-zag mode: neighbouring slices turn in opposition about fixed
              centres, 4 k_T restoring torque on inertia J = m l²/12; ∝ n² at fixed E, h, ρ, L),
    axial:    ω_s = 2 √(k_s/m)   (neighbouring slices in opposition along the chain).

The motion the answer needs is slower: ω_slow = max(1/t_c, j² ω₁, j ω_string) with j = RESOLVED_MODES:
the failure-time scale t_c = 1/(k √(g₀ a₀)), k = 2πν/L (Eq. 9); the lowest free–free bending mode
ω₁ = (β₁L)² √(EI/(ρhW L⁴)) (bending mode j at ≈ j² ω₁: the initial shape excites the bending modes, and
an accurate run resolves the lowest ones whatever the method); the tensioned string's fundamental
π/L √(T/(ρhW)) (mode j at j times it). The explicit step count forced by stability exceeds the one
accuracy needs by about ω_max/ω_slow, so the implicit method is chosen when that ratio exceeds
STIFFNESS_THRESHOLD, calibrated by running both methods on the paper's torsion runs for E = 4.5e9…4.5e13
Pa and n = 30…240 (validation/benchmark_reduced.py --choice): they cost the same near a ratio of 10–25,
and Radau is 1.2–4× cheaper from 45 on (it also damps the high bending modes the initial shape
excites, then steps over them). For torsion chains the ratio is ≈ n²/323 (Radau from n ≈ 90), for the
extensible TnT chain 10⁴–10⁶ (always Radau), for the rigid chain and the TnT chain without bending 0
(DOP853). The choice and its inputs
are recorded in Result.info (method, method_choice, omega_bending, omega_axial, omega_slow,
failure_rate = 1/t_c, stiffness_ratio, stiffness_threshold).

Output is sampled from the integrator's dense output on settings.sample_times() by the run skeleton
(solvers.skeleton; compiled integrators: sampling.CHUNK samples per call); the run stops at the first
sample whose amplitude reaches settings.failure_ratio × initial when settings.stop_at_failure. A failed
step or a non-finite state ends the run and is recorded in Result.error with the trajectory up to there.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import shapes, world_line
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.reduced.dop853 import Dop853
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.solvers.reduced.kinematics import ChainModel
from lightsail_mbs.solvers.reduced.radau import Radau as CompiledRadau
from lightsail_mbs.solvers.reduced.sampling import (
    CHUNK,
    compiled_advance,
    sampled_run,
    state_scales,
    stepper_advance,
    trajectory_result,
    world_scales,
)
from lightsail_mbs.solvers.reduced.warmup import compile_notice

COMPILED = {"DOP853": Dop853, "Radau": CompiledRadau}  # numba step loops
SCIPY = ("RK45", "BDF", "LSODA")  # scipy's steppers
METHODS = (*COMPILED, *SCIPY)
IMPLICIT = ("Radau", "BDF", "LSODA")
# Default tolerances, from the answer's accuracy (validation/benchmark_reduced.py --tolerances; reference
# rtol 1e-10): DOP853 at rtol 1e-8 moves the paper's failure times by ≤ 4e-4 relative (soft torsion
# n = 30: 5e-7, n = 120: 4e-4; rigid n = 40: 5e-5) and the stable sail's largest amplitude ratio by 1e-8,
# at least ten times below the error of the chain itself at the n where DOP853 is chosen (n < 90:
# ≥ 3e-3 relative, docs/convergence.md), and conserves energy in free vibration to 2e-8; 1e-9 costs 1.3×
# the steps. Radau at 1e-6: soft torsion to failure at n = 300 and 1000 moves ≤ 3e-6 relative from
# rtol 1e-6 to 1e-9, and each decade costs it ~2× more steps.
DEFAULT_RTOL = {"DOP853": 1e-8, "Radau": 1e-6}
OPTIONS = ("max_step", "first_step", "perturbation")
STIFFNESS_THRESHOLD = 25.0  # ω_max/ω_slow above which the implicit method is chosen (calibrated)
FREE_FREE_BETA_L = 4.730040744862704  # β₁L of the lowest free–free beam mode
RESOLVED_MODES = 10  # the lowest bending or string modes counted as motion the answer needs


def stiffness(params: SailParameters) -> dict:
    """The frequencies behind the method choice (rad/s; module docstring) and the ratio ω_max/ω_slow.

    Returns omega_bending (2√(k_T/J)), omega_axial (2√(k_s/m)), omega_slow, failure_rate (1/t_c) and
    stiffness_ratio (None when ω_slow = 0: nothing slow to resolve).
    """
    p = params
    model = ChainModel.from_params(p)
    omega_bend = 2.0 * math.sqrt(model.torsional_stiffness / model.inertia) if model.torsional_stiffness else 0.0
    omega_axial = 2.0 * math.sqrt(model.axial_stiffness / model.mass) if model.extensible else 0.0
    wavenumber = 2 * math.pi * p.defect_mode / p.length
    failure_rate = wavenumber * math.sqrt(max(p.nominal_acceleration, 0.0) * p.displacement_scale)
    line_mass = p.density * p.thickness * p.width  # kg/m
    omega_first = 0.0
    if model.torsional_stiffness:
        omega_first = FREE_FREE_BETA_L**2 * math.sqrt(
            p.youngs_modulus * p.second_moment_of_area / (line_mass * p.length**4)
        )
    omega_string = math.pi / p.length * math.sqrt(model.tension / line_mass) if model.tension > 0 else 0.0
    j = RESOLVED_MODES
    omega_slow = max(failure_rate, j * j * omega_first, j * omega_string)
    omega_max = max(omega_bend, omega_axial)
    ratio = omega_max / omega_slow if omega_slow > 0 else (None if omega_max > 0 else 0.0)
    return dict(
        omega_bending=omega_bend,
        omega_axial=omega_axial,
        omega_slow=omega_slow,
        failure_rate=failure_rate,
        stiffness_ratio=ratio,
    )


def choose_method(params: SailParameters) -> tuple[str, dict]:
    """("Radau" or "DOP853", the stiffness figures behind the choice): Radau when
    ω_max/ω_slow > STIFFNESS_THRESHOLD (or ω_slow = 0 < ω_max)."""
    figures = stiffness(params)
    ratio = figures["stiffness_ratio"]
    return ("Radau" if ratio is None or ratio > STIFFNESS_THRESHOLD else "DOP853"), figures


def run(
    params: SailParameters,
    settings: RunSettings,
    *,
    progress: bool = False,
    rtol: float | None = None,
    atol=None,
    method: str | None = None,
    **options,
) -> Result:
    """Integrate one case in minimal coordinates and return its Result (solver "reduced").

    rtol: relative tolerance (default DEFAULT_RTOL[method], 1e-6 for scipy's methods); atol: absolute
    tolerance, a scalar or one value per state entry (default rtol × state_scales(model, ν)); method:
    "auto" (default: choose_method, from the case's stiffness), DOP853, Radau, RK45, BDF or LSODA;
    options: max_step, first_step, perturbation (m: the amplitude of the seeded roughness
    shapes.initial_state adds to the start, the conditioning probe of solvers.uncertainty).
    """
    if params.boundary != "free" or params.tip_load != 0.0:  # validations: the dense constrained chain
        from lightsail_mbs.solvers.reduced import supports

        return supports.run(params, settings, progress=progress, rtol=rtol, atol=atol, method=method, **options)
    unknown = sorted(set(options) - set(OPTIONS))
    if unknown:
        raise ParameterError(f"option {unknown[0]!r} is invalid: allowed {', '.join(OPTIONS)}")
    if method in (None, "auto"):
        method, figures = choose_method(params)
        choice = "auto"
    elif method in METHODS:
        figures, choice = stiffness(params), "user"
    else:
        raise ParameterError(f"method={method!r} is invalid: allowed auto or one of {', '.join(METHODS)}")
    if rtol is None:
        rtol = DEFAULT_RTOL.get(method, 1e-6)
    rtol = float(rtol)
    if not 0 < rtol < 1:
        raise ParameterError(f"rtol={rtol!r} is invalid: allowed 0 < rtol < 1")
    model = ChainModel.from_params(params)
    world = params.integrated_trajectory
    dynamics = ChainDynamics(model, world)
    if atol is None:
        scales = state_scales(model, params.defect_mode)
        atol = rtol * (world_scales(scales) if world else scales)

    perturbation = float(options.pop("perturbation", 0.0))
    if not (perturbation >= 0 and np.isfinite(perturbation)):
        raise ParameterError(f"perturbation={perturbation!r} is invalid: allowed a finite value ≥ 0 (m)")
    start = shapes.initial_state(params, perturbation=perturbation)
    q0 = model.pack(start.x[0], start.y[0], start.theta, start.z)
    y0 = np.concatenate([q0, np.zeros_like(q0)])
    if world:  # the sail's world line after the chain's coordinates and rates (model/world_line.py)
        s0, u0 = world_line.start(params.initial_beta)
        y0 = np.concatenate([q0, s0, np.zeros_like(q0), u0])
    with compile_notice(method):  # one line on stderr if numba has to compile the kernels
        integrator, advance, chunk = _integrator(method, dynamics, y0, settings, rtol, atol, options)
        trajectory, error, wall = sampled_run(model, y0, settings, advance, chunk, progress)
        info = dict(
            method=method,
            method_choice=choice,
            stiffness_threshold=STIFFNESS_THRESHOLD,
            **figures,
            rtol=rtol,
            atol=float(np.min(atol)),
            steps=integrator.steps,
            nfev=integrator.nfev,
            njev=getattr(integrator, "njev", 0),
            nlu=getattr(integrator, "nlu", 0),
            coordinates=model.dof,
            formulation="minimal coordinates, O(n) joint-force recursion (block LDLT), compiled; implicit: "
            "O(n) compliant-joint Newton matrix",
        )
        if perturbation:
            info["perturbation"] = perturbation
        return trajectory_result(model, settings, trajectory, wall_time=wall, error=error, info=info)


def _integrator(method, dynamics, y0, settings, rtol, atol, options):
    """(integrator, its advance adapter for the sampling loop, samples per call) of one run."""
    if method in COMPILED:
        atol = np.broadcast_to(np.asarray(atol, float), y0.shape)
        integrator = COMPILED[method](
            dynamics.constants,
            y0,
            settings.t_final,
            rtol,
            atol,
            max_step=options.get("max_step", np.inf),
            first_step=options.get("first_step"),
        )
        integrator.advance(np.empty(0))  # load the kernel, f(y₀), first step: before the run's clock starts
        return integrator, compiled_advance(method, integrator), CHUNK
    import scipy.integrate

    kwargs = dict(rtol=rtol, atol=atol, **options)
    if method in IMPLICIT:
        scales = np.maximum(np.broadcast_to(atol, y0.shape) / rtol, 1e-300)
        kwargs["jac"] = lambda t, y: dynamics.jacobian(t, y, scales)
    integrator = getattr(scipy.integrate, method)(dynamics.rhs, 0.0, y0, settings.t_final, **kwargs)
    return integrator, stepper_advance(method, integrator, y0.size), settings.sample_times().size
