"""O(n) accelerations of the chain in minimal coordinates, compiled (numba) loops over slices.

The Euler–Lagrange equations M(q) q̈ + c(q, q̇) = Q(q, q̇) (Eq. 16; terms in reduced_kinematics.py)
are solved without forming M. Each slice obeys Newton–Euler with the joint force Λ_i that slice i
exerts on slice i+1 at joint i (the point r_i + a_i e_i = r_{i+1} − b e_{i+1}):

    m r̈_i = F_i + Λ_{i−1} − Λ_i,      J_G θ̈_i = τ_i − b p_i·Λ_{i−1} − a_i p_i·Λ_i      (Λ₀ = Λₙ = 0)

and the joints' acceleration constraints, from differentiating r_{i+1} = r_i + a_i e_i + b e_{i+1} twice,

    g_i ≡ r̈_{i+1} − r̈_i − a_i θ̈_i p_i − b θ̈_{i+1} p_{i+1} − w_i = z̈_i e_i,
    w_i = 2 ż_i θ̇_i p_i − a_i θ̇_i² e_i − b θ̇_{i+1}² e_{i+1}.

Substituting the first into the second gives g(Λ) = g(0) + K Λ with K symmetric positive definite
and block-tridiagonal (2×2 symmetric blocks, n−1 joints):

    K_ii = (2/m) I + (a_i²/J_G) p_i p_iᵀ + (b²/J_G) p_{i+1} p_{i+1}ᵀ,
    K_i,i+1 = −(1/m) I + (b a_{i+1}/J_G) p_{i+1} p_{i+1}ᵀ.

Inextensible chains (z ≡ 0): g = 0, so K Λ = −g(0), solved by block LDLᵀ (block Thomas) elimination
in O(n). Extensible TnT chain (Eqs 29–31, l_s = 0): the massless spring fixes the axial part,
Λ_i = s_i e_i + μ_i p_i with s_i = −k_s z_i − c_s ż_i; projecting g on p_i removes z̈_i and leaves the
scalar tridiagonal SPD system pᵀK p μ = −pᵀ g(s e); the projection on e_i then gives z̈_i = e_i·g_i.
The result is exactly M⁻¹(Q − c) (tested against the dense form in reduced_kinematics.py).

Loads: the net slice force of the shared load model, radiation f_i = (I(x_i) l W / c) cos θ_i
[2R cos θ_i n_i + α ŷ] (Eq. 11 for R = 1, α = 0) plus the frame force −m g₀ ŷ with their cancellation
done analytically (loads.applied_forces; its compiled twin loads.net_slice_force is called here), and
the follower end tensions −T e₁, T eₙ (Eq. 32). Torsion springs/dampers act on θ_{i+1} − θ_i (Eq. 23).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from lightsail_mbs.model.loads import gaussian_intensity, net_slice_force
from lightsail_mbs.model.parameters import SPEED_OF_LIGHT
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
) = range(18)
N_CONSTANTS = 18


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
    k[MEAN_INTENSITY] = p.mean_intensity  # the frame force is −(2R + α) Ī l W/c (loads.frame_force)
    k[EXTENSIBLE], k[UNIFORM] = float(model.extensible), float(p.uniform_beam)
    return k


@njit(cache=True)
def _slice_accelerations(lx, ly, fx, fy, tau, a, c, s, k, ax, ay, al):
    """(r̈_x, r̈_y, θ̈) of every slice for joint forces Λ (Newton–Euler above), written into ax, ay, al."""
    n = fx.size
    m, J, b = k[MASS], k[INERTIA], k[HALF]
    for i in range(n):
        px, py = -s[i], c[i]
        fxi, fyi, mom = fx[i], fy[i], tau[i]
        if i > 0:
            fxi += lx[i - 1]
            fyi += ly[i - 1]
            mom -= b * (px * lx[i - 1] + py * ly[i - 1])
        if i < n - 1:
            fxi -= lx[i]
            fyi -= ly[i]
            mom -= a[i] * (px * lx[i] + py * ly[i])
        ax[i] = fxi / m
        ay[i] = fyi / m
        al[i] = mom / J


@njit(cache=True)
def _constraint_residual(ax, ay, al, wx, wy, a, c, s, b, gx, gy):
    """g_i = r̈_{i+1} − r̈_i − a_i θ̈_i p_i − b θ̈_{i+1} p_{i+1} − w_i, written into gx, gy."""
    for i in range(a.size):
        gx[i] = ax[i + 1] - ax[i] + a[i] * al[i] * s[i] + b * al[i + 1] * s[i + 1] - wx[i]
        gy[i] = ay[i + 1] - ay[i] - a[i] * al[i] * c[i] - b * al[i + 1] * c[i + 1] - wy[i]


@njit(cache=True)
def _solve_joint_forces(rx, ry, a, c, s, k, lx, ly):
    """Solve K Λ = r (2×2 block-tridiagonal SPD, symmetric blocks) by block LDLᵀ elimination."""
    joints = rx.size
    m, J, b = k[MASS], k[INERTIA], k[HALF]
    inv_xx = np.empty(joints)  # (pivot block)⁻¹, symmetric
    inv_xy = np.empty(joints)
    inv_yy = np.empty(joints)
    u_xx = np.empty(joints)  # coupling block K_i,i+1 (symmetric)
    u_xy = np.empty(joints)
    u_yy = np.empty(joints)
    for i in range(joints):
        pxi, pyi, pxj, pyj = -s[i], c[i], -s[i + 1], c[i + 1]
        wa, wb = a[i] * a[i] / J, b * b / J
        d_xx = 2 / m + wa * pxi * pxi + wb * pxj * pxj
        d_xy = wa * pxi * pyi + wb * pxj * pyj
        d_yy = 2 / m + wa * pyi * pyi + wb * pyj * pyj
        r_x, r_y = rx[i], ry[i]
        if i > 0:  # eliminate joint i−1: D −= U W, r −= W r', W = U D'⁻¹ (U symmetric)
            ux, uxy, uy = u_xx[i - 1], u_xy[i - 1], u_yy[i - 1]
            w11 = ux * inv_xx[i - 1] + uxy * inv_xy[i - 1]
            w12 = ux * inv_xy[i - 1] + uxy * inv_yy[i - 1]
            w21 = uxy * inv_xx[i - 1] + uy * inv_xy[i - 1]
            w22 = uxy * inv_xy[i - 1] + uy * inv_yy[i - 1]
            d_xx -= w11 * ux + w12 * uxy
            d_xy -= w11 * uxy + w12 * uy
            d_yy -= w21 * uxy + w22 * uy
            r_x -= w11 * lx[i - 1] + w12 * ly[i - 1]
            r_y -= w21 * lx[i - 1] + w22 * ly[i - 1]
        det = d_xx * d_yy - d_xy * d_xy
        inv_xx[i], inv_xy[i], inv_yy[i] = d_yy / det, -d_xy / det, d_xx / det
        lx[i], ly[i] = r_x, r_y  # r' (the eliminated right-hand side), overwritten below
        if i < joints - 1:
            coupling = b * a[i + 1] / J
            u_xx[i] = -1 / m + coupling * pxj * pxj
            u_xy[i] = coupling * pxj * pyj
            u_yy[i] = -1 / m + coupling * pyj * pyj
    for i in range(joints - 1, -1, -1):
        r_x, r_y = lx[i], ly[i]
        if i < joints - 1:
            r_x -= u_xx[i] * lx[i + 1] + u_xy[i] * ly[i + 1]
            r_y -= u_xy[i] * lx[i + 1] + u_yy[i] * ly[i + 1]
        lx[i] = inv_xx[i] * r_x + inv_xy[i] * r_y
        ly[i] = inv_xy[i] * r_x + inv_yy[i] * r_y


@njit(cache=True)
def _solve_normal_forces(r, a, c, s, k, mu):
    """Solve pᵀK p μ = r (scalar tridiagonal SPD) by Thomas (LDLᵀ) elimination."""
    joints = r.size
    m, J, b = k[MASS], k[INERTIA], k[HALF]
    pivot = np.empty(joints)
    off = np.empty(joints)
    for i in range(joints):
        cos_rel = c[i] * c[i + 1] + s[i] * s[i + 1]  # p_i · p_{i+1}
        d = 2 / m + (a[i] * a[i] + b * b * cos_rel * cos_rel) / J
        ri = r[i]
        if i > 0:
            w = off[i - 1] / pivot[i - 1]
            d -= w * off[i - 1]
            ri -= w * mu[i - 1]
        pivot[i] = d
        mu[i] = ri
        if i < joints - 1:
            off[i] = cos_rel * (b * a[i + 1] / J - 1 / m)  # p_iᵀ K_i,i+1 p_{i+1}
    for i in range(joints - 1, -1, -1):
        ri = mu[i]
        if i < joints - 1:
            ri -= off[i] * mu[i + 1]
        mu[i] = ri / pivot[i]


@njit(cache=True)
def accelerations_into(q, qd, k, qdd):
    """q̈(q, q̇) of one state into qdd (the equations of the module docstring)."""
    n = int(k[N])
    b = k[HALF]
    extensible = k[EXTENSIBLE] != 0.0
    joints = n - 1
    th = q[2 : n + 2]
    om = qd[2 : n + 2]
    c = np.cos(th)
    s = np.sin(th)
    a = np.full(joints, b)
    zd = np.zeros(joints)
    if extensible:
        a += q[n + 2 :]
        zd[:] = qd[n + 2 :]
    # net loads (radiation + frame force) at the centres (x only matters for a non-uniform beam)
    fx = np.empty(n)
    fy = np.empty(n)
    x = q[0]
    for i in range(n):
        if i > 0:
            x += a[i - 1] * c[i - 1] + b * c[i]
        inten = k[INTENSITY]
        if k[UNIFORM] == 0.0:
            inten = gaussian_intensity(x, k[INTENSITY], k[CENTER], k[WAIST])
        fx[i], fy[i] = net_slice_force(th[i], c[i], s[i], inten, k[MEAN_INTENSITY], k[AREA_C], k[REFL], k[ABSORB])
    tension = k[TENSION]
    if tension != 0.0:
        fx[0] -= tension * c[0]
        fy[0] -= tension * s[0]
        fx[n - 1] += tension * c[n - 1]
        fy[n - 1] += tension * s[n - 1]
    tau = np.zeros(n)
    if k[K_T] != 0.0 or k[C_T] != 0.0:
        for i in range(joints):
            moment = k[K_T] * (th[i + 1] - th[i]) + k[C_T] * (om[i + 1] - om[i])
            tau[i] += moment
            tau[i + 1] -= moment
    wx = np.empty(joints)
    wy = np.empty(joints)
    for i in range(joints):
        o2i, o2j = om[i] * om[i], om[i + 1] * om[i + 1]
        wx[i] = -2 * zd[i] * om[i] * s[i] - a[i] * o2i * c[i] - b * o2j * c[i + 1]
        wy[i] = 2 * zd[i] * om[i] * c[i] - a[i] * o2i * s[i] - b * o2j * s[i + 1]
    lx = np.zeros(joints)
    ly = np.zeros(joints)
    if extensible:
        for i in range(joints):
            spring = -k[K_S] * q[n + 2 + i] - k[C_S] * zd[i]
            lx[i] = spring * c[i]
            ly[i] = spring * s[i]
    ax = np.empty(n)
    ay = np.empty(n)
    al = np.empty(n)
    gx = np.empty(joints)
    gy = np.empty(joints)
    _slice_accelerations(lx, ly, fx, fy, tau, a, c, s, k, ax, ay, al)
    _constraint_residual(ax, ay, al, wx, wy, a, c, s, b, gx, gy)
    if extensible:
        rhs = np.empty(joints)
        for i in range(joints):
            rhs[i] = s[i] * gx[i] - c[i] * gy[i]  # −p_i · g_i
        mu = np.empty(joints)
        _solve_normal_forces(rhs, a, c, s, k, mu)
        for i in range(joints):
            lx[i] -= mu[i] * s[i]
            ly[i] += mu[i] * c[i]
    else:
        for i in range(joints):
            gx[i] = -gx[i]
            gy[i] = -gy[i]
        _solve_joint_forces(gx, gy, a, c, s, k, lx, ly)
    _slice_accelerations(lx, ly, fx, fy, tau, a, c, s, k, ax, ay, al)
    qdd[0] = ax[0]
    qdd[1] = ay[0]
    qdd[2 : n + 2] = al
    if extensible:
        _constraint_residual(ax, ay, al, wx, wy, a, c, s, b, gx, gy)
        for i in range(joints):
            qdd[n + 2 + i] = c[i] * gx[i] + s[i] * gy[i]  # z̈_i = e_i · g_i


@njit(cache=True)
def rhs_into(y, k, ydot):
    """First-order form ẏ = (q̇, q̈) of y = (q, q̇) (Eq. 40 with M moved to the right), into ydot."""
    dof = y.size // 2
    ydot[:dof] = y[dof:]
    accelerations_into(y[:dof], y[dof:], k, ydot[dof:])


@njit(cache=True)
def _batch_accelerations(q, qd, k):
    out = np.empty_like(q)
    for j in range(q.shape[1]):
        accelerations_into(np.ascontiguousarray(q[:, j]), np.ascontiguousarray(qd[:, j]), k, out[:, j])
    return out


@njit(cache=True)
def jacobian_into(y, k, scales, jac):
    """∂ẏ/∂y into jac by forward differences (step √ε·max(abs(y_j), scale_j)); the q̇ rows are exact (0 | I)."""
    size = y.size
    dof = size // 2
    jac[:dof] = 0.0
    for i in range(dof):
        jac[i, dof + i] = 1.0
    base = np.empty(size)
    rhs_into(y, k, base)
    moved = y.copy()
    out = np.empty(size)
    for j in range(size):
        moved[j] = y[j] + 1.4901161193847656e-08 * max(abs(y[j]), scales[j])
        step = moved[j] - y[j]
        rhs_into(moved, k, out)
        for i in range(dof, size):
            jac[i, j] = (out[i] - base[i]) / step
        moved[j] = y[j]


class ChainDynamics:
    """q̈(q, q̇) for one chain model; states are (dof,) vectors or columns of (dof, k) arrays."""

    def __init__(self, model: ChainModel):
        self.model = model
        self.constants = constants(model)

    def accelerations(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """q̈ for states q, q̇ of shape (dof,) or (dof, k)."""
        q = np.asarray(q, float)
        qd = np.asarray(qd, float)
        if q.ndim == 1:
            out = np.empty_like(q)
            accelerations_into(np.ascontiguousarray(q), np.ascontiguousarray(qd), self.constants, out)
            return out
        return _batch_accelerations(q, qd, self.constants)

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """ẏ = (q̇, q̈) of y = (q, q̇), one state (size,) or a batch (size, k) (scipy's fun(t, y),
        vectorized or not)."""
        y = np.asarray(y, dtype=float)
        if y.ndim == 2:
            dof = y.shape[0] // 2
            return np.concatenate([y[dof:], _batch_accelerations(y[:dof], y[dof:], self.constants)])
        out = np.empty(y.size)
        rhs_into(np.ascontiguousarray(y), self.constants, out)
        return out

    def jacobian(self, t: float, y: np.ndarray, scales: np.ndarray) -> np.ndarray:
        """∂ẏ/∂y (dense, 2 dof + 1 right-hand-side calls, compiled); scales: typical abs(y_j) (difference steps)."""
        y = np.ascontiguousarray(y, dtype=float)
        jac = np.empty((y.size, y.size))
        jacobian_into(y, self.constants, np.ascontiguousarray(scales, float), jac)
        return jac
