"""Frequencies of a run: the dominant spectral peak of the slice angles, and a least-squares sinusoid fit.

* Spectral peak. The paper measures frequencies with a discrete Fourier transform (Appendix B) and
  compares the "vibrational frequency" of stable TnT sails across tensions and thicknesses
  (Figs 18–19). Here each signal θ_i(t) − mean_j θ_j(t) (the whole sail's rigid rotation removed) is
  linearly detrended, Hann-windowed and zero-padded; the power spectra of all slices are summed and the
  highest peak above the lowest resolvable frequency is refined by a parabola through the log-power of
  its three neighbouring bins (a fraction of a bin, ≪ 1/duration).
* Sinusoid fit. The model y(t) = c + a cos(ωt) + b sin(ωt) is linear in (c, a, b) for a given ω; ω is
  found by minimising the residual (variable projection), started from the spectral peak, searched
  within ± one FFT bin (bounded Brent) and polished by Gauss–Newton steps on all four parameters (the
  flat minimum limits a scalar search to ≈ √ε relative; Gauss–Newton reaches the least-squares
  optimum). For a clean sinusoid sampled over many periods the error is set by round-off and by any
  other modes in the signal, far below the FFT bin width 1/duration.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

PADDING = 8  # zero-padding factor of the FFT (interpolates the spectrum 8 times finer than 1/duration)


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
    a, b, c = np.log(np.maximum(power[k - 1 : k + 2], np.finfo(float).tiny))
    curvature = a - 2.0 * b + c
    shift = 0.5 * (a - c) / curvature if curvature < 0 else 0.0
    return float(freq[k] + shift * (freq[1] - freq[0]))


def angle_frequency(result) -> float:
    """Dominant oscillation frequency (Hz) of a Result's slice angles, rigid rotation removed."""
    theta = np.asarray(result.theta, float)
    return dominant_frequency(result.time, theta - theta.mean(axis=1, keepdims=True))


GAUSS_NEWTON_STEPS = 3


@dataclass(frozen=True)
class SineFit:
    """y ≈ offset + amplitude cos(2π frequency t + phase); rms of the residual."""

    frequency: float  # Hz
    amplitude: float
    phase: float  # rad
    offset: float
    residual_rms: float


def _linear_part(t: np.ndarray, y: np.ndarray, omega: float):
    basis = np.column_stack([np.ones_like(t), np.cos(omega * t), np.sin(omega * t)])
    coef, *_ = np.linalg.lstsq(basis, y, rcond=None)
    return coef, y - basis @ coef


def fit_sinusoid(time, signal, guess: float | None = None) -> SineFit:
    """Least-squares sinusoid through signal(time) (uniform or not); guess: starting frequency (Hz),
    default the FFT peak (uniform samples needed then)."""
    from scipy.optimize import minimize_scalar

    t = np.asarray(time, float)
    y = np.asarray(signal, float)
    t0 = t[0]
    t = t - t0
    duration = t[-1]
    f0 = dominant_frequency(t, y) if guess is None else float(guess)
    width = 1.0 / duration

    def cost(f):
        return float(np.sum(_linear_part(t, y, 2 * np.pi * f)[1] ** 2))

    best = minimize_scalar(
        cost,
        bounds=(max(f0 - width, 0.5 * f0), f0 + width),
        method="bounded",
        options={"xatol": 1e-12 * f0, "maxiter": 500},
    )
    omega = 2 * np.pi * float(best.x)
    for _ in range(GAUSS_NEWTON_STEPS):
        (c, a, b), residual = _linear_part(t, y, omega)
        slope = t * (-a * np.sin(omega * t) + b * np.cos(omega * t))  # ∂y/∂ω
        basis = np.column_stack([np.ones_like(t), np.cos(omega * t), np.sin(omega * t), slope])
        step, *_ = np.linalg.lstsq(basis, residual, rcond=None)
        omega += step[3]
    f = float(omega / (2 * np.pi))
    (c, a, b), residual = _linear_part(t, y, omega)
    phase = float(np.angle(np.exp(1j * (np.arctan2(-b, a) - omega * t0))))
    return SineFit(f, float(np.hypot(a, b)), phase, float(c), float(np.sqrt(np.mean(residual**2))))


@dataclass(frozen=True)
class DampedSineFit:
    """y ≈ e^(−decay_rate t) amplitude cos(2π frequency t + phase), t from the first sample."""

    frequency: float  # Hz
    decay_rate: float  # σ, 1/s
    amplitude: float
    phase: float  # rad
    residual_rms: float


def fit_damped_sinusoid(time, signal) -> DampedSineFit:
    """Least-squares damped sinusoid through signal(time): started from fit_sinusoid's frequency and
    no decay, all four parameters polished by trust-region least squares."""
    from scipy.optimize import least_squares

    t = np.asarray(time, float)
    t = t - t[0]
    y = np.asarray(signal, float)
    start = fit_sinusoid(t, y)
    scale = np.max(np.abs(y))

    def residual(v):
        omega, sigma, a, b = v
        return (np.exp(-sigma * t) * (a * np.cos(omega * t) + b * np.sin(omega * t)) - y) / scale

    a0, b0 = start.amplitude * np.cos(start.phase), -start.amplitude * np.sin(start.phase)
    fit = least_squares(residual, [2 * np.pi * start.frequency, 0.0, a0, b0], xtol=1e-15, ftol=1e-15, gtol=1e-15)
    omega, sigma, a, b = fit.x
    return DampedSineFit(
        float(omega / (2 * np.pi)),
        float(sigma),
        float(np.hypot(a, b)),
        float(np.arctan2(-b, a)),
        float(scale * np.sqrt(np.mean(fit.fun**2))),
    )
