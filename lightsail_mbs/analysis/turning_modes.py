"""The transverse modes of a spinning sheet measured from a run, in the frame that turns with it.

**Deflections in the turning frame.** The tiles are material points of the sheet, so the height of tile k's
centre above the sheet's centre of mass, w_k(t) = c_{k,z}(t) − Σ_j A_j c_{j,z}(t) / Σ_j A_j (A the tiles'
areas, the film uniform), is the deflection at that material point in the turning frame, whichever frame the
run was integrated in (the in-house solver's turning frame or Exudyn's inertial one): a rotation about ẑ
moves a point in the plane, not along ẑ. The point's polar angle in the turning frame is its initial angle
θ_k about the centre of mass (the frame turns with the sheet; its in-plane motion relative to the frame is
second order in w for a free flat disc). Subtracting the centre of mass removes the translation along ẑ
(n = s = 0, ω = 0).

**Angular harmonics** (:func:`ring_harmonics`). On a polar mesh the tiles sit on rings of m equal tiles at
equal angles; the n-th harmonic of ring r,

    c_{n,r}(t) = Σ_{k ∈ r} A_k w_k(t) e^(−i n θ_k),

keeps only the modes with n nodal diameters (cos nθ and sin nθ; on m sectors n and m − n alias, so a
ring of m tiles carries n ≤ m/2, the single tile at a polar mesh's centre only n = 0), each ring one
channel, its real and imaginary parts two real signals.

**Matrix pencil** (:func:`matrix_pencil`, Hua & Sarkar 1990, several channels sharing their poles). A
sum of M damped sinusoids y_c(t_j) = Σ_i a_{ci} z_i^j, z_i = e^(λ_i Δt), sampled at a uniform interval Δt,
makes every channel's Hankel matrix Y_c (rows [y_c(t_j), …, y_c(t_(j+P))]) of rank M with the same row
space: the right singular vectors V of the stacked Y = [Y_1; Y_2; …] span it, and with V₁, V₂ the rows
of V without its last and without its first row, the eigenvalues of V₁⁺V₂ are the z_i. Keeping the M
singular values above a relative threshold drops the round-off and what a finite step leaves; the
frequencies come from the shared poles, not from the bin of a Fourier transform, so their error falls
with the signal's noise, not with 1/duration (Nyquist still bounds them: |ω| < π/Δt). The amplitudes
a_{ci} are the least-squares fit of the z_i^j to each channel; a pole's weight is ‖a_{·i}‖₂.

:func:`measured_modes` gives, for every n, the oscillating poles (Im λ > 0 and |Re λ| < Im λ) with
their weights, ascending in ω: the turning-frame frequencies of the run's transverse modes, to be paired
with a spectrum's or a closed form's (n, s).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import planforms
from lightsail_mbs.model.parameters import SailParameters

THRESHOLD = 1e-9  # singular values kept: above this × the largest
PENCIL_ROWS = 400  # at most this many + 1 columns of each channel's Hankel matrix


def matrix_pencil(signals: np.ndarray, dt: float, threshold: float = THRESHOLD, order: int | None = None):
    """(λ (M,) in 1/s, weights (M,)) of the poles shared by real signals (C, T) sampled every dt (s)
    (module docstring). order: M, else the singular values above threshold × the largest."""
    y = np.atleast_2d(np.asarray(signals, float))
    count = y.shape[1]
    if not (dt > 0 and np.isfinite(dt)):
        raise ParameterError(f"dt={dt!r} is invalid: allowed a finite sampling interval > 0 (s)")
    columns = min(PENCIL_ROWS, count // 3)
    if columns < 2:
        raise ParameterError(f"signals have {count} samples: allowed ≥ 6 for a matrix pencil")
    rows = count - columns
    index = np.arange(rows)[:, None] + np.arange(columns + 1)[None, :]
    hankel = y[:, index].reshape(-1, columns + 1)
    _, sigma, vh = np.linalg.svd(hankel, full_matrices=False)
    if order is None:
        order = int(np.count_nonzero(sigma > threshold * sigma[0]))
    order = max(1, min(int(order), columns))
    v = vh[:order].conj().T
    poles = np.linalg.eigvals(np.linalg.pinv(v[:-1]) @ v[1:])
    vandermonde = poles[None, :] ** np.arange(count)[:, None]
    amplitudes, *_ = np.linalg.lstsq(vandermonde, y.T.astype(complex), rcond=None)
    return np.log(poles.astype(complex)) / dt, np.linalg.norm(amplitudes, axis=1)


def polar_rings(p: SailParameters) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(ring index (N,), polar angle θ_k (N,), area A_k (N,)) of the tiles of a sheet's mesh about its
    area-weighted centre: the turning frame's material angles (module docstring)."""
    if p.model != "sheet":
        raise ParameterError(f"model={p.model!r} is invalid for angular harmonics: allowed 'sheet'")
    mesh = planforms.mesh_of(p)
    rel = mesh.centres - mesh.areas @ mesh.centres / mesh.areas.sum()
    radius = np.hypot(rel[:, 0], rel[:, 1])
    ring = np.unique(np.round(radius / radius.max(), 9), return_inverse=True)[1]
    return ring, np.arctan2(rel[:, 1], rel[:, 0]), mesh.areas


def ring_harmonics(p: SailParameters, centres: np.ndarray, diameters: int) -> np.ndarray:
    """The n-th angular harmonic of the deflection (module docstring) of tile centres (T, N, 3) of a run:
    real channels (2 × rings, T), the real and imaginary parts of c_{n,r}(t) ring by ring, on the rings of
    at least 2n tiles (all-zero channels, as the imaginary parts for n = 0, left out)."""
    ring, theta, areas = polar_rings(p)
    z = np.asarray(centres, float)[..., 2]
    if z.ndim != 2 or z.shape[1] != ring.size:
        raise ParameterError(f"centres of shape {np.shape(centres)} are invalid: allowed (T, {ring.size}, 3)")
    w = z - (z @ areas / areas.sum())[:, None]
    phase = areas * np.exp(-1j * diameters * theta)
    counts = np.bincount(ring)
    rings = [r for r in range(counts.size) if 2 * diameters <= counts[r] or diameters == 0]
    channels = np.array([w[:, ring == r] @ phase[ring == r] for r in rings])
    real = np.vstack([channels.real, channels.imag])
    return real[np.abs(real).max(axis=1) > 0]


@dataclass(frozen=True)
class MeasuredMode:
    """An oscillating pole of a run's deflection with n nodal diameters: frequency ω (rad/s) in the
    turning frame, growth rate Re λ (1/s), its weight (the amplitudes' 2-norm over the channels) and that
    weight as a fraction of the largest weight of the same n."""

    diameters: int
    frequency: float
    growth_rate: float
    weight: float
    share: float


def measured_modes(
    p: SailParameters, times: np.ndarray, centres: np.ndarray, largest: int, threshold: float = THRESHOLD
) -> list[MeasuredMode]:
    """The oscillating transverse modes of a run of a spinning polar sheet with n = 0 … largest nodal
    diameters (module docstring), by n and then ascending ω. times (T,) uniform; centres (T, N, 3)."""
    times = np.asarray(times, float)
    steps = np.diff(times)
    if times.size < 6 or not np.allclose(steps, steps[0], rtol=1e-6, atol=0.0):
        raise ParameterError("times are invalid for a matrix pencil: allowed ≥ 6 uniform samples")
    modes = []
    for n in range(largest + 1):
        rates, weights = matrix_pencil(ring_harmonics(p, centres, n), float(steps[0]), threshold)
        keep = (rates.imag > 0) & (np.abs(rates.real) < rates.imag)
        top = weights[keep].max(initial=0.0)
        for k in np.nonzero(keep)[0][np.argsort(rates.imag[keep])]:
            modes.append(
                MeasuredMode(n, float(rates[k].imag), float(rates[k].real), float(weights[k]), weights[k] / top)
            )
    return modes
