"""The spun equilibrium (solvers.reduced.sheet_relax, case field spin_equilibrium): the flat disc's is the flat
sheet's centrifugal state, and the billowed map disc started there stays in shape in its turning frame where
the flat sheet's stress lets it flop."""

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import sheet
from lightsail_mbs.paper import spinning_maps
from lightsail_mbs.solvers.reduced.sheet import SheetModel
from lightsail_mbs.solvers.reduced.sheet_relax import relax, spun_equilibrium


def map_cap(spin: float, **changes) -> SailParameters:
    """The spin map's cell (paper.spinning_maps: 25-tile disc, R_c = 1 m, stem payload at 1.05 d*), unlit."""
    p = spinning_maps.BASE.replace(billow_radius=1.0, spin_rate=spin)
    return p.replace(payload_stem=1.05 * spinning_maps.d_star(p), intensity=0.0, **changes)


def shape_change(a: np.ndarray, b: np.ndarray) -> float:
    """The largest distance (m) between point sets a and b (N, 3) after the best rigid fit of b onto a (Kabsch)."""
    a0, b0 = a - a.mean(axis=0), b - b.mean(axis=0)
    U, _, Vt = np.linalg.svd(b0.T @ a0)
    R = U @ np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))]) @ Vt
    return float(np.linalg.norm(a0 @ R.T - b0, axis=1).max())


def test_the_flat_disc_rests_in_its_flat_centrifugal_state():
    """A flat disc's connectors carry the flat sheet's centrifugal stress, in which it rests (model.sheet_spin):
    the relaxation leaves its shape as it was, to round-off (the undamped rigid motion relative to the frame,
    ~1e-7 m and rad from the integration error of the rim's 40 m/s, is not part of the shape), and flat."""
    p = spinning_maps.BASE.replace(payload_mass=0.0, billow_radius=np.inf, billow_rest=False, spin_rate=80.0)
    centres, quaternions = spun_equilibrium(p.replace(intensity=0.0))
    start, _ = sheet.initial_quaternions(p)
    assert shape_change(start, centres) < 1e-13
    assert np.abs(centres[:, 2]).max() < 1e-15 and np.abs(quaternions[:, 1:3]).max() < 1e-15


def test_a_tilted_start_turns_the_relaxed_shape_once():
    """The relaxation finds the untilted shape; the run's start turns it by the case's tilt (model.sheet_pose), once:
    the flat disc (its relaxed shape its own) starts with the normal it has without spin_equilibrium, up to the
    relaxation's rigid drift (~1e-7 rad; turned twice it would differ by the tilt, 2.2e-2 rad)."""
    p = spinning_maps.BASE.replace(payload_mass=0.0, billow_radius=np.inf, billow_rest=False, spin_rate=80.0)
    p = p.replace(initial_tilt=0.02, initial_tilt_y=-0.01)
    normals = []
    for held in (True, False):
        model = SheetModel(p.replace(spin_equilibrium=held))
        centres = model.flat + model.inertial_y0().reshape(-1, 13)[:, 0:3]
        normal = np.linalg.svd(centres - centres.mean(axis=0))[2][-1]
        normals.append(normal * np.sign(normal[2]))
    assert np.linalg.norm(normals[0] - normals[1]) < 1e-6
    assert np.degrees(np.arccos(normals[1][2])) == pytest.approx(np.degrees(np.hypot(0.02, 0.01)), rel=1e-3)


@pytest.mark.slow
def test_the_billowed_map_disc_keeps_its_spun_shape():
    """The map's cap at 80 rad/s, unlit, over one turn: started in the spun equilibrium its shape (rigid motion
    removed) changes by < 1 mm; started in the flat sheet's stress it flops by > 1 cm in the same turn."""
    settings = RunSettings(t_final=2 * np.pi / 80.0, output_interval=0.01, stop_at_failure=False)
    changes = {}
    for held in (True, False):
        run = solve(map_cap(80.0, spin_equilibrium=held), "reduced", settings, uncertainty=False)
        assert run.error is None
        changes[held] = max(shape_change(run.tile_centres[0], c) for c in run.tile_centres)
    assert changes[True] < 1e-3 < 1e-2 < changes[False]


@pytest.mark.slow
def test_exudyn_starts_the_billowed_map_disc_in_its_spun_shape():
    """Exudyn's run of the same cap over one turn (a generalized-α step of 0.5 ms: its default 5 ms turns the sail
    by 0.4 rad a step): from the spun equilibrium its shape changes by < 1 mm, from the flat stress by > 1 cm."""
    settings = RunSettings(t_final=2 * np.pi / 80.0, output_interval=0.01, stop_at_failure=False)
    changes = {}
    for held in (True, False):
        run = solve(map_cap(80.0, spin_equilibrium=held), "exudyn", settings, uncertainty=False, step_size=5e-4)
        assert run.error is None
        changes[held] = max(shape_change(run.tile_centres[0], c) for c in run.tile_centres)
    assert changes[True] < 1e-3 < 1e-2 < changes[False]


@pytest.mark.slow
def test_tethers_slacken_as_the_unlit_spinning_cap_relaxes():
    """Why spin_equilibrium refuses tethers: the map's cap at 80 rad/s with six tethers (k = 1e3 N/m), relaxed
    unlit (the checks bypassed), leaves some tether shorter than its rest length (slack: the payload is held by
    nothing there)."""
    p = map_cap(80.0, payload_tethers=6, tether_stiffness=1e3)
    centres, quaternions = relax(p)
    model = SheetModel(p)
    tile, point, rest, _ = model.tethers
    ends = centres[tile] + np.einsum("kij,kj->ki", sheet.quaternion_rotation(quaternions[tile]), point)
    assert np.min(np.linalg.norm(centres[-1] - ends, axis=1) - rest) < -1e-3


def test_a_spun_equilibrium_needs_a_spin_about_the_normal():
    with pytest.raises(ParameterError, match="spin_equilibrium"):
        map_cap(0.0, spin_equilibrium=True)
    with pytest.raises(ParameterError, match="spin_equilibrium"):  # a nutating spin has no steady state
        map_cap(80.0, spin_tilt=0.1, spin_equilibrium=True)
    with pytest.raises(ParameterError, match="payload_tethers=6"):  # unlit tethers hold nothing
        SheetModel(map_cap(80.0, spin_equilibrium=True, payload_tethers=6, tether_stiffness=1e3))
