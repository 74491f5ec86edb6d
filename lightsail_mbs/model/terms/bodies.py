"""What every physics term reads and writes: the bodies of a family as rows of one array, the header of the
packed constants, and what a term may ask the kernels to compute for it.

A chain's bodies are its n slices; a sheet's are its N tiles. Their state reaches a term as one float
array ``bodies`` of shape (rows, …, count): row ``r`` is that quantity for every body (numpy forms may carry
leading axes of time or of a batch; compiled forms get (rows, count)). Forces go out the same way:
``forces`` (2, …, n) for the chain (x along the sail, y along the beam), (3, …, N) for the sheet (z along
the beam), in inertial directions at the body centres, in the frame accelerating with the flat sail.
"""

from __future__ import annotations

import numpy as np

# ---- the chain's slices: centre (x, y), angle θ with its cosine and sine, centre velocity, angular velocity
CHAIN_ROWS = 8
X, Y, THETA, COS, SIN, VX, VY, OMEGA = range(CHAIN_ROWS)

# ---- the sheet's tiles: centre, unit normal R ẑ (its x, y components computed without cancellation, from the
# small entries of R − I), centre velocity, angular velocity, the tile's in-plane axis R x̂ (global axes)
TILE_ROWS = 15
TX, TY, TZ, N1, N2, NB, TVX, TVY, TVZ, TWX, TWY, TWZ, E1X, E1Y, E1Z = range(TILE_ROWS)

# ---- the packed constants: [count, reads, then per active term: its ID, its block's size, its block]
COUNT, READS = 0, 1
HEADER = 2
ENTRY = 2  # ID and size before each block
# what a term reads beyond the angles (chain) or normals (sheet), bits of the header's READS: the kernels
# may compute positions, velocities and the tiles' in-plane axes only when an active term reads them
POSITIONS, VELOCITIES, AXES = 1, 2, 4


def chain_bodies(x, theta, y=None, vx=None, vy=None, omega=None) -> np.ndarray:
    """The (CHAIN_ROWS, …, n) bodies array of slice states (numpy forms); rows not given are 0."""
    theta = np.asarray(theta, float)
    bodies = np.zeros((CHAIN_ROWS, *theta.shape))
    bodies[X] = x
    bodies[THETA] = theta
    bodies[COS] = np.cos(theta)
    bodies[SIN] = np.sin(theta)
    for row, value in ((Y, y), (VX, vx), (VY, vy), (OMEGA, omega)):
        if value is not None:
            bodies[row] = value
    return bodies


def tile_bodies(centres, normals, velocities=None, angular_velocities=None, axes=None) -> np.ndarray:
    """The (TILE_ROWS, …, N) bodies array of tile states given as (…, N, 3) arrays (numpy forms); `axes` are the
    tiles' in-plane x axes R x̂ (rows left 0 when not given: only a term that reads them needs them)."""
    centres = np.asarray(centres, float)
    bodies = np.zeros((TILE_ROWS, *centres.shape[:-1]))
    bodies[TX : TZ + 1] = np.moveaxis(centres, -1, 0)
    bodies[N1 : NB + 1] = np.moveaxis(np.asarray(normals, float), -1, 0)
    if velocities is not None:
        bodies[TVX : TVZ + 1] = np.moveaxis(np.asarray(velocities, float), -1, 0)
    if angular_velocities is not None:
        bodies[TWX : TWZ + 1] = np.moveaxis(np.asarray(angular_velocities, float), -1, 0)
    if axes is not None:
        bodies[E1X : E1Z + 1] = np.moveaxis(np.asarray(axes, float), -1, 0)
    return bodies
