"""The sheet's model: grid and defects, the edge springs against the ν_p = 0 plate (patch tests), the
membrane-stress-free initial shape, the chain limit of its geometry, and the tile load against the
facet law and its small-slope series."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, SailParameters
from lightsail_mbs.model import loads, shapes, sheet, terms

C = 299_792_458.0
rng = np.random.default_rng(11)


def sheet_case(**changes) -> SailParameters:
    return SailParameters(model="sheet", **{"n": 7, "ny": 5, "youngs_modulus": 4.5e9, **changes})


@pytest.mark.parametrize(
    "changes",
    [dict(), dict(defect_mode_y=1.5), dict(defect_mode_y=1.0, defect_seed=3, defect_mode_count=3), dict(defect_seed=2)],
    ids=["1-D sine", "doubly sinusoidal", "2-D multi-mode", "1-D multi-mode"],
)
def test_initial_shape_is_membrane_stress_free(changes):
    """membrane_reference='initial': every translational spring is at rest in the initial shape, to the
    round-off of small quantities (1e-21 m), not of 1 m coordinates (1e-16 m)."""
    p = sheet_case(**changes)
    centres, q = sheet.initial_quaternions(p)
    conn = sheet.connectors(p, centres, q)
    d = sheet.relative_displacement(
        conn.tile_a, conn.tile_b, conn.local_a, conn.local_b, centres, q, sheet.flat_centres(p), conn.gap
    )
    assert np.max(np.abs(d)) < 1e-20 and not conn.offset.any()  # at rest, with the markers coinciding
    if p.defect_mode_y is None:  # exact chords: the hinges of a 1-D defect coincide, nothing to move
        assert np.max(np.abs(conn.gap)) < 1e-15
    else:  # a doubly curved defect does not fit the flat grid's midpoints: B's markers moved
        assert np.max(np.abs(conn.gap)) > 1e-12


def test_marker_points_coincide_on_the_flat_grid():
    p = sheet_case(boundary="clamped")
    conn = sheet.connectors(p)
    flat = sheet.flat_centres(p)
    a = np.where(conn.tile_a[:, None] < 0, conn.local_a, flat[np.maximum(conn.tile_a, 0)] + conn.local_a)
    np.testing.assert_allclose(flat[conn.tile_b] + conn.local_b - a, conn.gap, atol=4e-16)  # round-off of 1 m sums
    flat_case = sheet.connectors(p.replace(defect_amplitude=0.0))
    assert not flat_case.gap.any()
    nx, ny = p.n, p.ny
    assert len(conn) == ny * (nx - 1) + nx * (ny - 1) + 2 * (nx + ny)


@pytest.mark.parametrize("kind", ["bending", "twist"])
def test_edge_springs_store_the_plate_energy_with_poisson_ratio_zero(kind):
    """Patch tests: tiles on w = ½κx² or w = κxy, turned to its slope. The bending and twist springs store
    exactly the ν_p = 0 Kirchhoff energy ½D∫(w_xx² + w_yy² + 2w_xy²) of the area their edges span; the
    ν_p ≠ 0 energy of the twist would be (1 − ν_p) times it, so the match fixes ν_p = 0."""
    p = sheet_case(n=6, ny=4, defect_amplitude=0.0, membrane_reference="flat")
    t = sheet.Tiles.of(p)
    flat = sheet.flat_centres(p)
    x, y = flat[:, 0], flat[:, 1]
    kappa = 1e-3
    if kind == "bending":
        wx, wy = kappa * x, 0 * x
        density = 0.5 * t.bending_rigidity * kappa**2  # ½ D w_xx²
        area = (p.n - 1) * t.a * p.width  # the interior x-edges' cells
    else:
        wx, wy = kappa * y, kappa * x
        density = t.bending_rigidity * kappa**2  # ½ D · 2 w_xy²
        area = 0.5 * ((p.n - 1) * t.a * p.width + (p.ny - 1) * t.b * p.length)
    R = sheet.tilt_rotation(np.column_stack([-wx, -wy, np.ones_like(x)]))
    q = sheet.tilt_quaternion(np.column_stack([-wx, -wy, np.ones_like(x)]))
    np.testing.assert_allclose(sheet.quaternion_rotation(q), R, atol=1e-15)
    conn = sheet.connectors(p)
    relative = np.einsum("kji,kjl->kil", R[conn.tile_a], R[conn.tile_b])
    phi = sheet.angles_xyz(relative)
    energy = 0.5 * np.sum(conn.stiffness[:, 3:5] * phi[:, :2] ** 2)
    assert energy == pytest.approx(density * area, rel=1e-5)


def test_membrane_springs_store_the_stretch_energy():
    """Uniform stretch ε along x: ½ E_m h ε² per unit area of the cells the x-edges span."""
    p = sheet_case(n=5, ny=3, defect_amplitude=0.0, membrane_modulus=2e9)
    t = sheet.Tiles.of(p)
    conn = sheet.connectors(p)
    eps = 1e-6
    flat = sheet.flat_centres(p)
    centres = flat * np.array([1 + eps, 1, 1])
    d = sheet.relative_displacement(
        conn.tile_a, conn.tile_b, conn.local_a, conn.local_b, centres, np.tile([1.0, 0, 0, 0], (15, 1)), flat
    )
    energy = 0.5 * np.sum(conn.stiffness[:, :3] * d**2)
    assert energy == pytest.approx(0.5 * 2e9 * p.thickness * eps**2 * (p.n - 1) * t.a * p.width, rel=1e-9)


def test_one_dimensional_defect_is_the_chain_in_every_row():
    """A 1-D defect: every row of tiles is the chain's exact-chord shape (x, w, θ of shapes.initial_state)."""
    p = sheet_case(n=30, ny=3)
    centres, R = sheet.initial_state(p)
    chain = shapes.initial_state(sheet.as_strip(p))
    for j in range(p.ny):
        row = slice(j * p.n, (j + 1) * p.n)
        np.testing.assert_array_equal(centres[row, 0], chain.x)
        np.testing.assert_array_equal(centres[row, 2], chain.y)
        np.testing.assert_allclose(np.arctan2(R[row, 2, 0], R[row, 0, 0]), chain.theta, rtol=1e-15)


def test_doubly_sinusoidal_defect_and_the_normals():
    p = sheet_case(n=12, ny=10, defect_mode_y=0.5)
    centres, R = sheet.initial_state(p)
    x, y = centres[:, 0], centres[:, 1]
    kx, ky = 2 * np.pi * 1.5, 2 * np.pi * 0.5
    np.testing.assert_allclose(centres[:, 2], p.defect_amplitude * np.sin(kx * x) * np.sin(ky * y), rtol=1e-15)
    normal = np.column_stack(
        [
            -p.defect_amplitude * kx * np.cos(kx * x) * np.sin(ky * y),
            -p.defect_amplitude * ky * np.sin(kx * x) * np.cos(ky * y),
            np.ones_like(x),
        ]
    )
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    np.testing.assert_allclose(R[:, :, 2], normal, atol=1e-15)
    np.testing.assert_allclose(np.einsum("kij,kil->kjl", R, R), np.broadcast_to(np.eye(3), R.shape), atol=1e-15)
    # twist-free: the tile's x axis stays in the plane spanned by x̂ and the normal's tilt
    assert np.all(R[:, 0, 0] > 0.99)


def test_random_two_dimensional_defect_is_seeded_and_scaled():
    """Seeded: the same seed gives the same defect, another seed another one; RMS a₀/2 over the sail."""
    p = sheet_case(n=8, ny=8, defect_mode_y=1.0, defect_seed=5, defect_mode_count=4)
    w = sheet.defect_surface(p)[0]
    xs = np.linspace(0, 1, 401)
    grid = w(xs[:, None], xs[None, :])
    rms = math.sqrt(np.trapezoid(np.trapezoid(grid**2, xs, axis=1), xs))
    assert rms == pytest.approx(0.5 * p.defect_amplitude, rel=1e-3)
    again = sheet.defect_surface(p)[0](xs[:, None], xs[None, :])
    other = sheet.defect_surface(p.replace(defect_seed=6))[0](xs[:, None], xs[None, :])
    np.testing.assert_array_equal(grid, again)
    assert np.max(np.abs(other - grid)) > 0.1 * p.defect_amplitude
    # the derivatives are those of w
    wx = sheet.defect_surface(p)[1]
    h = 1e-6
    assert wx(0.3, 0.7) == pytest.approx((w(0.3 + h, 0.7) - w(0.3 - h, 0.7)) / (2 * h), rel=1e-6)


def test_tile_forces_are_the_facet_law_minus_the_frame_force():
    """At finite tilts the net tile force equals (I ab/c) cos θ [2R cos θ n + α ẑ] − (2R + α) Ī ab/c ẑ + p ab ẑ
    summed naively (which loses nothing that matters there), for a round Gaussian beam off centre."""
    p = sheet_case(beam_waist=0.6, beam_centre=0.3, beam_centre_y=0.7, reflectivity=0.7, absorptivity=0.2, pressure=0.3)
    t = sheet.Tiles.of(p)
    centres = sheet.flat_centres(p) + rng.normal(0, 0.02, (35, 3))
    normal = rng.normal(0, 0.3, (35, 3)) + [0, 0, 1]
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    f = terms.tile_forces(p, centres, normal)
    local = p.intensity * np.exp(-2 * ((centres[:, 0] - 0.3) ** 2 + (centres[:, 1] - 0.7) ** 2) / 0.36)
    cos = normal[:, 2]
    expected = (local * t.area / C * cos)[:, None] * (2 * 0.7 * cos[:, None] * normal + [0, 0, 0.2])
    expected[:, 2] += -(2 * 0.7 + 0.2) * p.mean_intensity * t.area / C + 0.3 * t.area
    np.testing.assert_allclose(f, expected, rtol=1e-12, atol=1e-14 * p.intensity * t.area / C)


@pytest.mark.parametrize("tilt", [1e-3, 1e-6, 1e-9])
def test_tile_force_keeps_its_digits_at_small_tilts(tilt):
    """Mirror, uniform beam, a tile tilted by θ about an oblique axis: f_z = −f₀(1 − cos³θ) to a few ulps
    (the naive f₀cos³θ − m g₀ has no digit left at θ = 1e-9)."""
    p = sheet_case()
    t = sheet.Tiles.of(p)
    f0 = 2 * p.intensity / C * t.area
    axis = np.array([0.6, 0.8])
    normal = np.array([[math.sin(tilt) * axis[1], -math.sin(tilt) * axis[0], math.cos(tilt)]])
    f = terms.tile_forces(p, np.array([[0.5, 0.5, 0.0]]), normal)[0]
    series = -f0 * (1.5 * tilt**2 - 0.875 * tilt**4)
    assert f[2] == pytest.approx(series, rel=8e-16 + tilt**4)
    np.testing.assert_allclose(f[:2], f0 * math.cos(tilt) ** 2 * normal[0, :2], rtol=1e-15)


def test_one_facet_law_for_chain_and_sheet():
    """The chain's slice force (radiation + frame force summed in floating point) is the sheet's law for a
    normal in the x–z plane (beam ŷ ↔ ẑ) to round-off of f₀, and the compiled twin is the array form."""
    chain = SailParameters(n=10, intensity=1e9, reflectivity=0.6, absorptivity=0.3, beam_waist=0.5)
    theta = rng.uniform(-0.5, 0.5, 10)
    x = rng.uniform(0, 1, 10)
    fx, fy = loads.net_slice_forces(chain, x, theta)
    across, along = loads.facet_forces(
        np.column_stack([-np.sin(theta), 0 * theta]),
        np.cos(theta),
        loads.intensity(chain, x),
        chain.mean_intensity,
        chain.slice_length * chain.width,
        0.6,
        0.3,
    )
    f0 = chain.flat_force
    np.testing.assert_allclose(across[:, 0], fx, rtol=0, atol=1e-14 * f0)
    np.testing.assert_allclose(along, fy, rtol=0, atol=1e-14 * f0)
    assert not across[:, 1].any()
    for k in range(10):
        n = (-np.sin(theta[k]) * 0.6, -np.sin(theta[k]) * 0.8, np.cos(theta[k]))
        compiled = loads.net_facet_force(*n, 2e9, 1.5e9, 0.01 / C, 0.6, 0.3)
        a, b = loads.facet_forces(np.array([n[:2]]), np.array([n[2]]), 2e9, 1.5e9, 0.01, 0.6, 0.3)
        np.testing.assert_allclose(compiled, [a[0, 0], a[0, 1], b[0]], rtol=1e-14)


def test_sheet_mean_intensity_is_the_round_beams_mean():
    p = sheet_case(beam_waist=0.7, beam_centre=0.2, beam_centre_y=0.9, width=1.5)
    xs, ys = np.linspace(0, 1, 801), np.linspace(0, 1.5, 1201)
    grid = loads.sheet_intensity(p, xs[:, None], ys[None, :])
    mean = np.trapezoid(np.trapezoid(grid, ys, axis=1), xs) / 1.5
    assert p.mean_intensity == pytest.approx(mean, rel=1e-6)
    assert p.nominal_acceleration == pytest.approx(2 * mean / (C * p.density * p.thickness), rel=1e-6)


def test_as_strip_is_the_torsion_chain():
    p = sheet_case(n=30, ny=4, defect_seed=3)
    chain = sheet.as_strip(p)
    assert chain.model == "torsion" and chain.n == 30 and chain.defect_seed == 3
    assert chain.torsional_stiffness == pytest.approx(
        sum([sheet.Tiles.of(p).bending_rigidity * p.width / p.ny / (1 / 30)] * 4)
    )
    with pytest.raises(ParameterError, match="sheet"):
        sheet.as_strip(chain)


def test_grid_warnings():
    notes = sheet.defect_warnings(sheet_case(n=40, ny=4, defect_mode_y=1.5), 1e-5)
    assert len(notes) == 1 and "ny = 4" in notes[0]
    coarse = sheet.defect_warnings(sheet_case(n=40, ny=12, defect_mode_y=1.5), 1e-5)
    assert len(coarse) == 1 and "4 tiles per half wavelength of the doubly curved defect" in coarse[0]
    assert sheet.defect_warnings(sheet_case(n=40, ny=24, defect_mode_y=1.5), 1e-5) == []
    along_x = sheet.defect_warnings(sheet_case(n=6, ny=24, defect_mode_y=1.5), 1e-5)
    assert len(along_x) == 1 and "n = 6 gives 2 tiles per half wavelength" in along_x[0]
    assert sheet.defect_warnings(sheet_case(n=18, ny=1), 1e-5) == []  # a 1-D sine: no 2-D note


def _rigid_part_removed(p, loads_):
    """The tile loads (N, 6) less their least-squares fit by rigid-body load patterns (net force and
    moment: what no internal pre-stress can cancel on a free sheet)."""
    centres, _ = sheet.initial_quaternions(p)
    rigid = np.zeros((loads_.size, 6))
    for i in range(3):
        axis = np.eye(3)[i]
        rigid[i::6, i] = 1.0
        rigid[0::6, 3 + i], rigid[1::6, 3 + i], rigid[2::6, 3 + i] = np.cross(axis, centres).T
        rigid[3 + i :: 6, 3 + i] = 1.0
    r = loads_.ravel()
    return r - rigid @ np.linalg.lstsq(rigid, r, rcond=None)[0]


@pytest.mark.parametrize(
    "changes",
    [
        dict(defect_mode_y=1.5, edge_tension=2e-5),  # doubly curved under tension
        dict(edge_tension=2e-5),  # the 1-D sine under tension
        dict(defect_mode_y=1.0),  # doubly curved, bending springs at rest flat
        dict(defect_mode_y=1.0, boundary="simply_supported", edge_tension=2e-5),  # no rigid modes
    ],
)
def test_initial_equilibrium_cancels_the_unlit_loads(changes):
    """initial_equilibrium: the corrected rest offsets leave no internal load on any tile in the initial
    shape but a rigid-body remainder (net force and moment of the followers on a curved edge), down from
    loads that set the sheet moving."""
    p = sheet_case(**changes)
    q = p.replace(initial_equilibrium=True)
    centres, quats = sheet.initial_quaternions(p)
    before = sheet.static_loads(p, sheet.connectors(p), centres, quats)
    after = sheet.static_loads(q, sheet.connectors(q), centres, quats)
    assert np.abs(before).max() > 0
    assert np.abs(_rigid_part_removed(p, after)).max() < 1e-9 * np.abs(before).max()
    if p.boundary != "free":
        assert np.abs(after).max() < 1e-9 * np.abs(before).max()
    # the rest strains change, the springs do not
    assert np.array_equal(sheet.connectors(p).stiffness, sheet.connectors(q).stiffness)


def test_static_loads_are_the_solvers_connector_law():
    """model.sheet.static_loads (numpy) against the in-house solver's compiled right-hand side at rest."""
    from lightsail_mbs.solvers.reduced import sheet as reduced_sheet

    p = sheet_case(defect_mode_y=1.5, edge_tension=3e-5, intensity=0.0, bending_reference="flat")
    model = reduced_sheet.SheetModel(p)
    rates = model.rhs(0.0, model.y0()).reshape(-1, reduced_sheet.STATE)
    centres, quats = sheet.initial_quaternions(p)
    loads_ = sheet.static_loads(p, model.conn, centres, quats)
    np.testing.assert_allclose(
        rates[:, 7:10] * model.tiles.mass, loads_[:, :3], rtol=1e-6, atol=1e-6 * np.abs(loads_[:, :3]).max()
    )
    torque_body = np.einsum("kji,kj->ki", sheet.quaternion_rotation(quats), loads_[:, 3:])
    np.testing.assert_allclose(
        rates[:, 10:] * model.tiles.inertia, torque_body, rtol=1e-6, atol=1e-6 * np.abs(torque_body).max()
    )


def test_initial_equilibrium_is_a_flag():
    with pytest.raises(ParameterError, match="initial_equilibrium"):
        sheet_case(initial_equilibrium=1)
    with pytest.raises(ParameterError, match="initial_equilibrium"):
        SailParameters(initial_equilibrium=True)
