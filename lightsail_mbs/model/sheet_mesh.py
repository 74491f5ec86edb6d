"""The sheet as a mesh (model "sheet"): its tiles as arrays and the connections between them, whatever the
planform. Every sheet solver and the sheet's model read the tiles only through a :class:`Mesh`; a planform
is a function that returns one (:mod:`lightsail_mbs.model.planforms` names them).

Tiles
-----
Tile k is a flat rigid polygon of area A_k in the plane z = 0, its reference point at its centroid c_k (its
centre), its body axes the global ones in the flat state. Its mass is ρh A_k and its centroidal inertia that
of a thin plate of the polygon, J = (m/12) [[g_yy + h², −g_xy, 0], [−g_xy, g_xx + h², 0], [0, 0, g_xx + g_yy]]
with g = (12/A) ∫ (x'², y'², x'y') dA over the polygon about c_k (a rectangle a × b: g = (a², b², 0)).

Connections
-----------
Two tiles that share an edge of length e whose centres are a span s apart along the unit direction d
(a → b) are joined by one connector (model.sheet_connectors) with its markers at the midpoint of the two
centres, l_a = +s d/2 from c_a and l_b = −s d/2 from c_b: on a surface w = ½κ(d·x)² two tiles tangent at
their centres then meet at that midpoint exactly, so bending strains no transverse-shear spring (the
rectangle's patch test, model.sheet_connectors), which holds when the centre line crosses the shared edge
at right angles (an orthogonal mesh: rectangles, polar sectors, equilateral triangles). The springs'
stiffnesses scale with e/s, the two-point flux of a finite-volume Laplacian, consistent on such a mesh.

A boundary edge (an edge of one tile only) of length e and outward unit normal n̂ carries the supports and
the edge tension at the point c + t n̂ on the edge's line, t = (v − c)·n̂ the distance from the centre to it:
a support is the connector to a mirrored neighbour 2t away, and the follower tension T e n̂ acts on the line
through the centre (no moment about it, so that the flat tensioned sheet is an exact equilibrium).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True, eq=False)
class Mesh:
    """The tiles and connections of a flat sheet (module docstring); all lengths in m, in the sail's plane.

    Attributes
    ----------
    centres : ndarray (N, 2)
        Tile centres (centroids) of the flat sail.
    areas : ndarray (N,)
        Tile areas (m²).
    gyration : ndarray (N, 3)
        (g_xx, g_yy, g_xy) = (12/A) ∫ (x'², y'², x'y') dA about the centre (m²).
    outlines : tuple of ndarray (V, 2)
        Each tile's polygon, counter-clockwise.
    pairs : ndarray (E, 2)
        The tiles (a, b) of each shared edge.
    marker_a, marker_b : ndarray (E, 2)
        The connector's marker in tile a's and in tile b's axes (from the tile's centre).
    edge_length, span : ndarray (E,)
        The shared edge's length e and the centres' distance s.
    direction : ndarray (E, 2)
        Unit vector from centre a to centre b.
    boundary_tile : ndarray (B,)
        The tile of each boundary edge.
    boundary_marker : ndarray (B, 2)
        The support's marker and the tension's point in the tile's axes (on the edge's line).
    boundary_normal : ndarray (B, 2)
        Outward unit normal of the edge.
    boundary_length, boundary_span : ndarray (B,)
        The edge's length e and twice the centre's distance to it (the span to a mirrored neighbour).
    lattice : ndarray (N,)
        ½ Σ e/s over the tile's connections: the in-plane lattice's top frequency is bounded by
        ω_max² = 4 E_m h · lattice / m (Gershgorin; model.sheet_grid.Tiles).
    across : (float, float)
        Tiles along L and across W (the resolution the defect checks read).
    grid : (int, int) or None
        (nx, ny) when tile k = j·nx + i is cell (i, j) of a uniform rectangular grid, else None.
    cell : (float, float) or None
        The grid's cell (a, b), else None.
    """

    centres: np.ndarray
    areas: np.ndarray
    gyration: np.ndarray
    outlines: tuple
    pairs: np.ndarray
    marker_a: np.ndarray
    marker_b: np.ndarray
    edge_length: np.ndarray
    span: np.ndarray
    direction: np.ndarray
    boundary_tile: np.ndarray
    boundary_marker: np.ndarray
    boundary_normal: np.ndarray
    boundary_length: np.ndarray
    boundary_span: np.ndarray
    lattice: np.ndarray
    across: tuple
    grid: tuple | None = None
    cell: tuple | None = None
    neighbours: list = field(init=False, repr=False)

    def __post_init__(self):
        nbrs = [{k} for k in range(len(self.areas))]
        for a, b in self.pairs:
            nbrs[a].add(int(b))
            nbrs[b].add(int(a))
        object.__setattr__(self, "neighbours", nbrs)

    @property
    def count(self) -> int:
        return len(self.areas)

    def masses(self, density: float, thickness: float) -> np.ndarray:
        """(N,) tile masses ρ h A (kg)."""
        if self.cell is not None:
            a, b = self.cell
            return np.full(self.count, density * thickness * a * b)
        return density * thickness * self.areas

    def inertias(self, density: float, thickness: float) -> np.ndarray:
        """(N, 3, 3) centroidal inertia tensors of the thin tiles (module docstring), kg m²."""
        m = self.masses(density, thickness)
        h = thickness
        gxx, gyy, gxy = self.gyration.T
        J = np.zeros((self.count, 3, 3))
        J[:, 0, 0] = m / 12.0 * (gyy + h * h)
        J[:, 1, 1] = m / 12.0 * (gxx + h * h)
        J[:, 2, 2] = m / 12.0 * (gxx + gyy)
        J[:, 0, 1] = J[:, 1, 0] = -m / 12.0 * gxy
        return J


def polygon_properties(vertices: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """(A, centroid (2,), g (3,)) of a simple polygon (V, 2), counter-clockwise: the shoelace sums for the
    area, first and second moments (about the vertices' mean, against cancellation); g = (12/A) ∫ (x'², y'²,
    x'y') dA about the centroid."""
    origin = vertices.mean(axis=0)
    x, y = vertices[:, 0] - origin[0], vertices[:, 1] - origin[1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = 0.5 * cross.sum()
    cx = ((x + xn) * cross).sum() / (6.0 * area)
    cy = ((y + yn) * cross).sum() / (6.0 * area)
    ixx = ((x * x + x * xn + xn * xn) * cross).sum() / 12.0  # ∫ x² dA about the origin
    iyy = ((y * y + y * yn + yn * yn) * cross).sum() / 12.0
    ixy = ((x * yn + 2 * x * y + 2 * xn * yn + xn * y) * cross).sum() / 24.0
    g = 12.0 / area * np.array([ixx - area * cx * cx, iyy - area * cy * cy, ixy - area * cx * cy])
    return area, origin + np.array([cx, cy]), g


def from_polygons(vertices: np.ndarray, cells: list, across: tuple) -> Mesh:
    """The Mesh of tiles given as polygons over shared vertices: vertices (V, 2), cells a list of vertex index
    sequences (counter-clockwise). Edges are matched by their vertex pairs: one used twice is a connection
    (tile order, in order of first use), one used once a boundary edge (module docstring)."""
    vertices = np.asarray(vertices, float)
    props = [polygon_properties(vertices[list(c)]) for c in cells]
    areas = np.array([q[0] for q in props])
    centres = np.array([q[1] for q in props])
    gyration = np.array([q[2] for q in props])
    owners: dict = {}
    order = []
    for k, cell in enumerate(cells):
        for i, j in zip(cell, list(cell[1:]) + [cell[0]]):
            key = (min(i, j), max(i, j))
            if key not in owners:
                owners[key] = []
                order.append(key)
            owners[key].append((k, i, j))
    pairs, boundary = [], []
    for key in order:
        use = owners[key]
        if len(use) == 2:
            pairs.append((use[0][0], use[1][0], key))
        elif len(use) == 1:
            boundary.append(use[0])
        else:
            raise ValueError(f"edge {key} is shared by {len(use)} tiles")
    pa = np.array([[a, b] for a, b, _ in pairs], int).reshape(-1, 2)
    delta = centres[pa[:, 1]] - centres[pa[:, 0]]
    span = np.linalg.norm(delta, axis=1)
    edge = np.array([np.linalg.norm(vertices[i] - vertices[j]) for _, _, (i, j) in pairs])
    lattice = np.zeros(len(cells))
    np.add.at(lattice, pa.ravel(), np.repeat(0.5 * edge / span, 2))
    tiles = np.array([k for k, _, _ in boundary], int)
    start = vertices[[i for _, i, _ in boundary]]
    tangent = vertices[[j for _, _, j in boundary]] - start
    length = np.linalg.norm(tangent, axis=1)
    normal = np.column_stack([tangent[:, 1], -tangent[:, 0]]) / length[:, None]  # outward of a ccw polygon
    reach = np.einsum("ij,ij->i", start - centres[tiles], normal)
    return Mesh(
        centres=centres,
        areas=areas,
        gyration=gyration,
        outlines=tuple(vertices[list(c)] for c in cells),
        pairs=pa,
        marker_a=0.5 * delta,
        marker_b=-0.5 * delta,
        edge_length=edge,
        span=span,
        direction=delta / span[:, None],
        boundary_tile=tiles,
        boundary_marker=reach[:, None] * normal,
        boundary_normal=normal,
        boundary_length=length,
        boundary_span=2.0 * reach,
        lattice=lattice,
        across=across,
    )


def rectangle(n: int, ny: int, length: float, width: float) -> Mesh:
    """The rectangular grid of n × ny tiles a × b (a = L/n, b = W/ny) on 0 ≤ x ≤ L, 0 ≤ y ≤ W: tile (i, j),
    k = j·n + i, centred at ((i + ½)a, (j + ½)b); connections: the x-edges (row by row), then the y-edges;
    boundary edges: the left and right ends of each row, then the bottom and top of each column."""
    nx = n
    a, b = length / nx, width / ny
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="xy")
    x = (i.ravel() + 0.5) * length / nx
    y = (j.ravel() + 0.5) * width / ny
    N = nx * ny
    k = np.arange(N).reshape(ny, nx)
    x_pairs = np.column_stack([k[:, :-1].ravel(), k[:, 1:].ravel()])
    y_pairs = np.column_stack([k[:-1, :].ravel(), k[1:, :].ravel()])
    ex, ey = len(x_pairs), len(y_pairs)
    sides = [(jj * nx + ii, s, 0) for jj in range(ny) for ii, s in ((0, -1.0), (nx - 1, 1.0))]
    sides += [(jj * nx + ii, s, 1) for ii in range(nx) for jj, s in ((0, -1.0), (ny - 1, 1.0))]
    normal = np.array([(s, 0.0) if axis == 0 else (0.0, s) for _, s, axis in sides]).reshape(-1, 2)
    half = np.array([(s * 0.5 * a, 0.0) if axis == 0 else (0.0, s * 0.5 * b) for _, s, axis in sides]).reshape(-1, 2)
    corners = np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]) * (a, b)
    centres = np.column_stack([x, y])
    return Mesh(
        centres=centres,
        areas=np.full(N, a * b),
        gyration=np.tile([a * a, b * b, 0.0], (N, 1)),
        outlines=tuple(c + corners for c in centres),
        pairs=np.concatenate([x_pairs, y_pairs]).astype(int),
        marker_a=np.array([(0.5 * a, 0.0)] * ex + [(0.0, 0.5 * b)] * ey).reshape(-1, 2),
        marker_b=np.array([(-0.5 * a, 0.0)] * ex + [(0.0, -0.5 * b)] * ey).reshape(-1, 2),
        edge_length=np.array([b] * ex + [a] * ey),
        span=np.array([a] * ex + [b] * ey),
        direction=np.array([(1.0, 0.0)] * ex + [(0.0, 1.0)] * ey).reshape(-1, 2),
        boundary_tile=np.array([t for t, _, _ in sides], int),
        boundary_marker=half,
        boundary_normal=normal,
        boundary_length=np.array([b if axis == 0 else a for _, _, axis in sides]),
        boundary_span=np.array([a if axis == 0 else b for _, _, axis in sides]),
        lattice=np.full(N, b / a + a / b),
        across=(nx, ny),
        grid=(nx, ny),
        cell=(a, b),
    )
