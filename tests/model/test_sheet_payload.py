"""A payload behind a sheet (model.sheet_payload, model.sheet_pose): its frame share, its start in the rigid
craft's equilibrium, the cable law, the tilted pose and the one-line refusals."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, SailParameters
from lightsail_mbs.model import sheet, sheet_payload, sheet_pose, terms

DISC = dict(model="sheet", n=9, ny=12, planform="disc", youngs_modulus=4.5e9, defect_amplitude=0.0)


def test_the_craft_accelerates_with_its_whole_mass():
    """Tiles' net forces on the flat sail plus the payload's own frame force add up to zero: g₀ is the whole
    craft's, c_n Ī A/(c (M_s + m_p)), and the sail's area is its mesh's (πL²/4 for the disc)."""
    p = SailParameters(**DISC, payload_mass=3e-4, payload_stem=0.4, beam_waist=0.7)
    centres, q = sheet.initial_quaternions(p)
    forces = terms.tile_forces(p, centres, sheet.normal_xyz(np.zeros_like(centres)))
    body = sheet_payload.payload(p, centres, q, sheet.connectors(p, centres, q))
    assert p.sail_area == pytest.approx(np.pi / 4, rel=1e-12)
    sail = p.density * p.thickness * p.sail_area
    assert p.nominal_acceleration == pytest.approx(2 * p.mean_intensity * p.sail_area / 299_792_458.0 / (sail + 3e-4))
    total = forces[:, 2].sum() + body.frame_force
    assert abs(total) < 1e-12 * abs(body.frame_force)
    assert np.allclose(forces[:, :2], 0.0)


def test_tethers_start_in_the_rigid_craft_equilibrium_and_spread_round_the_rim():
    p = SailParameters(**DISC, payload_mass=3e-4, payload_stem=0.4, payload_tethers=6, tether_stiffness=50.0)
    centres, q = sheet.initial_quaternions(p)
    body = sheet_payload.payload(p, centres, q, sheet.connectors(p, centres, q))
    ends = centres[body.tether_tile] + body.tether_point
    span = ends - body.start
    length = np.linalg.norm(span, axis=1)
    tension = body.tether_stiffness * (length - body.tether_rest)
    pull = (tension[:, None] * span / length[:, None]).sum(axis=0)
    np.testing.assert_allclose(pull, [0.0, 0.0, -body.frame_force], atol=1e-12 * abs(body.frame_force))
    angles = np.sort(np.degrees(np.arctan2(ends[:, 1] - 0.5, ends[:, 0] - 0.5)) % 360)
    assert np.all(np.diff(angles) == pytest.approx(60.0, abs=16.0))


def test_a_cable_pulls_and_never_pushes():
    k, c = 40.0, 0.5
    stretch = np.array([-1e-3, 0.0, 1e-3, 1e-3, 1e-3])
    rate = np.array([0.0, 5.0, 0.0, -0.07, -1.0])
    np.testing.assert_allclose(sheet_payload.tether_tension(stretch, rate, k, c), [0, 0, 0.04, 0.005, 0], atol=1e-17)


def test_the_tilt_turns_the_whole_craft_about_its_centre_of_mass():
    p = SailParameters(**DISC, payload_mass=3e-4, payload_stem=0.4, initial_tilt=0.1, initial_tilt_y=-0.05, spin_rate=5)
    centres, q = sheet.initial_quaternions(p)
    body = sheet_payload.payload(p, centres, q, sheet.connectors(p, centres, q))
    turned, qt, v, w = sheet_pose.initial_motion(p, centres, q, body)
    m = sheet_pose.body_masses(p, body)
    before = np.vstack([centres, body.start])
    np.testing.assert_allclose(m @ turned, m @ before, atol=1e-15)  # G stays
    Q = sheet_pose.tilt_matrix(p)
    np.testing.assert_allclose(
        sheet.quaternion_rotation(qt), Q @ sheet.quaternion_rotation(np.vstack([q, body.quaternion])), atol=1e-15
    )
    assert Q[2, 0] > 0 and Q[2, 1] < 0  # x turned towards +z, y away from it (α_y < 0)
    np.testing.assert_allclose(w, np.tile(Q @ [0, 0, 5.0], (len(w), 1)), atol=1e-14)
    g = m @ turned / m.sum()
    np.testing.assert_allclose(v, np.cross(w, turned - g), atol=1e-12)


@pytest.mark.parametrize(
    "changes, name",
    [
        (dict(payload_mass=1e-3, payload_stem=0.3, payload_tethers=2, tether_stiffness=1.0), "payload_tethers"),
        (dict(payload_mass=1e-3, payload_stem=0.3, payload_tethers=40, tether_stiffness=1.0), "payload_tethers"),
        (dict(payload_mass=1e-3, payload_stem=0.3, payload_tethers=6), "tether_stiffness"),
        (dict(payload_mass=1e-3, payload_tethers=6, tether_stiffness=1.0), "payload_stem"),
        (dict(payload_tethers=6, tether_stiffness=1.0), "payload_tethers"),
        (dict(initial_tilt_y=2.0), "initial_tilt_y"),
        (dict(payload_mass=1e-3, boundary="clamped"), "payload_mass"),
    ],
)
def test_bad_payloads_and_tilts_are_one_line(changes, name):
    with pytest.raises(ParameterError, match=name) as caught:
        SailParameters(**{**DISC, **changes})
    assert "\n" not in str(caught.value)
