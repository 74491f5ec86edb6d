"""The frame force the radiation term does not net: a payload's share.

The radiation term nets the frame force −c_n(0) Ī A/c b̂ of a sail accelerating at c_n(0) Ī/(c ρ h). With a
payload of mass m_p the craft accelerates at g₀ = c_n(0) Ī L W/(c (M + m_p)), so every slice carries the
difference c_n(0) Ī l W/c − m g₀ (loads.frame_force_excess), a physical O(f₀) push along the beam that the
stem carries. Chain only (a sheet has no payload); the payload's own frame force −m_p g₀ acts on the
composite slice, where each solver applies it with the payload's body.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import loads

ID = 2
FAMILIES = ("chain",)


def active(p) -> bool:
    return p.payload_mass != 0


def reads(p) -> int:
    return 0


def constants(p, family: str) -> np.ndarray:
    return np.array([loads.frame_force_excess(p)])


def chain(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds c_n(0) Ī l W/c − m g₀ along the beam on every slice (numpy form)."""
    forces[1] += loads.frame_force_excess(p)


@njit(cache=True)
def chain_into(block, bodies, forces):
    """Adds c_n(0) Ī l W/c − m g₀ along the beam on every slice (compiled form)."""
    excess = block[0]
    for i in range(forces.shape[1]):
        forces[1, i] += excess
