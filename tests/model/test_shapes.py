"""Initial shape: hinges on the sine of Eq. (1), exact chords, slices along the chords."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.model import shapes
from lightsail_mbs.model.shapes import hinge_points, initial_state


@pytest.mark.parametrize("model, extra", [("torsion", {}), ("rigid", {}), ("tnt", {"tension": 1e3})])
def test_hinges_on_sine_with_exact_chords(model, extra):
    p = SailParameters(model=model, n=40, defect_amplitude=1e-2, defect_mode=2.5, **extra)
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
    p = SailParameters(n=25, defect_amplitude=1e-3, defect_mode=1.5)
    s = initial_state(p)
    pts = hinge_points(p)
    l = p.slice_length
    left = np.c_[s.x - 0.5 * l * np.cos(s.theta), s.y - 0.5 * l * np.sin(s.theta)]
    right = np.c_[s.x + 0.5 * l * np.cos(s.theta), s.y + 0.5 * l * np.sin(s.theta)]
    np.testing.assert_allclose(left, pts[:-1], atol=1e-15)
    np.testing.assert_allclose(right, pts[1:], atol=1e-15)
    assert s.z.shape == (p.n - 1,) and not s.z.any()


def test_flat_sail_for_zero_amplitude():
    s = initial_state(SailParameters(defect_amplitude=0.0, n=10))
    assert not s.theta.any() and not s.y.any()
    np.testing.assert_allclose(s.x, (np.arange(10) + 0.5) / 10, atol=1e-15)


def test_multimode_defect_seeded_rms_and_chords():
    from lightsail_mbs.model.shapes import multimode_coefficients, multimode_profile

    p = SailParameters(n=60, defect_amplitude=1e-4, defect_seed=3, defect_mode_count=12, defect_spectrum=1.5)
    nu, a, phase = multimode_coefficients(p)
    nu2, a2, phase2 = multimode_coefficients(p)
    np.testing.assert_array_equal(a, a2)  # same seed, same defect
    assert not np.allclose(a, multimode_coefficients(p.replace(defect_seed=4))[1])
    np.testing.assert_allclose(nu, 0.5 * np.arange(1, 13))
    x = np.linspace(0, 1, 20001)
    w = multimode_profile(p)(x)
    assert np.sqrt(np.trapezoid(w * w, x)) == pytest.approx(1e-4 / np.sqrt(2), rel=1e-3)
    pts = hinge_points(p)
    np.testing.assert_allclose(pts[:, 1], multimode_profile(p)(pts[:, 0]), atol=1e-15)
    np.testing.assert_allclose(np.hypot(*np.diff(pts, axis=0).T), p.slice_length, rtol=1e-13)


def test_same_seed_same_defect_different_seed_different_defect():
    p = SailParameters(n=20, defect_seed=5)
    a, b, c = initial_state(p), initial_state(p), initial_state(p.replace(defect_seed=6))
    np.testing.assert_array_equal(a.theta, b.theta)
    assert not np.allclose(a.theta, c.theta)


def test_defect_warnings_when_the_chain_cannot_carry_the_defect():
    """n = 3 with ν = 3/2 draws one slice per half wave: the chain's initial amplitude is round-off, and
    both the resolution and the carried amplitude are flagged (and recorded in the Result); a₀ below
    1e-12 L is flagged for precision; the paper's n = 30 raises nothing."""
    from lightsail_mbs import RunSettings, solve
    from lightsail_mbs.analysis import amplitude

    coarse = SailParameters(n=3, defect_mode=1.5)
    start = shapes.initial_state(coarse)
    notes = shapes.defect_warnings(coarse, amplitude(start.x, start.y))
    assert len(notes) == 2 and "slices per half wavelength" in notes[0] and "round-off" in notes[1]
    assert solve(coarse, "reduced", RunSettings(t_final=0.01)).warnings == notes
    tiny = SailParameters(defect_amplitude=1e-13)
    start = shapes.initial_state(tiny)
    assert any("double precision" in note for note in shapes.defect_warnings(tiny, amplitude(start.x, start.y)))
    paper = SailParameters()
    start = shapes.initial_state(paper)
    assert shapes.defect_warnings(paper, amplitude(start.x, start.y)) == []
    assert shapes.defect_warnings(paper.replace(defect_amplitude=0.0), 0.0) == []
