"""Failure of a run read from its states: where it fails (trough or crest) and the hinges' heights.

The failure rule itself (amplitude from the total-least-squares line or plane, failure time) is the model's
(:mod:`lightsail_mbs.model.failure`: every solver stops by it and every Result reports it); its names are
importable from here too.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.model.failure import amplitude, failure_time, line_offsets, plane_amplitude, plane_offsets

__all__ = [
    "amplitude",
    "fails_at_trough",
    "failure_time",
    "hinge_heights",
    "line_offsets",
    "plane_amplitude",
    "plane_offsets",
]


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
