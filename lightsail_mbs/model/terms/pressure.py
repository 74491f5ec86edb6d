"""A dead pressure p along the beam (+z) on the sheet's tiles (the plate validations): p A_k ẑ on each tile k,
whatever its orientation."""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model.sheet_grid import Tiles

ID = 3
FAMILIES = ("sheet",)


def active(p) -> bool:
    return p.pressure != 0


def reads(p) -> int:
    return 0


def constants(p, family: str) -> np.ndarray:
    """p A_k of every tile k (N)."""
    return p.pressure * Tiles.of(p).areas


def tiles(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds p A_k ẑ on every tile (numpy form)."""
    forces[2] += constants(p, "sheet")


@njit(cache=True)
def tiles_into(block, bodies, forces):
    """Adds p A_k ẑ on every tile (compiled form)."""
    for k in range(forces.shape[1]):
        forces[2, k] += block[k]
