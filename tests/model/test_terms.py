"""The physics-term seam (model/terms): one packed layout, every term's compiled form equal to its numpy form
for both families, and the bodies each kernel hands the terms equal to the chain's kinematics."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.model import sheet, terms
from lightsail_mbs.model.terms import bodies as rows
from lightsail_mbs.solvers.exudyn.tree import ChainLayout, _slices_into
from lightsail_mbs.solvers.reduced.chain_constants import N_CONSTANTS, WORK_ROWS, constants
from lightsail_mbs.solvers.reduced.dynamics import slice_states_into
from lightsail_mbs.solvers.reduced.kinematics import ChainModel, centre_velocities, centres
from tests.model.grating_layouts import PIZZA, write

rng = np.random.default_rng(11)

CHAINS = {
    "facet-gaussian-pushed": SailParameters(
        n=9, intensity=1e9, beam_waist=0.4, beam_centre=0.3, reflectivity=0.7, absorptivity=0.2, body_force=0.3
    ),
    "facet-moving": SailParameters(n=7, intensity=1e9, reflectivity=0.6, absorptivity=0.3, velocity_terms=True),
    "gaussian-moving": SailParameters(n=10, intensity=1e9, beam_waist=0.5, velocity_terms=True),
    "mirror-table": SailParameters(n=8, intensity=1e9, optics="mirror", optics_layout="mirrored-halves"),
    "payload": SailParameters(n=12, youngs_modulus=4.5e9, payload_mass=1e-4, payload_stem=0.2, beam_waist=0.8),
    "doppler-moving-pushed": SailParameters(
        n=8, intensity=1e9, beam_waist=0.7, velocity_terms=True, body_force=0.2, initial_beta=0.15
    ),
}
UNIFORM_SHEET = SailParameters(model="sheet", n=5, ny=4, youngs_modulus=4.5e9)
SHEETS = {
    "uniform": UNIFORM_SHEET,
    "gaussian-pressure-pushed": UNIFORM_SHEET.replace(
        beam_waist=0.6, beam_centre_y=0.7, reflectivity=0.7, absorptivity=0.2, pressure=0.3, body_force=-0.2
    ),
    "gaussian-moving": UNIFORM_SHEET.replace(beam_waist=0.6, reflectivity=0.8, absorptivity=0.15, velocity_terms=True),
    "doppler-pressure": UNIFORM_SHEET.replace(pressure=0.2, velocity_terms=True, initial_beta=0.3),
    "payload-gaussian": UNIFORM_SHEET.replace(payload_mass=1e-4, payload_stem=0.2, beam_waist=0.8),
    "grating-gaussian": UNIFORM_SHEET.replace(grating=write("pizza", PIZZA), beam_waist=0.7, reflectivity=0.2),
}
TIME = 0.6  # s: the run's time at which the sums are compared (read by the Doppler term)


def test_the_packed_layout_names_every_active_term_once():
    assert len({t.ID for t in terms.TERMS}) == len(terms.TERMS)
    for family, cases in (("chain", CHAINS), ("sheet", SHEETS)):
        for p in cases.values():
            packed, active = terms.pack(p, family), terms.active_terms(p, family)
            assert packed[0] == len(active)
            at, reads = 2, 0
            for term in active:
                assert packed[at] == term.ID
                block = term.constants(p, family)
                assert np.array_equal(packed[at + 2 : at + 2 + block.size], block)
                at += 2 + block.size
                reads |= term.reads(p)
            assert at == packed.size and terms.reads(packed) == reads


@pytest.mark.parametrize("family", ["chain", "sheet"])
def test_every_registered_term_is_exercised_here(family):
    """Each term declared for a family is active in one of the cases below, so its dispatcher branch and its
    two forms are held to each other."""
    cases = CHAINS if family == "chain" else SHEETS
    seen = {t.ID for p in cases.values() for t in terms.active_terms(p, family)}
    assert seen == {t.ID for t in terms.TERMS if family in t.FAMILIES}


@pytest.mark.parametrize("name", CHAINS)
def test_compiled_chain_terms_equal_their_numpy_forms(name):
    p = CHAINS[name]
    theta = np.concatenate([rng.uniform(-0.5, 0.5, p.n - 2), [1e-9, -3e-7]])
    x = np.sort(rng.uniform(0, 1, p.n))
    y, vx, vy, omega = rng.normal(0, [[0.01], [1], [1], [10]], (4, p.n))  # read by the velocity term
    fx, fy = terms.chain_forces(p, x, theta, y, vx, vy, omega, time=TIME)
    forces = np.empty((2, p.n))
    terms.chain_forces_into(terms.pack(p, "chain"), rows.chain_bodies(x, theta, y, vx, vy, omega), forces, TIME)
    scale = p.flat_force
    np.testing.assert_allclose(forces[0], fx, rtol=1e-14, atol=1e-16 * scale)
    np.testing.assert_allclose(forces[1], fy, rtol=1e-13, atol=1e-15 * scale)


@pytest.mark.parametrize("name", SHEETS)
def test_compiled_sheet_terms_equal_their_numpy_forms(name):
    p = SHEETS[name]
    count = p.n * p.ny
    centres_ = sheet.flat_centres(p) + rng.normal(0, 0.02, (count, 3))
    normals = rng.normal(0, 0.2, (count, 3)) + [0, 0, 1]
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    velocities, spins = rng.normal(0, 1, (2, count, 3))  # read by the velocity term
    axes = np.cross(normals, rng.normal(0, 1, (count, 3)))  # in-plane axes, read by the grating term
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    expected = terms.tile_forces(p, centres_, normals, velocities, spins, time=TIME, axes=axes)
    forces = np.empty((3, count))
    bodies = rows.tile_bodies(centres_, normals, velocities, spins, axes)
    terms.tile_forces_into(terms.pack(p, "sheet"), bodies, forces, TIME)
    scale = 2 * p.intensity * sheet.Tiles.of(p).area / 299_792_458.0
    np.testing.assert_allclose(forces.T, expected, rtol=1e-13, atol=1e-15 * scale)


@pytest.mark.parametrize("model", ["torsion", "tnt"])
def test_reduced_chain_hands_the_terms_its_kinematics(model):
    """The reduced right-hand side's slice rows (positions and velocities, computed when a term reads them)
    are the dense kinematics' centres and centre velocities."""
    p = SailParameters(model=model, n=6, youngs_modulus=4.5e9, intensity=1e9, tension=1e-3 if model == "tnt" else 0.0)
    chain = ChainModel.from_params(p)
    q = rng.normal(size=chain.dof) * 0.3
    qd = rng.normal(size=chain.dof)
    if chain.extensible:
        q[p.n + 2 :] *= 1e-2
    k = constants(chain)
    k[N_CONSTANTS + rows.READS] = rows.POSITIONS | rows.VELOCITIES
    work = np.zeros((WORK_ROWS, p.n))
    slice_states_into(q, qd, k, work, chain.extensible)
    x, y = centres(chain, q)
    vx, vy = centre_velocities(chain, q, qd)
    for row, expected in ((rows.X, x), (rows.Y, y), (rows.VX, vx), (rows.VY, vy), (rows.OMEGA, qd[2 : p.n + 2])):
        np.testing.assert_allclose(work[row], expected, rtol=1e-12, atol=1e-14)
    np.testing.assert_array_equal(work[rows.THETA], q[2 : p.n + 2])


@pytest.mark.parametrize("model", ["torsion", "tnt"])
def test_exudyn_tree_hands_the_terms_its_kinematics(model):
    p = SailParameters(model=model, n=6, youngs_modulus=4.5e9, intensity=1e9, tension=1e-3 if model == "tnt" else 0.0)
    layout = ChainLayout.of(p)
    q = rng.normal(size=layout.size) * 0.3
    q_t = rng.normal(size=layout.size)
    if layout.stretch_index.size:
        q[layout.stretch_index] *= 1e-2
    got = np.zeros((rows.CHAIN_ROWS, p.n))
    reads = rows.POSITIONS | rows.VELOCITIES
    _slices_into(q, q_t, layout.angle_index, layout.stretch_index, layout.slice_length, reads, got)
    x, y, theta, _ = layout.positions(q)
    vx, vy, omega, _ = layout.velocities(q, q_t)
    for row, expected in (
        (rows.X, x),
        (rows.Y, y),
        (rows.THETA, theta),
        (rows.VX, vx),
        (rows.VY, vy),
        (rows.OMEGA, omega),
    ):
        np.testing.assert_allclose(got[row], expected, rtol=1e-12, atol=1e-14)
