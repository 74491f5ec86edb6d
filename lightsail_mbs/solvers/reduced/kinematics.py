"""Kinematics and Lagrangian terms of the chain in the paper's minimal coordinates.

Coordinates (paper Sec. III.A–C): q = (x₁, y₁, θ₁…θₙ) for the rigid, torsion and inextensible
TnT chains, and q = (x₁, y₁, θ₁…θₙ, z₁…zₙ₋₁) for the extensible TnT chain (l_s = 0).
With e_i = (cos θ_i, sin θ_i), p_i = (−sin θ_i, cos θ_i) and half-length b = l/2, the slice
centres follow Eqs (13)–(14) and (30)–(31) as the recursion

    r_{i+1} = r_i + a_i e_i + b e_{i+1},   a_i = l/2 + z_i   (z_i ≡ 0 when inextensible),

so ∂r_j/∂θ_k = c_jk p_k with c_jk = a_k [k < j] + b [2 ≤ k ≤ j], and ∂r_j/∂z_k = e_k [k < j].

This module builds the dense Lagrangian terms (for tests and as a reference):
M(q) = Σ_j m J_jᵀJ_j + J_G J_ωᵀJ_ω (Eqs 12, 23, 29), the velocity terms c(q, q̇) = Σ_j m J_jᵀ J̇_j q̇,
and the generalized forces Q(q, q̇) (Eqs 15, 32 plus −∂V/∂q and the dampers), so that
M q̈ + c = Q. The O(n) solver in reduced.py never forms them. All functions accept a batch
of states along trailing axes of θ (shape (n, …)).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightsail_mbs.model import terms
from lightsail_mbs.model.parameters import SailParameters


@dataclass(frozen=True)
class ChainModel:
    """The constants of one chain: sizes, masses, stiffnesses, dampers, end tension."""

    params: SailParameters
    n: int
    half_length: float  # b = l/2
    mass: float  # m
    inertia: float  # J_G = m l²/12
    torsional_stiffness: float  # k_T
    torsional_damping: float  # c_T + β k_T
    axial_stiffness: float  # k_s (0 when inextensible: not used)
    axial_damping: float  # c_s + β k_s
    tension: float  # T, follower end tension (Eq. 32)
    extensible: bool

    @classmethod
    def from_params(cls, p: SailParameters) -> ChainModel:
        return cls(
            params=p,
            n=p.n,
            half_length=0.5 * p.slice_length,
            mass=p.slice_mass,
            inertia=p.slice_inertia,
            torsional_stiffness=p.torsional_stiffness,
            torsional_damping=p.total_torsional_damping,
            axial_stiffness=p.axial_stiffness if p.extensible else 0.0,
            axial_damping=p.total_axial_damping,
            tension=p.tension if p.model == "tnt" else 0.0,
            extensible=p.extensible,
        )

    @property
    def dof(self) -> int:
        """Number of generalized coordinates: n + 2, or 2n + 1 for the extensible chain."""
        return 2 * self.n + 1 if self.extensible else self.n + 2

    def split(self, q: np.ndarray):
        """(x₁, y₁, θ (n, …), z (n−1, …)) from q (dof, …); z is zeros when inextensible."""
        n = self.n
        z = q[n + 2 :] if self.extensible else np.zeros((n - 1,) + q.shape[1:])
        return q[0], q[1], q[2 : n + 2], z

    def pack(self, x1, y1, theta, z) -> np.ndarray:
        parts = [np.atleast_1d(x1), np.atleast_1d(y1), theta] + ([z] if self.extensible else [])
        return np.concatenate(parts)

    def arms(self, z: np.ndarray) -> np.ndarray:
        """a_i = l/2 + z_i, i = 1…n−1 (distance from centre i to joint i along e_i)."""
        return self.half_length + z


def centres(model: ChainModel, q: np.ndarray):
    """Slice-centre coordinates (x_j, y_j), each (n, …), Eqs (13)–(14), (30)–(31)."""
    x1, y1, th, z = model.split(q)
    a, b = model.arms(z), model.half_length
    c, s = np.cos(th), np.sin(th)
    dx = a * c[:-1] + b * c[1:]
    dy = a * s[:-1] + b * s[1:]
    x = np.concatenate([x1[None], x1 + np.cumsum(dx, axis=0)])
    y = np.concatenate([y1[None], y1 + np.cumsum(dy, axis=0)])
    return x, y


def centre_velocities(model: ChainModel, q: np.ndarray, qd: np.ndarray):
    """(ẋ_j, ẏ_j), each (n, …): ṙ_{i+1} − ṙ_i = ż_i e_i + a_i θ̇_i p_i + b θ̇_{i+1} p_{i+1}."""
    _, _, th, z = model.split(q)
    vx1, vy1, om, zd = model.split(qd)
    a, b = model.arms(z), model.half_length
    c, s = np.cos(th), np.sin(th)
    dvx = zd * c[:-1] - a * om[:-1] * s[:-1] - b * om[1:] * s[1:]
    dvy = zd * s[:-1] + a * om[:-1] * c[:-1] + b * om[1:] * c[1:]
    vx = np.concatenate([vx1[None], vx1 + np.cumsum(dvx, axis=0)])
    vy = np.concatenate([vy1[None], vy1 + np.cumsum(dvy, axis=0)])
    return vx, vy


def centre_jacobian(model: ChainModel, q: np.ndarray) -> np.ndarray:
    """J_v: ∂(x_j, y_j)/∂q as an (n, 2, dof) array (one state)."""
    n = model.n
    _, _, th, z = model.split(q)
    a, b = model.arms(z), model.half_length
    j = np.arange(n)[:, None]
    k = np.arange(n)[None, :]
    arm_a = np.where(k < j, np.append(a, 0.0)[None, :], 0.0)
    arm_b = np.where((k >= 1) & (k <= j), b, 0.0)
    coef = arm_a + arm_b  # c_jk
    jac = np.zeros((n, 2, model.dof))
    jac[:, 0, 0] = 1.0
    jac[:, 1, 1] = 1.0
    jac[:, 0, 2 : n + 2] = -coef * np.sin(th)[None, :]
    jac[:, 1, 2 : n + 2] = coef * np.cos(th)[None, :]
    if model.extensible:
        below = np.arange(n - 1)[None, :] < j
        jac[:, 0, n + 2 :] = below * np.cos(th[:-1])[None, :]
        jac[:, 1, n + 2 :] = below * np.sin(th[:-1])[None, :]
    return jac


def mass_matrix(model: ChainModel, q: np.ndarray) -> np.ndarray:
    """M(q) = m Σ_j J_jᵀ J_j + J_G Σ_j ∂θ_j/∂qᵀ ∂θ_j/∂q (dof × dof, one state)."""
    jac = centre_jacobian(model, q)
    mass = model.mass * np.einsum("jai,jak->ik", jac, jac)
    idx = np.arange(2, model.n + 2)
    mass[idx, idx] += model.inertia
    return mass


def velocity_terms(model: ChainModel, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
    """c(q, q̇) = Σ_j m J_jᵀ (J̇_j q̇): the centripetal/Coriolis terms of the Euler–Lagrange equations.

    J̇_j q̇ is the centre acceleration at q̈ = 0: Σ_{i<j} (2 ż_i θ̇_i p_i − a_i θ̇_i² e_i) − Σ_{2≤k≤j} b θ̇_k² e_k.
    """
    _, _, th, z = model.split(q)
    _, _, om, zd = model.split(qd)
    a, b = model.arms(z), model.half_length
    c, s = np.cos(th), np.sin(th)
    dax = -2 * zd * om[:-1] * s[:-1] - a * om[:-1] ** 2 * c[:-1] - b * om[1:] ** 2 * c[1:]
    day = 2 * zd * om[:-1] * c[:-1] - a * om[:-1] ** 2 * s[:-1] - b * om[1:] ** 2 * s[1:]
    acc = np.stack([np.concatenate([[0.0], np.cumsum(dax)]), np.concatenate([[0.0], np.cumsum(day)])], axis=1)
    return model.mass * np.einsum("jai,ja->i", centre_jacobian(model, q), acc)


def torsion_torques(model: ChainModel, theta: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """τ_j = −∂V/∂θ_j − damping, V = ½ k_T Σ (θ_j − θ_{j−1})² (Eq. 23), damper c_T on θ̇_j − θ̇_{j−1}."""
    tau = np.zeros_like(theta)
    if not (model.torsional_stiffness or model.torsional_damping):
        return tau
    moment = model.torsional_stiffness * (theta[1:] - theta[:-1] - model.params.rest_turn)
    if model.torsional_damping:
        moment += model.torsional_damping * (omega[1:] - omega[:-1])
    tau[:-1] = moment
    tau[1:] -= moment
    return tau


def axial_forces(model: ChainModel, z: np.ndarray, zd: np.ndarray) -> np.ndarray:
    """s_i = −k_s z_i − c_s ż_i: the spring force on slice i+1 along e_i (Eq. 29)."""
    return -model.axial_stiffness * z - model.axial_damping * zd


def body_forces(model: ChainModel, x: np.ndarray, theta: np.ndarray):
    """Forces on the slice centres: the physics terms' numpy forms (terms.chain_forces: radiation, Eq. 11,
    and the frame force −m g₀) plus the follower end tensions −T e₁ on slice 1 and T eₙ on slice n
    (Eq. 32; applied at the slice ends along the slice, they have no moment about the centres)."""
    fx, fy = terms.chain_forces(model.params, x, theta)
    if model.tension:
        fx = fx.copy()
        fy = fy.copy()
        fx[0] -= model.tension * np.cos(theta[0])
        fy[0] -= model.tension * np.sin(theta[0])
        fx[-1] += model.tension * np.cos(theta[-1])
        fy[-1] += model.tension * np.sin(theta[-1])
    return fx, fy


def generalized_forces(model: ChainModel, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
    """Q(q, q̇) = Σ_j J_jᵀ F_j + torsion torques + axial spring forces (Eqs 15, 32, −∂V/∂q), one state."""
    x, _ = centres(model, q)
    _, _, th, z = model.split(q)
    _, _, om, zd = model.split(qd)
    fx, fy = body_forces(model, x, th)
    gen = np.einsum("jai,ja->i", centre_jacobian(model, q), np.stack([fx, fy], axis=1))
    gen[2 : model.n + 2] += torsion_torques(model, th, om)
    if model.extensible:
        gen[model.n + 2 :] += axial_forces(model, z, zd)
    return gen


def dense_accelerations(model: ChainModel, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
    """q̈ = M⁻¹ (Q − c): the reference O(n³) solution of the Euler–Lagrange equations (Eq. 16)."""
    return np.linalg.solve(mass_matrix(model, q), generalized_forces(model, q, qd) - velocity_terms(model, q, qd))
