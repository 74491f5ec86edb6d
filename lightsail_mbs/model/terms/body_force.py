"""A uniform in-plane body force per unit mass b along the sail's length (x̂): m b x̂ on every body.

A test load of the physics-term seam with a closed form: it acts on every body in proportion to its mass
and does not depend on the shape, so on a free sail in a uniform beam it only translates the sail,
x(t) = x_b=0(t) + b t²/2 for every body, and leaves its shape, its angles and the failure time as they are
(tests/model/test_body_force.py, both solvers of both families). The frame stays the one accelerating
along the beam at g₀; the body force is in-plane, so it changes no load of the beam's direction.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model.sheet_grid import Tiles
from lightsail_mbs.model.terms import uniform

ID = 4
FAMILIES = ("chain", "sheet")


def active(p) -> bool:
    return p.body_force != 0


def reads(p) -> int:
    return 0


def constants(p, family: str) -> np.ndarray:
    """m b: the force on each slice (m = ρ h W l, one value) or on each tile k (m_k = ρ h A_k, N values), N."""
    return uniform.per_body(family, lambda: p.slice_mass * p.body_force, lambda: Tiles.of(p).masses * p.body_force)


def chain(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds m b x̂ on every slice (numpy form)."""
    forces[0] += constants(p, "chain")[0]


def tiles(p, bodies: np.ndarray, forces: np.ndarray) -> None:
    """Adds m_k b x̂ on every tile (numpy form)."""
    forces[0] += constants(p, "sheet")


@njit(cache=True)
def into(block, bodies, forces, tiles):
    """Adds m b x̂ on every slice or m_k b x̂ on every tile: the compiled form of both families."""
    uniform.add_along(block, forces, 0, not tiles)
