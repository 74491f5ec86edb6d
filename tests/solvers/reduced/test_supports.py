"""The reduced solver's supported chains (solvers.reduced.supports) against the reference dense Lagrangian terms."""

import numpy as np
import pytest

from lightsail_mbs.solvers.reduced.kinematics import centre_jacobian, generalized_forces, mass_matrix, velocity_terms
from lightsail_mbs.solvers.reduced.supports import BoundedChainDynamics, dynamics_of, needs_boundary
from lightsail_mbs.studies import classic


def random_state(model, rng, scale=0.05):
    q = np.zeros(model.dof)
    q[2 : model.n + 2] = scale * rng.standard_normal(model.n)
    if model.extensible:
        q[model.n + 2 :] = model.params.tension / model.axial_stiffness * (1 + 0.1 * rng.standard_normal(model.n - 1))
    qd = 10 * scale * rng.standard_normal(model.dof)
    return q, qd


def test_free_unloaded_chain_keeps_the_fast_path():
    p = classic.free_beam_case(8)
    assert not needs_boundary(p)
    assert not isinstance(dynamics_of(p)[0], BoundedChainDynamics)


def test_cantilever_accelerations_equal_the_dense_reference():
    """M_ff q̈_f = (Q − c + P(t) ∂y_n/∂q)_f with the reference M, Q, c of reduced_kinematics; clamp at rest."""
    p = classic.cantilever_case(9, youngs_modulus=2e5)
    dyn, model = dynamics_of(p)
    rng = np.random.default_rng(1)
    q, qd = random_state(model, rng)
    qd[:3] = 0.0
    t = 0.2
    force = generalized_forces(model, q, qd) - velocity_terms(model, q, qd)
    force += p.tip_force(t) * centre_jacobian(model, q)[-1, 1]
    f = dyn.free
    expected = np.zeros(model.dof)
    expected[f] = np.linalg.solve(mass_matrix(model, q)[np.ix_(f, f)], force[f])
    assert np.allclose(dyn.accelerations(t, q, qd), expected, rtol=1e-10, atol=1e-12 * np.abs(expected).max())
    assert np.all(dyn.rhs(t, np.concatenate([q, qd]))[:3] == 0.0)


@pytest.mark.parametrize("springs", [False, True])
def test_pinned_accelerations_keep_the_supports(springs):
    """G q̈ + γ = 0 with γ = Ġq̇ checked by differentiating G(q) along q̇; and the remaining equations
    are the Lagrangian ones: Pᵀ(M q̈ − Q + c) = 0 on the null space of G."""
    p = classic.g3_string_case(7, axial_springs=springs)
    dyn, model = dynamics_of(p)
    rng = np.random.default_rng(2)
    q, qd = random_state(model, rng)
    qdd = dyn.accelerations(0.0, q, qd)
    G = dyn.constraint_jacobian(q, centre_jacobian(model, q))
    eps = 1e-6
    gamma = (
        dyn.constraint_jacobian(q + eps * qd, centre_jacobian(model, q + eps * qd)) @ qd
        - dyn.constraint_jacobian(q - eps * qd, centre_jacobian(model, q - eps * qd)) @ qd
    ) / (2 * eps)
    assert np.allclose(gamma, dyn.constraint_rates(q, qd), rtol=1e-6, atol=1e-9 * np.abs(gamma).max())
    assert np.allclose(G @ qdd, -gamma, rtol=1e-6, atol=1e-9 * np.abs(G @ qdd).max())
    residual = mass_matrix(model, q) @ qdd - generalized_forces(model, q, qd) + velocity_terms(model, q, qd)
    null = np.linalg.svd(G)[2][3:].T
    assert np.allclose(null.T @ residual, 0.0, atol=1e-9 * np.abs(generalized_forces(model, q, qd)).max())
