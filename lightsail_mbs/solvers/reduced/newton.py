"""O(n) Newton matrix of implicit integrators for the reduced chain: compliant joints, block LDLᵀ.

Why the minimal-coordinate Jacobian is not used
-----------------------------------------------
An implicit Runge–Kutta method applied to ẏ = f(y), y = (q, v), solves at every Newton iteration
linear systems (σ I − J) (Δq, Δv) = (r₁, r₂) with σ = μ/h (Radau IIA: one real μ and one complex
pair). In minimal coordinates J = [[0, I], [∂q̈/∂q, ∂q̈/∂q̇]] is dense, because q̈ = M(q)⁻¹(Q − c) and
M(q)⁻¹ couples every coordinate: a dense forward-difference Jacobian costs 2·dof right-hand sides
and its LU O(n³).

The stiffness that forces an implicit method is the springs', and in minimal coordinates the spring
and damper generalized forces are exactly linear:

    Q_springs = −K q − C q̇,    K = k_T L_θ ⊕ k_s I_z,    C = c_T L_θ ⊕ c_s I_z,

where L_θ is the graph Laplacian of the chain on the absolute angles θ (the bending springs act on
θ_{i+1} − θ_i, Eq. 23) and I_z the identity on the axial extensions z (Eq. 29). We therefore use the
approximate Jacobian (a simplified Newton / W-method Jacobian)

    J̃ = [[0, I], [−M⁻¹K, −M⁻¹C]],    M = M(q*) at the state q* where J̃ was last refreshed,

which drops ∂M⁻¹/∂q·(Q − c), the velocity terms and the load derivatives: all of the order of the
slow dynamics (the loads act at the slice centres along the normals; around the flat sail they
add no transverse stiffness to first order), while J̃ carries every stiff eigenvalue (bending up to
ω_max = 2√(k_T/J) ∝ n², axial up to 2√(k_s/m)).

Reduction to one mass-plus-compliance solve
-------------------------------------------
Eliminating Δq = (r₁ + Δv)/σ from the first block row and multiplying the second by M/σ:

    (M + D) Δv = M r₂/σ − K r₁/σ²,    D = C/σ + K/σ².

Write Δv = r₂/σ − y; then

    (M + D) y = g,    g = D r₂/σ + K r₁/σ²,    Δv = r₂/σ − y,    Δq = (r₁ + Δv)/σ.       (1)

No product with M is needed; D, K and C are tridiagonal (θ) and diagonal (z), so g costs O(n).

Solving (M + D) y = g in O(n): joints as compliant constraints
---------------------------------------------------------------
(M + D) y = g is the forward dynamics "M y = g − D y" of the chain with accelerations y, generalized
forces g and extra joint springs acting on the accelerations themselves: a moment
−κ_T(α_{i+1} − α_i) at every hinge and an axial force −κ_s z̈_i in every slider, with

    κ_T = c_T/σ + k_T/σ²,    κ_s = c_s/σ + k_s/σ².

Realise g as slice loads: (g_x, g_y) a force on slice 1, g_θi a torque on slice i, g_zi an axial joint
force (the virtual work of an axial joint force Λ_i·e_i on δz_i is Λ_i·e_i δz_i). Give each joint a
wrench λ_i = (Λ_i, ν_i): force Λ_i and moment ν_i exerted by slice i on slice i+1 (and −λ_i on slice i).
Slice accelerations u_j = (a_j, α_j) then follow from Newton–Euler

    u = M_abs⁻¹ (W + Gᵀ λ),    M_abs = diag(m, m, J) per slice,

where W are the slice loads above and G maps slice accelerations to the joints' relative accelerations
d_i = G_i u = (a_{i+1} − a_i − a_i α_i p_i − b α_{i+1} p_{i+1},  α_{i+1} − α_i) (λ_i·d_i is the power of the
joint wrench). The constitutive relations of the compliant joint are

    transverse (p_i): d_i·p_i = 0  (rigid hinge);   axial (e_i): d_i·e_i = z̈_i = (g_zi − e_i·Λ_i)/κ_s;
    rotation: α_{i+1} − α_i = −ν_i/κ_T,

i.e. d_i = d⁰_i − C_i λ_i with the compliance C_i = e_i e_iᵀ/κ_s ⊕ 1/κ_T and d⁰_i = (g_zi/κ_s) e_i ⊕ 0.
Substituting u:

    S λ = d⁰ − G M_abs⁻¹ W,     S = G M_abs⁻¹ Gᵀ + C,                                       (2)

S block tridiagonal with 3×3 blocks (with the slice's own (a, α) of u):

    S_ii = [[ (2/m) I + (a_i² p_i p_iᵀ + b² p_{i+1} p_{i+1}ᵀ)/J + e_i e_iᵀ/κ_s,  (a_i p_i − b p_{i+1})/J ],
            [ (a_i p_i − b p_{i+1})ᵀ/J,                                  2/J + 1/κ_T ]],
    S_i,i+1 = [[ −(1/m) I + (b a_{i+1}/J) p_{i+1} p_{i+1}ᵀ,  (b/J) p_{i+1} ],
               [ −(a_{i+1}/J) p_{i+1}ᵀ,                     −1/J ]],     S_{i+1,i} = S_i,i+1ᵀ.

For real σ > 0 and positive k, c the compliances are ≥ 0 and S is symmetric positive definite: block
LDLᵀ without pivoting (block Thomas), O(n). For Radau's complex σ the same factorisation runs in
complex arithmetic (complex symmetric, not Hermitian). The inextensible chain has no axial compliance
(κ_s = ∞, C_i's e-part is 0); a chain without bending springs (κ_T = 0: infinite compliance) has no
hinge moment, ν_i ≡ 0, which the code imposes by replacing that row and column by the identity.
Then y = (a₁, α₁…αₙ, (g_zi − e_i·Λ_i)/κ_s).

Geometric stiffness of the joint forces
---------------------------------------
A chain under tension (the TnT sail: T along the chain) is stiffened transversely by its joint forces:
with Λ held fixed, the torque τ_j = −b p_j·Λ_{j−1} − a_j p_j·Λ_j on slice j changes with its own angle as
∂τ_j/∂θ_j = b e_j·Λ_{j−1} + a_j e_j·Λ_j (∂p/∂θ = −e), a diagonal stiffness on θ_j

    k_g,j = −(b e_j·Λ_{j−1} + a_j e_j·Λ_j)    (= l T for a straight chain in tension T),

which sets the chain's string modes (up to ≈ 2√(lT/J), 190 rad/s for the paper's stable TnT sail at
n = 30). J̃ includes it as K → K + diag(k_g) on θ, evaluated with the joint forces of the state where J̃
is refreshed (one right-hand-side call); it enters (2) as a per-slice effective inertia
J_j' = J + k_g,j/σ² (M_abs⁻¹ = diag(1/m, 1/m, 1/J_j')). Compressive joint forces (k_g < 0) are left out
(k_g clipped at 0): they are weak in the paper's cases and would make S indefinite for large h.

Costs per joint: factorisation ≈ 150 flops (one 3×3 inversion, two 3×3 products), solve ≈ 60 flops,
against ≈ 60 ns per slice for one right-hand-side call.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.solvers.reduced.chain_constants import C_S, C_T, EXTENSIBLE, HALF, INERTIA, K_S, K_T, MASS, WORLD, N
from lightsail_mbs.solvers.reduced.dynamics import joint_forces


@njit(cache=True)
def geometry_into(t, y, k, work, cth, sth, arm, k_geo, geometric):
    """cos θ_i, sin θ_i, the joint arms a_i = b + z_i and (geometric=True) the geometric stiffness
    k_g,j ≥ 0 of the state y = (q, q̇) at the time t: everything J̃ needs from the configuration."""
    n = int(k[N])
    b = k[HALF]
    extensible = k[EXTENSIBLE] != 0.0
    for i in range(n):
        cth[i] = math.cos(y[2 + i])
        sth[i] = math.sin(y[2 + i])
    for i in range(n - 1):
        arm[i] = b + y[n + 2 + i] if extensible else b
    for j in range(n):
        k_geo[j] = 0.0
    if geometric:
        lx = np.empty(n - 1)
        ly = np.empty(n - 1)
        joint_forces(t, y, k, work, lx, ly)
        for j in range(n):
            v = 0.0
            if j > 0:
                v -= b * (cth[j] * lx[j - 1] + sth[j] * ly[j - 1])
            if j < n - 1:
                v -= arm[j] * (cth[j] * lx[j] + sth[j] * ly[j])
            k_geo[j] = max(v, 0.0)


@njit(cache=True)
def compliances(sigma, k, k_geo, inv_inertia):
    """(1/κ_T, 1/κ_s, hinge moment on?) for σ, 1/κ = σ²/(cσ + k) (κ_s = ∞ when inextensible), and the
    per-slice 1/J_j' = 1/(J + k_g,j/σ²) into inv_inertia."""
    has_moment = k[K_T] != 0.0 or k[C_T] != 0.0
    inv_kt = sigma * sigma / (k[C_T] * sigma + k[K_T]) if has_moment else 0.0 * sigma
    inv_ks = sigma * sigma / (k[C_S] * sigma + k[K_S]) if k[EXTENSIBLE] != 0.0 else 0.0 * sigma
    s2 = sigma * sigma
    for j in range(k_geo.size):
        inv_inertia[j] = 1.0 / (k[INERTIA] + k_geo[j] / s2)
    return inv_kt, inv_ks, has_moment


@njit(cache=True)
def _inverse3(a, out):
    """out = a⁻¹ for a 3×3 (real or complex) matrix by the adjugate."""
    c00 = a[1, 1] * a[2, 2] - a[1, 2] * a[2, 1]
    c01 = a[1, 2] * a[2, 0] - a[1, 0] * a[2, 2]
    c02 = a[1, 0] * a[2, 1] - a[1, 1] * a[2, 0]
    inv_det = 1.0 / (a[0, 0] * c00 + a[0, 1] * c01 + a[0, 2] * c02)
    out[0, 0] = c00 * inv_det
    out[1, 0] = c01 * inv_det
    out[2, 0] = c02 * inv_det
    out[0, 1] = (a[0, 2] * a[2, 1] - a[0, 1] * a[2, 2]) * inv_det
    out[1, 1] = (a[0, 0] * a[2, 2] - a[0, 2] * a[2, 0]) * inv_det
    out[2, 1] = (a[0, 1] * a[2, 0] - a[0, 0] * a[2, 1]) * inv_det
    out[0, 2] = (a[0, 1] * a[1, 2] - a[0, 2] * a[1, 1]) * inv_det
    out[1, 2] = (a[0, 2] * a[1, 0] - a[0, 0] * a[1, 2]) * inv_det
    out[2, 2] = (a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]) * inv_det


@njit(cache=True)
def factor(k, cth, sth, arm, inv_inertia, inv_kt, inv_ks, has_moment, pivots_inv, lower, couplings):
    """Block LDLᵀ of S (Eq. 2 of the module docstring) with per-slice inverse inertias 1/J_j'.

    pivots_inv[i] = D_i⁻¹ (Schur-complement pivots), lower[i] = S_{i−1,i}ᵀ D_{i−1}⁻¹ (i ≥ 1),
    couplings[i] = S_i,i+1; arrays (joints, 3, 3) of the dtype of inv_inertia.
    """
    n = int(k[N])
    m, b = k[MASS], k[HALF]
    joints = n - 1
    d = np.empty((3, 3), dtype=pivots_inv.dtype)
    for i in range(joints):
        pxi, pyi, pxj, pyj = -sth[i], cth[i], -sth[i + 1], cth[i + 1]
        a = arm[i]
        ji, jj = inv_inertia[i], inv_inertia[i + 1]
        wa, wb = a * a * ji, b * b * jj
        d[0, 0] = 2.0 / m + wa * pxi * pxi + wb * pxj * pxj + inv_ks * cth[i] * cth[i]
        d[0, 1] = wa * pxi * pyi + wb * pxj * pyj + inv_ks * cth[i] * sth[i]
        d[1, 1] = 2.0 / m + wa * pyi * pyi + wb * pyj * pyj + inv_ks * sth[i] * sth[i]
        d[1, 0] = d[0, 1]
        if has_moment:
            d[0, 2] = a * pxi * ji - b * pxj * jj
            d[1, 2] = a * pyi * ji - b * pyj * jj
            d[2, 2] = ji + jj + inv_kt
        else:
            d[0, 2] = 0.0
            d[1, 2] = 0.0
            d[2, 2] = 1.0
        d[2, 0] = d[0, 2]
        d[2, 1] = d[1, 2]
        if i < joints - 1:
            u = couplings[i]
            px, py, a1 = -sth[i + 1], cth[i + 1], arm[i + 1]
            w = b * a1 * jj
            u[0, 0] = -1.0 / m + w * px * px
            u[0, 1] = w * px * py
            u[1, 0] = w * px * py
            u[1, 1] = -1.0 / m + w * py * py
            if has_moment:
                u[0, 2] = b * px * jj
                u[1, 2] = b * py * jj
                u[2, 0] = -a1 * px * jj
                u[2, 1] = -a1 * py * jj
                u[2, 2] = -jj
            else:
                u[0, 2] = 0.0
                u[1, 2] = 0.0
                u[2, 0] = 0.0
                u[2, 1] = 0.0
                u[2, 2] = 0.0
        if i > 0:
            # lower_i = U_{i−1}ᵀ D_{i−1}⁻¹;  D_i −= lower_i U_{i−1}
            u = couplings[i - 1]
            p = pivots_inv[i - 1]
            low = lower[i]
            for r in range(3):
                for c in range(3):
                    low[r, c] = u[0, r] * p[0, c] + u[1, r] * p[1, c] + u[2, r] * p[2, c]
            for r in range(3):
                for c in range(3):
                    d[r, c] -= low[r, 0] * u[0, c] + low[r, 1] * u[1, c] + low[r, 2] * u[2, c]
        _inverse3(d, pivots_inv[i])


@njit(cache=True)
def solve_mass_compliance(g, k, cth, sth, arm, inv_inertia, inv_ks, has_moment, pivots_inv, lower, couplings, lam, y):
    """y = (M + D)⁻¹ g in O(n) with the factors of `factor` (module docstring, Eq. 2).
    lam: (joints, 3) scratch of the dtype of g."""
    n = int(k[N])
    m, b = k[MASS], k[HALF]
    extensible = k[EXTENSIBLE] != 0.0
    joints = n - 1
    for i in range(joints):  # r_i = d⁰_i − G_i M⁻¹ W, reduced forward (lam holds r')
        pxi, pyi, pxj, pyj = -sth[i], cth[i], -sth[i + 1], cth[i + 1]
        al_i = g[2 + i] * inv_inertia[i]
        al_j = g[3 + i] * inv_inertia[i + 1]
        rx = arm[i] * al_i * pxi + b * al_j * pxj
        ry = arm[i] * al_i * pyi + b * al_j * pyj
        if i == 0:
            rx += g[0] / m
            ry += g[1] / m
        if extensible:
            dz = g[n + 2 + i] * inv_ks
            rx += dz * cth[i]
            ry += dz * sth[i]
        rr = -(al_j - al_i) if has_moment else 0.0 * al_i
        if i > 0:
            low = lower[i]
            px, py, pr = lam[i - 1, 0], lam[i - 1, 1], lam[i - 1, 2]
            rx -= low[0, 0] * px + low[0, 1] * py + low[0, 2] * pr
            ry -= low[1, 0] * px + low[1, 1] * py + low[1, 2] * pr
            rr -= low[2, 0] * px + low[2, 1] * py + low[2, 2] * pr
        lam[i, 0] = rx
        lam[i, 1] = ry
        lam[i, 2] = rr
    for i in range(joints - 1, -1, -1):  # λ_i = D_i⁻¹ (r'_i − U_i λ_{i+1})
        rx, ry, rr = lam[i, 0], lam[i, 1], lam[i, 2]
        if i < joints - 1:
            u = couplings[i]
            nx, ny, nr = lam[i + 1, 0], lam[i + 1, 1], lam[i + 1, 2]
            rx -= u[0, 0] * nx + u[0, 1] * ny + u[0, 2] * nr
            ry -= u[1, 0] * nx + u[1, 1] * ny + u[1, 2] * nr
            rr -= u[2, 0] * nx + u[2, 1] * ny + u[2, 2] * nr
        p = pivots_inv[i]
        lam[i, 0] = p[0, 0] * rx + p[0, 1] * ry + p[0, 2] * rr
        lam[i, 1] = p[1, 0] * rx + p[1, 1] * ry + p[1, 2] * rr
        lam[i, 2] = p[2, 0] * rx + p[2, 1] * ry + p[2, 2] * rr
    for j in range(n):  # slice j gets +λ_{j−1}, −λ_j
        px, py = -sth[j], cth[j]
        torque = g[2 + j]
        if j > 0:
            torque += -b * (px * lam[j - 1, 0] + py * lam[j - 1, 1]) + lam[j - 1, 2]
        if j < joints:
            torque += -arm[j] * (px * lam[j, 0] + py * lam[j, 1]) - lam[j, 2]
        y[2 + j] = torque * inv_inertia[j]
    y[0] = (g[0] - lam[0, 0]) / m
    y[1] = (g[1] - lam[0, 1]) / m
    if extensible:
        for i in range(joints):
            y[n + 2 + i] = (g[n + 2 + i] - (cth[i] * lam[i, 0] + sth[i] * lam[i, 1])) * inv_ks


@njit(cache=True)
def spring_products(x, k, k_geo, with_damping, out):
    """out = (K + diag k_g) x (with_damping False) or C x (True), x a dof-vector (tridiagonal θ, diagonal z)."""
    n = int(k[N])
    kt = k[C_T] if with_damping else k[K_T]
    ks = k[C_S] if with_damping else k[K_S]
    out[0] = 0.0 * x[0]
    out[1] = 0.0 * x[0]
    for i in range(n):
        v = 0.0 * x[0]
        if i > 0:
            v += x[2 + i] - x[1 + i]
        if i < n - 1:
            v += x[2 + i] - x[3 + i]
        out[2 + i] = kt * v
        if not with_damping:
            out[2 + i] += k_geo[i] * x[2 + i]
    if k[EXTENSIBLE] != 0.0:
        for i in range(n - 1):
            out[n + 2 + i] = ks * x[n + 2 + i]


@njit(cache=True)
def newton_solve(
    r, sigma, k, cth, sth, arm, k_geo, inv_inertia, inv_ks, has_moment, pivots_inv, lower, couplings, lam, scratch
):
    """Solve (σ I − J̃) x = r in place (r = (r₁, r₂), size 2·dof), Eq. (1) of the module docstring.
    scratch: (3, dof) of r's dtype."""
    dof = r.size // 2
    r1 = r[:dof]
    r2 = r[dof:]
    kr = scratch[0]
    cr = scratch[1]
    y = scratch[2]
    spring_products(r2, k, k_geo, False, kr)  # K r₂
    spring_products(r2, k, k_geo, True, cr)  # C r₂
    s2 = sigma * sigma
    for i in range(dof):
        cr[i] = (cr[i] + kr[i] / sigma) / s2  # D r₂ / σ
    spring_products(r1, k, k_geo, False, kr)  # K r₁
    for i in range(dof):
        cr[i] += kr[i] / s2  # g
    solve_mass_compliance(cr, k, cth, sth, arm, inv_inertia, inv_ks, has_moment, pivots_inv, lower, couplings, lam, y)
    if k[WORLD] != 0.0:  # the world line's coordinates (model/world_line.py): J̃ = 0 there, Δv = r₂/σ
        for i in range(dof - 2, dof):
            y[i] = 0.0
    for i in range(dof):
        dv = r2[i] / sigma - y[i]
        r[dof + i] = dv
        r[i] = (r1[i] + dv) / sigma
