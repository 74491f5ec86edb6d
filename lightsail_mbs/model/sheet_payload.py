"""A payload behind a sheet: on a rigid stem from the middle, or on tethers from the rim.

The payload is one more rigid body of mass m_p (``payload_mass``) and isotropic inertia J_p
(``payload_inertia``), a distance d (``payload_stem``) from the sail's middle towards the laser: at
P₀ = (x_m, y_m, z_a − d) with (x_m, y_m) = (L/2, W/2) and z_a the height of the anchor tile, the tile whose
centre is nearest the middle (the disc's and the hexagon's central tile; on a grid with an even count the
first of the nearest). Both solvers add it as a body beside the tiles, so the sheet's own model is unchanged.

**Stem** (``payload_tethers = 0``). A rigid stem welds the payload to the anchor tile. It is the sheet's
own kind of connector (model.sheet_connectors: Exudyn's ``ObjectConnectorRigidBodySpringDamper`` law) with
both markers at the payload's centre, l_a = R_aᵀ(P₀ − c_a) on the tile and l_b = 0 on the payload, and a
stiffness as large as the sheet's around that tile: k_t = Σ k_∥ over the anchor's connectors in every
direction, k_r = k_t J_p/m_p about every axis (the same frequency; 0 for a point mass, whose own rotation
then carries no load), damped as the membrane, c = (β + β_m) k. The stem's compliance m_p g₀/k_t is
~1e-8 m for the paper's sail and 1 g. A point on the stem moves with the tile, so the lever d makes the
anchor's rotation stiff (k_t d²): the exact rigid limit is the chain's composite slice (model.payload).

**Tethers** (``payload_tethers = n_t ≥ 3``). Elastic cables from n_t boundary edges of the rim, spread
evenly in polar angle about the middle (edge j nearest the angle θ₀ + 2πj/n_t, θ₀ the angle of the edge
nearest +x), each from its edge's
point on the tile (the mesh's boundary marker) to the payload's centre. A cable of length ℓ, rest length ℓ₀
and stiffness k (``tether_stiffness``) pulls both ends together with the tension

    T = max(k (ℓ − ℓ₀) + c ℓ̇, 0)  for ℓ > ℓ₀,    T = 0  for ℓ ≤ ℓ₀ (slack: it carries nothing),

c = β k (the case's stiffness_damping), along the cable (:func:`tether_tension`).

**Start.** The craft accelerates at g₀ = c_n(0) Ī A/(c (M_s + m_p)) (SailParameters.nominal_acceleration);
in the frame accelerating with it the payload carries −m_p g₀ ẑ, which its stem or tethers must balance.
They start in that equilibrium of the rigid, flat-lit craft: the stem's offset carries m_p g₀ ẑ, the
tethers the least-norm tensions T with Σ_j T_j u_j = m_p g₀ ẑ (u_j the unit vector from the payload to
tether j's point; equal tensions T_j = m_p g₀/Σ u_j,z on a symmetric rim), ℓ₀ = ℓ − T/k. The sail carries the
matching excess c_n(0) Ī A_k/c − m_k g₀ on every tile (the physics term model/terms/frame.py), so the craft's
total force in the accelerating frame vanishes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.model import planforms
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.sheet_grid import Tiles, quaternion_rotation

POINT_INERTIA = 1e-4  # a point payload's inertia floor, m_p (this × L)²: its rotation carries no load


@dataclass(frozen=True, eq=False)
class SheetPayload:
    """The payload body and its attachment (module docstring; SI units, global axes of the untilted start)."""

    mass: float
    inertia: np.ndarray  # (3, 3) about its centre
    start: np.ndarray  # P₀ (3,)
    quaternion: np.ndarray  # (4,) its initial orientation: the anchor tile's (stem), identity (tethers)
    anchor: int  # the stem's tile (the nearest to the middle)
    stem: dict | None  # the stem as one connector row: tile_a, local_a, local_b, stiffness, damping, offset
    tether_tile: np.ndarray  # (n_t,) int
    tether_point: np.ndarray  # (n_t, 3) on the tile, in its axes
    tether_rest: np.ndarray  # (n_t,) ℓ₀ (m)
    tether_stiffness: float  # k (N/m)
    tether_damping: float  # c (N s/m)
    frame_force: float  # −m_p g₀ along z (N), before the Doppler factor (terms.beam_factor)

    @property
    def tethers(self) -> int:
        return len(self.tether_tile)


def anchor_tile(p: SailParameters) -> int:
    """The tile whose centre is nearest the sail's middle (L/2, W/2) (the first of equals)."""
    c = planforms.mesh_of(p).centres
    return int(np.argmin(np.hypot(c[:, 0] - 0.5 * p.length, c[:, 1] - 0.5 * p.width) + 1e-12 * np.arange(len(c))))


def tether_edges(p: SailParameters) -> np.ndarray:
    """The boundary edges of the n_t tethers: edge j nearest the polar angle 2πj/n_t about the middle."""
    m = planforms.mesh_of(p)
    points = m.centres[m.boundary_tile] + m.boundary_marker
    angle = np.arctan2(points[:, 1] - 0.5 * p.width, points[:, 0] - 0.5 * p.length)
    first = angle[np.argmin(np.abs(angle))]  # the edge nearest +x
    chosen: list[int] = []
    for j in range(p.payload_tethers):
        gap = np.abs(np.angle(np.exp(1j * (angle - first - 2.0 * math.pi * j / p.payload_tethers))))
        gap[chosen] = np.inf
        chosen.append(int(np.argmin(gap)))
    return np.array(chosen, dtype=int)


def tether_tension(stretch, rate, stiffness: float, damping: float):
    """T = max(k (ℓ − ℓ₀) + c ℓ̇, 0) where ℓ > ℓ₀, else 0 (N): a cable pulls and never pushes."""
    stretch, rate = np.asarray(stretch, float), np.asarray(rate, float)
    return np.where(stretch > 0.0, np.maximum(stiffness * stretch + damping * rate, 0.0), 0.0)


def payload(p: SailParameters, centres: np.ndarray, quaternions: np.ndarray, conn) -> SheetPayload | None:
    """The payload of sheet case p with the sail's initial tiles (centres, quaternions) and its connectors
    `conn` (model.sheet_connectors.Connectors); None without a payload."""
    if p.payload_mass <= 0.0:
        return None
    tiles = Tiles.of(p)
    mp, g0 = p.payload_mass, p.nominal_acceleration
    anchor = anchor_tile(p)
    start = np.array([0.5 * p.length, 0.5 * p.width, centres[anchor, 2] - p.payload_stem])
    own = p.payload_inertia if p.payload_inertia > 0 else mp * (POINT_INERTIA * p.length) ** 2
    identity = np.array([1.0, 0.0, 0.0, 0.0])
    common = dict(mass=mp, inertia=own * np.eye(3), start=start, anchor=anchor, frame_force=-mp * g0)
    if p.payload_tethers == 0:
        rotation = quaternion_rotation(quaternions[anchor])
        touching = (conn.tile_a == anchor) | (conn.tile_b == anchor)
        k = float(np.sum(np.max(conn.stiffness[touching, :2], axis=1)))
        kr = k * p.payload_inertia / mp
        stiffness = np.array([k, k, k, kr, kr, kr])
        offset = np.zeros(6)
        offset[:3] = rotation.T @ np.array([0.0, 0.0, mp * g0]) / k  # A K offset = m_p g₀ ẑ on the payload
        stem = dict(
            tile_a=anchor,
            local_a=rotation.T @ (start - centres[anchor]),
            local_b=np.zeros(3),
            stiffness=stiffness,
            damping=(p.stiffness_damping + tiles.membrane_damping) * stiffness,
            offset=offset,
        )
        empty = np.zeros(0)
        return SheetPayload(
            **common,
            quaternion=np.array(quaternions[anchor], float),
            stem=stem,
            tether_tile=np.zeros(0, dtype=int),
            tether_point=np.zeros((0, 3)),
            tether_rest=empty,
            tether_stiffness=0.0,
            tether_damping=0.0,
        )
    m = tiles.mesh
    edges = tether_edges(p)
    tile = m.boundary_tile[edges].astype(int)
    point = np.column_stack([m.boundary_marker[edges], np.zeros(len(edges))])
    ends = centres[tile] + np.einsum("kij,kj->ki", quaternion_rotation(quaternions[tile]), point)
    span = ends - start
    length = np.linalg.norm(span, axis=1)
    units = (span / length[:, None]).T  # (3, n_t)
    tension = units.T @ np.linalg.solve(units @ units.T, [0.0, 0.0, mp * g0])  # the least-norm balance
    k = float(p.tether_stiffness)
    return SheetPayload(
        **common,
        quaternion=identity,
        stem=None,
        tether_tile=tile,
        tether_point=point,
        tether_rest=length - tension / k,
        tether_stiffness=k,
        tether_damping=p.stiffness_damping * k,
    )


def record(centres: np.ndarray, velocities: np.ndarray) -> dict:
    """The payload's trajectory as a run's info records it: {"payload_centre": (T, 3), "payload_velocity":
    (T, 3)} as lists (m, m/s; global, the frame accelerating with the craft), {} without a payload (arrays
    (T, 0, 3) or (T, 1, 3))."""
    if centres.shape[1] == 0:
        return {}
    return {"payload_centre": centres[:, 0].tolist(), "payload_velocity": velocities[:, 0].tolist()}
