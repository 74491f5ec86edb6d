"""The reduced chain's Lagrangian terms: M(q) against the paper's rigid-model coefficients, M, c and Q
against a finite-difference Lagrangian."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.model import terms
from lightsail_mbs.solvers.reduced.kinematics import (
    ChainModel,
    centres,
    generalized_forces,
    mass_matrix,
    velocity_terms,
)
from tests.solvers.reduced.chains import IDS, MODELS, TNT, TNT_RIGID, TORSION, random_state


# ---- M(q) ----------------------------------------------------------------------------------
@pytest.mark.parametrize("p", MODELS, ids=IDS)
def test_mass_matrix_symmetric_positive_definite(p):
    model = ChainModel.from_params(p)
    for _ in range(5):
        mass = mass_matrix(model, random_state(model)[0])
        np.testing.assert_allclose(mass, mass.T, rtol=0, atol=1e-15 * np.abs(mass).max())
        assert np.linalg.eigvalsh(mass).min() > 0


def paper_rigid_rows(n, l, theta):
    """The rigid model's left-hand sides, Eqs (17)–(21) with the coefficients a^xy, a^θ1, a^θk (Eq. 22),
    as a matrix acting on (ẍ₁, ÿ₁, θ̈): row x₁ scaled by −2/m... as printed (x₁ row: −2n, a^xy sin θ)."""
    j = np.arange(1, n + 1)
    a_xy = np.where(j == 1, (n - 1) * l, (2 * n - 2 * j + 1) * l)
    rows = np.zeros((n + 2, n + 2))
    rows[0, 0] = -2 * n
    rows[0, 2:] = a_xy * np.sin(theta)
    rows[1, 1] = 2 * n
    rows[1, 2:] = a_xy * np.cos(theta)
    for k in range(1, n + 1):
        lever = 6 * (n - 1) * l if k == 1 else 6 * (2 * n - 2 * k + 1) * l
        rows[k + 1, 0] = -lever * np.sin(theta[k - 1])
        rows[k + 1, 1] = lever * np.cos(theta[k - 1])
        if k == 1:
            a = np.where(j == 1, 3 * (n - 1) * l**2 + l**2, 3 * (2 * n - 2 * j + 1) * l**2)
        else:
            a = np.select(
                [j == 1, j < k, j == k],
                [3 * (2 * n - 2 * k + 1) * l**2, 6 * (2 * n - 2 * k + 1) * l**2, 12 * (n - k) * l**2 + 4 * l**2],
                6 * (2 * n - 2 * j + 1) * l**2,
            )
        rows[k + 1, 2:] = a * np.cos(theta[k - 1] - theta)
    return rows


@pytest.mark.parametrize("n", [2, 3, 8, 40])
def test_mass_matrix_equals_paper_rigid_coefficients(n):
    """Eqs (17)–(22): x₁ row = −(2/m) M, y₁ row = (2/m) M, θ rows = (12/m) M."""
    p = SailParameters(model="rigid", n=n, intensity=1e11)
    model = ChainModel.from_params(p)
    scale = np.array([-2.0, 2.0] + [12.0] * n)[:, None] / model.mass
    for _ in range(3):
        q = random_state(model)[0]
        expected = paper_rigid_rows(n, p.slice_length, q[2:])
        np.testing.assert_allclose(
            scale * mass_matrix(model, q), expected, rtol=1e-12, atol=1e-13 * np.abs(expected).max()
        )


# ---- finite-difference Lagrangian -----------------------------------------------------------
def fd_jacobian(model, q, points):
    """∂points/∂q by complex steps (exact to round-off): points(q) -> (k, 2) from the centres."""
    h = 1e-30
    cols = []
    for k in range(model.dof):
        dq = np.zeros(model.dof, complex)
        dq[k] = 1j * h
        cols.append(points(q + dq).imag / h)
    return np.stack(cols, axis=-1)


def centre_points(model):
    return lambda q: np.stack(centres(model, q), axis=-1)


def end_points(model):
    """Left end of slice 1 and right end of slice n, from the centres and the end angles."""
    b, n = model.half_length, model.n

    def ends(q):
        x, y = centres(model, q)
        th = q[2 : n + 2]
        return np.array(
            [
                [x[0] - b * np.cos(th[0]), y[0] - b * np.sin(th[0])],
                [x[-1] + b * np.cos(th[-1]), y[-1] + b * np.sin(th[-1])],
            ]
        )

    return ends


def fd_mass_matrix(model, q):
    """∂²T/∂q̇² of T = ½ m Σ|ṙ_j|² + ½ J Σ θ̇_j² with ṙ_j = (∂r_j/∂q) q̇ from the centre positions."""
    jac = fd_jacobian(model, q, centre_points(model))
    mass = model.mass * np.einsum("jai,jak->ik", jac, jac)
    idx = np.arange(2, model.n + 2)
    mass[idx, idx] += model.inertia
    return mass


def fd_velocity_terms(model, q, qd, eps=1e-6):
    """Euler–Lagrange terms at q̈ = 0: d/dt(∂T/∂q̇) − ∂T/∂q = (∂(M q̇)/∂q) q̇ − ½ ∂(q̇ᵀ M q̇)/∂q."""
    dir_m = (fd_mass_matrix(model, q + eps * qd) - fd_mass_matrix(model, q - eps * qd)) / (2 * eps)
    grad = np.zeros(model.dof)
    for k in range(model.dof):
        dq = np.zeros(model.dof)
        dq[k] = eps
        grad[k] = qd @ (fd_mass_matrix(model, q + dq) - fd_mass_matrix(model, q - dq)) @ qd / (4 * eps)
    return dir_m @ qd - grad


def fd_generalized_forces(model, q, qd, eps=1e-7):
    """Q_k = Σ F_j·∂r_j/∂q_k + T-end virtual work − ∂V/∂q_k − ∂R/∂q̇_k (V: springs, R: Rayleigh dampers)."""
    p, n = model.params, model.n
    x, _ = centres(model, q)
    th = q[2 : n + 2]
    fx, fy = terms.chain_forces(p, x, th)
    gen = np.einsum("jai,ja->i", fd_jacobian(model, q, centre_points(model)), np.stack([fx, fy], axis=1))
    tension = model.tension * np.array([[-np.cos(th[0]), -np.sin(th[0])], [np.cos(th[-1]), np.sin(th[-1])]])
    gen += np.einsum("jai,ja->i", fd_jacobian(model, q, end_points(model)), tension)

    def potential(q):
        v = 0.5 * model.torsional_stiffness * np.sum(np.diff(q[2 : n + 2]) ** 2)
        return v + 0.5 * model.axial_stiffness * np.sum(q[n + 2 :] ** 2)

    def rayleigh(qd):
        r = 0.5 * model.torsional_damping * np.sum(np.diff(qd[2 : n + 2]) ** 2)
        return r + 0.5 * model.axial_damping * np.sum(qd[n + 2 :] ** 2)

    for k in range(model.dof):
        dq = np.zeros(model.dof)
        dq[k] = eps
        gen[k] -= (potential(q + dq) - potential(q - dq)) / (2 * eps)
        gen[k] -= (rayleigh(qd + dq) - rayleigh(qd - dq)) / (2 * eps)
    return gen


@pytest.mark.parametrize("p", [TORSION, TNT, TNT_RIGID], ids=IDS[:3])
def test_mass_matrix_and_forces_match_finite_difference_lagrangian(p):
    model = ChainModel.from_params(p)
    for _ in range(3):
        q, qd = random_state(model)
        mass = mass_matrix(model, q)
        np.testing.assert_allclose(mass, fd_mass_matrix(model, q), rtol=1e-12, atol=1e-14 * np.abs(mass).max())
        c = velocity_terms(model, q, qd)
        np.testing.assert_allclose(c, fd_velocity_terms(model, q, qd), rtol=1e-6, atol=1e-7 * np.abs(c).max())
        gen = generalized_forces(model, q, qd)
        np.testing.assert_allclose(gen, fd_generalized_forces(model, q, qd), rtol=1e-6, atol=1e-7 * np.abs(gen).max())
