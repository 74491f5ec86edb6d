"""The compiled kernels of the reduced sheet (solvers.reduced.sheet): its right-hand side, the scatter of
a coloured difference quotient into the sparse Jacobian, and the unpacking of states into angles.

State per tile (STATE = 13 entries): the centre displacement u from its flat grid point, a quaternion q
(scalar first) and the body-frame angular velocity ω_b, then v = u̇; the equations and the connector law
are in the docstring of solvers.reduced.sheet.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model.terms import beam_factor, tile_forces_into
from lightsail_mbs.model.terms.bodies import E1X, N1, N2, NB, TILE_ROWS, TVX, TWX, TX, TY, TZ
from lightsail_mbs.solvers.reduced.sheet_tethers import STATE, add_tethers


@njit(cache=True)
def rotation_minus_identity(q0, q1, q2, q3, R):
    """R − I of the rotation of the (not necessarily unit) quaternion q, from small products only."""
    n = 1.0 / (q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    R[0, 0] = -2.0 * (q2 * q2 + q3 * q3) * n
    R[0, 1] = 2.0 * (q1 * q2 - q0 * q3) * n
    R[0, 2] = 2.0 * (q1 * q3 + q0 * q2) * n
    R[1, 0] = 2.0 * (q1 * q2 + q0 * q3) * n
    R[1, 1] = -2.0 * (q1 * q1 + q3 * q3) * n
    R[1, 2] = 2.0 * (q2 * q3 - q0 * q1) * n
    R[2, 0] = 2.0 * (q1 * q3 - q0 * q2) * n
    R[2, 1] = 2.0 * (q2 * q3 + q0 * q1) * n
    R[2, 2] = -2.0 * (q1 * q1 + q2 * q2) * n


@njit(cache=True)
def rhs_kernel(
    y,
    flat,
    mass,
    inertia,
    inverse,
    diagonal,
    ta,
    tb,
    la,
    lb,
    gap,
    K,
    Dm,
    off,
    frame,
    framed,
    fol_tile,
    fol_point,
    fol_force,
    packed,
    time,
    lit,
    dead,
    tether_tile,
    tether_point,
    tether_rest,
    tether_law,
    out,
):
    """dy/dt of the sheet (solvers.reduced.sheet). Per body: mass, inertia (3, 3) and its inverse, diagonal
    (its inertia is diagonal); per connector: frame (3, 3), a support's axes where framed; packed: the
    sheet's physics terms (model/terms: terms.pack), summed at the time `time` (s) on the first `lit` bodies
    (the tiles); a body after them (the payload, model.sheet_payload) carries the dead force `dead` along z
    times the beam's factor, and the tethers (tile, point on it, rest length; law (k, c)) join it to the
    tiles (sheet_tethers.add_tethers)."""
    N = flat.shape[0]
    R = np.empty((N, 3, 3))
    RmI = np.empty((N, 3, 3))
    W = np.empty((N, 3))  # global angular velocity
    F = np.zeros((N, 3))
    T = np.zeros((N, 3))  # global torque about the centre
    for k in range(N):
        b = STATE * k
        rotation_minus_identity(y[b + 3], y[b + 4], y[b + 5], y[b + 6], RmI[k])
        for i in range(3):
            for j in range(3):
                R[k, i, j] = RmI[k, i, j] + (1.0 if i == j else 0.0)
        for i in range(3):
            W[k, i] = R[k, i, 0] * y[b + 10] + R[k, i, 1] * y[b + 11] + R[k, i, 2] * y[b + 12]
    ra = np.empty(3)
    rb = np.empty(3)
    sa = np.empty(3)
    sb = np.empty(3)
    d = np.empty(3)
    dv = np.empty(3)
    dw = np.empty(3)
    loc = np.empty(6)
    RA = np.empty((3, 3))
    Rrel = np.empty((3, 3))
    fg = np.empty(3)
    mg = np.empty(3)
    for c in range(ta.shape[0]):
        A = ta[c]
        B = tb[c]
        bB = STATE * B
        for i in range(3):
            sb[i] = RmI[B, i, 0] * lb[c, 0] + RmI[B, i, 1] * lb[c, 1] + RmI[B, i, 2] * lb[c, 2]
            rb[i] = lb[c, i] + sb[i]
        if A >= 0:
            bA = STATE * A
            for i in range(3):
                for j in range(3):
                    RA[i, j] = R[A, i, j]
            for i in range(3):
                sa[i] = RmI[A, i, 0] * la[c, 0] + RmI[A, i, 1] * la[c, 1] + RmI[A, i, 2] * la[c, 2]
                ra[i] = la[c, i] + sa[i]
            for i in range(3):
                d[i] = (y[bB + i] - y[bA + i]) + sb[i] - sa[i] + gap[c, i]
            wa0, wa1, wa2 = W[A, 0], W[A, 1], W[A, 2]
            va0 = y[bA + 7] + wa1 * ra[2] - wa2 * ra[1]
            va1 = y[bA + 8] + wa2 * ra[0] - wa0 * ra[2]
            va2 = y[bA + 9] + wa0 * ra[1] - wa1 * ra[0]
        else:
            for i in range(3):
                for j in range(3):
                    RA[i, j] = frame[c, i, j] if framed[c] else (1.0 if i == j else 0.0)
                ra[i] = 0.0
                d[i] = y[bB + i] + sb[i] + gap[c, i]
            wa0 = wa1 = wa2 = 0.0
            va0 = va1 = va2 = 0.0
        wb0, wb1, wb2 = W[B, 0], W[B, 1], W[B, 2]
        dv[0] = y[bB + 7] + wb1 * rb[2] - wb2 * rb[1] - va0
        dv[1] = y[bB + 8] + wb2 * rb[0] - wb0 * rb[2] - va1
        dv[2] = y[bB + 9] + wb0 * rb[1] - wb1 * rb[0] - va2
        dw[0] = wb0 - wa0
        dw[1] = wb1 - wa1
        dw[2] = wb2 - wa2
        for i in range(3):
            for j in range(3):
                Rrel[i, j] = RA[0, i] * R[B, 0, j] + RA[1, i] * R[B, 1, j] + RA[2, i] * R[B, 2, j]
        if A < 0 and framed[c]:  # frameᵀ R_B frame: the support's rotation in its own axes
            for i in range(3):
                r0, r1, r2 = Rrel[i, 0], Rrel[i, 1], Rrel[i, 2]
                for j in range(3):
                    Rrel[i, j] = r0 * frame[c, 0, j] + r1 * frame[c, 1, j] + r2 * frame[c, 2, j]
        phi1 = math.atan2(Rrel[0, 2], math.sqrt(Rrel[1, 2] ** 2 + Rrel[2, 2] ** 2))
        phi0 = math.atan2(-Rrel[1, 2], Rrel[2, 2])
        phi2 = math.atan2(-Rrel[0, 1], Rrel[0, 0])
        for i in range(3):
            dl = RA[0, i] * d[0] + RA[1, i] * d[1] + RA[2, i] * d[2]
            vl = RA[0, i] * dv[0] + RA[1, i] * dv[1] + RA[2, i] * dv[2]
            wl = RA[0, i] * dw[0] + RA[1, i] * dw[1] + RA[2, i] * dw[2]
            loc[i] = K[c, i] * (dl - off[c, i]) + Dm[c, i] * vl
            loc[3 + i] = Dm[c, 3 + i] * wl
        loc[3] += K[c, 3] * (phi0 - off[c, 3])
        loc[4] += K[c, 4] * (phi1 - off[c, 4])
        loc[5] += K[c, 5] * (phi2 - off[c, 5])
        for i in range(3):
            fg[i] = RA[i, 0] * loc[0] + RA[i, 1] * loc[1] + RA[i, 2] * loc[2]
            mg[i] = RA[i, 0] * loc[3] + RA[i, 1] * loc[4] + RA[i, 2] * loc[5]
        F[B, 0] -= fg[0]
        F[B, 1] -= fg[1]
        F[B, 2] -= fg[2]
        T[B, 0] -= rb[1] * fg[2] - rb[2] * fg[1] + mg[0]
        T[B, 1] -= rb[2] * fg[0] - rb[0] * fg[2] + mg[1]
        T[B, 2] -= rb[0] * fg[1] - rb[1] * fg[0] + mg[2]
        if A >= 0:
            F[A, 0] += fg[0]
            F[A, 1] += fg[1]
            F[A, 2] += fg[2]
            T[A, 0] += ra[1] * fg[2] - ra[2] * fg[1] + mg[0]
            T[A, 1] += ra[2] * fg[0] - ra[0] * fg[2] + mg[1]
            T[A, 2] += ra[0] * fg[1] - ra[1] * fg[0] + mg[2]
    for f in range(fol_tile.shape[0]):
        k = fol_tile[f]
        for i in range(3):
            ra[i] = R[k, i, 0] * fol_point[f, 0] + R[k, i, 1] * fol_point[f, 1] + R[k, i, 2] * fol_point[f, 2]
            fg[i] = R[k, i, 0] * fol_force[f, 0] + R[k, i, 1] * fol_force[f, 1] + R[k, i, 2] * fol_force[f, 2]
        F[k, 0] += fg[0]
        F[k, 1] += fg[1]
        F[k, 2] += fg[2]
        T[k, 0] += ra[1] * fg[2] - ra[2] * fg[1]
        T[k, 1] += ra[2] * fg[0] - ra[0] * fg[2]
        T[k, 2] += ra[0] * fg[1] - ra[1] * fg[0]
    if tether_tile.shape[0] > 0:
        add_tethers(y, flat, R, W, F, T, lit, tether_tile, tether_point, tether_rest, tether_law[0], tether_law[1])
    bodies = np.zeros((TILE_ROWS, lit))  # the tiles as the physics terms read them (model/terms/bodies.py)
    for k in range(lit):
        b = STATE * k
        bodies[TX, k] = flat[k, 0] + y[b]
        bodies[TY, k] = flat[k, 1] + y[b + 1]
        bodies[TZ, k] = flat[k, 2] + y[b + 2]
        bodies[N1, k] = RmI[k, 0, 2]  # the normal R ẑ: its x, y components are the small entries of R − I
        bodies[N2, k] = RmI[k, 1, 2]
        bodies[NB, k] = R[k, 2, 2]
        for i in range(3):
            bodies[TVX + i, k] = y[b + 7 + i]
            bodies[TWX + i, k] = W[k, i]
            bodies[E1X + i, k] = R[k, i, 0]  # the in-plane axis R x̂
    loads = np.empty((3, lit))
    tile_forces_into(packed, bodies, loads, time)
    factor = beam_factor(packed, time) if N > lit else 1.0
    for k in range(N):
        b = STATE * k
        if k < lit:
            F[k, 0] += loads[0, k]
            F[k, 1] += loads[1, k]
            F[k, 2] += loads[2, k]
        else:
            F[k, 2] += dead * factor
        q0, q1, q2, q3 = y[b + 3], y[b + 4], y[b + 5], y[b + 6]
        w0, w1, w2 = y[b + 10], y[b + 11], y[b + 12]
        out[b] = y[b + 7]
        out[b + 1] = y[b + 8]
        out[b + 2] = y[b + 9]
        out[b + 3] = 0.5 * (-q1 * w0 - q2 * w1 - q3 * w2)
        out[b + 4] = 0.5 * (q0 * w0 + q2 * w2 - q3 * w1)
        out[b + 5] = 0.5 * (q0 * w1 + q3 * w0 - q1 * w2)
        out[b + 6] = 0.5 * (q0 * w2 + q1 * w1 - q2 * w0)
        out[b + 7] = F[k, 0] / mass[k]
        out[b + 8] = F[k, 1] / mass[k]
        out[b + 9] = F[k, 2] / mass[k]
        tb0 = R[k, 0, 0] * T[k, 0] + R[k, 1, 0] * T[k, 1] + R[k, 2, 0] * T[k, 2]
        tb1 = R[k, 0, 1] * T[k, 0] + R[k, 1, 1] * T[k, 1] + R[k, 2, 1] * T[k, 2]
        tb2 = R[k, 0, 2] * T[k, 0] + R[k, 1, 2] * T[k, 1] + R[k, 2, 2] * T[k, 2]
        if diagonal[k]:
            J0, J1, J2 = inertia[k, 0, 0], inertia[k, 1, 1], inertia[k, 2, 2]
            out[b + 10] = (tb0 - (w1 * J2 * w2 - w2 * J1 * w1)) / J0
            out[b + 11] = (tb1 - (w2 * J0 * w0 - w0 * J2 * w2)) / J1
            out[b + 12] = (tb2 - (w0 * J1 * w1 - w1 * J0 * w0)) / J2
        else:  # J ω̇ = τ − ω × J ω with the full tensor
            h0 = inertia[k, 0, 0] * w0 + inertia[k, 0, 1] * w1 + inertia[k, 0, 2] * w2
            h1 = inertia[k, 1, 0] * w0 + inertia[k, 1, 1] * w1 + inertia[k, 1, 2] * w2
            h2 = inertia[k, 2, 0] * w0 + inertia[k, 2, 1] * w1 + inertia[k, 2, 2] * w2
            r0 = tb0 - (w1 * h2 - w2 * h1)
            r1 = tb1 - (w2 * h0 - w0 * h2)
            r2 = tb2 - (w0 * h1 - w1 * h0)
            for i in range(3):
                out[b + 10 + i] = inverse[k, i, 0] * r0 + inverse[k, i, 1] * r1 + inverse[k, i, 2] * r2


@njit(cache=True)
def fill_jacobian(data, indptr, indices, f0, fpert, group_cols, group_eps):
    """Scatter one coloured difference quotient into the CSC data: column c of the group owns the rows
    of its pattern."""
    for g in range(group_cols.shape[0]):
        c = group_cols[g]
        e = group_eps[g]
        for p in range(indptr[c], indptr[c + 1]):
            data[p] = (fpert[indices[p]] - f0[indices[p]]) / e


@njit(cache=True)
def unpack_into(Y, angles, omega):
    """The xyz angles and the global angular velocities of state rows Y (T, N, 13) into angles, omega (T, N, 3)."""
    R = np.empty((3, 3))
    for t in range(Y.shape[0]):
        for k in range(Y.shape[1]):
            rotation_minus_identity(Y[t, k, 3], Y[t, k, 4], Y[t, k, 5], Y[t, k, 6], R)
            for i in range(3):
                R[i, i] += 1.0
            angles[t, k, 1] = math.atan2(R[0, 2], math.sqrt(R[1, 2] ** 2 + R[2, 2] ** 2))
            angles[t, k, 0] = math.atan2(-R[1, 2], R[2, 2])
            angles[t, k, 2] = math.atan2(-R[0, 1], R[0, 0])
            for i in range(3):
                omega[t, k, i] = R[i, 0] * Y[t, k, 10] + R[i, 1] * Y[t, k, 11] + R[i, 2] * Y[t, k, 12]
