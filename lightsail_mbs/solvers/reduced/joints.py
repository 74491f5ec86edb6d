"""Sweeps 2–3 of the chain's accelerations (dynamics.py): the joint forces Λ and from them q̈, in O(n).

Given the unconstrained accelerations A⁰ of sweep 1 in the workspace, each function assembles the joints'
system K Λ = −g(0) (module docstring of dynamics.py) and eliminates it in one forward pass, then back
substitutes for Λ interleaved with the final slice accelerations:

* rigid_joints: an inextensible chain, block LDLᵀ of the 2×2-block tridiagonal K;
* rigid_joints_with_payload: the same with one composite (slice + payload) slice, whose arms are general;
* sliding_joints: the extensible TnT chain, the scalar tridiagonal system of the normal joint forces μ.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.solvers.reduced.chain_constants import (
    AL,
    ARM,
    AX,
    AY,
    COS,
    HALF,
    I_XX,
    I_XY,
    I_YY,
    INERTIA,
    MASS,
    PAY_CE,
    PAY_CP,
    PAY_INERTIA,
    PAY_MASS,
    PAY_SLICE,
    R_X,
    R_Y,
    SIN,
    U_XX,
    U_XY,
    U_YY,
    N,
)


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
def rigid_joints_with_payload(qd, k, work, qdd):
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
def rigid_joints(qd, k, work, qdd):
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
def sliding_joints(qd, k, work, qdd):
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
