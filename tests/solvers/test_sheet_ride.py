"""The two sheet solvers on a spinning, tilted, offset disc riding a Gaussian beam for 1 s: lateral position,
tilt and spin rate at 1 s within 1e-3 relative, shape amplitude within 1e-3 a₀ (analysis.ride3d)."""

import numpy as np
import pytest

from lightsail_mbs import RunSettings
from lightsail_mbs.analysis.ride3d import sheet_ride
from lightsail_mbs.paper.spinning_beam import CROSSCHECK
from lightsail_mbs.solvers.exudyn import sheet as exudyn_sheet
from lightsail_mbs.solvers.reduced import sheet as reduced_sheet

# a 1 m disc (49 tiles), spinning at 20 rad/s, offset by (5, −2) cm from a beam 0.4 m wide, tilted 0.02 and
# −0.01 rad, with a manufactured (stress-free) defect of a₀ = 1 mm
DISC = CROSSCHECK


@pytest.mark.slow
def test_the_two_solvers_agree_on_a_spinning_tilted_offset_disc_riding_the_beam():
    settings = RunSettings(t_final=1.0, output_interval=0.05, stop_at_failure=False)
    rides = [
        sheet_ride(reduced_sheet.run(DISC, settings)),
        sheet_ride(exudyn_sheet.run(DISC, settings, step_size=1e-4)),
    ]
    a, b = rides
    assert a.time[-1] == pytest.approx(1.0) and b.time[-1] == pytest.approx(1.0)
    for name in ("lateral", "tilt"):
        x, y = getattr(a, name)[-1], getattr(b, name)[-1]
        np.testing.assert_allclose(y, x, rtol=1e-3, err_msg=name)
        assert np.all(np.abs(x - getattr(a, name)[0]) > 1e-3 * np.abs(x))  # they moved
    assert b.spin_rate[-1] == pytest.approx(a.spin_rate[-1], rel=1e-3)
    assert np.max(np.abs(a.amplitude - b.amplitude)) <= 1e-3 * DISC.defect_amplitude
    assert a.verdict == b.verdict == "rides"
