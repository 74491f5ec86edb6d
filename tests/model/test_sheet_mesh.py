"""The sheet as a mesh (model.sheet_mesh, model.planforms): the generic polygon mesh reproduces the grid's
arrays, the tiles' properties are the polygons', and the reduced solver's colouring is a distance-2 colouring."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import planforms, sheet, sheet_mesh
from lightsail_mbs.solvers.reduced.sheet import SheetModel
from lightsail_mbs.solvers.reduced.sheet_radau import distance2_colouring


def grid_polygons(nx, ny, length, width):
    """The n × ny grid as shared vertices and counter-clockwise cells."""
    xs, ys = np.linspace(0, length, nx + 1), np.linspace(0, width, ny + 1)
    vertices = np.array([(x, y) for y in ys for x in xs])
    v = lambda i, j: j * (nx + 1) + i  # noqa: E731
    cells = [[v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)] for j in range(ny) for i in range(nx)]
    return vertices, cells


def test_polygon_mesh_of_a_grid_is_the_rectangle_generator():
    """from_polygons, given the grid's cells, finds the rectangle generator's connections, boundary edges
    and tile properties (to round-off: its arithmetic differs, its order of edges too)."""
    nx, ny, L, W = 5, 3, 1.0, 0.6
    grid = sheet_mesh.rectangle(nx, ny, L, W)
    poly = sheet_mesh.from_polygons(*grid_polygons(nx, ny, L, W), across=(nx, ny))
    np.testing.assert_allclose(poly.centres, grid.centres, atol=1e-15)
    np.testing.assert_allclose(poly.areas, grid.areas, rtol=1e-12)
    np.testing.assert_allclose(poly.gyration, grid.gyration, rtol=1e-10, atol=1e-15)
    np.testing.assert_allclose(poly.lattice[poly.lattice.argmax()], grid.lattice[0], rtol=1e-12)

    def edges(m):
        return sorted(
            (tuple(sorted(p)), round(e, 12), round(s, 12), tuple(np.round(np.abs(d), 12)))
            for p, e, s, d in zip(m.pairs, m.edge_length, m.span, m.direction)
        )

    assert edges(poly) == edges(grid)

    def boundary(m):
        return sorted(
            (int(t), tuple(np.round(mk, 12)), tuple(np.round(n, 12)), round(e, 12), round(s, 12))
            for t, mk, n, e, s in zip(
                m.boundary_tile, m.boundary_marker, m.boundary_normal, m.boundary_length, m.boundary_span
            )
        )

    assert boundary(poly) == boundary(grid)


def test_polygon_properties_of_a_right_triangle():
    """A = ab/2, centroid (a/3, b/3), ∫x'² dA = a³b/36, ∫x'y' dA = −a²b²/72 (closed forms)."""
    a, b = 2.0, 3.0
    area, centre, g = sheet_mesh.polygon_properties(np.array([[0, 0], [a, 0], [0, b]], float))
    assert area == pytest.approx(a * b / 2)
    np.testing.assert_allclose(centre, [a / 3, b / 3])
    np.testing.assert_allclose(g, 12 / area * np.array([a**3 * b / 36, a * b**3 / 36, -(a**2) * b**2 / 72]))


def test_tiles_of_the_grid_are_the_cuboids():
    p = SailParameters(model="sheet", n=4, ny=3)
    t = sheet.Tiles.of(p)
    a, b, h = p.length / 4, p.width / 3, p.thickness
    m = p.density * h * a * b
    assert np.all(t.masses == m) and t.count == 12 == sheet.tile_count(p)
    expected = m / 12 * np.diag([b * b + h * h, a * a + h * h, a * a + b * b])
    np.testing.assert_array_equal(np.abs(t.inertias), np.broadcast_to(expected, (12, 3, 3)))


@pytest.mark.parametrize("shape", [(6, 6), (7, 3), (12, 1), (2, 2)])
def test_colouring_is_distance_two_and_minimal_on_grids(shape):
    """No two tiles of one colour share a neighbour; a grid of at least 3 × 3 takes 5 colours (a tile and
    its four neighbours all differ), a strip 3."""
    model = SheetModel(SailParameters(model="sheet", n=shape[0], ny=shape[1]))
    for group in model.groups:
        seen = set()
        for k in group:
            assert not (model.tiles.mesh.neighbours[k] & seen)
            seen |= model.tiles.mesh.neighbours[k]
    expected = {(6, 6): 5, (7, 3): 5, (12, 1): 3, (2, 2): 4}[shape]
    assert len(model.groups) == expected


def test_colouring_of_an_irregular_graph():
    """A star (one centre, six leaves) needs 7 colours at distance 2; a path 3."""
    star = [{0, *range(1, 7)}] + [{k, 0} for k in range(1, 7)]
    assert distance2_colouring(star).max() + 1 == 7
    path = [{k, k - 1, k + 1} & set(range(9)) for k in range(9)]
    colours = distance2_colouring(path)
    assert colours.max() + 1 == 3 and all(colours[k] != colours[k + 2] for k in range(7))


def test_planform_field():
    assert SailParameters(model="sheet", n=3, ny=2).planform == planforms.DEFAULT
    with pytest.raises(ParameterError, match="planform"):
        SailParameters(model="sheet", n=3, ny=2, planform="ellipse")
    with pytest.raises(ParameterError, match="planform"):
        SailParameters(model="torsion", n=3, planform="disc")
    assert "planform" not in SailParameters(model="sheet", n=3, ny=2).to_dict()
