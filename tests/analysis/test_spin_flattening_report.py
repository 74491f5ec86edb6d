"""The spin reports' measure of a flattened cap: the sphere through its apex and rim."""

import numpy as np
import pytest

from lightsail_mbs.analysis import spin_spectrum
from lightsail_mbs.paper import spinning_maps as maps
from tests.helpers import validation_script


@pytest.mark.parametrize("radius", [0.75, 1.0, 2.0])
def test_the_unmoved_cap_fits_its_own_sphere(radius):
    """A state that leaves every tile at the cap's start gives the cap's own radius and its sag r²/(R + √(R² − r²))."""
    p = maps.BASE.replace(billow_radius=radius, payload_stem=1.0)
    flat, start, quaternions, _ = spin_spectrum._start(p)
    rows = np.zeros((len(start), 13))
    rows[:, 0:3], rows[:, 3:7] = start - flat, quaternions
    sag, fit = validation_script("spin_equilibrium_cells").lit_fit(p, rows.ravel())
    rim = np.hypot(*(start[:-1, :2] - start[:-1, :2].mean(axis=0)).T).max()
    assert fit == pytest.approx(radius, rel=1e-12)
    assert sag == pytest.approx(rim**2 / (radius + np.sqrt(radius**2 - rim**2)), rel=1e-12)


def test_a_flattened_cap_fits_a_larger_sphere():
    """Tiles lifted towards the rim's plane by half the sag: the fitted sphere is larger than R_c."""
    p = maps.BASE.replace(billow_radius=1.0, payload_stem=1.0)
    flat, start, quaternions, _ = spin_spectrum._start(p)
    rows = np.zeros((len(start), 13))
    rows[:, 0:3], rows[:, 3:7] = start - flat, quaternions
    sag, _ = validation_script("spin_equilibrium_cells").lit_fit(p, rows.ravel())
    rows[:-1, 2] += 0.5 * (start[:-1, 2].max() - start[:-1, 2])  # every tile halfway to the rim's height
    half, fit = validation_script("spin_equilibrium_cells").lit_fit(p, rows.ravel())
    assert half == pytest.approx(sag / 2, rel=1e-9)
    assert fit > 1.9
