"""Oscillation frequency of a run: the dominant spectral peak of the slice angles θ_i(t).

The paper measures frequencies with a discrete Fourier transform (Appendix B) and compares the
"vibrational frequency" of stable TnT sails across tensions and thicknesses (Figs 18–19). Here each
signal θ_i(t) − mean_j θ_j(t) (the whole sail's rigid rotation removed) is linearly detrended,
Hann-windowed and zero-padded; the power spectra of all slices are summed and the highest peak
above the lowest resolvable frequency is refined by a parabola through the log-power of its three
neighbouring bins (a fraction of a bin, ≪ 1/duration).
"""
from __future__ import annotations

import numpy as np

PADDING = 8   # zero-padding factor of the FFT (interpolates the spectrum 8 times finer than 1/duration)


def power_spectrum(time: np.ndarray, signals: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(frequencies in Hz, summed power) of signals (T,) or (T, k) sampled at uniform times (T,).

    Each column is detrended (least-squares line) and Hann-windowed before a zero-padded real FFT.
    """
    time = np.asarray(time, float)
    signals = np.asarray(signals, float).reshape(time.size, -1)
    if time.size < 8:
        raise ValueError(f"time has {time.size} samples: allowed ≥ 8 for a spectrum")
    dt = np.diff(time)
    if not np.allclose(dt, dt[0], rtol=1e-6, atol=0.0):
        raise ValueError("time samples are not uniform: allowed a uniform output interval")
    basis = np.vstack([np.ones_like(time), time - time.mean()]).T
    coefficients, *_ = np.linalg.lstsq(basis, signals, rcond=None)
    residual = (signals - basis @ coefficients) * np.hanning(time.size)[:, None]
    size = PADDING * time.size
    power = (np.abs(np.fft.rfft(residual, n=size, axis=0)) ** 2).sum(axis=1)
    return np.fft.rfftfreq(size, d=dt[0]), power


def dominant_frequency(time: np.ndarray, signals: np.ndarray) -> float:
    """Frequency (Hz) of the highest peak of power_spectrum above 1.5 / duration, parabola-refined.

    Returns nan when the signals are constant (no peak).
    """
    freq, power = power_spectrum(time, signals)
    duration = float(time[-1] - time[0])
    usable = np.nonzero(freq >= 1.5 / duration)[0]
    if usable.size < 3 or not np.any(power[usable] > 0):
        return float("nan")
    k = int(usable[np.argmax(power[usable])])
    if k == 0 or k == freq.size - 1:
        return float(freq[k])
    a, b, c = np.log(np.maximum(power[k - 1:k + 2], np.finfo(float).tiny))
    curvature = a - 2.0 * b + c
    shift = 0.5 * (a - c) / curvature if curvature < 0 else 0.0
    return float(freq[k] + shift * (freq[1] - freq[0]))


def angle_frequency(result) -> float:
    """Dominant oscillation frequency (Hz) of a Result's slice angles, rigid rotation removed."""
    theta = np.asarray(result.theta, float)
    return dominant_frequency(result.time, theta - theta.mean(axis=1, keepdims=True))
