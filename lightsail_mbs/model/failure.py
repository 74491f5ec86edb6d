"""Amplitude and failure of chain and sheet states and trajectories: the one failure rule of every solver,
of the Result and of every report (lightsail_mbs.analysis re-exports it).

Failure criterion: amplitude(t) is half the peak-to-peak spread of the slice
centres' perpendicular offsets from their least-squares line, which removes rigid drift
and rotation. The sail has failed when amplitude(t) ≥ ratio · amplitude(0) (the paper's
"amplitude doubled" for ratio = 2).

The sheet's rule is the same one dimension up (:func:`plane_amplitude`): half the peak-to-peak spread
of the tile centres' signed offsets from their total-least-squares plane (through the centroid, normal
along a principal axis of the centred point cloud). Of the three principal axes the one with the
largest |z| component is the normal: for any sheet-like cloud that is the smallest-variance axis, and
for a single row of tiles (ny = 1, no variance across the width, so the plane must contain ŷ) it makes
the rule exactly the chain's line rule in the x–z plane.
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


def crossing(amp: np.ndarray, ratio: float = 2.0) -> int | None:
    """Index of the first sample whose amplitude reaches ratio · amplitude(0); None if none does, and for a
    sail that starts flat (amplitude(0) = 0: no defect to grow, as the solvers' stop rule has it)."""
    amp = np.asarray(amp, float)
    if not amp.size or not amp[0] > 0:
        return None
    above = np.nonzero(amp >= ratio * amp[0])[0]
    return int(above[0]) if above.size else None


def failure_time(time: np.ndarray, amp: np.ndarray, ratio: float = 2.0) -> float | None:
    """First time amplitude(t) reaches ratio · amplitude(0), linearly interpolated between the samples that
    bracket it (crossing); None if never, and for a sail that starts flat."""
    k = crossing(amp, ratio)
    if k is None:
        return None
    limit = ratio * amp[0]
    if k == 0:
        return float(time[0])
    a0, a1 = amp[k - 1], amp[k]
    return float(time[k - 1] + (limit - a0) / (a1 - a0) * (time[k] - time[k - 1]))


def plane_offsets(centres: np.ndarray) -> np.ndarray:
    """Signed offsets of tile centres (..., N, 3) from their total-least-squares plane, (..., N) (m);
    positive towards +z (the beam's push), so a trough has a negative offset (module docstring)."""
    c = np.asarray(centres, float)
    d = c - c.mean(axis=-2, keepdims=True)
    _, axes = np.linalg.eigh(np.einsum("...ki,...kj->...ij", d, d))  # columns: principal axes
    pick = np.argmax(np.abs(axes[..., 2, :]), axis=-1)
    normal = np.take_along_axis(axes, pick[..., None, None], axis=-1)[..., 0]
    normal = normal * np.where(normal[..., 2:3] < 0, -1.0, 1.0)
    return np.einsum("...ki,...i->...k", d, normal)


def plane_amplitude(centres: np.ndarray):
    """Half the peak-to-peak spread of plane_offsets: a float for one state (N, 3), (T,) for a trajectory."""
    off = plane_offsets(centres)
    amp = 0.5 * (off.max(axis=-1) - off.min(axis=-1))
    return float(amp) if np.ndim(amp) == 0 else amp
