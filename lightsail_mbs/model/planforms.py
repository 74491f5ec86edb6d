"""The sheet's planforms: the name a case gives (the field ``planform``) and the mesh generator behind it.

A planform is one function (n, ny, L, W) → :class:`~lightsail_mbs.model.sheet_mesh.Mesh` and one check of
the case's sizes; it is registered here by name, and everything else of the sheet (loads, connectors,
supports, edge tension, defects, both solvers, frames) reads only the mesh. ``PLANFORMS`` lists them; the
case's validation and the command line's choices are made from it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from lightsail_mbs.model import sheet_mesh, sheet_planforms


class Planform(NamedTuple):
    mesh: Callable  # (n, ny, length, width) → Mesh
    problems: Callable  # (n, ny, length, width) → [(field, value, allowed)] of a case it cannot mesh
    help: str  # how n, ny, L and W make the sail


def _rectangle_problems(n, ny, length, width) -> list:
    return []


PLANFORMS = {
    "rectangle": Planform(
        sheet_mesh.rectangle, _rectangle_problems, "L × W in n × ny rectangular tiles (0 ≤ x ≤ L, 0 ≤ y ≤ W)"
    ),
    "disc": Planform(
        sheet_planforms.disc,
        sheet_planforms.round_problems("disc", 3, 6),
        "diameter L (width = L), n tiles across it in rings, ny sectors",
    ),
    "hexagon": Planform(
        sheet_planforms.hexagon,
        sheet_planforms.round_problems("hexagon", 2, 1),
        "regular, corner to corner L along x (width = L), 6m² equilateral triangles, m = n // 2",
    ),
}
DEFAULT = "rectangle"


@lru_cache(maxsize=16)
def _mesh(planform: str, n: int, ny: int, length: float, width: float) -> sheet_mesh.Mesh:
    return PLANFORMS[planform].mesh(n, ny, length, width)


def mesh_of(p) -> sheet_mesh.Mesh:
    """The mesh of a sheet case (built once per planform and size)."""
    return _mesh(p.planform, int(p.n), int(p.ny), float(p.length), float(p.width))


def problems(p) -> list:
    """[(field, value, allowed)]: why the case's planform cannot be meshed at its sizes (empty if it can)."""
    return PLANFORMS[p.planform].problems(p.n, p.ny, p.length, p.width)


def mean_intensity(p) -> float:
    """Ī over a planform other than the rectangle: the area-weighted mean of the round Gaussian beam at the
    tile centres, Σ A_k I(c_k) / Σ A_k, so that the frame force cancels the flat sail's net radiation force
    exactly (the rectangle's closed form, model.derived, does so up to the grid's quadrature error)."""
    if math.isinf(p.beam_waist):
        return p.intensity
    m = mesh_of(p)
    r2 = (m.centres[:, 0] - p.beam_centre) ** 2 + (m.centres[:, 1] - p.sheet_beam_centre_y) ** 2
    local = p.intensity * np.exp(-2.0 * r2 / p.beam_waist**2)
    return float(np.sum(m.areas * local) / np.sum(m.areas))
