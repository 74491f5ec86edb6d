"""A payload behind a sheet in both solvers (model.sheet_payload): the stiff craft accelerates with its whole
mass, tethers hold the payload's share of the load, a slack tether carries nothing, the solvers agree."""

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs.model import sheet
from lightsail_mbs.model.sheet_grid import Tiles
from lightsail_mbs.solvers.exudyn import sheet as exudyn_sheet
from lightsail_mbs.solvers.exudyn.sheet_tethers import cable_force
from lightsail_mbs.solvers.reduced import sheet as reduced_sheet
from lightsail_mbs.solvers.reduced.sheet import STATE, SheetModel

# a stiff disc (D = 83 N m) with a payload of a quarter of its mass: it stays nearly rigid
STIFF = SailParameters(model="sheet", n=5, ny=6, planform="disc", thickness=1e-5, intensity=1e9, defect_amplitude=0.0)
STIFF = STIFF.replace(youngs_modulus=1e18, membrane_modulus=4.5e9, payload_mass=2e-3, payload_stem=0.3)
STIFF = STIFF.replace(stiffness_damping=2e-3)  # c = β k on every spring: the start's ringing dies away
TETHERED = STIFF.replace(payload_tethers=6, tether_stiffness=1e3)
RUN = RunSettings(t_final=0.1, output_interval=0.01, stop_at_failure=False)


def centre_of_mass(p, result) -> np.ndarray:
    masses = Tiles.of(p).masses
    payload = np.array(result.info["payload_centre"])
    return (np.einsum("k,tki->ti", masses, result.tile_centres) + p.payload_mass * payload) / (
        masses.sum() + p.payload_mass
    )


def tensions(p, result) -> tuple[np.ndarray, np.ndarray]:
    """(T, n_t) tether tensions k (ℓ − ℓ₀) along the run (stiff tethers, no damping) and (T,) their pull
    Σ_j T_j u_j,z on the payload towards the sail."""
    model = SheetModel(p)
    tile, point, rest, (k, _) = model.tethers
    rotations = sheet.rotation_xyz(result.tile_angles[:, tile])
    ends = result.tile_centres[:, tile] + np.einsum("tkij,kj->tki", rotations, point)
    span = ends - np.array(result.info["payload_centre"])[:, None]
    length = np.linalg.norm(span, axis=-1)
    tension = k * (length - rest)
    return tension, np.sum(tension * span[..., 2] / length, axis=1)


@pytest.fixture(scope="module")
def runs():
    return {
        (name, solver): module.run(p, RUN, **options)
        for name, p in (("stem", STIFF), ("tethers", TETHERED))
        for solver, module, options in (
            ("reduced", reduced_sheet, {}),
            ("exudyn", exudyn_sheet, dict(step_size=2.5e-4)),
        )
    }


@pytest.mark.parametrize("name", ["stem", "tethers"])
@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_the_stiff_craft_accelerates_with_its_whole_mass(runs, name, solver):
    """In the frame accelerating at g₀ = F/(M_s + m_p) the craft's centre of mass stays put; with the sail's
    own g₀ it would drift by ½ (g₀,sail − g₀) t² (0.65 m here)."""
    p = STIFF if name == "stem" else TETHERED
    r = runs[name, solver]
    assert r.error is None
    sail_only = 2 * p.intensity / (299_792_458.0 * p.density * p.thickness)
    drift = 0.5 * (sail_only - p.nominal_acceleration) * RUN.t_final**2
    g = centre_of_mass(p, r)
    assert np.max(np.abs(g - g[0])) < 1e-5 * drift
    payload = np.array(r.info["payload_centre"])
    assert np.max(np.abs(payload[:, 2] - payload[0, 2])) < 1e-3 * drift


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_tethers_carry_the_payloads_share_of_the_load(runs, solver):
    """The tethers pull (all taut, alike) and, once the start's ringing has died away, hold the payload's
    share of the load, Σ T u_z = m_p g₀, to 1e-3."""
    r = runs["tethers", solver]
    T, pull = tensions(TETHERED, r)
    share = TETHERED.payload_mass * TETHERED.nominal_acceleration
    assert np.all(T > 0)
    np.testing.assert_allclose(T, T[:, :1] * np.ones(T.shape[1]), rtol=1e-3)
    np.testing.assert_allclose(pull[-3:], share, rtol=1e-3)


def test_the_two_solvers_agree_on_the_payloads_path(runs):
    for name in ("stem", "tethers"):
        a, b = (np.array(runs[name, s].info["payload_centre"]) for s in ("reduced", "exudyn"))
        moved = np.max(np.abs(a - a[0]))
        assert np.max(np.abs(a - b)) <= 1e-3 * max(moved, 1e-9), name
        amplitude = runs[name, "reduced"].amplitude
        np.testing.assert_allclose(runs[name, "exudyn"].amplitude, amplitude, atol=1e-3 * amplitude.max())


def test_a_slack_tether_carries_nothing():
    """The payload moved 1 mm towards the sail slackens every tether: it feels its frame force alone."""
    model = SheetModel(TETHERED)
    y = model.y0()
    y.reshape(-1, STATE)[-1, 2] += 1e-3
    acceleration = model.rhs(0.0, y).reshape(-1, STATE)[-1, 7:10]
    np.testing.assert_array_equal(acceleration, [0.0, 0.0, -TETHERED.nominal_acceleration])
    law = cable_force(TETHERED.tether_stiffness, 0.0)
    assert law(None, 0.0, 0, -1e-3, 0.0, 0.0, 0.0, 0.0) == 0.0
    assert law(None, 0.0, 0, 1e-3, 0.0, 0.0, 0.0, 0.0) == pytest.approx(1.0)
