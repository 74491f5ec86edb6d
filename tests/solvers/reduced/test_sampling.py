"""The compiled output of the reduced solver equals the numpy definitions: the Result arrays
(kinematics.centres, centre_velocities) and the failure monitor's amplitudes (analysis.amplitude)."""

import numpy as np
import pytest

from lightsail_mbs import analysis
from lightsail_mbs.solvers.reduced.kinematics import ChainModel, centre_velocities, centres
from lightsail_mbs.solvers.reduced.sampling import Trajectory
from tests.solvers.reduced.chains import IDS, MODELS, random_state


@pytest.mark.parametrize("p", MODELS, ids=IDS)
def test_compiled_output_equals_numpy_kinematics(p):
    model = ChainModel.from_params(p)
    states = [random_state(model) for _ in range(5)]
    q = np.stack([s[0] for s in states], axis=1)
    qd = np.stack([s[1] for s in states], axis=1)
    rows = np.concatenate([q, qd]).T
    trajectory = Trajectory(model, 8)
    amp = np.concatenate([trajectory.fill(rows[:2]), trajectory.fill(rows[2:])])  # filled in two batches
    trajectory.truncate(4)
    out = trajectory.arrays()
    x_ref, y_ref = centres(model, q)
    vx_ref, vy_ref = centre_velocities(model, q, qd)
    _, _, theta_ref, z_ref = model.split(q)
    for name, ref in [("x", x_ref), ("y", y_ref), ("vx", vx_ref), ("vy", vy_ref), ("theta", theta_ref)]:
        np.testing.assert_allclose(out[name], ref.T[:4], rtol=0, atol=1e-13 * np.abs(ref).max())
    assert out["z"].shape == (4, p.n - 1 if model.extensible else 0)
    if model.extensible:
        np.testing.assert_array_equal(out["z"], z_ref.T[:4])
    np.testing.assert_allclose(amp, analysis.amplitude(x_ref.T, y_ref.T), rtol=1e-12)
    np.testing.assert_array_equal(out["amplitude"], amp[:4])
    np.testing.assert_allclose(trajectory.coordinates(), q[:, :4], rtol=0, atol=1e-15)
