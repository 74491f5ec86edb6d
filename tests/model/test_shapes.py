"""Initial shape: hinges on the sine of Eq. (1), exact chords, slices along the chords."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, SailParameters
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


# ---- billowed start ---------------------------------------------------------------------------------
def billow_centre(p):
    """The centre of curvature C = (L/2, −R_c)."""
    return np.array([0.5 * p.length, -p.billow_radius])


@pytest.mark.parametrize("radius", [0.4, 2.0, -1.3, 50.0])
@pytest.mark.parametrize("n", [7, 30])
def test_billowed_hinges_on_the_circle_with_exact_chords(radius, n):
    p = SailParameters(n=n, billow_radius=radius, defect_amplitude=0.0)
    pts = hinge_points(p)
    np.testing.assert_allclose(np.hypot(*(pts - billow_centre(p)).T), abs(radius), rtol=1e-14)
    np.testing.assert_allclose(np.hypot(*np.diff(pts, axis=0).T), p.slice_length, rtol=1e-13)
    # symmetric about the apex x = L/2; the edges lie towards the laser (−y) for R_c > 0, downstream for R_c < 0
    np.testing.assert_allclose(pts[:, 0] - 0.5, -(pts[::-1, 0] - 0.5), atol=1e-15)
    np.testing.assert_allclose(pts[:, 1], pts[::-1, 1], atol=1e-15)
    assert np.sign(pts[0, 1]) == -np.sign(radius) and np.max(np.abs(pts[:, 1])) == pytest.approx(abs(pts[0, 1]))
    sagitta = abs(radius) * (1 - np.cos(np.arcsin(0.5 * np.ptp(pts[:, 0]) / abs(radius))))
    assert abs(pts[0, 1]) == pytest.approx(sagitta, rel=1e-12)  # the apex (L/2, 0) is on the circle
    if n % 2 == 0:
        np.testing.assert_allclose(pts[n // 2], [0.5, 0.0], atol=1e-15)
    s = initial_state(p)
    np.testing.assert_allclose(s.theta, -s.theta[::-1], atol=1e-14)  # slopes antisymmetric about the apex
    assert np.all(np.diff(s.theta) * radius < 0)  # each slice turns the same way along a circle


@pytest.mark.parametrize("radius", [2.0, -0.8])
def test_defect_on_top_of_the_arc_along_its_normal(radius):
    p = SailParameters(n=40, billow_radius=radius, defect_amplitude=2e-3, defect_mode=2.5)
    pts = hinge_points(p)
    np.testing.assert_allclose(np.hypot(*np.diff(pts, axis=0).T), p.slice_length, rtol=1e-13)
    # each hinge sits w(u) off the circle along the radius, u its arc length from hinge 0 along the arc
    rel = pts - billow_centre(p)
    kappa = 1.0 / radius
    psi = np.arctan2(rel[:, 0] * np.sign(radius), rel[:, 1] * np.sign(radius))
    s = 0.5 * p.length + psi / kappa
    u = s - s[0] + 0.0
    offset = (np.hypot(*rel.T) - abs(radius)) * np.sign(radius)
    w0 = offset[0]
    assert w0 == pytest.approx(0.0, abs=1e-15)
    np.testing.assert_allclose(offset, 2e-3 * np.sin(2 * np.pi * 2.5 * u), atol=1e-13)


def test_billowed_tnt_chords_and_the_flat_limit():
    p = SailParameters(model="tnt", tension=1e3, n=20, billow_radius=3.0, defect_amplitude=1e-3)
    chords = np.hypot(*np.diff(hinge_points(p), axis=0).T)
    expected = np.full(p.n, p.slice_length)
    expected[:-1] += p.tension / p.axial_stiffness
    np.testing.assert_allclose(chords, expected, rtol=1e-13)
    # a huge radius gives the flat construction back (up to L²/R_c and the centring of the chain)
    flat = SailParameters(n=24, defect_amplitude=1e-3, defect_mode=1.5)
    wide = hinge_points(flat.replace(billow_radius=1e9))
    straight = hinge_points(flat)
    shift = wide[0, 0] - straight[0, 0]
    assert abs(shift) < 1e-5
    np.testing.assert_allclose(wide - [shift, 0.0], straight, atol=1e-8)


def test_billow_radius_validated_and_absent_from_records_at_its_default():
    with pytest.raises(ParameterError, match="billow_radius"):
        SailParameters(n=30, billow_radius=0.3)  # 30 chords of 1/30 m need R_c ≥ 0.3185 m for ≤ 180°
    SailParameters(n=30, billow_radius=0.3185)
    for bad in (0.0, float("nan"), "2", True):
        with pytest.raises(ParameterError, match="billow_radius"):
            SailParameters(billow_radius=bad)
    with pytest.raises(ParameterError, match="boundary"):
        SailParameters(billow_radius=2.0, boundary="cantilever")
    assert "billow_radius" not in SailParameters().to_dict()
    p = SailParameters(billow_radius=-2.5)
    assert p.to_dict()["billow_radius"] == -2.5 and SailParameters.from_dict(p.to_dict()) == p


def test_both_solvers_start_from_the_billowed_sail_and_agree():
    from lightsail_mbs import RunSettings, solve

    p = SailParameters(model="torsion", n=12, youngs_modulus=4.5e9, billow_radius=1.5, defect_amplitude=1e-4)
    settings = RunSettings(t_final=0.05, output_interval=1e-3)
    start = initial_state(p)
    runs = [solve(p, solver, settings) for solver in ("reduced", "exudyn")]
    for r in runs:
        np.testing.assert_allclose(r.theta[0], start.theta, atol=1e-14)
        np.testing.assert_allclose(r.y[0], start.y, atol=1e-14)
    moved = np.max(np.abs(runs[0].theta[-1] - start.theta))
    assert moved > 0.05  # the load turns the edges of the billowed film flatter (0.31 → 0.21 rad in 50 ms)
    # Exudyn's default 1 ms step (generalized-α) against DOP853 at rtol 1e-9: 4e-4 of the motion measured
    assert np.max(np.abs(runs[0].theta[-1] - runs[1].theta[-1])) < 2e-3 * moved


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
