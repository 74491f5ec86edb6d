"""The in-house reduced-Lagrangian solver (`solve(params, "reduced")`), independent of Exudyn.

Minimal coordinates q = (x₁, y₁, θ₁…θₙ[, z₁…zₙ₋₁]) (paper Eqs 13–14, 30–31), equations of
motion M(q) q̈ = Q(q, q̇) − c(q, q̇) (Eq. 16, 39) solved for q̈ in O(n) by reduced_dynamics.py, and
integrated as the first-order system ẏ = (q̇, q̈) (Eq. 40):

* rigid, torsion and inextensible TnT chains: explicit 8th-order Dormand–Prince (DOP853);
* extensible TnT chain (axial springs, ω ~ √(k_s/m) ~ 10⁵–10⁶ rad/s): implicit Radau IIA (order 5)
  with the dense forward-difference Jacobian of the compiled right-hand side.

Both run as numba-compiled step loops (reduced_integrator.py, reduced_radau.py: the same steps as
scipy's DOP853 and Radau, tested) on the compiled O(n) right-hand side (reduced_dynamics.py);
RK45, BDF and LSODA use scipy's steppers on the same right-hand side.

Output is sampled from the integrator's dense output on settings.sample_times() by the run skeleton
(solvers.skeleton; compiled integrators: sampling.CHUNK samples per call); the run stops at the first
sample whose amplitude reaches settings.failure_ratio × initial when settings.stop_at_failure. A failed
step or a non-finite state ends the run and is recorded in Result.error with the trajectory up to there.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import BDF, LSODA, RK45

from lightsail_mbs import analysis
from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import ParameterError, SailParameters
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.reduced import supports
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
)
from lightsail_mbs.solvers.settings import RunSettings

COMPILED = {"DOP853": Dop853, "Radau": CompiledRadau}  # numba step loops
METHODS = {**COMPILED, "RK45": RK45, "BDF": BDF, "LSODA": LSODA}  # the others: scipy's steppers
IMPLICIT = ("Radau", "BDF", "LSODA")
# Convergence study (validation/reduced_scaling.py --tolerances): failure times of the soft paper cases
# move < 2e-4 (DOP853) and < 4e-5 (Radau) relative from rtol 1e-6 to 1e-9. DOP853 runs at 1e-9, where
# free vibration conserves energy to 1e-8, for < 2× the cost of 1e-6; Radau stays at 1e-6 (each decade
# costs it ~2× more steps, and its L-stable damping of the axial modes is not energy-conserving anyway).
DEFAULT_RTOL = {"DOP853": 1e-9, "Radau": 1e-6}
OPTIONS = ("max_step", "first_step", "perturbation")


def default_method(p: SailParameters) -> str:
    """DOP853 for the non-stiff chains, Radau for the stiff extensible TnT chain."""
    return "Radau" if p.extensible else "DOP853"


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

    rtol: relative tolerance (default DEFAULT_RTOL[method], 1e-6 for scipy's methods); atol: absolute tolerance,
    a scalar or one value per state entry (default rtol × state_scales(model, ν)); method: DOP853, RK45,
    Radau, BDF or LSODA (default: default_method(params)); options: max_step, first_step, perturbation (m:
    the amplitude of the seeded roughness shapes.initial_state adds to the start, the conditioning probe of
    solvers.uncertainty).
    """
    if supports.needs_boundary(params):  # supports or a tip load (validations): dense constrained chain
        return supports.run(params, settings, progress=progress, rtol=rtol, atol=atol, method=method, **options)
    unknown = sorted(set(options) - set(OPTIONS))
    if unknown:
        raise ParameterError(f"option {unknown[0]!r} is invalid: allowed {', '.join(OPTIONS)}")
    method = method or default_method(params)
    if method not in METHODS:
        raise ParameterError(f"method={method!r} is invalid: allowed one of {', '.join(METHODS)}")
    if rtol is None:
        rtol = DEFAULT_RTOL.get(method, 1e-6)
    rtol = float(rtol)
    if not 0 < rtol < 1:
        raise ParameterError(f"rtol={rtol!r} is invalid: allowed 0 < rtol < 1")
    model = ChainModel.from_params(params)
    dynamics = ChainDynamics(model)
    if atol is None:
        atol = rtol * state_scales(model, params.defect_mode)

    perturbation = float(options.pop("perturbation", 0.0))
    if not (perturbation >= 0 and np.isfinite(perturbation)):
        raise ParameterError(f"perturbation={perturbation!r} is invalid: allowed a finite value ≥ 0 (m)")
    start = shapes.initial_state(params, perturbation=perturbation)
    q0 = model.pack(start.x[0], start.y[0], start.theta, start.z)
    y0 = np.concatenate([q0, np.zeros_like(q0)])
    if method in COMPILED:
        atol = np.broadcast_to(np.asarray(atol, float), y0.shape)
        extra = dict(jac_scales=np.maximum(atol / rtol, 1e-300)) if method == "Radau" else {}
        integrator = COMPILED[method](
            dynamics.constants,
            y0,
            settings.t_final,
            rtol,
            atol,
            max_step=options.get("max_step", np.inf),
            first_step=options.get("first_step"),
            **extra,
        )
        advance, chunk = compiled_advance(method, integrator), CHUNK
    else:
        kwargs = dict(rtol=rtol, atol=atol, **options)
        if method in IMPLICIT:
            scales = np.maximum(np.broadcast_to(atol, y0.shape) / rtol, 1e-300)
            kwargs["jac"] = lambda t, y: dynamics.jacobian(t, y, scales)
        integrator = METHODS[method](dynamics.rhs, 0.0, y0, settings.t_final, **kwargs)
        advance, chunk = stepper_advance(method, integrator, y0.size), settings.sample_times().size
    states, error, wall = sampled_run(
        model, y0, analysis.amplitude(start.x, start.y), settings, advance, chunk, progress
    )
    info = dict(
        method=method,
        rtol=rtol,
        atol=float(np.min(atol)),
        steps=integrator.steps,
        nfev=integrator.nfev,
        njev=getattr(integrator, "njev", 0),
        nlu=getattr(integrator, "nlu", 0),
        coordinates=model.dof,
        formulation="minimal coordinates, O(n) joint-force recursion (block LDLT), compiled",
    )
    if perturbation:
        info["perturbation"] = perturbation
    return trajectory_result(model, settings, states, wall_time=wall, error=error, info=info)
