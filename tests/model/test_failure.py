"""Amplitude and failure criterion (model.failure, read through analysis): invariant to rigid motion,
interpolated failure time, troughs (analysis.fails_at_trough)."""

import numpy as np
import pytest

from lightsail_mbs import analysis


def sine_state(amplitude=1e-5, n=30, mode=1.5):
    x = (np.arange(n) + 0.5) / n
    return x, amplitude * np.sin(2 * np.pi * mode * x)


def test_amplitude_invariant_to_rigid_motion():
    x, y = sine_state()
    a = analysis.amplitude(x, y)
    phi = 0.3
    xr = np.cos(phi) * x - np.sin(phi) * y + 5.0
    yr = np.sin(phi) * x + np.cos(phi) * y - 2.0
    assert analysis.amplitude(xr, yr) == pytest.approx(a, rel=1e-9)


def test_amplitude_of_a_straight_tilted_line_is_zero():
    x = np.linspace(0, 1, 30)
    assert analysis.amplitude(x, 0.1 * x + 3) < 1e-15


def test_amplitude_scales_and_vectorises():
    x, y = sine_state()
    amps = analysis.amplitude(np.vstack([x, x, x]), np.vstack([y, 2 * y, 3 * y]))
    np.testing.assert_allclose(amps / amps[0], [1, 2, 3], rtol=1e-9)


def test_failure_time_interpolated():
    """e^t sampled every 0.1 s doubles at ln 2 = 0.693 s, between the samples 0.6 and 0.7: the failure time
    is the straight line between them crossing 2 (exactly), within the chord's error of ln 2 — and not
    either sample."""
    t = np.linspace(0, 1, 11)
    amp = np.exp(t)
    ft = analysis.failure_time(t, amp, 2.0)
    chord = 0.6 + (2.0 - np.exp(0.6)) / (np.exp(0.7) - np.exp(0.6)) * 0.1
    assert ft == pytest.approx(chord, abs=1e-12)
    assert 0 < np.log(2) - ft < 0.1**2 / 8  # the chord of a convex curve lies above it: crosses early, < Δt²/8
    assert analysis.failure_time(t, np.ones_like(t), 2.0) is None


def test_trough_detection():
    x, y = sine_state(mode=1.5)
    y = y.copy()
    y[np.argmin(y)] -= 5e-5  # a deep trough
    assert analysis.fails_at_trough(x, y)
    assert not analysis.fails_at_trough(x, -y)


def test_failure_time_at_another_ratio():
    """Tripling: between the samples 1.0 and 1.1 s, on the chord."""
    t = np.linspace(0, 2, 21)
    chord = 1.0 + (3.0 - np.exp(1.0)) / (np.exp(1.1) - np.exp(1.0)) * 0.1
    assert analysis.failure_time(t, np.exp(t), 3.0) == pytest.approx(chord, abs=1e-12)


def test_plane_rule_is_the_line_rule_for_one_row_of_tiles():
    """One row of tiles (ny = 1) or a 1-D shape repeated across the width: the plane rule gives the chain's
    line rule in the x–z plane."""
    from lightsail_mbs import SailParameters
    from lightsail_mbs.model import sheet

    one = SailParameters(model="sheet", n=30, ny=1)
    centres, _ = sheet.initial_state(one)
    line = analysis.amplitude(centres[:, 0], centres[:, 2])
    assert analysis.plane_amplitude(centres) == pytest.approx(line, rel=1e-12)
    three, _ = sheet.initial_state(one.replace(ny=3))
    assert analysis.plane_amplitude(three) == pytest.approx(line, rel=1e-12)
    np.testing.assert_allclose(analysis.plane_offsets(centres), analysis.line_offsets(centres[:, 0], centres[:, 2]))


def test_plane_rule_ignores_rigid_motion_and_vectorises():
    rng = np.random.default_rng(3)
    x, y = np.meshgrid(np.linspace(0, 1, 9), np.linspace(0, 0.7, 6))
    w = 1e-5 * np.sin(3 * x) * np.cos(4 * y) + 1e-6 * rng.standard_normal(x.shape)
    cloud = np.column_stack([x.ravel(), y.ravel(), w.ravel()])
    a = analysis.plane_amplitude(cloud)
    off = analysis.plane_offsets(cloud)
    assert a == pytest.approx(0.5 * (off.max() - off.min()))
    angle = 0.3
    R = np.array([[np.cos(angle), 0, np.sin(angle)], [0, 1, 0], [-np.sin(angle), 0, np.cos(angle)]])
    moved = cloud @ R.T + [1.0, -2.0, 5.0]
    assert analysis.plane_amplitude(moved) == pytest.approx(a, rel=1e-9)
    trajectory = np.stack([cloud, moved, 2 * cloud])
    np.testing.assert_allclose(analysis.plane_amplitude(trajectory), [a, a, 2 * a], rtol=1e-9)
    assert analysis.plane_amplitude(cloud * [1, 1, 0]) == pytest.approx(0.0, abs=1e-17)


def test_failure_time_at_a_sample_and_of_a_flat_start():
    t = np.array([0.0, 0.5, 1.0])
    assert analysis.failure_time(t, np.array([1.0, 2.0, 3.0]), 2.0) == 0.5
    assert analysis.failure_time(t, np.array([0.0, 1e-9, 1.0]), 2.0) is None  # a flat start has no failure
