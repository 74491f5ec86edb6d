"""Supports and tip load for the reduced solver: chains that are not free (validations, Appendices A–B).

Same minimal coordinates and Lagrangian terms as the free chain (reduced_kinematics: M(q), c(q, q̇),
Q(q, q̇), Eq. 16), assembled densely (O(n³) per call: meant for the validation sizes, n ≲ 100 in
time, not for the sail studies, which keep the O(n) path of reduced_dynamics), plus:

* tip load (paper Eq. 43): P(t) ŷ at the centre of slice n, Q += P(t) ∂y_n/∂q;
* cantilever (Appendix A): slice 1 clamped; x₁, y₁, θ₁ are removed from the equations (their rates
  and accelerations are zero), M_ff q̈_f = (Q − c)_f on the free coordinates f;
* pinned (Appendix B): hinge 0 (r₁ − b e₁) pinned at its initial position and hinge n
  (r_n + b e_n) on a roller at its initial height; the follower end tension (Eq. 32) still pulls
  along the end slices (at the pin it only loads the support; at the roller its axial part is
  the string tension). Constraints g(q) = 0 with Jacobian G enter by Lagrange multipliers at
  acceleration level (index 1):

      M q̈ = Q − c + Gᵀλ,   G q̈ = −γ,   γ = Ġ q̇   ⇒   (G M⁻¹ Gᵀ) λ = −γ − G M⁻¹ (Q − c).

  With g = 0 and G q̇ = 0 initially the exact solution keeps them; the integrator's drift is
  reported in Result.info["constraint_drift"] (validation runs: ≲ 1e-12 m).

run() integrates these chains with scipy's implicit steppers (Radau by default: the clamped and
tensioned chains are stiff), sampling the dense output like the free chain (sampling.py); solver.run hands every
case with supports or a tip load over to it.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import BDF, LSODA, Radau
from scipy.linalg import solve_triangular

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.solvers.reduced.kinematics import (
    ChainModel,
    axial_forces,
    body_forces,
    centre_jacobian,
    centres,
    torsion_torques,
)
from lightsail_mbs.solvers.reduced.sampling import sampled_run, state_scales, stepper_advance, trajectory_result

METHODS = {"Radau": Radau, "BDF": BDF, "LSODA": LSODA}
DEFAULT_RTOL = 1e-6
OPTIONS = ("max_step", "first_step")


def needs_boundary(p) -> bool:
    """True when the chain has supports or a tip load (the dense path of this module)."""
    return p.boundary != "free" or p.tip_load != 0.0


def _cholesky_solve(lower: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """x with L Lᵀ x = rhs."""
    return solve_triangular(
        lower.T, solve_triangular(lower, rhs, lower=True, check_finite=False), lower=False, check_finite=False
    )


def _bias_accelerations(model: ChainModel, th, om, z, zd):
    """Centre accelerations at q̈ = 0 (n each): Σ_{i<j} (2 ż_i θ̇_i p_i − a_i θ̇_i² e_i) − Σ_{2≤k≤j} b θ̇_k² e_k."""
    a, b = model.arms(z), model.half_length
    c, s = np.cos(th), np.sin(th)
    dax = -2 * zd * om[:-1] * s[:-1] - a * om[:-1] ** 2 * c[:-1] - b * om[1:] ** 2 * c[1:]
    day = 2 * zd * om[:-1] * c[:-1] - a * om[:-1] ** 2 * s[:-1] - b * om[1:] ** 2 * s[1:]
    return np.concatenate([[0.0], np.cumsum(dax)]), np.concatenate([[0.0], np.cumsum(day)])


class BoundedChainDynamics:
    """q̈(t, q, q̇) of a supported or tip-loaded chain; states are columns of (dof, k) arrays."""

    def __init__(self, model: ChainModel, q0: np.ndarray):
        self.model = model
        p = model.params
        self.params = p
        dof, n = model.dof, model.n
        fixed = [0, 1, 2] if p.boundary == "cantilever" else []
        self.fixed = np.array(fixed, dtype=int)
        self.free = np.setdiff1d(np.arange(dof), fixed)
        self.pinned = p.boundary == "pinned"
        self.reference = self.constraint_values(np.asarray(q0, float)) if self.pinned else None
        self._tip = n - 1
        self._angles = np.arange(2, n + 2)

    # ---- constraints of the pinned chain -------------------------------------------------
    def constraint_values(self, q: np.ndarray) -> np.ndarray:
        """(x, y) of hinge 0 and y of hinge n."""
        m = self.model
        b, n = m.half_length, m.n
        th = q[2 : n + 2]
        _, y = centres(m, q[:, None])
        return np.array([q[0] - b * np.cos(th[0]), q[1] - b * np.sin(th[0]), y[-1, 0] + b * np.sin(th[-1])])

    def constraint_jacobian(self, q: np.ndarray, jac: np.ndarray) -> np.ndarray:
        """G = ∂g/∂q (3 × dof) from the centre Jacobian jac (n, 2, dof)."""
        m = self.model
        b, n = m.half_length, m.n
        th = q[2 : n + 2]
        G = np.zeros((3, m.dof))
        G[0, 0] = 1.0
        G[0, 2] = b * np.sin(th[0])
        G[1, 1] = 1.0
        G[1, 2] = -b * np.cos(th[0])
        G[2] = jac[-1, 1]
        G[2, n + 1] += b * np.cos(th[-1])
        return G

    def constraint_rates(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """γ = Ġ q̇: the constraint accelerations at q̈ = 0 (hinge 0: b θ̇₁² e₁; hinge n, y part:
        ÿ_n(q̈ = 0) − b θ̇_n² sin θ_n)."""
        m = self.model
        b = m.half_length
        _, _, th, z = m.split(q)
        _, _, om, zd = m.split(qd)
        _, ay = _bias_accelerations(m, th, om, z, zd)
        return np.array(
            [b * om[0] ** 2 * np.cos(th[0]), b * om[0] ** 2 * np.sin(th[0]), ay[-1] - b * om[-1] ** 2 * np.sin(th[-1])]
        )

    def constraint_violation(self, q: np.ndarray) -> np.ndarray:
        """|g(q)| for states q (dof, k): drift of the pinned chain's supports (zeros otherwise)."""
        q = np.asarray(q, float).reshape(self.model.dof, -1)
        if not self.pinned:
            return np.zeros(q.shape[1])
        return np.array([np.max(np.abs(self.constraint_values(col) - self.reference)) for col in q.T])

    # ---- accelerations -------------------------------------------------------------------
    def _one(self, t: float, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """q̈ of one state: M q̈ = Jᵀ(F − m a⁰) + τ (+ Gᵀλ), a⁰ the centre accelerations at q̈ = 0
        (the velocity terms c = m Jᵀ a⁰ of reduced_kinematics.velocity_terms), one centre Jacobian J."""
        m, p = self.model, self.params
        n = m.n
        jac = centre_jacobian(m, q)
        _, _, th, z = m.split(q)
        _, _, om, zd = m.split(qd)
        x, _ = centres(m, q[:, None])
        fx, fy = body_forces(m, x[:, 0], th)
        ax, ay = _bias_accelerations(m, th, om, z, zd)
        force = np.einsum("jai,ja->i", jac, np.stack([fx - m.mass * ax, fy - m.mass * ay], axis=1))
        force[2 : n + 2] += torsion_torques(m, th, om)
        if m.extensible:
            force[n + 2 :] += axial_forces(m, z, zd)
        if p.tip_load:
            force += p.tip_force(t) * jac[self._tip, 1]
        flat = jac.reshape(2 * n, m.dof)
        mass = m.mass * (flat.T @ flat)
        mass[self._angles, self._angles] += m.inertia
        f = self.free
        qdd = np.zeros(m.dof)
        lower = np.linalg.cholesky(mass[np.ix_(f, f)])
        free_acc = _cholesky_solve(lower, force[f])
        if self.pinned:
            G = self.constraint_jacobian(q, jac)[:, f]
            response = _cholesky_solve(lower, G.T)  # M⁻¹ Gᵀ
            lam = np.linalg.solve(G @ response, -self.constraint_rates(q, qd) - G @ free_acc)
            free_acc = free_acc + response @ lam
        qdd[f] = free_acc
        return qdd

    def accelerations(self, t: float, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """q̈ for states of shape (dof,) or (dof, k)."""
        if q.ndim == 1:
            return self._one(t, q, qd)
        return np.stack([self._one(t, q[:, i], qd[:, i]) for i in range(q.shape[1])], axis=1)

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """ẏ = (q̇, q̈) of y = (q, q̇) (Eq. 40); the clamped coordinates keep zero rate."""
        dof = self.model.dof
        qd = y[dof:].copy()
        qd[self.fixed] = 0.0
        return np.concatenate([qd, self.accelerations(t, y[:dof], y[dof:])])


def dynamics_of(p: SailParameters):
    """(dynamics with rhs(t, y), ChainModel) of the reduced solver for p: the O(n) ChainDynamics of
    reduced_dynamics for a free, unloaded chain, BoundedChainDynamics otherwise."""
    model = ChainModel.from_params(p)
    if not needs_boundary(p):
        return ChainDynamics(model), model
    start = shapes.initial_state(p)
    return BoundedChainDynamics(model, model.pack(start.x[0], start.y[0], start.theta, start.z)), model


def run(params: SailParameters, settings: RunSettings, *, progress: bool, rtol, atol, method, **options) -> Result:
    """Integrate a chain with supports or a tip load (module docstring) and return its Result; called by
    solver.run with its arguments.

    rtol: relative tolerance (None: 1e-6); atol: absolute tolerance, scalar or per state entry (None:
    rtol × state_scales(model, 1)); method: Radau (None), BDF or LSODA; options: max_step, first_step.
    """
    unknown = sorted(set(options) - set(OPTIONS))
    if unknown:
        raise ParameterError(f"option {unknown[0]!r} is invalid: allowed {', '.join(OPTIONS)}")
    method = method or "Radau"
    if method not in METHODS:
        raise ParameterError(
            f"method={method!r} is invalid with supports or a tip load: allowed one of "
            f"{', '.join(METHODS)} (the supported chains are stiff)"
        )
    rtol = DEFAULT_RTOL if rtol is None else float(rtol)
    if not 0 < rtol < 1:
        raise ParameterError(f"rtol={rtol!r} is invalid: allowed 0 < rtol < 1")
    dynamics, model = dynamics_of(params)
    if atol is None:
        atol = rtol * state_scales(model, 1.0)
    start = shapes.initial_state(params)
    q0 = model.pack(start.x[0], start.y[0], start.theta, start.z)
    y0 = np.concatenate([q0, np.zeros_like(q0)])
    integrator = METHODS[method](
        dynamics.rhs, 0.0, y0, settings.t_final, rtol=rtol, atol=atol, vectorized=method != "LSODA", **options
    )
    trajectory, error, wall = sampled_run(
        model,
        y0,
        settings,
        stepper_advance(method, integrator, y0.size),
        settings.sample_times().size,
        progress,
    )
    q = trajectory.coordinates()
    info = dict(
        method=method,
        rtol=rtol,
        atol=float(np.min(atol)),
        steps=integrator.steps,
        nfev=integrator.nfev,
        njev=integrator.njev,
        nlu=integrator.nlu,
        coordinates=model.dof,
        boundary=params.boundary,
        constraint_drift=float(np.max(dynamics.constraint_violation(q))),
        formulation="minimal coordinates, dense M(q) with supports (reduced_boundary)",
    )
    return trajectory_result(model, settings, trajectory, wall_time=wall, error=error, info=info)
