"""Frequencies of a run (analysis.frequencies): the refined FFT peak of many slices, rigid rotation ignored;
least-squares sinusoid fits beyond the FFT bin, damped decay."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters
from lightsail_mbs.analysis.frequencies import angle_frequency, dominant_frequency, fit_damped_sinusoid, fit_sinusoid
from tests.sweep_fake import fake_result


@pytest.mark.parametrize("frequency", [0.4, 2.74, 17.0])
def test_dominant_frequency_of_a_drifting_multi_slice_signal(frequency):
    t = np.arange(0.0, 6.0, 1e-3)
    signals = np.column_stack(
        [
            np.sin(2 * np.pi * frequency * t + phase) + 0.3 * np.sin(2 * np.pi * 2.3 * frequency * t) + 0.05 * t
            for phase in (0.0, 1.0, 2.0)
        ]
    )
    # resolution of the raw FFT is 1/6 Hz; the refined peak is far better
    assert dominant_frequency(t, signals) == pytest.approx(frequency, rel=2e-3)


def test_angle_frequency_ignores_rigid_rotation():
    p = SailParameters(n=12)
    result = fake_result(p, growth_rate=0.0)
    t = result.time = np.linspace(0.0, 4.0, 2001)
    x = (np.arange(p.n) + 0.5) / p.n
    result.theta = 0.3 * t[:, None] + 1e-4 * np.cos(2 * np.pi * 3.0 * t)[:, None] * np.cos(3 * np.pi * x)[None, :]
    assert angle_frequency(result) == pytest.approx(3.0, rel=2e-3)


def test_spectrum_rejects_uneven_sampling():
    with pytest.raises(ValueError, match="uniform"):
        dominant_frequency(np.r_[0.0, np.cumsum(np.linspace(1.0, 2.0, 20))], np.ones(21))


def test_fit_sinusoid_recovers_frequency_beyond_the_fft_bin():
    t = 0.25 + np.arange(0, 0.05, 1e-5)
    y = 2e-4 + 1e-4 * np.cos(2 * np.pi * 195.2813 * t + 1.1)
    fit = fit_sinusoid(t, y)
    assert fit.frequency == pytest.approx(195.2813, rel=1e-10)
    assert fit.amplitude == pytest.approx(1e-4, rel=1e-9) and fit.offset == pytest.approx(2e-4, rel=1e-9)


def test_damped_fit_recovers_decay_rate_and_frequency():
    """A clean e^(−σt) cos(2πft + φ): σ and f to round-off level (no offset in the damped model)."""
    t = np.arange(0.0, 4.0, 1e-3)
    y = 1e-3 * np.exp(-0.5 * t) * np.cos(2 * np.pi * 3.7 * t + 0.4)
    fit = fit_damped_sinusoid(t, y)
    assert fit.decay_rate == pytest.approx(0.5, rel=1e-9)
    assert fit.frequency == pytest.approx(3.7, rel=1e-10)
    assert fit.amplitude == pytest.approx(1e-3, rel=1e-9)
