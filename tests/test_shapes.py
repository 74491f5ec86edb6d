"""Initial shape: hinges on the sine of Eq. (1), exact chords, slices along the chords."""
import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.shapes import hinge_points, initial_state


@pytest.mark.parametrize("model, extra", [("torsion", {}), ("rigid", {}), ("tnt", {"tension": 1e3})])
def test_hinges_on_sine_with_exact_chords(model, extra):
    p = SailParameters(model=model, n=40, amplitude=1e-2, mode=2.5, **extra)
    pts = hinge_points(p)
    assert pts[0] == pytest.approx([0.0, 0.0])
    np.testing.assert_allclose(pts[:, 1], 1e-2 * np.sin(5 * np.pi * pts[:, 0]), atol=1e-15)
    chords = np.hypot(*np.diff(pts, axis=0).T)
    expected = np.full(p.n, p.slice_length)
    if p.extensible:
        expected[:-1] += p.tension / p.axial_stiffness
    np.testing.assert_allclose(chords, expected, rtol=1e-13)
    # the chain is shorter in x than L (the sine is longer than its projection)
    assert pts[-1, 0] < p.length


def test_slices_along_chords_at_their_centres():
    p = SailParameters(n=25, amplitude=1e-3, mode=1.5)
    s = initial_state(p)
    pts = hinge_points(p)
    l = p.slice_length
    left = np.c_[s.x - 0.5 * l * np.cos(s.theta), s.y - 0.5 * l * np.sin(s.theta)]
    right = np.c_[s.x + 0.5 * l * np.cos(s.theta), s.y + 0.5 * l * np.sin(s.theta)]
    np.testing.assert_allclose(left, pts[:-1], atol=1e-15)
    np.testing.assert_allclose(right, pts[1:], atol=1e-15)
    assert s.z.shape == (p.n - 1,) and not s.z.any()


def test_flat_sail_for_zero_amplitude():
    s = initial_state(SailParameters(amplitude=0.0, n=10))
    assert not s.theta.any() and not s.y.any()
    np.testing.assert_allclose(s.x, (np.arange(10) + 0.5) / 10, atol=1e-15)
