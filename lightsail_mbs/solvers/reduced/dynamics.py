"""O(n) accelerations of the chain in minimal coordinates: compiled (numba) sweeps over the slices.

The Euler–Lagrange equations M(q) q̈ + c(q, q̇) = Q(q, q̇) (Eq. 16; the terms in kinematics.py) are
solved without forming M. Coordinates q = (x₁, y₁, θ₁…θₙ[, z₁…zₙ₋₁]); e_i = (cos θ_i, sin θ_i),
p_i = (−sin θ_i, cos θ_i), b = l/2 and the joint arms a_i = b + z_i (z ≡ 0 when inextensible). Each slice
obeys Newton–Euler with the joint force Λ_i that slice i exerts on slice i+1 at joint i (the point
r_i + a_i e_i = r_{i+1} − b e_{i+1}):

    m r̈_i = F_i + Λ_{i−1} − Λ_i,      J θ̈_i = τ_i − b p_i·Λ_{i−1} − a_i p_i·Λ_i      (Λ₀ = Λₙ = 0),

and the joints' acceleration constraints, from differentiating r_{i+1} = r_i + a_i e_i + b e_{i+1} twice,

    g_i ≡ r̈_{i+1} − r̈_i − a_i θ̈_i p_i − b θ̈_{i+1} p_{i+1} − w_i = z̈_i e_i,
    w_i = 2 ż_i θ̇_i p_i − a_i θ̇_i² e_i − b θ̇_{i+1}² e_{i+1}.

Substituting the first into the second gives g(Λ) = g(0) + K Λ with K symmetric positive definite
and block tridiagonal (2×2 symmetric blocks, n−1 joints):

    K_ii = (2/m) I + (a_i²/J) p_i p_iᵀ + (b²/J) p_{i+1} p_{i+1}ᵀ,
    K_i,i+1 = −(1/m) I + (b a_{i+1}/J) p_{i+1} p_{i+1}ᵀ.

* Inextensible chains (z ≡ 0): g = 0, so K Λ = −g(0), solved by block LDLᵀ (block Thomas)
  elimination in O(n).
* Extensible TnT chain (Eqs 29–31, l_s = 0): the massless spring fixes the axial part,
  Λ_i = s_i e_i + μ_i p_i with s_i = −k_s z_i − c_s ż_i; projecting g on p_i removes z̈_i and leaves the
  scalar tridiagonal SPD system pᵀK p μ = −pᵀ g(s e); the projection on e_i then gives z̈_i = e_i·g_i.

The result is exactly M⁻¹(Q − c) (tested against the dense form of kinematics.py).

How one right-hand side is evaluated (`rhs_into`: three sweeps over the slices, no allocation; the
caller owns a `workspace(n)`):

1. Slices: θ_i, cos θ_i, sin θ_i, the arms a_i, and the centres and their velocities where a term reads
   them (`slice_states_into`); the net applied force F_i on every slice from the physics terms
   (model/terms: `chain_forces_into` over the packed terms — the radiation load of model/loads.py, Eq. 11
   generalised to Gaussian beams, partial reflectors and optical tables, with the frame force −m g₀ ŷ
   netted analytically, and a payload's share of the frame force); then the follower end tensions −T e₁,
   T eₙ (Eq. 32), the torsion
   spring/damper torques on θ_{i+1} − θ_i (Eq. 23), the prescribed axial joint forces s_i e_i
   (extensible chain) and from them the unconstrained accelerations A⁰_i = (F_i, τ_i)/(m, J).
2. Joints, forward: the right-hand side −g_i(Λ⁰) from A⁰ and w_i, assembled and eliminated in the
   same pass as the blocks of K (pivots inverted, couplings stored).
3. Joints, backward: back substitution for Λ_i interleaved with the final slice accelerations
   (slice i+1 needs Λ_i and Λ_{i+1}, both known once the sweep has passed joint i).

Sweeps 2–3 are in joints.py. The constants of a chain travel to the kernels as one float vector
(chain_constants.py: `constants` and the names of its indices).
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import heating, world_line
from lightsail_mbs.model.terms import beam_factor, chain_forces_into, set_beam_factor
from lightsail_mbs.model.terms.bodies import CHAIN_ROWS, POSITIONS, READS, VELOCITIES
from lightsail_mbs.solvers.reduced.chain_constants import (
    ABSCISSA,
    AL,
    ARM,
    AX,
    AY,
    C_S,
    C_T,
    COS,
    EXTENSIBLE,
    FRAME,
    HALF,
    HEAT,
    HEIGHT,
    INERTIA,
    K_S,
    K_T,
    MASS,
    N_CONSTANTS,
    OMEGA,
    PAY_CE,
    PAY_CP,
    PAY_INERTIA,
    PAY_MASS,
    PAY_RE,
    PAY_RP,
    PAY_SLICE,
    R_X,
    R_Y,
    REST_TURN,
    SIN,
    TENSION,
    THETA,
    VX,
    VY,
    WORK_ROWS,
    WORLD,
    WORLD_RATE,
    N,
    constants,
)
from lightsail_mbs.solvers.reduced.joints import rigid_joints, rigid_joints_with_payload, sliding_joints
from lightsail_mbs.solvers.reduced.kinematics import ChainModel


@njit(cache=True)
def workspace(n):
    """Scratch memory for one right-hand-side evaluation of an n-slice chain."""
    return np.empty((WORK_ROWS, n))


@njit(cache=True)
def slice_states_into(q, qd, k, work, extensible):
    """The slices as the physics terms read them (model/terms/bodies.py, the first CHAIN_ROWS rows of work):
    θ_i, cos θ_i, sin θ_i, and the arms a_i; the centres r_i and their velocities ṙ_i, ω_i only when a packed
    term reads them (r₁ = (q₀, q₁), r_{i+1} = r_i + a_i e_i + b e_{i+1} and its derivative)."""
    n = int(k[N])
    b = k[HALF]
    cth, sth, arm, x, y = work[COS], work[SIN], work[ARM], work[ABSCISSA], work[HEIGHT]
    for i in range(n):
        work[THETA, i] = q[2 + i]
        cth[i] = math.cos(q[2 + i])
        sth[i] = math.sin(q[2 + i])
    for i in range(n - 1):
        arm[i] = b + q[n + 2 + i] if extensible else b
    reads = int(k[N_CONSTANTS + READS])
    if reads & POSITIONS:
        x[0] = q[0]
        y[0] = q[1]
        for i in range(1, n):
            x[i] = x[i - 1] + arm[i - 1] * cth[i - 1] + b * cth[i]
            y[i] = y[i - 1] + arm[i - 1] * sth[i - 1] + b * sth[i]
    if reads & VELOCITIES:
        vx, vy, omega = work[VX], work[VY], work[OMEGA]
        vx[0] = qd[0]
        vy[0] = qd[1]
        for i in range(n):
            omega[i] = qd[2 + i]
        for i in range(1, n):
            rate = qd[n + 1 + i] if extensible else 0.0  # ż_{i−1}
            turn = arm[i - 1] * omega[i - 1]
            vx[i] = vx[i - 1] + rate * cth[i - 1] - turn * sth[i - 1] - b * omega[i] * sth[i]
            vy[i] = vy[i - 1] + rate * sth[i - 1] + turn * cth[i - 1] + b * omega[i] * cth[i]


@njit(cache=True)
def _free_accelerations(t, q, qd, k, work, extensible):
    """Sweep 1: the slices' states, the applied forces of the physics terms at the time t, and A⁰ = the
    accelerations under them, the end tensions, springs and dampers (plus the prescribed axial joint forces
    of the extensible chain)."""
    n = int(k[N])
    m, J, b = k[MASS], k[INERTIA], k[HALF]
    cth, sth = work[COS], work[SIN]
    ax, ay, al = work[AX], work[AY], work[AL]
    inv_m, inv_j = 1.0 / m, 1.0 / J
    slice_states_into(q, qd, k, work, extensible)
    chain_forces_into(k[N_CONSTANTS:], work[:CHAIN_ROWS], work[AX : AY + 1], t)  # the physics terms (model/terms)
    tension = k[TENSION]
    heat = k[int(k[HEAT]) :]  # a heated film's table (model/heating.py), read at the beam's factor D
    j_heat, f_heat = heating.weights(heat, beam_factor(k[N_CONSTANTS:], t)) if k[HEAT] != 0.0 else (0, 0.0)
    if k[HEAT] != 0.0:
        tension = heating.tension(heat, j_heat, f_heat)
    if tension != 0.0:
        ax[0] -= tension * cth[0]
        ay[0] -= tension * sth[0]
        ax[n - 1] += tension * cth[n - 1]
        ay[n - 1] += tension * sth[n - 1]
    k_t, c_t, k_s, c_s = k[K_T], k[C_T], k[K_S], k[C_S]
    springs = k_t != 0.0 or c_t != 0.0
    rest = k[REST_TURN]
    for i in range(n):
        c, s = cth[i], sth[i]
        fx, fy, tau = ax[i], ay[i], 0.0
        if springs:
            if i > 0:
                tau -= k_t * (q[2 + i] - q[1 + i] - rest) + c_t * (qd[2 + i] - qd[1 + i])
            if i < n - 1:
                tau += k_t * (q[3 + i] - q[2 + i] - rest) + c_t * (qd[3 + i] - qd[2 + i])
        if extensible:  # axial spring forces s_j e_j: +s on slice j+1, −s on slice j
            if i > 0:
                sp = -k_s * q[n + 1 + i] - c_s * qd[n + 1 + i]
                if k[HEAT] != 0.0:
                    sp += k_s * heating.rest_extension(heat, n, j_heat, f_heat, i - 1)
                fx += sp * cth[i - 1]
                fy += sp * sth[i - 1]
                tau -= b * (-s * sp * cth[i - 1] + c * sp * sth[i - 1])
            if i < n - 1:  # its moment arm a_i e_i is parallel to the force: no torque
                sp = -k_s * q[n + 2 + i] - c_s * qd[n + 2 + i]
                if k[HEAT] != 0.0:
                    sp += k_s * heating.rest_extension(heat, n, j_heat, f_heat, i)
                fx -= sp * c
                fy -= sp * s
        ax[i] = fx * inv_m
        ay[i] = fy * inv_m
        al[i] = tau * inv_j
        if i == k[PAY_SLICE]:
            _payload_free_acceleration(k, c, s, fx, fy, tau, ax, ay, al, i, t)


@njit(cache=True)
def _payload_free_acceleration(k, c, s, fx, fy, tau, ax, ay, al, j, t):
    """A⁰ of the composite slice j (slice + payload, model/payload.py) at its centre of mass: the applied
    force F_j at the slice centre, the payload's frame force F_p = −m_p g₀ ŷ at the payload (times the beam's
    factor at the time t, model/terms/doppler.py), the spring torques τ; moments about the composite centre
    of mass ρ_c (offsets ρ_c, ρ in slice j's axes)."""
    mp = k[PAY_MASS] - k[MASS]
    fpy = k[FRAME] * mp / k[MASS] * beam_factor(k[N_CONSTANTS:], t)  # −m_p g₀ (k[FRAME] = −m g₀)
    cx = k[PAY_CE] * c - k[PAY_CP] * s  # ρ_c in inertial axes
    cy = k[PAY_CE] * s + k[PAY_CP] * c
    rx = k[PAY_RE] * c - k[PAY_RP] * s - cx  # payload from the composite centre of mass (x; F_p is along y)
    moment = tau + (-cx * fy + cy * fx) + rx * fpy
    ax[j] = fx / k[PAY_MASS]
    ay[j] = (fy + fpy) / k[PAY_MASS]
    al[j] = moment / k[PAY_INERTIA]


@njit(cache=True)
def rhs_into(t, y, k, work, ydot):
    """ẏ = (q̇, q̈) of y = (q, q̇) at the time t (Eq. 40 with M moved to the right) into ydot, with the
    workspace work. With the sail's world line in the state (k[WORLD]), q and q̇ end with its coordinates
    (t, x/c) and 4-velocity (γ, γβ) (model/world_line.py): their accelerations, and the beam's factor D of
    that 4-velocity written into the packed Doppler term before the loads are summed."""
    dof = y.size // 2
    q = y[:dof]
    qd = y[dof:]
    for i in range(dof):
        ydot[i] = qd[i]
    if k[WORLD] != 0.0:
        at = dof - world_line.COORDINATES
        ratio = set_beam_factor(k[N_CONSTANTS:], world_line.doppler(qd[at], qd[at + 1]))  # and c_n(0) at λ'
        a_time, a_distance, _ = world_line.accelerations(k[WORLD_RATE] * ratio, qd[at], qd[at + 1])
        ydot[dof + at] = a_time
        ydot[dof + at + 1] = a_distance
    extensible = k[EXTENSIBLE] != 0.0
    _free_accelerations(t, q, qd, k, work, extensible)
    if extensible:
        sliding_joints(qd, k, work, ydot[dof:])
    elif k[PAY_SLICE] >= 0.0:
        rigid_joints_with_payload(qd, k, work, ydot[dof:])
    else:
        rigid_joints(qd, k, work, ydot[dof:])


@njit(cache=True)
def joint_forces(t, y, k, work, lam_x, lam_y):
    """Λ_i (force of slice i on slice i+1, N) at the time t and state y into lam_x, lam_y: one right-hand-side
    evaluation, read back from the workspace (extensible chain: s_i e_i + μ_i p_i)."""
    n = int(k[N])
    dof = y.size // 2
    ydot = np.empty_like(y)
    rhs_into(t, y, k, work, ydot)
    if k[EXTENSIBLE] != 0.0:
        heat = k[int(k[HEAT]) :]
        j_heat, f_heat = heating.weights(heat, beam_factor(k[N_CONSTANTS:], t)) if k[HEAT] != 0.0 else (0, 0.0)
        for i in range(n - 1):
            s = -k[K_S] * y[n + 2 + i] - k[C_S] * y[dof + n + 2 + i]
            if k[HEAT] != 0.0:
                s += k[K_S] * heating.rest_extension(heat, n, j_heat, f_heat, i)
            mu = work[R_X, i]
            lam_x[i] = s * work[COS, i] - mu * work[SIN, i]
            lam_y[i] = s * work[SIN, i] + mu * work[COS, i]
    else:
        for i in range(n - 1):
            lam_x[i] = work[R_X, i]
            lam_y[i] = work[R_Y, i]


@njit(cache=True)
def _batch_rhs(t, y, k):
    """ẏ of every column of y (size, count) at the time t."""
    work = workspace(int(k[N]))
    column = np.empty(y.shape[0])
    out = np.empty(y.shape[0])
    result = np.empty_like(y)
    for j in range(y.shape[1]):
        for i in range(y.shape[0]):
            column[i] = y[i, j]
        rhs_into(t, column, k, work, out)
        for i in range(y.shape[0]):
            result[i, j] = out[i]
    return result


@njit(cache=True)
def jacobian_into(t, y, k, scales, jac):
    """∂ẏ/∂y into jac by forward differences (step √ε·max(abs(y_j), scale_j)); the q̇ rows are exact (0 | I).
    Dense, 2·dof + 1 right-hand sides: for scipy's implicit methods (the compiled Radau uses newton.py)."""
    size = y.size
    dof = size // 2
    work = workspace(int(k[N]))
    jac[:dof] = 0.0
    for i in range(dof):
        jac[i, dof + i] = 1.0
    base = np.empty(size)
    rhs_into(t, y, k, work, base)
    moved = y.copy()
    out = np.empty(size)
    for j in range(size):
        moved[j] = y[j] + 1.4901161193847656e-08 * max(abs(y[j]), scales[j])
        step = moved[j] - y[j]
        rhs_into(t, moved, k, work, out)
        for i in range(dof, size):
            jac[i, j] = (out[i] - base[i]) / step
        moved[j] = y[j]


class ChainDynamics:
    """q̈(q, q̇) for one chain model; states are (dof,) vectors or columns of (dof, k) arrays."""

    def __init__(self, model: ChainModel, world: bool = False):
        self.model = model
        self.constants = constants(model, world)
        self._work = np.empty((WORK_ROWS, model.n))  # workspace(n), without loading a kernel

    def accelerations(self, q: np.ndarray, qd: np.ndarray, t: float = 0.0) -> np.ndarray:
        """q̈ for states q, q̇ of shape (dof,) or (dof, k) at the time t."""
        q = np.asarray(q, float)
        return self.rhs(t, np.concatenate([q, np.asarray(qd, float)]))[q.shape[0] :]

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """ẏ = (q̇, q̈) of y = (q, q̇), one state (size,) or a batch (size, k) (scipy's fun(t, y),
        vectorized or not)."""
        y = np.asarray(y, dtype=float)
        if y.ndim == 2:
            return _batch_rhs(float(t), np.ascontiguousarray(y), self.constants)
        out = np.empty(y.size)
        rhs_into(float(t), np.ascontiguousarray(y), self.constants, self._work, out)
        return out

    def joint_forces(self, y: np.ndarray, t: float = 0.0) -> np.ndarray:
        """Λ_i, the force of slice i on slice i+1 at the state y = (q, q̇) and time t, as an (n−1, 2) array (N)."""
        lam = np.empty((2, self.model.n - 1))
        joint_forces(float(t), np.ascontiguousarray(y, dtype=float), self.constants, self._work, lam[0], lam[1])
        return lam.T

    def jacobian(self, t: float, y: np.ndarray, scales: np.ndarray) -> np.ndarray:
        """∂ẏ/∂y (dense, 2 dof + 1 right-hand-side calls, compiled); scales: typical abs(y_j) (difference steps)."""
        y = np.ascontiguousarray(y, dtype=float)
        jac = np.empty((y.size, y.size))
        jacobian_into(float(t), y, self.constants, np.ascontiguousarray(scales, float), jac)
        return jac
