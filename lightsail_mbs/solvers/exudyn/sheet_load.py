"""The load of Exudyn's sheet (solvers.exudyn.sheet) as one compiled pass over the tiles.

From the ODE2 coordinates of each tile (centre displacement u from its flat grid point, Tait–Bryan xyz
angles φ) and, where a physics term reads them, their rates: the rows the terms read (model/terms/bodies.py)
— the centre p = flat + u, the unit normal n = R ẑ = (sin φ₁, −sin φ₀ cos φ₁, cos φ₀ cos φ₁)
(model.sheet_grid.normal_xyz), where a term reads it (bodies.AXES) the in-plane axis R x̂ = (cos φ₁ cos φ₂,
cos φ₀ sin φ₂ + sin φ₀ sin φ₁ cos φ₂, sin φ₀ sin φ₂ − cos φ₀ sin φ₁ cos φ₂), the centre velocity u̇ and the global
angular velocity ω = φ̇₀ x̂ + R_x φ̇₁ ŷ + R_x R_y φ̇₂ ẑ (solvers.exudyn.sheet.angular_velocity_xyz) — then the terms'
compiled sum (terms.tile_forces_into, held to the numpy forms by tests/model/test_terms.py), written into the
translational entries of the generalised force vector. Exudyn calls the load before every Newton residual; the
numpy forms cost ~0.6 ms a call on 400 tiles inside its solver (a third of the run), this pass ~20 µs.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model.terms import tile_forces_into
from lightsail_mbs.model.terms.bodies import (
    AXES,
    E1X,
    E1Y,
    E1Z,
    N1,
    N2,
    NB,
    READS,
    TILE_ROWS,
    TVX,
    TVY,
    TVZ,
    TWX,
    TWY,
    TWZ,
    TX,
    TY,
    TZ,
)

COORDINATES = 6  # per body: u (3), xyz angles (3)


@njit(cache=True)
def load_into(packed, flat, q, q_t, tiles, time, force):
    """force[6k : 6k + 3] = the packed terms' force on tile k < `tiles` (N) at coordinates q, rates q_t (an
    empty array when no term reads velocities) and the run's time τ (s); the other entries are left as
    they are."""
    bodies = np.zeros((TILE_ROWS, tiles))
    rates = q_t.shape[0] > 0
    axes = int(packed[READS]) & AXES != 0
    for k in range(tiles):
        b = COORDINATES * k
        c0, s0 = math.cos(q[b + 3]), math.sin(q[b + 3])
        c1, s1 = math.cos(q[b + 4]), math.sin(q[b + 4])
        bodies[TX, k] = flat[k, 0] + q[b]
        bodies[TY, k] = flat[k, 1] + q[b + 1]
        bodies[TZ, k] = flat[k, 2] + q[b + 2]
        bodies[N1, k] = s1
        bodies[N2, k] = -s0 * c1
        bodies[NB, k] = c0 * c1
        if axes:
            c2, s2 = math.cos(q[b + 5]), math.sin(q[b + 5])  # R x̂ of R = R_x(φ₀) R_y(φ₁) R_z(φ₂)
            bodies[E1X, k] = c1 * c2
            bodies[E1Y, k] = c0 * s2 + s0 * s1 * c2
            bodies[E1Z, k] = s0 * s2 - c0 * s1 * c2
        if rates:
            bodies[TVX, k] = q_t[b]
            bodies[TVY, k] = q_t[b + 1]
            bodies[TVZ, k] = q_t[b + 2]
            d0, d1, d2 = q_t[b + 3], q_t[b + 4], q_t[b + 5]
            bodies[TWX, k] = d0 + s1 * d2
            bodies[TWY, k] = c0 * d1 - s0 * c1 * d2
            bodies[TWZ, k] = s0 * d1 + c0 * c1 * d2
    forces = np.empty((3, tiles))
    tile_forces_into(packed, bodies, forces, time)
    for k in range(tiles):
        for i in range(3):
            force[COORDINATES * k + i] = forces[i, k]


def add_load_items(mbs, nodes: list, force: np.ndarray, block: int) -> tuple[list, list]:
    """The load's carriers: one ``ObjectGenericODE2`` per `block` consecutive nodes, each with the constant
    ``forceVector`` of its nodes' entries of `force` (6 a node); returns (object numbers, node ranges (a, b))."""
    from exudyn.itemInterface import ObjectGenericODE2

    blocks = [(a, min(a + block, len(nodes))) for a in range(0, len(nodes), block)]
    items = [
        mbs.AddObject(
            ObjectGenericODE2(nodeNumbers=nodes[a:b], forceVector=force[COORDINATES * a : COORDINATES * b].tolist())
        )
        for a, b in blocks
    ]
    return items, blocks
