"""Eigenfrequencies of the chain linearised about the flat state, from each solver's own equations.

* exudyn: the assembled Exudyn system (solvers.exudyn_chain.build, supports included) and Exudyn's
  ``ComputeODE2Eigenvalues``: mass matrix and static-solver Jacobian of the KinematicTree at the
  initial (flat) state; with supports, Exudyn projects both on the null space of the constraint
  Jacobian. Exudyn solves the symmetric problem K v = ω² M v, so this is meant for conservative
  linearisations (no radiation load: intensity = 0).
* reduced: the reduced solver's right-hand side q̈(q, q̇) (O(n) ChainDynamics for free chains,
  BoundedChainDynamics with supports), differentiated by central differences about the flat
  state at rest, A = ∂q̈/∂q, restricted to the tangent space of the supports (orthonormal basis N:
  free coordinates of the cantilever, null space of G for the pinned chain); ω² = −eig(Nᵀ A N).

Both return all ω (rad/s) ascending, rigid-body modes as (near) zeros; elastic(ω, p) drops those.
stability.py linearises the lit free sail (load stiffness, growth rates); this module adds the
supports of the validations (SailParameters.boundary) and Exudyn's own eigenvalue solver.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import null_space

from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.analysis.linear_stability import flat

RIGID_MODES = {"free": 3, "cantilever": 0, "pinned": 0}
# Central-difference step (rad for angles, × l for positions): the error ∝ (ω_max/ω₁)² step² from the
# geometric nonlinearity plus round-off ∝ 1/step is ≈ 1e-11 on the validation chains at 1e-8.
FD_STEP = 1e-8


def exudyn_angular_frequencies(p: SailParameters) -> np.ndarray:
    """ω (rad/s) from Exudyn's ComputeODE2Eigenvalues of the built system (flat state)."""
    import exudyn as exu

    from lightsail_mbs.solvers.exudyn import chain as exudyn_chain

    printing = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        _, mbs, *_ = exudyn_chain.build(flat(p))
        values, _ = mbs.ComputeODE2Eigenvalues()
    finally:
        exu.config.printToConsole = printing
    return np.sort(np.sqrt(np.abs(np.asarray(values, float))))


def reduced_jacobian(p: SailParameters):
    """(A = ∂q̈/∂q at the flat state at rest, N: orthonormal basis of the supports' tangent space)."""
    from lightsail_mbs.solvers.reduced.supports import dynamics_of
    from lightsail_mbs.solvers.reduced.kinematics import centre_jacobian

    p = flat(p)
    dynamics, model = dynamics_of(p)
    start = shapes.initial_state(p)
    q0 = model.pack(start.x[0], start.y[0], start.theta, start.z)
    dof = model.dof
    scale = np.full(dof, p.slice_length)
    scale[2:p.n + 2] = 1.0                                   # angles (rad)
    step = FD_STEP * scale
    shifts = np.concatenate([np.diag(step), -np.diag(step)], axis=1)
    states = np.concatenate([q0[:, None] + shifts, np.zeros((dof, 2 * dof))])
    qdd = np.stack([dynamics.rhs(0.0, state)[dof:] for state in states.T], axis=1)
    A = (qdd[:, :dof] - qdd[:, dof:]) / (2 * step)
    if p.boundary == "pinned":
        basis = null_space(dynamics.constraint_jacobian(q0, centre_jacobian(model, q0)))
    elif p.boundary == "cantilever":
        basis = np.eye(dof)[:, dynamics.free]
    else:
        basis = np.eye(dof)
    return A, basis


def reduced_angular_frequencies(p: SailParameters) -> np.ndarray:
    """ω (rad/s) of the reduced solver's linearised right-hand side (module docstring)."""
    A, N = reduced_jacobian(p)
    w2 = -np.linalg.eigvals(N.T @ A @ N).real
    return np.sort(np.sqrt(np.clip(w2, 0.0, None)))


def elastic(omega: np.ndarray, p: SailParameters) -> np.ndarray:
    """The elastic ω of a solver's spectrum: without the 3 rigid-body modes (x, y, rotation) of a free
    chain (their ω are round-off of the difference quotients, not exactly 0); supported chains have none."""
    return np.asarray(omega, float)[RIGID_MODES[p.boundary]:]
