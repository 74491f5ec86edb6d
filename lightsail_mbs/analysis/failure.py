"""Amplitude and failure of chain states and trajectories: the one failure rule of every solver.

Failure criterion: amplitude(t) is half the peak-to-peak spread of the slice
centres' perpendicular offsets from their least-squares line, which removes rigid drift
and rotation. The sail has failed when amplitude(t) ≥ ratio · amplitude(0) (the paper's
"amplitude doubled" for ratio = 2).
"""

from __future__ import annotations

import numpy as np


def line_offsets(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Signed perpendicular offsets of the centres from their total-least-squares line.

    x, y: (n,) or (T, n). The line passes through the centroid along the principal axis
    (angle φ with tan 2φ = 2 s_xy / (s_xx − s_yy)); the offset is positive towards +y
    (the beam's push direction), so a trough has a negative offset.
    """
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    dx = x - x.mean(axis=-1, keepdims=True)
    dy = y - y.mean(axis=-1, keepdims=True)
    phi = 0.5 * np.arctan2(2.0 * (dx * dy).sum(axis=-1), (dx * dx).sum(axis=-1) - (dy * dy).sum(axis=-1))
    phi = np.asarray(phi)[..., None]
    return -np.sin(phi) * dx + np.cos(phi) * dy


def amplitude(x: np.ndarray, y: np.ndarray):
    """Half the peak-to-peak spread of line_offsets: a float for one state, (T,) for a trajectory."""
    off = line_offsets(x, y)
    amp = 0.5 * (off.max(axis=-1) - off.min(axis=-1))
    return float(amp) if amp.ndim == 0 else amp


def failure_time(time: np.ndarray, amp: np.ndarray, ratio: float = 2.0) -> float | None:
    """First time amplitude(t) reaches ratio · amplitude(0), linearly interpolated; None if never, and for a
    sail that starts flat (amplitude(0) = 0: no defect to grow, as the solvers' stop rule has it)."""
    if not amp[0] > 0:
        return None
    limit = ratio * amp[0]
    above = np.nonzero(amp >= limit)[0]
    if above.size == 0:
        return None
    k = int(above[0])
    if k == 0:
        return float(time[0])
    a0, a1 = amp[k - 1], amp[k]
    return float(time[k - 1] + (limit - a0) / (a1 - a0) * (time[k] - time[k - 1]))


def fails_at_trough(x: np.ndarray, y: np.ndarray) -> bool:
    """True when the largest deviation from the line of one state is a trough (negative offset)."""
    off = line_offsets(x, y)
    return bool(-off.min() > off.max())


def hinge_heights(result) -> np.ndarray:
    """Transverse positions of the hinges 0…n over time (T, n+1) (m): left end y − (l/2) sin θ of each
    slice, and the right end of slice n (the displacements w of chain_theory for an inextensible chain)."""
    half = 0.5 * result.params.slice_length
    left = result.y - half * np.sin(result.theta)
    right = result.y[:, -1:] + half * np.sin(result.theta[:, -1:])
    return np.concatenate([left, right], axis=1)
