"""A force per body along one axis, the same for every slice of a chain or one value per tile of a sheet:
the shared shape of the body-force and frame terms (their constants, numpy and compiled forms).

A chain's slices are alike, so its block holds one value; a sheet's block holds one value per tile k.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from lightsail_mbs.base.kernels import njit


def per_body(family: str, chain_value: Callable[[], float], tile_values: Callable[[], np.ndarray]) -> np.ndarray:
    """The block of constants: [chain_value()] for a chain, tile_values() (N values) for a sheet."""
    return np.array([chain_value()]) if family == "chain" else tile_values()


@njit(cache=True)
def add_along(block, forces, row, alike):
    """forces[row, k] += block[0] (alike: every body the same) or block[k], for every body k (compiled)."""
    for k in range(forces.shape[1]):
        forces[row, k] += block[0] if alike else block[k]
