"""The frame force the radiation term does not net: a payload's share.

The radiation term nets the frame force −c_n(0) Ī A/c b̂ of a sail accelerating at c_n(0) Ī/(c ρ h). With a
payload of mass m_p the craft accelerates at g₀ = c_n(0) Ī L W/(c (M + m_p)), so every slice carries the
difference c_n(0) Ī l W/c − m g₀ (loads.frame_force_excess), a physical O(f₀) push along the beam that the
stem carries; every tile k of a sheet likewise c_n(0) Ī A_k/c − m_k g₀ along z, which the stem or the tethers
carry (model.sheet_payload). The payload's own frame force −m_p g₀ acts on the composite slice (chain) or
the payload's body (sheet), where each solver applies it with the payload.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import loads
from lightsail_mbs.model.sheet_grid import Tiles
from lightsail_mbs.model.terms import uniform

ID = 2
FAMILIES = ("chain", "sheet")


def active(p) -> bool:
    return p.payload_mass != 0


def reads(p) -> int:
    return 0


def constants(p, family: str) -> np.ndarray:
    """Chain: [c_n(0) Ī l W/c − m g₀]; sheet: c_n(0) Ī A_k/c − m_k g₀ of every tile k."""
    return uniform.per_body(family, lambda: loads.frame_force_excess(p), lambda: _tile_excess(Tiles.of(p), p))


def _tile_excess(tiles: Tiles, p) -> np.ndarray:
    return p.normal_momentum * p.mean_intensity * tiles.areas / SPEED_OF_LIGHT - tiles.masses * p.nominal_acceleration


def chain(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds c_n(0) Ī l W/c − m g₀ along the beam on every slice (numpy form)."""
    forces[1] += loads.frame_force_excess(p)


def tiles(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds c_n(0) Ī A_k/c − m_k g₀ along the beam on every tile (numpy form)."""
    forces[2] += constants(p, "sheet")


@njit(cache=True)
def into(block, bodies, forces, tiles):
    """Adds the excess along the beam (y of a chain's slices, z of a sheet's tiles) on every body: the
    compiled form of both families."""
    uniform.add_along(block, forces, 2 if tiles else 1, not tiles)
