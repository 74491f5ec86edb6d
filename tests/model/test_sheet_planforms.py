"""The round planforms (model.sheet_planforms): the meshes' geometry, the flat tensioned sail's equilibrium,
circular-plate theory (statics and frequencies, the membrane) and the two solvers on them."""

import math

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import planforms, plate_theory, sheet, terms
from lightsail_mbs.solvers.exudyn import sheet as exudyn_sheet
from lightsail_mbs.solvers.reduced import sheet as reduced_sheet

PLATE = dict(model="sheet", length=1.0, width=1.0, thickness=0.01, youngs_modulus=1.2e9, intensity=0.0)
PLATE = dict(PLATE, defect_amplitude=0.0)


def shared_edge(mesh, a, b):
    """The two vertices tiles a and b share (their outlines' common points)."""
    pa, pb = mesh.outlines[a], mesh.outlines[b]
    common = [v for v in pa if np.min(np.linalg.norm(pb - v, axis=1)) < 1e-12]
    assert len(common) == 2
    return np.array(common)


@pytest.mark.parametrize(
    "planform, n, ny, area", [("disc", 9, 12, math.pi / 4), ("hexagon", 8, 1, 3 * math.sqrt(3) / 8)]
)
def test_meshes_are_orthogonal_and_exact_in_area(planform, n, ny, area):
    """The tiles fill the planform's area; every centre line crosses its shared edge at right angles, and
    its markers meet at the midpoint of the centres; the boundary closes (Σ e n̂ = 0)."""
    p = SailParameters(model="sheet", planform=planform, n=n, ny=ny, length=1.0, width=1.0)
    mesh = planforms.mesh_of(p)
    assert mesh.areas.sum() == pytest.approx(area, rel=1e-13)
    for (a, b), d, e in zip(mesh.pairs, mesh.direction, mesh.edge_length):
        v = shared_edge(mesh, a, b)
        assert abs(np.dot(v[1] - v[0], d)) < 1e-12 and np.linalg.norm(v[1] - v[0]) == pytest.approx(e)
    np.testing.assert_allclose(
        mesh.centres[mesh.pairs[:, 0]] + mesh.marker_a, mesh.centres[mesh.pairs[:, 1]] + mesh.marker_b
    )
    closure = (mesh.boundary_length[:, None] * mesh.boundary_normal).sum(axis=0)
    assert np.max(np.abs(closure)) < 1e-13
    assert sheet.tile_count(p) == mesh.count == len(sheet.flat_centres(p))


def test_round_planforms_check_their_sizes():
    with pytest.raises(ParameterError, match="width"):
        SailParameters(model="sheet", planform="disc", n=9, ny=12, length=1.0, width=0.5)
    with pytest.raises(ParameterError, match="ny"):
        SailParameters(model="sheet", planform="disc", n=9, ny=4, length=1.0, width=1.0)
    with pytest.raises(ParameterError, match="n="):
        SailParameters(model="sheet", planform="hexagon", n=1, ny=1, length=1.0, width=1.0)


@pytest.mark.parametrize("planform, n, ny", [("disc", 9, 12), ("hexagon", 8, 1)])
def test_flat_tensioned_round_sail_is_at_rest(planform, n, ny):
    """The pre-stressed connectors and the boundary followers balance on every tile (forces and moments):
    the flat sheet under the isotropic tension T is an exact equilibrium on any orthogonal mesh."""
    p = SailParameters(model="sheet", planform=planform, n=n, ny=ny, length=1.0, width=1.0, edge_tension=1e-3)
    centres, q = sheet.initial_quaternions(p.replace(defect_amplitude=0.0))
    loads = sheet.static_loads(p, sheet.connectors(p, centres, q), centres, q)
    assert np.max(np.abs(loads)) < 1e-12 * p.edge_tension * p.length


@pytest.mark.parametrize("boundary, factor", [("clamped", 1.0), ("simply_supported", 5.0)])
def test_circular_plate_under_pressure(boundary, factor):
    """w₀ = qR⁴/(64D) clamped, (5 + ν_p)qR⁴/(64(1 + ν_p)D) simply supported (ν_p = 0) within 2 % on
    17 × 24 polar tiles, and the two solvers' statics agree (a tilted support's frame in both)."""
    p = SailParameters(n=17, ny=24, pressure=0.01, boundary=boundary, planform="disc", **PLATE)
    exact = factor * p.pressure * 0.5**4 / (64 * plate_theory.bending_rigidity(p))
    reduced = reduced_sheet.static_centres(p)
    exudyn = exudyn_sheet.static_centres(p)
    centre = int(np.argmin(np.hypot(reduced[:, 0] - 0.5, reduced[:, 1] - 0.5)))
    assert reduced[centre, 2] == pytest.approx(exact, rel=0.02)
    assert np.max(np.abs(reduced[:, 2] - exudyn[:, 2])) < 1e-9 * exact


def test_clamped_circular_plate_frequencies():
    """λ² = 10.216, 21.26, 34.88 (ω = λ²√(D/(ρh))/R²) within 1 % on 33 × 48 polar tiles."""
    p = SailParameters(n=33, ny=48, boundary="clamped", planform="disc", **PLATE)
    omega = np.sort(reduced_sheet.eigenfrequencies(p, 6))
    scale = math.sqrt(plate_theory.bending_rigidity(p) / (p.density * p.thickness)) / 0.5**2
    np.testing.assert_allclose(omega[[0, 1, 3]] / scale, [10.216, 21.26, 34.88], rtol=0.01)
    assert omega[2] == pytest.approx(omega[1], rel=1e-6) and omega[4] == pytest.approx(omega[3], rel=1e-6)


def test_tensioned_circular_membrane():
    """ω₀₁ = 2.405 √(T/(ρh))/R within 1 % on 33 × 48 polar tiles."""
    membrane = dict(PLATE, thickness=1e-6, youngs_modulus=4.5e9, bending=False, edge_tension=1.0)
    p = SailParameters(n=33, ny=48, planform="disc", boundary="simply_supported", **membrane)
    omega = float(np.min(reduced_sheet.eigenfrequencies(p, 3)))
    assert omega == pytest.approx(2.405 * math.sqrt(1.0 / (p.density * p.thickness)) / 0.5, rel=0.01)


@pytest.mark.parametrize("planform, n, ny", [("disc", 9, 12), ("hexagon", 8, 1)])
def test_solvers_agree_on_a_round_sail_in_a_gaussian_beam(planform, n, ny):
    """Failure times of the two solvers within 1e-3 (relative) on a free round sail under a round Gaussian
    beam with edge tension and a 2-D defect."""
    p = SailParameters(
        model="sheet",
        planform=planform,
        n=n,
        ny=ny,
        length=1.0,
        width=1.0,
        youngs_modulus=4.5e9,
        beam_waist=0.6,
        edge_tension=1e-4,
        defect_mode_y=1.0,
    )
    settings = RunSettings(t_final=2e-3, output_interval=2e-5)
    times = [solve(p, s, settings, uncertainty=False).failure_time for s in ("reduced", "exudyn")]
    assert times[0] is not None and abs(times[1] - times[0]) < 1e-3 * times[0]


def test_mean_intensity_is_the_tiles_mean():
    """Ī over a round planform: the flat sail's net force (radiation minus frame force) vanishes."""
    p = SailParameters(
        model="sheet", planform="disc", n=9, ny=12, length=1.0, width=1.0, beam_waist=0.4, beam_centre=0.6
    )
    centres = sheet.flat_centres(p)
    forces = terms.tile_forces(p, centres, np.tile([0.0, 0.0, 1.0], (len(centres), 1)))
    assert abs(forces[:, 2].sum()) < 1e-12 * np.abs(forces[:, 2]).sum()


def test_a_sweep_runs_round_sails_under_their_own_keys(tmp_path):
    """The planform is part of a case's store key (left out at 'rectangle'); a sweep runs disc and hexagon."""
    from lightsail_mbs.studies.sweep import Case, run_sweep

    base = SailParameters(model="sheet", n=8, ny=8, length=1.0, width=1.0, youngs_modulus=4.5e9, beam_waist=0.6)
    settings = RunSettings(t_final=1e-4, output_interval=2e-5)
    cases = [Case(base.replace(planform=f), "reduced", settings=settings) for f in ("rectangle", "disc", "hexagon")]
    assert len({c.key for c in cases}) == 3
    assert Case(base, "reduced", settings=settings).key == cases[0].key
    records = run_sweep(cases, tmp_path, workers=1)
    assert [r["status"] for r in records] == ["ok"] * 3
    assert [r["tiles"] for r in records] == [64, 1 + 3 * 8, 6 * 16]
