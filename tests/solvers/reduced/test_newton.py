"""The O(n) Newton matrix of the implicit integrator: its solve equals a dense solve of (σI − J̃) x = r with
J̃ = [[0, I], [−M⁻¹K̃, −M⁻¹C]] assembled from the dense mass matrix of kinematics.py, for real and complex σ,
every chain kind, seeded random states; its geometric stiffness is the string stiffness l·T."""

import numpy as np
import pytest

from lightsail_mbs import paper_case
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics, constants, workspace
from lightsail_mbs.solvers.reduced.kinematics import ChainModel, mass_matrix
from lightsail_mbs.solvers.reduced.newton import compliances, factor, geometry_into, newton_solve

CASES = [
    paper_case("torsion-soft", n=7),
    paper_case("torsion-stable", n=12, stiffness_damping=1e-3),
    paper_case("tnt-stable", n=9),
    paper_case("tnt-soft", n=8, bending=True, stiffness_damping=1e-6),
    paper_case("tnt-stable", n=6, axial_springs=False, bending=True),
    paper_case("tnt-stable", n=6, axial_springs=False),
    paper_case("rigid", n=5),
]
IDS = [
    "torsion",
    "torsion-damped",
    "tnt-extensible",
    "tnt-extensible-bending-damped",
    "tnt-rigid-bending",
    "tnt-rigid",
    "rigid",
]


def dense_newton_jacobian(model, q, k_geo):
    """J̃ of newton.py, dense: springs K = k_T L_θ + diag(k_g) ⊕ k_s I_z, dampers C, M = M(q)."""
    n, dof = model.n, model.dof
    stiff, damp = np.zeros((dof, dof)), np.zeros((dof, dof))
    laplacian = np.diag(np.r_[1.0, 2.0 * np.ones(n - 2), 1.0]) - np.eye(n, k=1) - np.eye(n, k=-1)
    stiff[2 : n + 2, 2 : n + 2] = model.torsional_stiffness * laplacian + np.diag(k_geo)
    damp[2 : n + 2, 2 : n + 2] = model.torsional_damping * laplacian
    if model.extensible:
        stiff[n + 2 :, n + 2 :] = model.axial_stiffness * np.eye(n - 1)
        damp[n + 2 :, n + 2 :] = model.axial_damping * np.eye(n - 1)
    inverse_mass = np.linalg.inv(mass_matrix(model, q))
    jac = np.zeros((2 * dof, 2 * dof))
    jac[:dof, dof:] = np.eye(dof)
    jac[dof:, :dof] = -inverse_mass @ stiff
    jac[dof:, dof:] = -inverse_mass @ damp
    return jac


def structured_solve(model, y, sigma, r):
    """x = (σI − J̃)⁻¹ r by newton.py (factor + newton_solve), and the geometric stiffness used."""
    n, dof = model.n, model.dof
    k = constants(model)
    dtype = complex if isinstance(sigma, complex) else float
    cth, sth, arm, k_geo = (np.empty(n) for _ in range(4))
    geometry_into(0.0, y, k, workspace(n), cth, sth, arm, k_geo, True)
    inv_inertia = np.empty(n, dtype)
    inv_kt, inv_ks, has_moment = compliances(sigma, k, k_geo, inv_inertia)
    pivots, lower, couplings = (np.empty((n - 1, 3, 3), dtype) for _ in range(3))
    factor(k, cth, sth, arm, inv_inertia, inv_kt, inv_ks, has_moment, pivots, lower, couplings)
    x = np.array(r, dtype)
    lam, scratch = np.empty((n - 1, 3), dtype), np.empty((3, dof), dtype)
    newton_solve(
        x, sigma, k, cth, sth, arm, k_geo, inv_inertia, inv_ks, has_moment, pivots, lower, couplings, lam, scratch
    )
    return x, k_geo


@pytest.mark.parametrize("params", CASES, ids=IDS)
@pytest.mark.parametrize("sigma", [3.7e2, 1e5, 20.0 + 9.0j, 4e4 - 3e4j])
def test_structured_newton_solve_equals_dense_solve(params, sigma):
    rng = np.random.default_rng(7)
    model = ChainModel.from_params(params)
    n, dof = model.n, model.dof
    y = np.concatenate([rng.normal(0, 0.2, dof), rng.normal(0, 1.0, dof)])
    if model.extensible:
        y[n + 2 : dof] = params.tension / model.axial_stiffness * (1 + 0.1 * rng.normal(size=n - 1))
    r = rng.normal(size=2 * dof) * (1 + (0.5j if isinstance(sigma, complex) else 0))
    x, k_geo = structured_solve(model, y, sigma, r)
    expected = np.linalg.solve(sigma * np.eye(2 * dof) - dense_newton_jacobian(model, y[:dof], k_geo), r)
    np.testing.assert_allclose(x, expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())


def test_geometric_stiffness_of_a_straight_chain_in_tension_is_l_times_T():
    """A straight, unloaded TnT chain at rest carries Λ_i = −T e along it (slice i pulls slice i+1 back):
    k_g = b T at the end slices
    (one joint) and 2 b T = l T inside (Eq. 32's tension, the string's transverse stiffness)."""
    p = paper_case("tnt-stable", n=10, intensity=0.0, defect_amplitude=0.0, axial_springs=False)
    model = ChainModel.from_params(p)
    y = np.zeros(2 * model.dof)
    k_geo = np.empty(p.n)
    geometry_into(0.0, y, constants(model), workspace(p.n), *(np.empty(p.n) for _ in range(3)), k_geo, True)
    expected = p.slice_length * p.tension * np.r_[0.5, np.ones(p.n - 2), 0.5]
    np.testing.assert_allclose(k_geo, expected, rtol=1e-12)
    joint = ChainDynamics(model).joint_forces(y)
    np.testing.assert_allclose(joint, np.tile([-p.tension, 0.0], (p.n - 1, 1)), rtol=1e-12, atol=1e-12 * p.tension)


def test_newton_matrix_carries_the_stiff_eigenvalues():
    """J̃ keeps the stiff part of the exact Jacobian: near the flat state of a stiff torsion chain, at σ of
    its top bending mode, (σI − J̃)⁻¹ solves (σI − J)x = r up to the neglected load and velocity terms, a
    small fraction of r (the simplified Newton iteration's contraction rate)."""
    p = paper_case("torsion-stable", n=60)
    model = ChainModel.from_params(p)
    rng = np.random.default_rng(3)
    y = np.concatenate([rng.normal(0, 1e-5, model.dof), rng.normal(0, 1e-5, model.dof)])
    exact = ChainDynamics(model).jacobian(0.0, y, np.full(y.size, 1e-6))
    for sigma in (2 * np.sqrt(model.torsional_stiffness / model.inertia), 3e3 + 2e3j):
        r = rng.normal(size=y.size)
        x, _ = structured_solve(model, y, sigma, r)
        residual = r - (sigma * np.eye(y.size) - exact) @ x
        assert np.linalg.norm(residual) < 0.05 * np.linalg.norm(r)
