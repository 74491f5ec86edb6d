"""O(n) accelerations of the chain in minimal coordinates, vectorised over slices and states.

The Euler–Lagrange equations M(q) q̈ + c(q, q̇) = Q(q, q̇) (Eq. 16; terms in reduced_kinematics.py)
are solved without forming M. Each slice obeys Newton–Euler with the joint force Λ_i that slice i
exerts on slice i+1 at joint i (the point r_i + a_i e_i = r_{i+1} − b e_{i+1}):

    m r̈_i = F_i + Λ_{i−1} − Λ_i,      J_G θ̈_i = τ_i − b p_i·Λ_{i−1} − a_i p_i·Λ_i      (Λ₀ = Λₙ = 0)

and the joints' acceleration constraints, from differentiating r_{i+1} = r_i + a_i e_i + b e_{i+1} twice,

    r̈_{i+1} − r̈_i − a_i θ̈_i p_i − b θ̈_{i+1} p_{i+1} − w_i = z̈_i e_i,
    w_i = 2 ż_i θ̇_i p_i − a_i θ̇_i² e_i − b θ̇_{i+1}² e_{i+1}.

Substituting the first into the second gives K Λ = −g₀ with K symmetric positive definite and
block-tridiagonal (2×2 blocks, n−1 joints), solved by banded Cholesky in O(n):

    K_ii = (2/m) I + (a_i²/J_G) p_i p_iᵀ + (b²/J_G) p_{i+1} p_{i+1}ᵀ,  K_i,i+1 = −(1/m) I + (b a_{i+1}/J_G) p_{i+1} p_{i+1}ᵀ.

Inextensible chains (z ≡ 0): all of Λ is unknown. Extensible TnT chain (Eqs 29–31, l_s = 0): the
massless spring fixes the axial part, Λ_i = s_i e_i + μ_i p_i with s_i = −k_s z_i − c_s ż_i; projecting
the constraint on p_i removes z̈_i and leaves the scalar tridiagonal system pᵀK p μ = −pᵀ g(s e); the
projection on e_i then gives z̈_i. The result is exactly M⁻¹(Q − c) (tested against the dense form).

Every array has the slice index first and a batch of states last: one call solves many states at
once (one stacked banded system), which is what the implicit integrator's Jacobian uses.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import solveh_banded
from scipy.linalg.lapack import dpbsv

from .reduced_kinematics import ChainModel, axial_forces, body_forces, centres, torsion_torques


def _pad(v: np.ndarray):
    """(Λ_{i−1}, Λ_i) per slice i = 1…n from joint values Λ_1…Λ_{n−1} (zeros at the free ends)."""
    zero = np.zeros((1,) + v.shape[1:])
    return np.concatenate([zero, v]), np.concatenate([v, zero])


class ChainDynamics:
    """q̈(q, q̇) for one chain model; states are columns of (dof, k) arrays."""

    def __init__(self, model: ChainModel):
        self.model = model
        n = model.n
        self._bands = np.zeros((4, 2 * (n - 1)))    # K in LAPACK upper band storage (one state)
        self._joint_rhs = np.zeros((2 * (n - 1), 1))
        self._sum_x = np.zeros(n)
        self._sum_y = np.zeros(n)

    # ---- Newton–Euler pieces ---------------------------------------------------------------
    def _slice_accelerations(self, lam_x, lam_y, fx, fy, tau, a, c, s):
        """(r̈_x, r̈_y, θ̈) of every slice for joint forces Λ (n−1, k)."""
        m, J, b = self.model.mass, self.model.inertia, self.model.half_length
        prev_x, next_x = _pad(lam_x)
        prev_y, next_y = _pad(lam_y)
        arm = np.concatenate([a, np.zeros((1,) + a.shape[1:])])
        moment = tau - b * (-s * prev_x + c * prev_y) - arm * (-s * next_x + c * next_y)
        return (fx + prev_x - next_x) / m, (fy + prev_y - next_y) / m, moment / J

    def _constraint_residual(self, ax, ay, alpha, w_x, w_y, a, c, s):
        """g_i = r̈_{i+1} − r̈_i − a_i θ̈_i p_i − b θ̈_{i+1} p_{i+1} − w_i (= z̈_i e_i when consistent)."""
        b = self.model.half_length
        gx = np.diff(ax, axis=0) + a * alpha[:-1] * s[:-1] + b * alpha[1:] * s[1:] - w_x
        gy = np.diff(ay, axis=0) - a * alpha[:-1] * c[:-1] - b * alpha[1:] * c[1:] - w_y
        return gx, gy

    # ---- banded systems --------------------------------------------------------------------
    def _solve_joint_forces(self, rhs_x, rhs_y, a, c, s):
        """Solve K Λ = rhs (2×2 block-tridiagonal, SPD) for all states at once; returns (Λ_x, Λ_y)."""
        m, J, b = self.model.mass, self.model.inertia, self.model.half_length
        joints, k = rhs_x.shape
        px, py = -s, c
        pxi, pyi, pxj, pyj = px[:-1], py[:-1], px[1:], py[1:]
        d_xx = 2 / m + (a * a * pxi * pxi + b * b * pxj * pxj) / J
        d_yy = 2 / m + (a * a * pyi * pyi + b * b * pyj * pyj) / J
        d_xy = (a * a * pxi * pyi + b * b * pxj * pyj) / J
        # coupling of joint i to joint i+1 through slice i+1: −I/m + (b a_{i+1}/J) p_{i+1} p_{i+1}ᵀ
        coupling = np.zeros_like(a)
        coupling[:-1] = b * a[1:] / J
        u_xx = np.where(np.arange(joints)[:, None] < joints - 1, -1 / m, 0.0) + coupling * pxj * pxj
        u_yy = np.where(np.arange(joints)[:, None] < joints - 1, -1 / m, 0.0) + coupling * pyj * pyj
        u_xy = coupling * pxj * pyj

        def interleave(xpart, ypart):
            return np.stack([xpart.T, ypart.T], axis=-1).reshape(-1)

        size = 2 * joints * k
        ab = np.zeros((4, size))
        ab[3] = interleave(d_xx, d_yy)
        ab[2, 1::2] = d_xy.T.reshape(-1)
        ab[2, 2::2] = u_xy.T.reshape(-1)[:-1]
        ab[1, 2:] = interleave(u_xx, u_yy)[:-2]
        ab[0, 3::2] = u_xy.T.reshape(-1)[:-1]
        sol = solveh_banded(ab, interleave(rhs_x, rhs_y), check_finite=False).reshape(k, joints, 2)
        return sol[..., 0].T, sol[..., 1].T

    def _solve_normal_forces(self, rhs, a, c, s):
        """Solve pᵀK p μ = rhs (scalar tridiagonal, SPD) for the extensible chain."""
        m, J, b = self.model.mass, self.model.inertia, self.model.half_length
        joints, k = rhs.shape
        cos_rel = c[:-1] * c[1:] + s[:-1] * s[1:]          # p_i · p_{i+1}
        diag = 2 / m + (a * a + b * b * cos_rel * cos_rel) / J
        off = np.zeros_like(a)
        off[:-1] = cos_rel[:-1] * (b * a[1:] / J - 1 / m)     # p_iᵀ K_i,i+1 p_{i+1}
        ab = np.zeros((2, joints * k))
        ab[1] = diag.T.reshape(-1)
        ab[0, 1:] = off.T.reshape(-1)[:-1]
        return solveh_banded(ab, rhs.T.reshape(-1), check_finite=False).reshape(k, joints).T

    # ---- the right-hand side ---------------------------------------------------------------
    def accelerations(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """q̈ for states q, q̇ of shape (dof,) or (dof, k)."""
        single = q.ndim == 1
        if single:
            q, qd = q[:, None], qd[:, None]
        model = self.model
        b = model.half_length
        _, _, th, z = model.split(q)
        _, _, om, zd = model.split(qd)
        a = model.arms(z)
        c, s = np.cos(th), np.sin(th)
        x, _ = centres(model, q)
        fx, fy = body_forces(model, x, th)
        tau = torsion_torques(model, th, om)
        om2 = om * om
        w_x = -2 * zd * om[:-1] * s[:-1] - a * om2[:-1] * c[:-1] - b * om2[1:] * c[1:]
        w_y = 2 * zd * om[:-1] * c[:-1] - a * om2[:-1] * s[:-1] - b * om2[1:] * s[1:]
        zeros = np.zeros_like(a)
        if model.extensible:
            spring = axial_forces(model, z, zd)
            lam_x, lam_y = spring * c[:-1], spring * s[:-1]
            gx, gy = self._constraint_residual(*self._slice_accelerations(lam_x, lam_y, fx, fy, tau, a, c, s),
                                               w_x, w_y, a, c, s)
            mu = self._solve_normal_forces(s[:-1] * gx - c[:-1] * gy, a, c, s)
            lam_x, lam_y = lam_x - mu * s[:-1], lam_y + mu * c[:-1]
        else:
            gx, gy = self._constraint_residual(*self._slice_accelerations(zeros, zeros, fx, fy, tau, a, c, s),
                                               w_x, w_y, a, c, s)
            lam_x, lam_y = self._solve_joint_forces(-gx, -gy, a, c, s)
        ax, ay, alpha = self._slice_accelerations(lam_x, lam_y, fx, fy, tau, a, c, s)
        parts = [ax[:1], ay[:1], alpha]
        if model.extensible:
            gx, gy = self._constraint_residual(ax, ay, alpha, w_x, w_y, a, c, s)
            parts.append(c[:-1] * gx + s[:-1] * gy)        # z̈_i = e_i · g_i
        qdd = np.concatenate(parts)
        return qdd[:, 0] if single else qdd

    def inextensible_accelerations(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """q̈ of ONE state of an inextensible chain: the same equations as accelerations() with
        a_i = b, written with the fewest array operations (this is the explicit integrator's hot path).

        With β = b/J_G, t_i = τ_i/J_G, u_i = b(t_i sin θ_i + θ̇_i² cos θ_i), v_i = b(θ̇_i² sin θ_i − t_i cos θ_i):
        g₀ = (ΔF/m + u_i + u_{i+1}, ΔF_y/m + v_i + v_{i+1}), and θ̈_i = t_i − β p_i·(Λ_{i−1} + Λ_i).
        """
        model = self.model
        n, m, b, J = model.n, model.mass, model.half_length, model.inertia
        th, om = q[2:], qd[2:]
        c, s = np.cos(th), np.sin(th)
        x = np.empty(n)
        x[0] = 0.0
        np.cumsum(b * (c[:-1] + c[1:]), out=x[1:])
        fx, fy = body_forces(model, x + q[0], th)
        t = torsion_torques(model, th, om) / J
        om2 = om * om
        u = b * (t * s + om2 * c)
        v = b * (om2 * s - t * c)
        rhs = self._joint_rhs[:, 0]
        rhs[0::2] = (fx[:-1] - fx[1:]) / m - u[:-1] - u[1:]
        rhs[1::2] = (fy[:-1] - fy[1:]) / m - v[:-1] - v[1:]
        beta = 3.0 / m                                     # b²/J_G
        s2, c2, sc = beta * s * s, beta * c * c, beta * s * c
        ab = self._bands
        ab[3, 0::2] = 2 / m + s2[:-1] + s2[1:]
        ab[3, 1::2] = 2 / m + c2[:-1] + c2[1:]
        ab[2, 1::2] = -(sc[:-1] + sc[1:])
        ab[2, 2::2] = -sc[1:-1]
        ab[1, 2::2] = s2[1:-1] - 1 / m
        ab[1, 3::2] = c2[1:-1] - 1 / m
        ab[0, 3::2] = -sc[1:-1]
        _, lam, info = dpbsv(ab, self._joint_rhs)
        if info:
            raise np.linalg.LinAlgError(f"joint-force matrix not positive definite (LAPACK info {info})")
        lam_x, lam_y = lam[0::2, 0], lam[1::2, 0]
        sx, sy = self._sum_x, self._sum_y
        sx[:-1] = lam_x
        sx[-1] = 0.0
        sx[1:] += lam_x
        sy[:-1] = lam_y
        sy[-1] = 0.0
        sy[1:] += lam_y
        qdd = np.empty(n + 2)
        qdd[0] = (fx[0] - lam_x[0]) / m
        qdd[1] = (fy[0] - lam_y[0]) / m
        qdd[2:] = t - (b / J) * (c * sy - s * sx)
        return qdd

    def rhs(self, t: float, y: np.ndarray) -> np.ndarray:
        """First-order form ẏ = (q̇, q̈) of y = (q, q̇) (Eq. 40 with M moved to the right)."""
        dof = self.model.dof
        if y.ndim == 1 and not self.model.extensible:
            return np.concatenate([y[dof:], self.inextensible_accelerations(y[:dof], y[dof:])])
        return np.concatenate([y[dof:], self.accelerations(y[:dof], y[dof:])])
