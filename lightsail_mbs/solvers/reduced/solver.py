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

Output is sampled from the integrator's dense output every params.sample_interval (compiled
integrators: CHUNK samples per call); the run stops at the first sample whose amplitude (analysis.amplitude) reaches failure_ratio × initial
when params.stop_at_failure. A failed step or a non-finite state ends the run and is recorded
in Result.error with the trajectory up to that point.
"""
from __future__ import annotations

import math
import time as clock

import numpy as np
from scipy.integrate import BDF, LSODA, RK45

from lightsail_mbs import analysis
from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import ParameterError, SailParameters
from lightsail_mbs.solvers.progress import Progress
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.reduced import supports as reduced_boundary
from lightsail_mbs.solvers.reduced.supports import needs_boundary
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.solvers.reduced.dop853 import FINISHED, STATUS, Dop853
from lightsail_mbs.solvers.reduced.radau import Radau as CompiledRadau
from lightsail_mbs.solvers.reduced.kinematics import ChainModel, centre_velocities, centres

COMPILED = {"DOP853": Dop853, "Radau": CompiledRadau}          # numba step loops
METHODS = {**COMPILED, "RK45": RK45, "BDF": BDF, "LSODA": LSODA}   # the others: scipy's steppers
IMPLICIT = ("Radau", "BDF", "LSODA")
# Convergence study (validation/reduced_scaling.py --tolerances): failure times of the soft paper cases
# move < 2e-4 (DOP853) and < 4e-5 (Radau) relative from rtol 1e-6 to 1e-9. DOP853 runs at 1e-9, where
# free vibration conserves energy to 1e-8, for < 2× the cost of 1e-6; Radau stays at 1e-6 (each decade
# costs it ~2× more steps, and its L-stable damping of the axial modes is not energy-conserving anyway).
DEFAULT_RTOL = {"DOP853": 1e-9, "Radau": 1e-6}
OPTIONS = ("max_step", "first_step")


def default_method(p: SailParameters) -> str:
    """DOP853 for the non-stiff chains, Radau for the stiff extensible TnT chain."""
    return "Radau" if p.extensible else "DOP853"


def state_scales(model: ChainModel) -> np.ndarray:
    """Typical magnitudes of y = (q, q̇) for the absolute tolerances.

    Positions: the defect amplitude a₀ (p.displacement_scale: 1e-6 L for a flat sail) (x₁, y₁ and the extensions z, which therefore carry the same
    absolute accuracy as the transverse displacements: the stiff axial vibration at √(k_s/m) is then
    not resolved but damped by the L-stable implicit method, as in Exudyn's generalized-α) and the
    defect slope 2πνa₀/L (θ); rates: those over the fastest bending/axial time scale of the chain
    (floored by a 1 ms time scale).
    """
    p = model.params
    position = p.displacement_scale
    slope = 2 * math.pi * p.mode * position / p.length
    rate = 1e3
    if model.torsional_stiffness:
        rate = max(rate, math.sqrt(model.torsional_stiffness / model.inertia))
    scales = [position, position] + [slope] * p.n
    if model.extensible:
        scales += [position] * (p.n - 1)
        rate = max(rate, math.sqrt(model.axial_stiffness / model.mass))
    scales = np.array(scales)
    return np.concatenate([scales, scales * rate])


def run(params: SailParameters, *, progress: bool = False, rtol: float | None = None, atol=None,
        method: str | None = None, **options) -> Result:
    """Integrate one case in minimal coordinates and return its Result (solver "reduced").

    rtol: relative tolerance (default DEFAULT_RTOL[method], 1e-6 for scipy's methods); atol: absolute tolerance,
    a scalar or one value per state entry (default rtol × state_scales); method: DOP853, RK45,
    Radau, BDF or LSODA (default: default_method(params)); options: max_step, first_step.
    """
    if needs_boundary(params):      # supports or a tip load (validations): dense constrained chain
        return reduced_boundary.run(params, progress=progress, rtol=rtol, atol=atol, method=method, **options)
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
        atol = rtol * state_scales(model)

    start = shapes.initial_state(params)
    q0 = model.pack(start.x[0], start.y[0], start.theta, start.z)
    y0 = np.concatenate([q0, np.zeros_like(q0)])
    sample_times = params.sample_times()
    amp0 = analysis.amplitude(start.x, start.y)
    limit = params.failure_ratio * amp0

    def failed_at(batch):
        """Index of the first sample of the batch at or above the failure amplitude, or None."""
        if not params.stop_at_failure or limit <= 0:     # a flat sail (a₀ = 0) has no failure to stop at
            return None
        x, y = centres(model, batch[:model.dof])
        above = np.nonzero(analysis.amplitude(x.T, y.T) >= limit)[0]
        return above[0] if above.size else None

    wall0 = clock.perf_counter()
    bar = Progress(params.t_final, progress, label="reduced")
    try:
        if method in COMPILED:
            atol = np.broadcast_to(np.asarray(atol, float), y0.shape)
            extra = dict(jac_scales=np.maximum(atol / rtol, 1e-300)) if method == "Radau" else {}
            integrator = COMPILED[method](dynamics.constants, y0, params.t_final, rtol, atol,
                                          max_step=options.get("max_step", np.inf),
                                          first_step=options.get("first_step"), **extra)
            states, error = _run_compiled(method, integrator, y0, sample_times, failed_at, bar)
        else:
            states, error, integrator = _run_scipy(method, dynamics, y0, params.t_final, rtol, atol, sample_times,
                                                   failed_at, bar, options)
    finally:
        bar.close()
    wall = clock.perf_counter() - wall0

    ys = np.concatenate(states, axis=1)
    count = ys.shape[1]
    q, qd = ys[:model.dof], ys[model.dof:]
    x, y = centres(model, q)
    vx, vy = centre_velocities(model, q, qd)
    _, _, theta, z = model.split(q)
    _, _, omega, z_rate = model.split(qd)
    info = dict(method=method, rtol=rtol, atol=float(np.min(atol)), steps=integrator.steps, nfev=integrator.nfev,
                njev=getattr(integrator, "njev", 0), nlu=getattr(integrator, "nlu", 0), coordinates=model.dof,
                formulation="minimal coordinates, O(n) joint-force recursion (block LDLT), compiled")
    return Result.from_trajectory(
        params, "reduced", sample_times[:count], x.T, y.T, theta.T, vx.T, vy.T, omega.T,
        z=z.T if model.extensible else None, z_rate=z_rate.T if model.extensible else None,
        wall_time=wall, error=error, info=info)


CHUNK = 50      # samples per call of the compiled integrator (failure check and progress in between)


def _run_compiled(method, integrator, y0, sample_times, failed_at, bar):
    """A compiled integrator (DOP853: reduced_integrator.py, Radau: reduced_radau.py), CHUNK samples per call."""
    states, error, next_sample = [y0[:, None]], None, 1
    while next_sample < sample_times.size:
        batch = integrator.advance(sample_times[next_sample:next_sample + CHUNK])
        states.append(batch)
        next_sample += batch.shape[1]
        stop = failed_at(batch)
        if stop is not None:
            states[-1] = batch[:, :stop + 1]
            break
        if integrator.status in STATUS:
            error = f"{method} failed at t = {integrator.t:.6g} s: {STATUS[integrator.status]}"
            break
        bar.update(integrator.t)
        if integrator.status == FINISHED:
            break
    return states, error


def _run_scipy(method, dynamics, y0, t_final, rtol, atol, sample_times, failed_at, bar, options):
    """scipy's solve_ivp steppers on the compiled right-hand side; implicit ones get the compiled
    dense Jacobian (reduced_dynamics.ChainDynamics.jacobian)."""
    kwargs = dict(rtol=rtol, atol=atol, **options)
    if method in IMPLICIT:
        scales = np.maximum(np.broadcast_to(atol, y0.shape) / rtol, 1e-300)
        kwargs["jac"] = lambda t, y: dynamics.jacobian(t, y, scales)
    integrator = METHODS[method](dynamics.rhs, 0.0, y0, t_final, **kwargs)
    integrator.steps = 0
    states, error, next_sample = [y0[:, None]], None, 1
    try:
        while next_sample < sample_times.size:
            message = integrator.step()
            integrator.steps += 1
            if integrator.status == "failed" or not np.all(np.isfinite(integrator.y)):
                error = f"{method} failed at t = {integrator.t:.6g} s: {message or 'non-finite state'}"
                break
            stop = np.searchsorted(sample_times, integrator.t, side="right")
            if stop > next_sample:
                batch = integrator.dense_output()(sample_times[next_sample:stop])
                states.append(batch)
                next_sample = stop
                above = failed_at(batch)
                if above is not None:
                    states[-1] = batch[:, :above + 1]
                    break
            bar.update(integrator.t)
            if integrator.status == "finished":
                break
    except (np.linalg.LinAlgError, ValueError, FloatingPointError) as exc:
        error = f"{method} failed at t = {integrator.t:.6g} s: {exc}"
    return states, error, integrator
