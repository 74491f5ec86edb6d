"""Round sails as meshes (model.sheet_mesh): the disc in polar tiles and the regular hexagon in equilateral
triangles, both centred in the L × L square (width = length).

Disc (planform "disc"): diameter L, n tiles across it, ny sectors
----------------------------------------------------------------
Rings of radial size Δr = L/n around a central regular ny-gon (radius Δr for even n, Δr/2 for odd n, so
that n tiles span the diameter), each ring cut into ny sectors by the radial lines θ_j = 2πj/ny; every
tile is the polygon of its corners (a trapezoid, the centre an ny-gon), so the mesh is orthogonal — the
line between two neighbours' centroids is radial or a chord about the bisector, and crosses their shared
edge at right angles — and its outer boundary is an ny-gon. All radii are scaled by
√((2π/ny)/sin(2π/ny)) so that the polygon has the disc's area πR² exactly (the boundary's area error is
what a plate's deflection feels first: a clamped plate's w₀ ∝ R⁴ ∝ area²).

Why polar tiles, not a masked grid: the clamped edge must be where the plate ends. On a grid masked to the
disc the clamped boundary is a staircase whose distance from the circle varies by up to a tile from tile to
tile, and its deflection does not converge monotonically. Measured (validation/circular_plates.md, clamped
disc under uniform pressure, centre deflection against pR⁴/(64D), in-house statics): the staircase of
square cells whose centre lies inside the disc (no cut cells: exact boundary areas would correct the mass
and load, not where the supports sit) is off by +18.6 %, −5.7 %, −0.32 %, −1.03 % at 9, 17, 33 and
65 cells across (69 to 3313 tiles); the polar tiles by +1.69 %, +0.89 %, +0.37 % at n × ny = 9 × 12,
17 × 24, 33 × 48 (49, 193, 769 tiles), monotonically (observed order 1.0–1.3; simply supported −5.3 %,
−1.3 %, −0.32 %, order 2.15).

Hexagon (planform "hexagon"): corner-to-corner diagonal L along x, triangles of side L/(2m), m = ⌊n/2⌋
---------------------------------------------------------------------------------------------------------
The regular hexagon with corners at distance L/2 from the centre (corners on the x axis; across flats
√3 L/2), cut into 6m² equilateral triangles on the triangular lattice (m = ⌊n/2⌋ triangle sides from the
centre to a corner; ny is not used). Equilateral triangles tile it exactly, their centroids are their
circumcentres, so the mesh is orthogonal with every connection's marker at its shared edge's midpoint,
and the boundary is the hexagon's own edges.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.model.sheet_mesh import Mesh, from_polygons


def disc(n: int, ny: int, length: float, width: float) -> Mesh:
    """The disc of diameter L in polar tiles (module docstring): n tiles across the diameter, ny sectors."""
    radius = 0.5 * length
    step = length / n
    rings = (n - 1) // 2  # annuli around the central polygon
    inner = radius - rings * step
    scale = math.sqrt((2.0 * math.pi / ny) / math.sin(2.0 * math.pi / ny))  # the polygon's area is πR²
    radii = scale * (inner + step * np.arange(rings + 1))
    theta = 2.0 * math.pi * np.arange(ny) / ny
    centre = np.array([0.5 * length, 0.5 * width])
    vertices = centre + (radii[:, None, None] * np.stack([np.cos(theta), np.sin(theta)], axis=-1)).reshape(-1, 2)

    def v(ring, j):
        return ring * ny + j % ny

    cells = [[v(0, j) for j in range(ny)]]
    cells += [[v(i - 1, j), v(i, j), v(i, j + 1), v(i - 1, j + 1)] for i in range(1, rings + 1) for j in range(ny)]
    return from_polygons(vertices, cells, across=(n, n))


def hexagon(n: int, ny: int, length: float, width: float) -> Mesh:
    """The regular hexagon of corner-to-corner diagonal L in 6m² equilateral triangles, m = ⌊n/2⌋ (module
    docstring); ny is not used."""
    m = max(1, n // 2)
    side = length / (2 * m)
    e1, e2 = np.array([side, 0.0]), np.array([0.5 * side, 0.5 * math.sqrt(3.0) * side])
    centre = np.array([0.5 * length, 0.5 * width])
    index, vertices = {}, []
    for i in range(-m, m + 1):
        for j in range(-m, m + 1):
            if max(abs(i), abs(j), abs(i + j)) <= m:
                index[(i, j)] = len(vertices)
                vertices.append(centre + i * e1 + j * e2)
    cells = []
    for i, j in ((i, j) for i in range(-m - 1, m + 1) for j in range(-m - 1, m + 1)):
        up = [(i, j), (i + 1, j), (i, j + 1)]
        down = [(i + 1, j), (i + 1, j + 1), (i, j + 1)]
        cells += [[index[q] for q in tri] for tri in (up, down) if all(q in index for q in tri)]
    return from_polygons(np.array(vertices), cells, across=(2 * m, 2 * m))


def round_problems(name: str, least_n: int, least_ny: int):
    """The size checks of a round planform: width = length (it is centred in the L × L square), n ≥ least_n,
    ny ≥ least_ny."""

    def problems(n, ny, length, width) -> list:
        out = []
        if width != length:
            out.append(("width", width, f"= length ({length:g} m) for a {name}: it is centred in the L × L square"))
        if n < least_n:
            out.append(("n", n, f"≥ {least_n} for a {name}"))
        if ny < least_ny:
            out.append(("ny", ny, f"≥ {least_ny} for a {name} (its sectors)"))
        return out

    return problems
