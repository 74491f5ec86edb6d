"""The grating term (model/terms/grating.py, model/sheet_grating.py): in-plane optical pressures on a sheet's
tiles by sectors — its layout files, the rigid tilted sail against the law by hand, both solvers' kernels, zero
coefficients as today's load to the bit, and the two solvers on a lit, spinning grating disc."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters
from lightsail_mbs.analysis.ride3d import sheet_ride
from lightsail_mbs.model import sheet, sheet_grating, terms
from lightsail_mbs.model.sheet_grid import rotation_xyz
from lightsail_mbs.solvers import contract
from lightsail_mbs.solvers.exudyn.sheet import SheetSystem
from lightsail_mbs.solvers.reduced.sheet import SheetModel
from tests.model.grating_layouts import CUBIC, PIZZA, QUINTIC, TE, TM, WIDE, ZERO, write

C = 299_792_458.0
PLATE = SailParameters(model="sheet", n=6, ny=4, length=0.8, width=0.6, youngs_modulus=4.5e9, intensity=1e9)
DISC = SailParameters(model="sheet", planform="disc", n=5, ny=8, youngs_modulus=4.5e9, intensity=1e9)


def law(coefficients, u1, u2) -> np.ndarray:
    """(c_g, c_l, c_n) of a sector's law at the direction cosines (u₁, u₂), by hand: the k-th coefficient of
    degree n multiplies u₁^(n − k) u₂^k."""
    out = []
    for c in coefficients:
        exponents = [(n - k, k) for n in range(10) for k in range(n + 1)][: len(c)]
        out.append(sum(v * u1**a * u2**b for v, (a, b) in zip(c, exponents)))
    return np.array(out)


def cross2(a, b) -> float:
    return a[0] * b[1] - a[1] * b[0]


def rigid(p, angles):
    """Centres, normals and in-plane axes of the flat sheet turned rigidly by the xyz angles about its middle."""
    R = rotation_xyz(np.asarray(angles, float))
    middle = np.array([p.length / 2, p.width / 2, 0.0])
    centres = (sheet.flat_centres(p) - middle) @ R.T + middle
    return centres, np.tile(R[:, 2], (len(centres), 1)), np.tile(R[:, 0], (len(centres), 1)), R, middle


def grating_force(p, centres, normals, axes):
    plain = terms.tile_forces(p.replace(grating=None), centres, normals, axes=axes)
    return terms.tile_forces(p, centres, normals, axes=axes) - plain


@pytest.mark.parametrize(
    "direction, coefficients", [(0.0, TE), (35.0, TE), (90.0, TE), (35.0, QUINTIC), (-120.0, CUBIC)]
)
def test_a_rigid_tilted_sheet_carries_the_law_of_its_grating(direction, coefficients):
    """One grating over the whole plate (one sector of 360°), the plate turned rigidly (small tilts and a yaw) in
    a uniform beam: the grating's force is (I L W/c) cos θ [c_g ĝ + c_l (n̂ × ĝ) + c_n n̂] at the direction cosines
    u₁ = ĝ·ẑ, u₂ = (n̂ × ĝ)·ẑ of the turned grating vector ĝ = R (cos ψ, sin ψ, 0), and its torque about the
    middle vanishes (every tile carries the same force per area); for laws of degree 2, 3 (lists of mixed
    degree) and 5."""
    name = f"uniform{direction:g}_{len(coefficients[0])}"
    p = PLATE.replace(grating=write(name, [(0, 360, direction, coefficients)]))
    centres, normals, axes, R, middle = rigid(p, [0.03, -0.05, 0.7])
    psi = math.radians(direction)
    g = R @ [math.cos(psi), math.sin(psi), 0.0]
    n = R[:, 2]
    l = np.cross(n, g)
    c = law(coefficients, g[2], l[2])
    expected = p.intensity * p.length * p.width / C * n[2] * (c[0] * g + c[1] * l + c[2] * n)
    f = grating_force(p, centres, normals, axes)
    np.testing.assert_allclose(f.sum(axis=0), expected, rtol=1e-12)
    torque = np.cross(centres - middle, f).sum(axis=0)
    np.testing.assert_allclose(torque, 0.0, atol=1e-12 * np.abs(expected).max() * p.length)


def test_opposite_sectors_of_a_tilted_plate_give_the_torque_of_their_laws():
    """Two sectors, the plate's right half (TE, ĝ = +x) and its left half (TM, ĝ = −x), turned rigidly: the
    torque about the middle is M_right × f_right + M_left × f_left, with the halves' first moments
    M = ±(L W/2)(L/4) R x̂ and their forces per area f = (I/c) cos θ [c_g ĝ + c_l l̂ + c_n n̂] by hand; the force
    is (L W/2)(f_right + f_left)."""
    p = PLATE.replace(grating=write("halves", [(-90, 90, 0, TE), (90, 270, 180, TM)]))
    centres, normals, axes, R, middle = rigid(p, [-0.04, 0.06, 0.3])
    n = R[:, 2]
    half = p.length * p.width / 2
    per_area = []
    for coefficients, sign in ((TE, 1.0), (TM, -1.0)):
        g = sign * R[:, 0]
        l = np.cross(n, g)
        c = law(coefficients, g[2], l[2])
        per_area.append(p.intensity / C * n[2] * (c[0] * g + c[1] * l + c[2] * n))
    moment = half * p.length / 4 * R[:, 0]
    f = grating_force(p, centres, normals, axes)
    np.testing.assert_allclose(f.sum(axis=0), half * (per_area[0] + per_area[1]), rtol=1e-12)
    expected = np.cross(moment, per_area[0]) - np.cross(moment, per_area[1])
    np.testing.assert_allclose(np.cross(centres - middle, f).sum(axis=0), expected, rtol=1e-10)


def test_tiles_carry_the_shares_of_the_sectors_they_lie_in():
    """FlexSailSim's pizza (TE ±30° about ±x, TM between): on the 49-tile disc (12 sectors of 30°) every ring
    tile lies in one sector and carries its law exactly; on the 17-tile disc (8 sectors of 45°) the first ring's
    tile over 0…45° is cut by the 30° ray, and carries the laws by the areas of the two pieces (a triangle from
    the middle, by hand: the tile's quadrilateral less the wedge beyond the ray); the middle tiles' in-plane
    pressures at normal incidence cancel by symmetry."""
    layout = write("pizza", PIZZA)
    te, tm = (sheet_grating.rotated(np.array(law), math.radians(d)).ravel() for d, law in ((0, TE), (90, TM)))
    fine = DISC.replace(n=9, ny=12, grating=layout)
    angles = np.degrees(np.arctan2(*(sheet.flat_centres(fine)[:, 1::-1] - 0.5).T))
    c = sheet_grating.tile_coefficients(fine)
    for k in range(1, len(c)):
        sector = PIZZA[int(np.searchsorted([30, 150, 210, 330], np.mod(angles[k] + 360, 360)) % 4)]
        expected = sheet_grating.rotated(np.array(sector[3]), math.radians(sector[2])).ravel()
        np.testing.assert_allclose(c[k], expected, rtol=1e-12, atol=1e-14)
    p = DISC.replace(grating=layout)
    mesh = sheet.Tiles.of(p).mesh
    angles = np.degrees(np.arctan2(*(mesh.centres[:, 1::-1] - 0.5).T))
    k = int(np.flatnonzero(np.isclose(angles, 22.5))[0])
    quad = np.asarray(mesh.outlines[k]) - 0.5
    ray = np.array([math.cos(math.pi / 6), math.sin(math.pi / 6)])
    cut = []  # where the 30° ray crosses the quadrilateral's edges
    for a, b in zip(quad, np.roll(quad, -1, axis=0)):
        side_a, side_b = cross2(ray, a), cross2(ray, b)
        if side_a * side_b < 0:
            cut.append(a + (b - a) * side_a / (side_a - side_b))
    beyond = [v for v in quad if cross2(ray, v) > 0]  # the vertices past the ray (towards 45°)
    piece = np.array([cut[0], *beyond, cut[1]]) if len(beyond) else np.array(cut)
    area = lambda v: 0.5 * abs(np.dot(v[:, 0], np.roll(v[:, 1], -1)) - np.dot(v[:, 1], np.roll(v[:, 0], -1)))  # noqa: E731
    share_tm = area(piece) / area(quad)
    assert 0.2 < share_tm < 0.45
    np.testing.assert_allclose(sheet_grating.tile_coefficients(p)[k], (1 - share_tm) * te + share_tm * tm, rtol=1e-12)
    np.testing.assert_allclose(c[0, [0, 6]], 0.0, atol=1e-12)


def test_zero_coefficients_are_todays_load_to_the_bit():
    """A layout of zeros adds exactly nothing: the terms' sums, the reduced right-hand side and Exudyn's
    compiled load are bit for bit those of the sheet without it."""
    base = DISC.replace(beam_waist=0.4, beam_centre=0.45, spin_rate=700.0, initial_tilt=0.02)
    zero = base.replace(grating=write("zero", [(-30, 30, 0, ZERO), (30, 330, 90, ZERO)]))
    rng = np.random.default_rng(5)
    centres = sheet.flat_centres(base) + rng.normal(0, 0.01, (17, 3))
    R = rotation_xyz(rng.normal(0, 0.05, (17, 3)))
    assert np.array_equal(
        terms.tile_forces(zero, centres, R[..., 2], axes=R[..., 0]), terms.tile_forces(base, centres, R[..., 2])
    )
    reduced = [SheetModel(p) for p in (base, zero)]
    y = reduced[0].y0() + rng.normal(0, 1e-4, reduced[0].y0().size)
    assert np.array_equal(reduced[0].rhs(0.1, y), reduced[1].rhs(0.1, y))
    systems = [SheetSystem(p) for p in (base, zero)]
    q = rng.normal(0, 0.05, systems[0].force.size)
    assert np.array_equal(systems[0].force_vector(q, None, 0.1), systems[1].force_vector(q, None, 0.1))


@pytest.mark.parametrize("sectors", ["PIZZA", "WIDE"])
def test_both_kernels_hand_the_grating_the_tiles_axes(sectors):
    """The grating's part of the reduced right-hand side (its accelerations times the tiles' masses) and of
    Exudyn's compiled load, at a random turned state, is the term's numpy force at those tiles' centres, normals
    R ẑ and in-plane axes R x̂: for the quadratic pizza and for laws of degree 5 and 3 (WIDE)."""
    layout = {"PIZZA": PIZZA, "WIDE": WIDE}[sectors]
    p = DISC.replace(grating=write(sectors.lower(), layout), beam_waist=0.4, beam_centre=0.45)
    rng = np.random.default_rng(8)
    reduced = [SheetModel(q) for q in (p.replace(grating=None), p)]
    y = reduced[0].y0() + rng.normal(0, 0.05, reduced[0].y0().size)
    rows = y.reshape(-1, 13)
    difference = (reduced[1].rhs(0.0, y) - reduced[0].rhs(0.0, y)).reshape(-1, 13)[:, 7:10]
    R = sheet.quaternion_rotation(rows[:, 3:7])
    centres = reduced[0].flat + rows[:, :3]
    expected = grating_force(p, centres, R[..., 2], R[..., 0])
    masses = sheet.Tiles.of(p).masses
    np.testing.assert_allclose(difference * masses[:, None], expected, rtol=1e-9, atol=1e-12 * np.abs(expected).max())
    systems = [SheetSystem(q) for q in (p.replace(grating=None), p)]
    q = rng.normal(0, 0.05, systems[0].force.size)
    force = (systems[1].force_vector(q, None, 0.0) - systems[0].force_vector(q, None, 0.0)).reshape(-1, 6)
    Q = q.reshape(-1, 6)
    R = rotation_xyz(Q[:, 3:])
    expected = grating_force(p, systems[0].flat + Q[:, :3], sheet.normal_xyz(Q[:, 3:]), R[..., 0])
    np.testing.assert_allclose(force[:, :3], expected, rtol=1e-9, atol=1e-12 * np.abs(expected).max())


def test_layouts_and_cases_are_checked():
    for sectors, what in (
        ([(-30, 30, 0, TE), (20, 90, 90, TM)], "overlap"),
        ([(30, 30, 0, TE)], "0 < to − from ≤ 360"),
        ([(0, 90, 0, (TE[0][:5], TE[1], TE[2]))], r"along must be \(d \+ 1\)\(d \+ 2\)/2 finite numbers"),
    ):
        with pytest.raises(ParameterError, match=what):
            DISC.replace(grating=write("bad", sectors))
    with pytest.raises(ParameterError, match="no such file"):
        DISC.replace(grating="/nonexistent/layout.toml")
    with pytest.raises(ParameterError, match="velocity_terms"):
        DISC.replace(grating=write("pizza", PIZZA), velocity_terms=True)
    with pytest.raises(ParameterError, match="grating"):
        SailParameters(grating=write("pizza", PIZZA))


@pytest.mark.slow
def test_both_solvers_agree_on_a_lit_spinning_grating_disc():
    """The 17-tile disc spinning at 120 Hz, offset and tilted in a Gaussian beam, with the pizza layout, over
    0.02 s (2.4 turns) in both solvers: what the grating changes in the lateral path and the tilt (the run with
    it less the run without) agrees between them to 2 % of itself (measured: 0.6 % in the tilt at Exudyn's step
    6.25e-6 s, 2 % at 1.25e-5 s: its step's error; 1e-4 in the lateral path)."""
    p = DISC.replace(
        length=1.0, width=1.0, thickness=4e-7, density=2700.0, youngs_modulus=2.7e11, beam_waist=0.4,
        beam_centre=0.45, beam_centre_y=0.45, initial_tilt=0.035, initial_tilt_y=-0.035, spin_rate=2 * math.pi * 120,
        reflectivity=0.2, absorptivity=1e-5,
    )  # fmt: skip
    settings = RunSettings(t_final=0.02, output_interval=0.002, stop_at_failure=False)
    changes = {}
    for solver, options in (("reduced", {"rtol": 1e-6}), ("exudyn", {"step_size": 6.25e-6})):
        rides = []
        for q in (p, p.replace(grating=write("pizza", PIZZA))):
            result = contract.lookup(solver, q).run(q, settings, **options)
            rides.append(sheet_ride(result))
        changes[solver] = [rides[1].lateral - rides[0].lateral, rides[1].tilt - rides[0].tilt]
    for key in range(2):
        change = changes["reduced"][key]
        assert np.abs(change).max() > 0
        np.testing.assert_allclose(changes["exudyn"][key], change, rtol=0, atol=2e-2 * np.abs(change).max())
