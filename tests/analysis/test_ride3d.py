"""The sheet riding the beam in 3-D (analysis.ride3d, analysis.ride3d_criterion): the rigid cap's closed form
against the discrete sheet's own loads, the criterion's limits, and a run's histories and verdict."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters
from lightsail_mbs.analysis.ride3d import sheet_ride
from lightsail_mbs.analysis.ride3d_criterion import cap_criterion, stem_boundaries
from lightsail_mbs.model import sheet, terms
from lightsail_mbs.paper.spinning_beam import CROSSCHECK
from lightsail_mbs.solvers.reduced import sheet as reduced_sheet

CAP = SailParameters(
    model="sheet", n=33, ny=48, planform="disc", billow_radius=1.0, beam_waist=0.6, defect_amplitude=0.0, intensity=1e8
)
PAYLOAD = 1e-3 * math.pi / 4  # the sail's own mass


def lateral_load(p, shift=0.0, tilt=0.0):
    """(F_x, F_z) of the discrete cap's tiles moved by `shift` along x and turned by `tilt` (x towards +z)
    about the centre of curvature."""
    centres, q = sheet.initial_quaternions(p)
    normals = sheet.quaternion_rotation(q)[:, :, 2]
    c = np.array([0.5, 0.5, -p.billow_radius])
    turn = np.array([[math.cos(tilt), 0, -math.sin(tilt)], [0, 1, 0], [math.sin(tilt), 0, math.cos(tilt)]])
    centres = c + (centres - c) @ turn.T + [shift, 0, 0]
    forces = terms.tile_forces(p.replace(intensity=p.intensity), centres, normals @ turn.T)
    frame = p.normal_momentum * p.mean_intensity * sheet.Tiles.of(p).areas / 299_792_458.0
    return forces[:, 0].sum(), (forces[:, 2] + frame).sum()


def test_the_closed_form_loads_are_the_discrete_caps():
    """k, F_e and F₀ of the criterion against central differences of the sheet's own radiation load on the
    33 × 48 disc laid on its cap (the mesh's quadrature error: 0.05–0.1 %)."""
    c = cap_criterion(CAP, PAYLOAD, 3.0)
    h = 1e-5
    k = -(lateral_load(CAP, h)[0] - lateral_load(CAP, -h)[0]) / (2 * h)
    edge = -(lateral_load(CAP, tilt=h)[0] - lateral_load(CAP, tilt=-h)[0]) / (2 * h)
    assert k == pytest.approx(c.k, rel=2e-3)
    assert edge == pytest.approx(c.edge_force, rel=2e-3)
    assert lateral_load(CAP)[1] == pytest.approx(c.axial_force, rel=2e-3)


def test_the_centre_of_mass_must_lie_beyond_the_centre_of_curvature_unless_spun_fast():
    """Without spin the cap drifts out below d* (G between C and the sail: Popova et al.'s condition) and
    rides just above it; fast spin stabilises it below d* (gyroscopically: two unstable directions)."""
    c = cap_criterion(CAP, PAYLOAD, 3.0)
    below = 0.9 * c.static_boundary
    assert cap_criterion(CAP, PAYLOAD, below, 0.0).growth_rate > 1.0
    assert cap_criterion(CAP, PAYLOAD, below, 30.0).growth_rate > 1.0
    assert cap_criterion(CAP, PAYLOAD, below, 1000.0).stable
    crossings = stem_boundaries(CAP.replace(spin_rate=0.0), PAYLOAD, 0.5, 60.0)
    assert crossings[0][0] == pytest.approx(c.static_boundary, rel=1e-6) and crossings[0][1]
    stable = [d for d in np.geomspace(0.5, 60.0, 80) if cap_criterion(CAP, PAYLOAD, d, 0.0).stable]
    assert stable and all(cap_criterion(CAP, PAYLOAD, d).D < 0 for d in stable)


def test_a_flatter_cap_needs_a_longer_stem_and_a_flat_sail_never_rides():
    flatter = cap_criterion(CAP.replace(billow_radius=4.0), PAYLOAD, 3.0)
    assert flatter.static_boundary > cap_criterion(CAP, PAYLOAD, 3.0).static_boundary
    with pytest.raises(ParameterError, match="billow_radius"):
        cap_criterion(CAP.replace(billow_radius=math.inf), PAYLOAD, 3.0)
    nearly_flat = CAP.replace(billow_radius=1e4)
    assert not any(cap_criterion(nearly_flat, PAYLOAD, d).stable for d in (0.1, 1.0, 10.0, 100.0))


def test_a_runs_histories_start_from_its_pose_and_give_a_verdict():
    p = CROSSCHECK.replace(n=5, ny=6, youngs_modulus=4.5e13, defect_amplitude=0.0, bending_reference="flat")
    r = reduced_sheet.run(p, RunSettings(t_final=0.05, output_interval=0.01, stop_at_failure=False))
    ride = sheet_ride(r)
    np.testing.assert_allclose(ride.lateral[0], [0.05, -0.02], atol=1e-12)
    np.testing.assert_allclose(ride.tilt[0], [0.02, -0.01], atol=1e-4)  # α_y after α_x: 2nd order
    assert ride.spin_rate[0] == pytest.approx(20.0, rel=1e-12)
    assert ride.verdict == "rides" and ride.decided_at is None
    assert ride.deformation[0] < 1e-15 and 0 < ride.deformation.max() < 1e-2
    assert sheet_ride(r, crumple=1e-12).verdict == "crumples"
    assert sheet_ride(r, drift_factor=0.05).verdict == "drifts out"
    with pytest.raises(ParameterError, match="crumple"):
        sheet_ride(r, crumple=0.0)
