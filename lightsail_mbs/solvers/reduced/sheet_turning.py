"""The in-house sheet integrated in the frame that turns with its spin (option ``frame="turning"``, the default
for a spinning sheet): :class:`TurningFrame`, which solvers.reduced.sheet.SheetModel holds as its ``turning``.

Why. In the inertial frame a spinning sail's state turns at Ω: the centres' in-plane displacements and
velocities, the quaternions and the body rates change by O(1) every turn, and the stiff in-plane connectors
turn with the tiles. Simplified Newton on Radau's collocation system then stops contracting once the sail
turns by about 1e-2 rad in a step, also with a Jacobian fresh at the step's start or with the full, unreduced
Newton matrix (measured on the unlit 49-tile Si₃N₄ disc at 120 Hz: 1294 steps and 1267 Jacobians for 6 turns,
or 2575 and 2562 with a pre-stress different in its round-off only; tests/solvers/test_sheet_turning.py,
validation/spin_benchmark.md). In a frame
that turns with the sail the spun equilibrium is steady (exactly, for a load symmetric about the spin axis):
the state moves only as the shape does, the Jacobian stays valid, and the steps follow the shape's time
scales (the same disc: 17 steps, one Jacobian).

The frame turns at the sail's initial angular velocity Ω (constant, global axes) about the point a, the tiles'
centre of mass at t = 0 (model.sheet_spin, model.sheet_pose: every body starts at v = Ω × (c − a)), by
Q(t) = exp(t [Ω]×). Per body the turning frame's state is the centre displacement u_r (c_r = X + u_r, X the
body's reference point), the quaternion q_r, the velocity relative to the frame w = ċ_r and the body-frame
angular velocity relative to the frame ω_rel. The inertial state the right-hand side kernel reads is

    u = Q u_r + (Q − I)(X − a),   q = q_Q ⊗ q_r,   v = Q (w + Ω × ρ),   ω_b = ω_rel + R_rᵀ Ω,

with ρ = c_r − a, q_Q the quaternion of Q and R_r the rotation of q_r (R = Q R_r; QᵀΩ = Ω, so R_rᵀΩ = RᵀΩ is
the frame's rate in the body's axes, and Ṙ = R [ω_b]× follows from Q̇ = [Ω]× Q and Ṙ_r = R_r [ω_rel]×). From
the kernel's inertial rates v̇ and ω̇_b (the same kernel as an inertial run: the same connectors and loads,
the load at the inertial positions and time) the turning frame's equations are

    u̇_r = w,   q̇_r = ½ q_r ⊗ (0, ω_rel),
    ẇ = Qᵀ v̇ − 2 Ω × w − Ω × (Ω × ρ)                    (Coriolis, centrifugal),
    ω̇_rel = ω̇_b + ω_rel × R_rᵀ Ω                        (d(R_rᵀΩ)/dt = −ω_rel × R_rᵀΩ),

from v = Q(w + Ω × ρ): v̇ = Q(ẇ + 2Ω × w + Ω × (Ω × ρ)). The transformation is exact, so a run in either frame
solves the same equations; only the integrator's path differs (tests: the two frames agree to the
integrator's tolerance, and the unlit spun sail rests in the turning frame). The first-order state keeps the
form ẋ = B(x) V of solvers.reduced.sheet_radau (B the same per-body I₃ and ½ Q(q_r)), so the velocity-reduced
Newton solve applies unchanged, and the block it drops, ∂(B V)/∂X = O(|ω_rel|), is now small. The samples of
a run are transformed back to the inertial frame at their times; a Result does not depend on the frame.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import sheet
from lightsail_mbs.solvers.reduced.sheet_kernels import rotation_minus_identity
from lightsail_mbs.solvers.reduced.sheet_tethers import STATE


@njit(cache=True)
def to_inertial(y, flat, axis, spin, Q, QmI, qQ, out):
    """The inertial state `out` (13 per body) of the turning frame's state y (module docstring); Q, QmI = Q − I
    (3, 3) and qQ (4,) the frame's rotation at the time."""
    R = np.empty((3, 3))
    rho = np.empty(3)
    rel = np.empty(3)
    for k in range(flat.shape[0]):
        b = STATE * k
        for i in range(3):
            rho[i] = flat[k, i] - axis[i] + y[b + i]
        for i in range(3):
            out[b + i] = 0.0
            for j in range(3):
                out[b + i] += Q[i, j] * y[b + j] + QmI[i, j] * (flat[k, j] - axis[j])
        p0, p1, p2, p3 = qQ[0], qQ[1], qQ[2], qQ[3]
        r0, r1, r2, r3 = y[b + 3], y[b + 4], y[b + 5], y[b + 6]
        out[b + 3] = p0 * r0 - p1 * r1 - p2 * r2 - p3 * r3
        out[b + 4] = p0 * r1 + p1 * r0 + p2 * r3 - p3 * r2
        out[b + 5] = p0 * r2 - p1 * r3 + p2 * r0 + p3 * r1
        out[b + 6] = p0 * r3 + p1 * r2 - p2 * r1 + p3 * r0
        rel[0] = y[b + 7] + spin[1] * rho[2] - spin[2] * rho[1]
        rel[1] = y[b + 8] + spin[2] * rho[0] - spin[0] * rho[2]
        rel[2] = y[b + 9] + spin[0] * rho[1] - spin[1] * rho[0]
        for i in range(3):
            out[b + 7 + i] = Q[i, 0] * rel[0] + Q[i, 1] * rel[1] + Q[i, 2] * rel[2]
        rotation_minus_identity(r0, r1, r2, r3, R)
        for i in range(3):
            R[i, i] += 1.0
        for i in range(3):
            out[b + 10 + i] = y[b + 10 + i] + R[0, i] * spin[0] + R[1, i] * spin[1] + R[2, i] * spin[2]


@njit(cache=True)
def to_turning_rates(y, f, flat, axis, spin, Q, out):
    """The turning frame's rates `out` of its state y, from the kernel's inertial rates f of the same state
    (module docstring)."""
    R = np.empty((3, 3))
    rho = np.empty(3)
    acc = np.empty(3)
    frame_rate = np.empty(3)
    s0, s1, s2 = spin[0], spin[1], spin[2]
    for k in range(flat.shape[0]):
        b = STATE * k
        for i in range(3):
            rho[i] = flat[k, i] - axis[i] + y[b + i]
            out[b + i] = y[b + 7 + i]
        q0, q1, q2, q3 = y[b + 3], y[b + 4], y[b + 5], y[b + 6]
        w0, w1, w2 = y[b + 10], y[b + 11], y[b + 12]
        out[b + 3] = 0.5 * (-q1 * w0 - q2 * w1 - q3 * w2)
        out[b + 4] = 0.5 * (q0 * w0 + q2 * w2 - q3 * w1)
        out[b + 5] = 0.5 * (q0 * w1 + q3 * w0 - q1 * w2)
        out[b + 6] = 0.5 * (q0 * w2 + q1 * w1 - q2 * w0)
        for i in range(3):
            acc[i] = Q[0, i] * f[b + 7] + Q[1, i] * f[b + 8] + Q[2, i] * f[b + 9]
        v0, v1, v2 = y[b + 7], y[b + 8], y[b + 9]
        c0 = s1 * rho[2] - s2 * rho[1]  # Ω × ρ
        c1 = s2 * rho[0] - s0 * rho[2]
        c2 = s0 * rho[1] - s1 * rho[0]
        out[b + 7] = acc[0] - 2.0 * (s1 * v2 - s2 * v1) - (s1 * c2 - s2 * c1)
        out[b + 8] = acc[1] - 2.0 * (s2 * v0 - s0 * v2) - (s2 * c0 - s0 * c2)
        out[b + 9] = acc[2] - 2.0 * (s0 * v1 - s1 * v0) - (s0 * c1 - s1 * c0)
        rotation_minus_identity(q0, q1, q2, q3, R)
        for i in range(3):
            R[i, i] += 1.0
        for i in range(3):
            frame_rate[i] = R[0, i] * s0 + R[1, i] * s1 + R[2, i] * s2
        out[b + 10] = f[b + 10] + w1 * frame_rate[2] - w2 * frame_rate[1]
        out[b + 11] = f[b + 11] + w2 * frame_rate[0] - w0 * frame_rate[2]
        out[b + 12] = f[b + 12] + w0 * frame_rate[1] - w1 * frame_rate[0]


def frame_rotation(spin: np.ndarray, t: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(Q, Q − I, q_Q) of the frame turned by |Ω| t about Ω: Rodrigues, Q − I = sin θ [n]× + 2 sin²(θ/2) [n]×²
    (small entries from small products at small θ)."""
    rate = float(np.linalg.norm(spin))
    if rate == 0.0:
        return np.eye(3), np.zeros((3, 3)), np.array([1.0, 0.0, 0.0, 0.0])
    n = spin / rate
    theta = rate * t
    cross = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    QmI = math.sin(theta) * cross + 2.0 * math.sin(0.5 * theta) ** 2 * (cross @ cross)
    return np.eye(3) + QmI, QmI, np.r_[math.cos(0.5 * theta), math.sin(0.5 * theta) * n]


class TurningFrame:
    """The turning frame of a SheetModel (module docstring): its rate Ω (global), its centre a, the model's start
    in it, and the transformations of states and rates."""

    def __init__(self, model):
        start = model.inertial_y0().reshape(model.count, STATE)
        self.flat = model.flat
        self.spin = sheet.quaternion_rotation(start[:1, 3:7])[0] @ start[0, 10:13]  # ω of body 0, global
        centres = model.flat + start[:, 0:3]
        tiles = model.lit
        self.axis = model.masses[:tiles] @ centres[:tiles] / model.masses[:tiles].sum()
        rows = start.copy()
        rows[:, 7:10] -= np.cross(self.spin, centres - self.axis)
        rows[:, 10:13] -= np.einsum("kji,j->ki", sheet.quaternion_rotation(start[:, 3:7]), self.spin)
        self.start = rows.ravel()
        self._inertial = np.empty(model.n)
        self._rates = np.empty(model.n)

    def rates(self, t, y, inertial_rhs, out):
        """The turning frame's rates of its state y at time t into out, through inertial_rhs(t, y, out)."""
        Q, QmI, qQ = frame_rotation(self.spin, float(t))
        to_inertial(y, self.flat, self.axis, self.spin, Q, QmI, qQ, self._inertial)
        inertial_rhs(t, self._inertial, self._rates)
        to_turning_rates(y, self._rates, self.flat, self.axis, self.spin, Q, out)
        return out

    def inertial(self, times, rows) -> np.ndarray:
        """The inertial states (T, 13N) of turning-frame state rows (T, 13N) at the times (T,)."""
        rows = np.asarray(rows, float)
        out = np.empty_like(rows)
        for i, t in enumerate(np.asarray(times, float)):
            Q, QmI, qQ = frame_rotation(self.spin, float(t))
            to_inertial(np.ascontiguousarray(rows[i]), self.flat, self.axis, self.spin, Q, QmI, qQ, out[i])
        return out
