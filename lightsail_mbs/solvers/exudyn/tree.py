"""The sail as an Exudyn KinematicTree: layout, kinematics and the exact generalized load.

The chain of n planar rigid slices is one ``ObjectKinematicTree`` in minimal (joint)
coordinates, ordered along the chain:

    q = [X, Y, θ₁, (z₁), φ₂, (z₂), φ₃, …, (z_{n−1}), φₙ]

X, Y (PrismaticX, PrismaticY, massless links) place the left end (hinge 0) of slice 1;
θ₁ (RevoluteZ) is its angle; φ_k = θ_k − θ_{k−1} (RevoluteZ at the hinge, a slice length
l further along the parent slice) is the relative angle of slice k; in the extensible TnT
model a massless PrismaticX link z_k sits between slice k and slice k+1 and slides along
slice k's axis (paper Eqs 30–31 with l_s = 0). Slices carry m = ρhWl at their centre
(l/2 along their axis) and J = ml²/12.

Everything that is linear in the joint coordinates runs in C++ inside the tree:
torsional spring-dampers k_T φ_k + c_T φ̇_k (Eq. 23) as the joint P/D control of the
revolute joints (offset 0: the flat sail is stress-free) and axial spring-dampers k_s z_k +
c_s ż_k (Eq. 29) as the P/D control of the sliding joints. The state-dependent loads — the net
slice force in the accelerating frame (the radiation load of Eq. 11, or its generalisation, plus
the frame force −m g₀ ŷ, with their cancellation done analytically: the physics terms of
model/terms) at every slice centre and the follower tension T(−cos θ₁, −sin θ₁) at hinge 0 and T(cos θₙ, sin θₙ) at the
right end (Eq. 32) — enter through ONE compiled force user function returning the generalized
forces Q = Σ_i (∂r_i/∂q)ᵀ F_i (virtual work). It is evaluated by Exudyn at the current Newton
iterate or explicit stage, so the load is exact at the converged state (never lagged).

The tree's gravity is off. Applied as gravity, the frame force −m g₀ enters Q as torques of order
f₀ n l/2 that cancel the load's torques to ~1e-8 of themselves; the round-off of that sum, divided by
the small inertia of the short-wave coordinates in M⁻¹, made relative errors of 2e-4 to 4e-3 in the
angular accelerations, concentrated at short waves, which the instability amplifies (docs:
validation, round-off budget). With the net slice force the error is ~1e-10.

With P_j = Σ_{k>j} f_k + T eₙ, the force carried across joint j, and the slice axis
e_j = (cos θ_j, sin θ_j), normal e_j^⊥ = (−sin θ_j, cos θ_j):

    Q_X, Q_Y  = Σ_k f_k + T (eₙ − e₁)
    G_j       = e_j^⊥ · [(l + z_j) P_j + (l/2) f_j]     (torque about hinge j; z_n ≡ 0)
    Q_θ₁      = Σ_j G_j,   Q_φk = Σ_{j≥k} G_j,   Q_zj = e_j · P_j
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import heating, payload, shapes, terms
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.terms import beam_factor, chain_forces_into
from lightsail_mbs.model.terms.bodies import (
    CHAIN_ROWS,
    COS,
    OMEGA,
    POSITIONS,
    READS,
    SIN,
    THETA,
    VELOCITIES,
    VX,
    VY,
    X,
    Y,
)


@dataclass(frozen=True)
class ChainLayout:
    """Where each slice's joint coordinates sit in q."""

    n: int
    slice_length: float
    angle_index: np.ndarray  # (n,) indices of θ₁, φ₂, …, φₙ
    stretch_index: np.ndarray  # (n−1,) indices of z₁…z_{n−1}, empty if inextensible

    @property
    def size(self) -> int:
        return 2 + self.n + self.stretch_index.size

    @classmethod
    def of(cls, p: SailParameters) -> ChainLayout:
        if p.extensible:
            angle = np.array([2] + [3 + 2 * (k - 1) + 1 for k in range(1, p.n)])
            stretch = np.array([3 + 2 * (k - 1) for k in range(1, p.n)])
        else:
            angle = np.arange(2, 2 + p.n)
            stretch = np.zeros(0, dtype=int)
        return cls(p.n, p.slice_length, angle, stretch)

    # ---- kinematics, vectorised over leading axes -----------------------------------------
    def segments(self, q: np.ndarray) -> np.ndarray:
        """Hinge-to-hinge lengths l + z_k (the last slice: l)."""
        seg = np.full(q.shape[:-1] + (self.n,), self.slice_length)
        if self.stretch_index.size:
            seg[..., :-1] += q[..., self.stretch_index]
        return seg

    def positions(self, q: np.ndarray):
        """Slice centres x, y, angles θ and extensions z from joint coordinates q (…, size)."""
        q = np.asarray(q, float)
        theta = np.cumsum(q[..., self.angle_index], axis=-1)
        c, s = np.cos(theta), np.sin(theta)
        seg = self.segments(q)
        half = 0.5 * self.slice_length
        x = q[..., :1] + _exclusive_cumsum(seg * c) + half * c
        y = q[..., 1:2] + _exclusive_cumsum(seg * s) + half * s
        return x, y, theta, q[..., self.stretch_index]

    def velocities(self, q: np.ndarray, q_t: np.ndarray):
        """Centre velocities vx, vy, angular velocities ω and extension rates ż."""
        q, q_t = np.asarray(q, float), np.asarray(q_t, float)
        theta = np.cumsum(q[..., self.angle_index], axis=-1)
        omega = np.cumsum(q_t[..., self.angle_index], axis=-1)
        c, s = np.cos(theta), np.sin(theta)
        seg = self.segments(q)
        seg_t = np.zeros_like(seg)
        if self.stretch_index.size:
            seg_t[..., :-1] = q_t[..., self.stretch_index]
        half = 0.5 * self.slice_length
        vx = q_t[..., :1] + _exclusive_cumsum(seg_t * c - seg * omega * s) - half * omega * s
        vy = q_t[..., 1:2] + _exclusive_cumsum(seg_t * s + seg * omega * c) + half * omega * c
        return vx, vy, omega, q_t[..., self.stretch_index]

    def coordinates(self, state: shapes.ChainState) -> np.ndarray:
        """Joint coordinates q of a chain state (centres, angles, extensions)."""
        q = np.zeros(self.size)
        half = 0.5 * self.slice_length
        q[0] = state.x[0] - half * np.cos(state.theta[0])
        q[1] = state.y[0] - half * np.sin(state.theta[0])
        q[self.angle_index] = np.diff(state.theta, prepend=0.0)
        q[self.stretch_index] = state.z[: self.stretch_index.size]
        return q


def _exclusive_cumsum(a: np.ndarray) -> np.ndarray:
    """[0, a₀, a₀+a₁, …] along the last axis (same length as a)."""
    out = np.zeros_like(a)
    np.cumsum(a[..., :-1], axis=-1, out=out[..., 1:])
    return out


def generalized_force(p: SailParameters, layout: ChainLayout, beam_factor_of=None):
    """The force user function (q, q̇, t) ↦ Q: the physics terms' forces on the slice centres (model/terms: the
    radiation with the frame force netted analytically, a payload's share of the frame force) and the
    follower tension, as generalized forces by virtual work (module docstring); q̇ (default 0) is read
    only when a packed term reads velocities.

    The tree's gravity is off. With a payload the craft accelerates at g₀ < c_n(0) Ī/(c ρ h): the terms add
    c_n(0) Ī l W/c − m g₀ on every slice (the net form's frame force minus the craft's), and the payload
    carries its frame force −m_p g₀ ŷ at its position on the composite link. One compiled pass over the
    slices (about 5 µs a call at n = 30): it runs at every Newton iterate or explicit stage. Returns the
    same array, overwritten, at every call. beam_factor_of: a function () ↦ D of the run's state (the sail's
    world line, solvers.exudyn.world_line), written into the packed Doppler term before each sum; None: the
    term's closed form.
    """
    attached = payload.attachment(p)
    angle_index = np.ascontiguousarray(layout.angle_index, dtype=np.int64)
    stretch_index = np.ascontiguousarray(layout.stretch_index, dtype=np.int64)
    constants = np.array(
        [
            layout.slice_length,
            p.tension,
            -1.0 if attached is None else attached.slice_index,
            0.0 if attached is None else attached.along,
            0.0 if attached is None else attached.across,
            -p.payload_mass * p.nominal_acceleration,
            0.0,  # the start of a heated film's table (model/heating.py) in these constants; 0: none
            p.axial_stiffness if p.extensible else 0.0,
        ]
    )
    if p.heated:
        constants[6] = constants.size
        constants = np.concatenate([constants, heating.table(p)])
    packed = terms.pack(p, "chain")
    rates = terms.reads(packed) & VELOCITIES
    Q = np.zeros(layout.size)
    rest = np.zeros(layout.size)

    def force(q, q_t=None, t=0.0) -> np.ndarray:
        q_t = np.asarray(q_t, dtype=np.float64) if rates and q_t is not None else rest
        q = np.asarray(q, dtype=np.float64)
        if beam_factor_of is not None:
            terms.set_beam_factor(packed, beam_factor_of())
        _generalized_force_into(q, q_t, float(t), angle_index, stretch_index, constants, packed, Q)
        return Q

    return force


@njit(cache=True)
def _slices_into(q, q_t, angle_index, stretch_index, l, reads, bodies):
    """The slices as the physics terms read them (model/terms/bodies.py) at coordinates q, q̇: θ_j, cos, sin and
    the centres' abscissae; heights, centre velocities and angular velocities when a term reads them."""
    n = angle_index.size
    extensible = stretch_index.size > 0
    half = 0.5 * l
    angle = 0.0
    x = q[0]
    for j in range(n):
        angle += q[angle_index[j]]
        bodies[THETA, j] = angle
        bodies[COS, j] = math.cos(angle)
        bodies[SIN, j] = math.sin(angle)
        if j > 0:  # centre of slice j from the centre of slice j − 1
            seg = l + q[stretch_index[j - 1]] if extensible else l
            x += (seg - half) * bodies[COS, j - 1] + half * bodies[COS, j]
        else:
            x += half * bodies[COS, 0]
        bodies[X, j] = x
    if reads & POSITIONS:
        y = q[1] + half * bodies[SIN, 0]
        bodies[Y, 0] = y
        for j in range(1, n):
            seg = l + q[stretch_index[j - 1]] if extensible else l
            y += (seg - half) * bodies[SIN, j - 1] + half * bodies[SIN, j]
            bodies[Y, j] = y
    if reads & VELOCITIES:
        c, s, omega = bodies[COS], bodies[SIN], bodies[OMEGA]
        rate = 0.0
        for j in range(n):
            rate += q_t[angle_index[j]]
            omega[j] = rate
        bodies[VX, 0] = q_t[0] - half * omega[0] * s[0]
        bodies[VY, 0] = q_t[1] + half * omega[0] * c[0]
        for j in range(1, n):
            seg = l + q[stretch_index[j - 1]] if extensible else l
            stretch = q_t[stretch_index[j - 1]] if extensible else 0.0
            turn = (seg - half) * omega[j - 1]
            bodies[VX, j] = bodies[VX, j - 1] + stretch * c[j - 1] - turn * s[j - 1] - half * omega[j] * s[j]
            bodies[VY, j] = bodies[VY, j - 1] + stretch * s[j - 1] + turn * c[j - 1] + half * omega[j] * c[j]


@njit(cache=True)
def _generalized_force_into(q, q_t, t, angle_index, stretch_index, k, packed, Q):
    """Q of the physics terms' slice forces, the end tensions and a payload's frame force at coordinates q
    (velocities q̇) and the time t, written into Q. Constants k: l, T, the payload's slice j (−1: none), its
    offsets along e_j and p_j from the slice centre, −m_p g₀ (times the beam's factor at t, terms.beam_factor), the
    start of a heated film's table in k (0: none; model/heating.py) and k_s;
    packed: the chain's physics terms (terms.pack).

        P_j = Σ_{k>j} f_k + T eₙ,  G_j = e_j^⊥ · [(l + z_j) P_j + (l/2) f_j],
        Q_X, Q_Y = Σ_k f_k + T (eₙ − e₁),  Q_φk = Σ_{j≥k} G_j,  Q_zj = e_j · P_j.
    """
    l, tension, payload_slice, along, across = k[0], k[1], int(k[2]), k[3], k[4]
    payload_fy = k[5] * beam_factor(packed, t) if payload_slice >= 0 else k[5]
    n = angle_index.size
    heat = k[int(k[6]) :]  # a heated film: the end tension N(D) and the springs' thermal rest extensions
    j_heat, f_heat = heating.weights(heat, beam_factor(packed, t)) if k[6] != 0.0 else (0, 0.0)
    if k[6] != 0.0:
        tension = heating.tension(heat, j_heat, f_heat)
    extensible = stretch_index.size > 0
    half = 0.5 * l
    bodies = np.zeros((CHAIN_ROWS, n))
    forces = np.empty((2, n))
    _slices_into(q, q_t, angle_index, stretch_index, l, int(packed[READS]), bodies)
    chain_forces_into(packed, bodies, forces, t)
    c, s, fx, fy = bodies[COS], bodies[SIN], forces[0], forces[1]
    px = tension * c[n - 1]  # P_j, carried across joint j, built from the free end
    py = tension * s[n - 1]
    torque = 0.0
    for j in range(n - 1, -1, -1):
        seg = l + q[stretch_index[j]] if extensible and j < n - 1 else l
        torque += seg * (c[j] * py - s[j] * px) + half * (c[j] * fy[j] - s[j] * fx[j])
        if j == payload_slice:  # −m_p g₀ ŷ at the payload, (l/2 + ρ_e) e_j + ρ_p p_j from hinge j
            torque += ((half + along) * c[j] - across * s[j]) * payload_fy
        Q[angle_index[j]] = torque
        if extensible and j < n - 1:
            Q[stretch_index[j]] = c[j] * px + s[j] * py
            if k[6] != 0.0:  # the joint's P control pulls with −k_s z; the heated rest length adds k_s l α_T ΔT_j
                Q[stretch_index[j]] += k[7] * heating.rest_extension(heat, n, j_heat, f_heat, j)
        px += fx[j]
        py += fy[j]
        if j == payload_slice:
            py += payload_fy
    Q[0] = px - tension * c[0]
    Q[1] = py - tension * s[0]


def tree_arguments(p: SailParameters, layout: ChainLayout, exu) -> dict:
    """Keyword arguments of ObjectKinematicTree (without node and user function): massless
    PrismaticX/PrismaticY base links, one RevoluteZ link per slice (mass m at l/2, inertia J;
    joint offset l from the previous slice's hinge, or 0 after a slide), massless PrismaticX
    slides at l along the previous slice; P/D control = springs/dampers with offset 0. A payload makes its
    slice's link the composite body of model/payload.py (mass M, centre of mass ρ_c from the slice centre,
    inertia J_c); the payload's frame force is in the net load (generalized_force)."""
    l, m, J = p.slice_length, p.slice_mass, p.slice_inertia
    size = layout.size
    types = [exu.JointType.PrismaticX, exu.JointType.PrismaticY] + [None] * (size - 2)
    offsets = [[0.0, 0.0, 0.0] for _ in range(size)]
    masses = np.zeros(size)
    coms = [[0.0, 0.0, 0.0] for _ in range(size)]
    inertias = [np.zeros((3, 3)) for _ in range(size)]
    stiffness = np.zeros(size)
    damping = np.zeros(size)
    rest = np.zeros(size)  # joint P control's set point: the rest angle of a sail made curved
    for k, i in enumerate(layout.angle_index):
        types[i] = exu.JointType.RevoluteZ
        masses[i] = m
        coms[i] = [0.5 * l, 0.0, 0.0]
        inertias[i] = np.diag([J, J, J])
        if k > 0:
            stiffness[i] = p.torsional_stiffness
            damping[i] = p.total_torsional_damping
            rest[i] = p.rest_turn
            if not layout.stretch_index.size:
                offsets[i] = [l, 0.0, 0.0]
    attached = payload.attachment(p)
    if attached is not None:  # slice j and the payload as one composite link (model/payload.py)
        i = layout.angle_index[attached.slice_index]
        centre = np.array([0.5 * l + attached.centre_along, attached.centre_across])
        masses[i] = attached.mass
        coms[i] = [centre[0], centre[1], 0.0]
        inertias[i] = np.diag([attached.inertia] * 3)
    for i in layout.stretch_index:
        types[i] = exu.JointType.PrismaticX
        offsets[i] = [l, 0.0, 0.0]
        stiffness[i] = p.axial_stiffness
        damping[i] = p.total_axial_damping
    return dict(
        gravity=[0.0, 0.0, 0.0],  # the frame force is in the net load (generalized_force)
        jointTypes=types,
        linkParents=list(range(-1, size - 1)),
        jointTransformations=exu.Matrix3DList([np.eye(3)] * size),
        jointOffsets=exu.Vector3DList(offsets),
        linkInertiasCOM=exu.Matrix3DList(inertias),
        linkCOMs=exu.Vector3DList(coms),
        linkMasses=masses,
        jointPControlVector=stiffness,
        jointDControlVector=damping,
        jointPositionOffsetVector=rest,
        jointVelocityOffsetVector=np.zeros(size),
    )
