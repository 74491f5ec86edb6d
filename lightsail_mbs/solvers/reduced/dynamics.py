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

1. Slices: cos θ_i, sin θ_i, the arms a_i and the abscissae x_i of the centres; the net applied force
   F_i on every slice from ONE function, `slice_forces_into` (angles and abscissae → forces: the
   radiation load of model/loads.py, Eq. 11 generalised to Gaussian beams and partial reflectors, plus
   the frame force −m g₀ ŷ, with their near-cancellation done analytically: loads.applied_forces, whose
   compiled twin loads.net_slice_force is called here); then the follower end tensions −T e₁, T eₙ (Eq. 32), the torsion
   spring/damper torques on θ_{i+1} − θ_i (Eq. 23), the prescribed axial joint forces s_i e_i
   (extensible chain) and from them the unconstrained accelerations A⁰_i = (F_i, τ_i)/(m, J).
2. Joints, forward: the right-hand side −g_i(Λ⁰) from A⁰ and w_i, assembled and eliminated in the
   same pass as the blocks of K (pivots inverted, couplings stored).
3. Joints, backward: back substitution for Λ_i interleaved with the final slice accelerations
   (slice i+1 needs Λ_i and Λ_{i+1}, both known once the sweep has passed joint i).

The constants of a chain travel to the kernels as one float vector (`constants`, indices below).
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import loads, optics, payload
from lightsail_mbs.model.loads import net_slice_force
from lightsail_mbs.model.optics import packed_net_force
from lightsail_mbs.solvers.reduced.kinematics import ChainModel

# layout of the constants vector of one chain (read by the compiled kernels)
(
    N,
    MASS,
    INERTIA,
    HALF,
    K_T,
    C_T,
    K_S,
    C_S,
    TENSION,
    INTENSITY,
    AREA_C,
    WAIST,
    CENTER,
    REFL,
    ABSORB,
    MEAN_INTENSITY,
    EXTENSIBLE,
    UNIFORM,
    PAY_SLICE,
    PAY_MASS,
    PAY_INERTIA,
    PAY_CE,
    PAY_CP,
    PAY_RE,
    PAY_RP,
    REST_TURN,
    FRAME,
    FRAME_EXCESS,
    MOMENTUM,
) = range(29)
N_CONSTANTS = 29

# rows of the workspace of one right-hand-side evaluation
(COS, SIN, ARM, ABSCISSA, AX, AY, AL, I_XX, I_XY, I_YY, U_XX, U_XY, U_YY, R_X, R_Y) = range(15)
WORK_ROWS = 15


def constants(model: ChainModel) -> np.ndarray:
    """The chain's constants as the float vector the compiled kernels read (indices above)."""
    p = model.params
    k = np.zeros(N_CONSTANTS)
    k[N], k[MASS], k[INERTIA], k[HALF] = model.n, model.mass, model.inertia, model.half_length
    k[K_T], k[C_T] = model.torsional_stiffness, model.torsional_damping
    k[K_S], k[C_S], k[TENSION] = model.axial_stiffness, model.axial_damping, model.tension
    k[INTENSITY], k[AREA_C] = p.intensity, p.slice_length * p.width / SPEED_OF_LIGHT
    k[WAIST] = 1.0 if p.uniform_beam else p.beam_waist
    k[CENTER], k[REFL], k[ABSORB] = p.beam_center, p.reflectivity, p.absorptivity
    k[MEAN_INTENSITY] = p.mean_intensity  # the net form's frame force is −(2R + α) Ī l W/c
    k[EXTENSIBLE], k[UNIFORM] = float(model.extensible), float(p.uniform_beam)
    k[REST_TURN] = p.rest_turn  # the springs' rest angle between neighbours (a sail made curved)
    k[FRAME] = -p.slice_mass * p.nominal_acceleration  # −m g₀ on each slice (the payload's is scaled from it)
    k[MOMENTUM] = p.normal_momentum
    k[PAY_SLICE] = -1.0  # a payload (model/payload.py): its composite slice j, M, J_c, ρ_c, ρ in slice j's axes
    attached = payload.attachment(p)
    if attached is not None:
        k[PAY_SLICE], k[PAY_MASS], k[PAY_INERTIA] = attached.slice_index, attached.mass, attached.inertia
        k[PAY_CE], k[PAY_CP] = attached.centre_along, attached.centre_across
        k[PAY_RE], k[PAY_RP] = attached.along, attached.across
        k[FRAME_EXCESS] = loads.frame_force_excess(p)  # c_n(0) Ī l W/c − m g₀ (0 without a payload)
    if p.optics is not None:  # an optical table: the slices' flags and the packed table follow the constants
        k = np.concatenate([k, optics.solver_block(p)])
    return k


@njit(cache=True)
def workspace(n):
    """Scratch memory for one right-hand-side evaluation of an n-slice chain."""
    return np.empty((WORK_ROWS, n))


@njit(cache=True)
def slice_forces_into(theta, cth, sth, x, k, fx, fy):
    """Net applied force on every slice centre (N), in inertial directions: the load model of
    model/loads.py (loads.applied_forces), compiled.

    theta, cth, sth: slice angles θ_i and their cosines and sines; x: abscissae of the centres (read
    only by the Gaussian beam). Radiation f_i = (I(x_i) l W / c) cos θ_i [2R cos θ_i n_i + α ŷ]
    (Eq. 11 for R = 1, α = 0; I = I₀ or I₀ exp(−2(x − x_c)²/w²)) plus the frame force
    −(2R + α) Ī l W/c ŷ = −m g₀ ŷ, summed analytically by loads.net_slice_force: the two nearly cancel
    (their sum is O(θ²) of each), and summing them in floating point would leave a round-off of
    ε·m g₀ that the short waves of the chain amplify. With an optical table after the constants
    (case.optics), its law in the same net form (optics.packed_net_force, frame force −c_n(0) Ī l W/c ŷ).
    With a payload the craft accelerates at g₀ < c_n(0) Ī/(c ρ h); the difference of the frame forces,
    c_n(0) Ī l W/c − m g₀ per slice (k[FRAME_EXCESS], a physical O(f₀) push the stem carries), is added.
    """
    inten0, area_c, refl, absorb, mean = k[INTENSITY], k[AREA_C], k[REFL], k[ABSORB], k[MEAN_INTENSITY]
    uniform = k[UNIFORM] != 0.0
    excess, momentum = k[FRAME_EXCESS], k[MOMENTUM]
    n = theta.size
    table = k[N_CONSTANTS + n :]  # an optical table (model/optics.py), after the n slices' mirrored flags
    for i in range(n):
        inten = inten0
        if not uniform:
            dx = (x[i] - k[CENTER]) / k[WAIST]
            inten *= math.exp(-2.0 * dx * dx)
        if table.size:
            mirrored = k[N_CONSTANTS + i] != 0.0
            fx[i], fy[i] = packed_net_force(table, inten, mean, area_c, cth[i], sth[i], theta[i], mirrored, momentum)
        else:
            fx[i], fy[i] = net_slice_force(theta[i], cth[i], sth[i], inten, mean, area_c, refl, absorb)
        fy[i] += excess


@njit(cache=True)
def _free_accelerations(q, qd, k, work, extensible):
    """Sweep 1: cos/sin, arms, abscissae, and A⁰ = the accelerations under the applied forces, end
    tensions, springs and dampers (plus the prescribed axial joint forces of the extensible chain)."""
    n = int(k[N])
    m, J, b = k[MASS], k[INERTIA], k[HALF]
    cth, sth, arm, x = work[COS], work[SIN], work[ARM], work[ABSCISSA]
    ax, ay, al = work[AX], work[AY], work[AL]
    inv_m, inv_j = 1.0 / m, 1.0 / J
    for i in range(n):
        cth[i] = math.cos(q[2 + i])
        sth[i] = math.sin(q[2 + i])
    for i in range(n - 1):
        arm[i] = b + q[n + 2 + i] if extensible else b
    if k[UNIFORM] == 0.0:  # abscissae: only the Gaussian beam's intensity depends on them
        x[0] = q[0]
        for i in range(1, n):
            x[i] = x[i - 1] + arm[i - 1] * cth[i - 1] + b * cth[i]
    slice_forces_into(q[2 : n + 2], cth, sth, x, k, ax, ay)
    tension = k[TENSION]
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
                fx += sp * cth[i - 1]
                fy += sp * sth[i - 1]
                tau -= b * (-s * sp * cth[i - 1] + c * sp * sth[i - 1])
            if i < n - 1:  # its moment arm a_i e_i is parallel to the force: no torque
                sp = -k_s * q[n + 2 + i] - c_s * qd[n + 2 + i]
                fx -= sp * c
                fy -= sp * s
        ax[i] = fx * inv_m
        ay[i] = fy * inv_m
        al[i] = tau * inv_j
        if i == k[PAY_SLICE]:
            _payload_free_acceleration(k, c, s, fx, fy, tau, ax, ay, al, i)


@njit(cache=True)
def _payload_free_acceleration(k, c, s, fx, fy, tau, ax, ay, al, j):
    """A⁰ of the composite slice j (slice + payload, model/payload.py) at its centre of mass: the applied
    force F_j at the slice centre, the payload's frame force F_p = −m_p g₀ ŷ at the payload, the spring
    torques τ; moments about the composite centre of mass ρ_c (offsets ρ_c, ρ in slice j's axes)."""
    mp = k[PAY_MASS] - k[MASS]
    fpy = k[FRAME] * mp / k[MASS]  # −m_p g₀ (k[FRAME] = −m g₀)
    cx = k[PAY_CE] * c - k[PAY_CP] * s  # ρ_c in inertial axes
    cy = k[PAY_CE] * s + k[PAY_CP] * c
    rx = k[PAY_RE] * c - k[PAY_RP] * s - cx  # payload from the composite centre of mass (x; F_p is along y)
    moment = tau + (-cx * fy + cy * fx) + rx * fpy
    ax[j] = fx / k[PAY_MASS]
    ay[j] = (fy + fpy) / k[PAY_MASS]
    al[j] = moment / k[PAY_INERTIA]


@njit(cache=True)
def _arms(k, cth, sth, i):
    """Arms of slice i from its reference point (centre, or the composite centre of mass) to its left and right
    joints, (L_x, L_y, R_x, R_y), and its inverse mass and inertia."""
    b = k[HALF]
    c, s = cth[i], sth[i]
    lx, ly, rx, ry = -b * c, -b * s, b * c, b * s
    if i == k[PAY_SLICE]:
        cx = k[PAY_CE] * c - k[PAY_CP] * s
        cy = k[PAY_CE] * s + k[PAY_CP] * c
        return lx - cx, ly - cy, rx - cx, ry - cy, 1.0 / k[PAY_MASS], 1.0 / k[PAY_INERTIA]
    return lx, ly, rx, ry, 1.0 / k[MASS], 1.0 / k[INERTIA]


@njit(cache=True)
def _inextensible_payload(qd, k, work, qdd):
    """Sweeps 2–3 of a chain with rigid joints and a composite (payload) slice: slice i's arms L_i, R_i from
    its reference point to its joints are general vectors there, and with v⊥ = (−v_y, v_x)

        K_ii = (1/m_i + 1/m_{i+1}) I + R⊥_i R⊥_iᵀ/J_i + L⊥_{i+1} L⊥_{i+1}ᵀ/J_{i+1},
        K_i,i+1 = −(1/m_{i+1}) I − L⊥_{i+1} R⊥_{i+1}ᵀ/J_{i+1} = K_i+1,iᵀ,
        −g_i(0) = ω²_{i+1} L_{i+1} − ω²_i R_i − (A⁰_{i+1} + α⁰_{i+1} L⊥_{i+1} − A⁰_i − α⁰_i R⊥_i);

    K is still symmetric and block tridiagonal (the off-diagonal blocks are not symmetric): block LDLᵀ."""
    n = int(k[N])
    cth, sth, ax, ay, al = work[COS], work[SIN], work[AX], work[AY], work[AL]
    joints = n - 1
    inv = np.empty((3, joints))  # D'⁻¹ (xx, xy, yy)
    up = np.empty((4, joints))  # U = K_i,i+1 (xx, xy, yx, yy)
    rr = np.empty((2, joints))
    for i in range(joints):
        _, _, rix, riy, im_i, ij_i = _arms(k, cth, sth, i)
        ljx, ljy, rjx, rjy, im_j, ij_j = _arms(k, cth, sth, i + 1)
        oi, oj = qd[2 + i], qd[3 + i]
        pr_x, pr_y = -riy, rix  # R⊥_i
        pl_x, pl_y = -ljy, ljx  # L⊥_{i+1}
        r_x = oj * oj * ljx - oi * oi * rix - (ax[i + 1] + al[i + 1] * pl_x - ax[i] - al[i] * pr_x)
        r_y = oj * oj * ljy - oi * oi * riy - (ay[i + 1] + al[i + 1] * pl_y - ay[i] - al[i] * pr_y)
        d_xx = im_i + im_j + ij_i * pr_x * pr_x + ij_j * pl_x * pl_x
        d_xy = ij_i * pr_x * pr_y + ij_j * pl_x * pl_y
        d_yy = im_i + im_j + ij_i * pr_y * pr_y + ij_j * pl_y * pl_y
        if i > 0:  # D −= Uᵀ D'⁻¹ U, r −= Uᵀ D'⁻¹ r' with U, D'⁻¹, r' of joint i − 1
            uxx, uxy, uyx, uyy = up[0, i - 1], up[1, i - 1], up[2, i - 1], up[3, i - 1]
            axx, axy, ayy = inv[0, i - 1], inv[1, i - 1], inv[2, i - 1]
            # W = Uᵀ D'⁻¹
            w11 = uxx * axx + uyx * axy
            w12 = uxx * axy + uyx * ayy
            w21 = uxy * axx + uyy * axy
            w22 = uxy * axy + uyy * ayy
            d_xx -= w11 * uxx + w12 * uyx
            d_xy -= w11 * uxy + w12 * uyy
            d_yy -= w21 * uxy + w22 * uyy
            r_x -= w11 * rr[0, i - 1] + w12 * rr[1, i - 1]
            r_y -= w21 * rr[0, i - 1] + w22 * rr[1, i - 1]
        inv_det = 1.0 / (d_xx * d_yy - d_xy * d_xy)
        inv[0, i], inv[1, i], inv[2, i] = d_yy * inv_det, -d_xy * inv_det, d_xx * inv_det
        rr[0, i], rr[1, i] = r_x, r_y
        if i < joints - 1:
            qr_x, qr_y = -rjy, rjx  # R⊥_{i+1}
            up[0, i] = -im_j - ij_j * pl_x * qr_x
            up[1, i] = -ij_j * pl_x * qr_y
            up[2, i] = -ij_j * pl_y * qr_x
            up[3, i] = -im_j - ij_j * pl_y * qr_y
    lx_next, ly_next = 0.0, 0.0
    for i in range(joints - 1, -1, -1):  # Λ_i = D'⁻¹ (r' − U Λ_{i+1}), then slice i+1's angular acceleration
        r_x, r_y = rr[0, i], rr[1, i]
        if i < joints - 1:
            r_x -= up[0, i] * lx_next + up[1, i] * ly_next
            r_y -= up[2, i] * lx_next + up[3, i] * ly_next
        lx = inv[0, i] * r_x + inv[1, i] * r_y
        ly = inv[1, i] * r_x + inv[2, i] * r_y
        work[R_X, i], work[R_Y, i] = lx, ly
        ljx, ljy, rjx, rjy, _, ij_j = _arms(k, cth, sth, i + 1)
        # slice i+1: +Λ_i at its left joint, −Λ_{i+1} at its right joint
        qdd[3 + i] = al[i + 1] + ij_j * ((-ljy * lx + ljx * ly) - (-rjy * lx_next + rjx * ly_next))
        lx_next, ly_next = lx, ly
    _, _, r0x, r0y, im0, ij0 = _arms(k, cth, sth, 0)
    qdd[0] = ax[0] - lx_next * im0
    qdd[1] = ay[0] - ly_next * im0
    qdd[2] = al[0] - ij0 * (-r0y * lx_next + r0x * ly_next)


@njit(cache=True)
def _inextensible(qd, k, work, qdd):
    """Sweeps 2–3 of a chain with rigid joints: K Λ = −g(0) by block LDLᵀ, then q̈."""
    n = int(k[N])
    m, J, b = k[MASS], k[INERTIA], k[HALF]
    cth, sth, ax, ay, al = work[COS], work[SIN], work[AX], work[AY], work[AL]
    ixx, ixy, iyy = work[I_XX], work[I_XY], work[I_YY]
    uxx, uxy, uyy, rx, ry = work[U_XX], work[U_XY], work[U_YY], work[R_X], work[R_Y]
    joints = n - 1
    inv_m, inv_j = 1.0 / m, 1.0 / J
    two_m = 2.0 * inv_m
    wb = b * b * inv_j
    for i in range(joints):  # sweep 2: assemble and eliminate
        pxi, pyi, pxj, pyj = -sth[i], cth[i], -sth[i + 1], cth[i + 1]
        oi, oj = qd[2 + i], qd[3 + i]
        # −g_i(0) = w_i − (A⁰_{i+1} − A⁰_i − b α⁰_i p_i − b α⁰_{i+1} p_{i+1})
        wx = -b * oi * oi * cth[i] - b * oj * oj * cth[i + 1]
        wy = -b * oi * oi * sth[i] - b * oj * oj * sth[i + 1]
        r_x = wx - (ax[i + 1] - ax[i] - b * al[i] * pxi - b * al[i + 1] * pxj)
        r_y = wy - (ay[i + 1] - ay[i] - b * al[i] * pyi - b * al[i + 1] * pyj)
        d_xx = two_m + wb * (pxi * pxi + pxj * pxj)
        d_xy = wb * (pxi * pyi + pxj * pyj)
        d_yy = two_m + wb * (pyi * pyi + pyj * pyj)
        if i > 0:  # eliminate joint i−1: D −= U W, r −= W r', W = U D'⁻¹ (U symmetric)
            ux, uxy_, uy = uxx[i - 1], uxy[i - 1], uyy[i - 1]
            w11 = ux * ixx[i - 1] + uxy_ * ixy[i - 1]
            w12 = ux * ixy[i - 1] + uxy_ * iyy[i - 1]
            w21 = uxy_ * ixx[i - 1] + uy * ixy[i - 1]
            w22 = uxy_ * ixy[i - 1] + uy * iyy[i - 1]
            d_xx -= w11 * ux + w12 * uxy_
            d_xy -= w11 * uxy_ + w12 * uy
            d_yy -= w21 * uxy_ + w22 * uy
            r_x -= w11 * rx[i - 1] + w12 * ry[i - 1]
            r_y -= w21 * rx[i - 1] + w22 * ry[i - 1]
        inv_det = 1.0 / (d_xx * d_yy - d_xy * d_xy)
        ixx[i], ixy[i], iyy[i] = d_yy * inv_det, -d_xy * inv_det, d_xx * inv_det
        rx[i], ry[i] = r_x, r_y
        if i < joints - 1:
            uxx[i] = -inv_m + wb * pxj * pxj
            uxy[i] = wb * pxj * pyj
            uyy[i] = -inv_m + wb * pyj * pyj
    # sweep 3: back substitution (Λ_i kept in rx, ry) and the accelerations of slice i+1
    lx_next, ly_next = 0.0, 0.0
    for i in range(joints - 1, -1, -1):
        r_x, r_y = rx[i], ry[i]
        if i < joints - 1:
            r_x -= uxx[i] * lx_next + uxy[i] * ly_next
            r_y -= uxy[i] * lx_next + uyy[i] * ly_next
        lx = ixx[i] * r_x + ixy[i] * r_y
        ly = ixy[i] * r_x + iyy[i] * r_y
        rx[i], ry[i] = lx, ly
        j = i + 1
        pxj, pyj = -sth[j], cth[j]
        qdd[2 + j] = al[j] - b * (pxj * (lx + lx_next) + pyj * (ly + ly_next)) * inv_j
        lx_next, ly_next = lx, ly
    px0, py0 = -sth[0], cth[0]  # slice 1: only Λ₁ acts
    qdd[0] = ax[0] - lx_next * inv_m
    qdd[1] = ay[0] - ly_next * inv_m
    qdd[2] = al[0] - b * (px0 * lx_next + py0 * ly_next) * inv_j


@njit(cache=True)
def _joint_residual(qd, k, work, i):
    """g_i with the accelerations currently in the workspace (extensible chain)."""
    n = int(k[N])
    b = k[HALF]
    cth, sth, arm, ax, ay, al = work[COS], work[SIN], work[ARM], work[AX], work[AY], work[AL]
    pxi, pyi, pxj, pyj = -sth[i], cth[i], -sth[i + 1], cth[i + 1]
    oi, oj, zd = qd[2 + i], qd[3 + i], qd[n + 2 + i]
    a = arm[i]
    wx = 2.0 * zd * oi * pxi - a * oi * oi * cth[i] - b * oj * oj * cth[i + 1]
    wy = 2.0 * zd * oi * pyi - a * oi * oi * sth[i] - b * oj * oj * sth[i + 1]
    g_x = ax[i + 1] - ax[i] - a * al[i] * pxi - b * al[i + 1] * pxj - wx
    g_y = ay[i + 1] - ay[i] - a * al[i] * pyi - b * al[i + 1] * pyj - wy
    return g_x, g_y


@njit(cache=True)
def _extensible(qd, k, work, qdd):
    """Sweeps 2–3 of the extensible chain: (pᵀK p) μ = −pᵀ g(s e) by Thomas elimination, then q̈, z̈."""
    n = int(k[N])
    m, J, b = k[MASS], k[INERTIA], k[HALF]
    cth, sth, arm, ax, ay, al = work[COS], work[SIN], work[ARM], work[AX], work[AY], work[AL]
    piv, off, rhs = work[I_XX], work[I_XY], work[R_X]
    joints = n - 1
    for i in range(joints):  # sweep 2: g_i(s e) projected on p_i, Thomas elimination
        pxi, pyi, pxj, pyj = -sth[i], cth[i], -sth[i + 1], cth[i + 1]
        a = arm[i]
        g_x, g_y = _joint_residual(qd, k, work, i)
        cos_rel = pxi * pxj + pyi * pyj
        d = 2.0 / m + (a * a + b * b * cos_rel * cos_rel) / J
        r = -(pxi * g_x + pyi * g_y)
        if i > 0:
            w = off[i - 1] / piv[i - 1]
            d -= w * off[i - 1]
            r -= w * rhs[i - 1]
        piv[i] = d
        rhs[i] = r
        if i < joints - 1:
            off[i] = cos_rel * (b * arm[i + 1] / J - 1.0 / m)  # p_iᵀ K_i,i+1 p_{i+1}
    mu_next = 0.0
    for i in range(joints - 1, -1, -1):  # μ_i, then the accelerations of slice i+1
        r = rhs[i]
        if i < joints - 1:
            r -= off[i] * mu_next
        mu = r / piv[i]
        j = i + 1
        pxi, pyi, pxj, pyj = -sth[i], cth[i], -sth[j], cth[j]
        # slice j: +μ_i p_i at its left joint, −μ_j p_j at its right joint
        ax[j] += (mu * pxi - mu_next * pxj) / m
        ay[j] += (mu * pyi - mu_next * pyj) / m
        moment = -b * mu * (pxj * pxi + pyj * pyi)
        if j < joints:
            moment -= arm[j] * mu_next
        al[j] += moment / J
        rhs[i] = mu
        mu_next = mu
    pxi, pyi = -sth[0], cth[0]
    ax[0] -= mu_next * pxi / m
    ay[0] -= mu_next * pyi / m
    al[0] -= arm[0] * mu_next / J
    qdd[0] = ax[0]
    qdd[1] = ay[0]
    for i in range(n):
        qdd[2 + i] = al[i]
    for i in range(joints):  # z̈_i = e_i·g_i with the final accelerations
        g_x, g_y = _joint_residual(qd, k, work, i)
        qdd[n + 2 + i] = cth[i] * g_x + sth[i] * g_y


@njit(cache=True)
def rhs_into(y, k, work, ydot):
    """ẏ = (q̇, q̈) of y = (q, q̇) (Eq. 40 with M moved to the right) into ydot, with the workspace work."""
    dof = y.size // 2
    q = y[:dof]
    qd = y[dof:]
    for i in range(dof):
        ydot[i] = qd[i]
    extensible = k[EXTENSIBLE] != 0.0
    _free_accelerations(q, qd, k, work, extensible)
    if extensible:
        _extensible(qd, k, work, ydot[dof:])
    elif k[PAY_SLICE] >= 0.0:
        _inextensible_payload(qd, k, work, ydot[dof:])
    else:
        _inextensible(qd, k, work, ydot[dof:])


@njit(cache=True)
def joint_forces(y, k, work, lam_x, lam_y):
    """Λ_i (force of slice i on slice i+1, N) at the state y into lam_x, lam_y: one right-hand-side
    evaluation, read back from the workspace (extensible chain: s_i e_i + μ_i p_i)."""
    n = int(k[N])
    dof = y.size // 2
    ydot = np.empty_like(y)
    rhs_into(y, k, work, ydot)
    if k[EXTENSIBLE] != 0.0:
        for i in range(n - 1):
            s = -k[K_S] * y[n + 2 + i] - k[C_S] * y[dof + n + 2 + i]
            mu = work[R_X, i]
            lam_x[i] = s * work[COS, i] - mu * work[SIN, i]
            lam_y[i] = s * work[SIN, i] + mu * work[COS, i]
    else:
        for i in range(n - 1):
            lam_x[i] = work[R_X, i]
            lam_y[i] = work[R_Y, i]


@njit(cache=True)
def _batch_rhs(y, k):
    """ẏ of every column of y (size, count)."""
    work = workspace(int(k[N]))
    column = np.empty(y.shape[0])
    out = np.empty(y.shape[0])
    result = np.empty_like(y)
    for j in range(y.shape[1]):
        for i in range(y.shape[0]):
            column[i] = y[i, j]
        rhs_into(column, k, work, out)
        for i in range(y.shape[0]):
            result[i, j] = out[i]
    return result


@njit(cache=True)
def jacobian_into(y, k, scales, jac):
    """∂ẏ/∂y into jac by forward differences (step √ε·max(abs(y_j), scale_j)); the q̇ rows are exact (0 | I).
    Dense, 2·dof + 1 right-hand sides: for scipy's implicit methods (the compiled Radau uses newton.py)."""
    size = y.size
    dof = size // 2
    work = workspace(int(k[N]))
    jac[:dof] = 0.0
    for i in range(dof):
        jac[i, dof + i] = 1.0
    base = np.empty(size)
    rhs_into(y, k, work, base)
    moved = y.copy()
    out = np.empty(size)
    for j in range(size):
        moved[j] = y[j] + 1.4901161193847656e-08 * max(abs(y[j]), scales[j])
        step = moved[j] - y[j]
        rhs_into(moved, k, work, out)
        for i in range(dof, size):
            jac[i, j] = (out[i] - base[i]) / step
        moved[j] = y[j]


class ChainDynamics:
    """q̈(q, q̇) for one chain model; states are (dof,) vectors or columns of (dof, k) arrays."""

    def __init__(self, model: ChainModel):
        self.model = model
        self.constants = constants(model)
        self._work = np.empty((WORK_ROWS, model.n))  # workspace(n), without loading a kernel

    def accelerations(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """q̈ for states q, q̇ of shape (dof,) or (dof, k)."""
        q = np.asarray(q, float)
        return self.rhs(0.0, np.concatenate([q, np.asarray(qd, float)]))[q.shape[0] :]

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """ẏ = (q̇, q̈) of y = (q, q̇), one state (size,) or a batch (size, k) (scipy's fun(t, y),
        vectorized or not)."""
        y = np.asarray(y, dtype=float)
        if y.ndim == 2:
            return _batch_rhs(np.ascontiguousarray(y), self.constants)
        out = np.empty(y.size)
        rhs_into(np.ascontiguousarray(y), self.constants, self._work, out)
        return out

    def joint_forces(self, y: np.ndarray) -> np.ndarray:
        """Λ_i, the force of slice i on slice i+1 at the state y = (q, q̇), as an (n−1, 2) array (N)."""
        lam = np.empty((2, self.model.n - 1))
        joint_forces(np.ascontiguousarray(y, dtype=float), self.constants, self._work, lam[0], lam[1])
        return lam.T

    def jacobian(self, t: float, y: np.ndarray, scales: np.ndarray) -> np.ndarray:
        """∂ẏ/∂y (dense, 2 dof + 1 right-hand-side calls, compiled); scales: typical abs(y_j) (difference steps)."""
        y = np.ascontiguousarray(y, dtype=float)
        jac = np.empty((y.size, y.size))
        jacobian_into(y, self.constants, np.ascontiguousarray(scales, float), jac)
        return jac
