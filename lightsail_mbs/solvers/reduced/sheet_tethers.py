"""The payload of the reduced sheet (model.sheet_payload): its body appended to the tiles, its stem as one more
connector, and the compiled forces of its tethers.

The payload is body N (after the N tiles) in every per-body array of the reduced sheet's model
(:class:`~lightsail_mbs.solvers.reduced.sheet.SheetModel`: reference point, mass, inertia) and in the state;
its stem is one row of the connector arrays, run by the kernel's connector law; its tethers are the cables of
model.sheet_payload: tether j from the point l_j of tile k_j, p_a = X_k + u_k + R_k l_j, to the payload's
centre p_b = X_N + u_N, with d = p_b − p_a, ℓ = |d|, ℓ̇ = d̂·(v_N − v_k − ω_k × R_k l_j) and the tension
T = max(k(ℓ − ℓ₀) + c ℓ̇, 0) for ℓ > ℓ₀, else 0: +T d̂ on the tile at p_a (and its moment), −T d̂ on the
payload.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import sheet_payload, sheet_ride

STATE = 13  # u(3) q(4) v(3) ω_b(3) per body


@njit(cache=True)
def add_tethers(y, flat, R, W, F, T, payload, tile, point, rest, stiffness, damping):
    """Adds the tethers' forces and moments (global) on the tiles and the payload (body `payload`) to F, T."""
    bp = STATE * payload
    ra = np.empty(3)
    d = np.empty(3)
    for j in range(tile.shape[0]):
        k = tile[j]
        b = STATE * k
        for i in range(3):
            ra[i] = R[k, i, 0] * point[j, 0] + R[k, i, 1] * point[j, 1] + R[k, i, 2] * point[j, 2]
        for i in range(3):
            d[i] = (flat[payload, i] + y[bp + i]) - (flat[k, i] + y[b + i] + ra[i])
        length = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
        if length <= rest[j]:
            continue
        va0 = y[b + 7] + W[k, 1] * ra[2] - W[k, 2] * ra[1]
        va1 = y[b + 8] + W[k, 2] * ra[0] - W[k, 0] * ra[2]
        va2 = y[b + 9] + W[k, 0] * ra[1] - W[k, 1] * ra[0]
        rate = (d[0] * (y[bp + 7] - va0) + d[1] * (y[bp + 8] - va1) + d[2] * (y[bp + 9] - va2)) / length
        tension = stiffness * (length - rest[j]) + damping * rate
        if tension <= 0.0:
            continue
        f0, f1, f2 = tension * d[0] / length, tension * d[1] / length, tension * d[2] / length
        F[k, 0] += f0
        F[k, 1] += f1
        F[k, 2] += f2
        T[k, 0] += ra[1] * f2 - ra[2] * f1
        T[k, 1] += ra[2] * f0 - ra[0] * f2
        T[k, 2] += ra[0] * f1 - ra[1] * f0
        F[payload, 0] -= f0
        F[payload, 1] -= f1
        F[payload, 2] -= f2


def append_payload(model, payload) -> None:
    """Appends the payload (model.sheet_payload.SheetPayload, or None) to a SheetModel's per-body and connector
    arrays, and sets its tether arrays, `lit` (the tiles, which the physics terms load) and `dead` (−m_p g₀)."""
    N = model.tiles.count
    model.lit, model.dead = N, 0.0
    model.tethers = (np.zeros(0, np.int64), np.zeros((0, 3)), np.zeros(0), np.zeros(2))
    if payload is None:
        return
    model.dead = payload.frame_force
    model.flat = np.vstack([model.flat, payload.start])
    model.masses = np.append(model.masses, payload.mass)
    model.inertia = np.concatenate([model.inertia, payload.inertia[None]])
    model.inverse = np.concatenate([model.inverse, np.linalg.inv(payload.inertia)[None]])
    model.diagonal = np.append(model.diagonal, True)
    stem = payload.stem
    if stem is not None:
        gap = payload.start + stem["local_b"] - model.flat[stem["tile_a"]] - stem["local_a"]
        model.ta = np.append(model.ta, stem["tile_a"]).astype(np.int64)
        model.tb = np.append(model.tb, N).astype(np.int64)
        for name, row in (("la", stem["local_a"]), ("lb", stem["local_b"]), ("gap", gap)):
            setattr(model, name, np.ascontiguousarray(np.vstack([getattr(model, name), row])))
        for name, key in (("K", "stiffness"), ("Dm", "damping"), ("off", "offset")):
            setattr(model, name, np.ascontiguousarray(np.vstack([getattr(model, name), stem[key]])))
        model.frame = np.ascontiguousarray(np.concatenate([model.frame, np.eye(3)[None]]))
        model.framed = np.append(model.framed, False)
    law = np.array([payload.tether_stiffness, payload.tether_damping])
    tile, point = payload.tether_tile.astype(np.int64), np.ascontiguousarray(payload.tether_point)
    model.tethers = (tile, point, payload.tether_rest, law)


def split_bodies(params, lit: int, arrays: tuple) -> tuple[tuple, dict]:
    """The tiles' (centres, angles, velocities, angular velocities), each (T, lit, 3), of the bodies' arrays,
    and what the run's info records beside them: the payload's path and the ride histories (model.sheet_ride)."""
    centres, _, velocities, omega = arrays
    payload = sheet_payload.record(centres[:, lit:], velocities[:, lit:])
    tiles = tuple(a[:, :lit] for a in arrays)
    return tiles, {**payload, **sheet_ride.record(params, tiles[0], tiles[3], payload)}
