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
revolute joints (offset 0: the flat sail is stress-free), axial spring-dampers k_s z_k +
c_s ż_k (Eq. 29) as the P/D control of the sliding joints, and the frame force −m g₀ ŷ as
the tree's gravity. The state-dependent loads — the radiation load (Eq. 11, or its
generalisation in loads.radiation_forces) at every slice centre and the follower tension
T(−cos θ₁, −sin θ₁) at hinge 0 and T(cos θₙ, sin θₙ) at the right end (Eq. 32) — enter
through ONE vectorised Python force user function returning the generalized forces
Q = Σ_i (∂r_i/∂q)ᵀ F_i (virtual work). It is evaluated by Exudyn at the current Newton
iterate, so the load is exact at the converged state (never lagged).

With P_j = Σ_{k>j} f_k + T eₙ, the force carried across joint j, and the slice axis
e_j = (cos θ_j, sin θ_j), normal e_j^⊥ = (−sin θ_j, cos θ_j):

    Q_X, Q_Y  = Σ_k f_k + T (eₙ − e₁)
    G_j       = e_j^⊥ · [(l + z_j) P_j + (l/2) f_j]     (torque about hinge j; z_n ≡ 0)
    Q_θ₁      = Σ_j G_j,   Q_φk = Σ_{j≥k} G_j,   Q_zj = e_j · P_j
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightsail_mbs.model import loads, optics, payload, shapes
from lightsail_mbs.model.parameters import SPEED_OF_LIGHT, SailParameters


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


def generalized_force(p: SailParameters, layout: ChainLayout):
    """The force user function q ↦ Q: radiation load + follower tension (module docstring).

    The frame force −m g₀ is not included: the tree applies it as gravity. Written for speed
    (≈ 20 numpy calls on length-n arrays): it runs at every Newton iterate. For the paper's
    beam (uniform, R = 1, α = 0) the load is Eq. (11) inline, f = f₀ cos²θ n, the same
    expression as loads.radiation_forces; otherwise loads.radiation_forces is called; with an optical
    table (case.optics) its law, optics.normal_tangential_into.
    """
    size, idx, zidx = layout.size, layout.angle_index, layout.stretch_index
    l = layout.slice_length
    half = 0.5 * l
    tension = p.tension
    i_f0 = 1j * p.flat_force
    ideal = p.uniform_beam and p.reflectivity == 1.0 and p.absorptivity == 0.0
    extensible = bool(zidx.size)
    if p.optics is not None:  # an optical table: components along n and t from model/optics.py, compiled
        packed, flags = p.optical_table().packed(), optics.slice_flags(p)
        push = np.full(p.n, 0.5 * p.flat_force)  # I l W / c of the uniform beam
        normal, tangential = np.empty(p.n), np.empty(p.n)
    acc = np.add.accumulate
    Q = np.zeros(size)

    def force(q) -> np.ndarray:
        # complex notation: e_j = exp(iθ_j), normal e_j^⊥ = i e_j, a^⊥·b = Im(conj(a) b)
        q = np.fromiter(q, float, size)
        theta = acc(q[idx])
        e = np.exp(1j * theta)
        c = e.real
        seg = layout.segments(q) if extensible else l
        if p.optics is not None:
            if not p.uniform_beam:
                x = q[0] + _exclusive_cumsum(seg * c) + half * c
                push[:] = loads.intensity(p, x) * (p.slice_length * p.width / SPEED_OF_LIGHT)
            optics.normal_tangential_into(packed, flags, push, c, e.imag, theta, normal, tangential)
            f = (tangential + 1j * normal) * e
        elif ideal:
            f = i_f0 * (c * c) * e  # Eq. (11): f₀ cos²θ n
        else:
            x = q[0] + _exclusive_cumsum(seg * c) + half * c
            fx, fy = loads.radiation_forces(p, x, theta)
            f = fx + 1j * fy
        carried = acc(f[::-1])[::-1]  # Σ_{k≥j} f_k
        total = carried[0] + tension * (e[-1] - e[0])
        Q[0], Q[1] = total.real, total.imag
        carried -= f  # P_j = Σ_{k>j} f_k + T eₙ
        if tension:
            carried += tension * e[-1]
        local = np.conj(e) * carried  # P_j in slice j's axes
        torque = seg * local.imag + half * (np.conj(e) * f).imag
        Q[idx] = acc(torque[::-1])[::-1]
        if extensible:
            Q[zidx] = local.real[:-1]
        return Q

    return force


def tree_arguments(p: SailParameters, layout: ChainLayout, exu) -> dict:
    """Keyword arguments of ObjectKinematicTree (without node and user function): massless
    PrismaticX/PrismaticY base links, one RevoluteZ link per slice (mass m at l/2, inertia J;
    joint offset l from the previous slice's hinge, or 0 after a slide), massless PrismaticX
    slides at l along the previous slice; P/D control = springs/dampers with offset 0. A payload makes its
    slice's link the composite body of model/payload.py (mass M, centre of mass ρ_c from the slice centre,
    inertia J_c); the tree's gravity −g₀ then carries the payload's frame force too."""
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
        gravity=[0.0, -p.nominal_acceleration, 0.0],
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
