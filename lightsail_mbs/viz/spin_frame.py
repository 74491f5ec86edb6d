"""The frame a sheet run is shown in: the inertial frame of the Result, or the frame that turns with the sail.

A Result's tile arrays are given in the frame that accelerates with the flat sail at g₀ and does not turn
(the inertial frame here). The **rotating frame** turns about the sail's normal through its centre of mass
at the mean in-plane spin rate of the tiles, so that a sail spinning as a whole stands still in it and
only its deformation moves:

* centre of mass c(t) = Σ m_k x_k / M (tile masses m_k, model.sheet_grid.Tiles);
* normal n̂(t): the mass-weighted mean of the tile normals R_k ẑ, normalised;
* spin rate Ω(t) = Σ m_k ω_k·n̂ / M (ω_k the tiles' angular velocities), equal to the rate of a rigid
  rotation about n̂;
* angle ψ(t) = ∫₀ᵗ Ω dt by the trapezoidal rule over the Result's samples (exact for a constant rate;
  O(Δt²) in the sample interval otherwise), ψ(0) = 0, so that both frames agree at the start.

A point x is shown at x' = c + Q(x − c) with Q = Q(n̂, −ψ) the rotation by −ψ about n̂ (Rodrigues): the
centre of mass keeps its path and the spin is taken out. Vectors turn with Q; a velocity loses the frame's
motion, v' = ċ + Q(v − ċ − Ω n̂ × (x − c)), and an angular velocity its spin, ω' = Q(ω − Ω n̂), with ċ the
centre of mass's velocity Σ m_k v_k / M. (The tilting of n̂ itself is slow next to the spin and is not
taken out.) A tile's rotation becomes Q R_k.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import sheet
from lightsail_mbs.result import Result

FRAMES = ("inertial", "rotating")


def require_sheet_run(result: Result, what: str) -> None:
    """One line if the run is not a sheet's: `what` needs a sheet run."""
    if not result.is_sheet:
        raise ParameterError(f"{what} needs a sheet run: this run is of model {result.params.model!r} (a chain)")


def check_frame(frame: str) -> None:
    if frame not in FRAMES:
        raise ParameterError(f"frame={frame!r} is invalid: allowed {', '.join(FRAMES)}")


def spin(result: Result) -> dict:
    """The rotating frame's motion over the run (module docstring): centre of mass "centre" (T, 3) and its
    velocity "centre_velocity" (T, 3), unit normal "normal" (T, 3), spin rate "rate" (T,) (rad/s) and
    angle "angle" (T,) (rad)."""
    require_sheet_run(result, "the rotating frame")
    weights = sheet.Tiles.of(result.params).masses
    weights = weights / weights.sum()
    centre = np.einsum("k,tkj->tj", weights, result.tile_centres)
    centre_velocity = np.einsum("k,tkj->tj", weights, result.tile_velocities)
    normal = np.einsum("k,tkj->tj", weights, sheet.normal_xyz(result.tile_angles))
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    rate = np.einsum("k,tk->t", weights, np.einsum("tkj,tj->tk", result.tile_angular_velocities, normal))
    steps = np.diff(result.time) * 0.5 * (rate[1:] + rate[:-1])
    angle = np.concatenate([[0.0], np.cumsum(steps)])
    return {"centre": centre, "centre_velocity": centre_velocity, "normal": normal, "rate": rate, "angle": angle}


def axis_rotation(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """(..., 3, 3): the rotation by `angle` (...) about the unit `axis` (..., 3) (Rodrigues:
    Q = I + sin ψ K + (1 − cos ψ) K², K the cross-product matrix of the axis)."""
    a = np.asarray(axis, float)
    K = np.zeros(a.shape[:-1] + (3, 3))
    K[..., 0, 1], K[..., 0, 2] = -a[..., 2], a[..., 1]
    K[..., 1, 0], K[..., 1, 2] = a[..., 2], -a[..., 0]
    K[..., 2, 0], K[..., 2, 1] = -a[..., 1], a[..., 0]
    s = np.sin(angle)[..., None, None]
    c = np.cos(angle)[..., None, None]
    return np.eye(3) + s * K + (1.0 - c) * (K @ K)


def frame_rotation(result: Result, frame: str) -> tuple[np.ndarray, np.ndarray]:
    """(Q (T, 3, 3), centre (T, 3)): the rotation that takes the Result's frame to `frame` and the point it
    turns about (the centre of mass; zeros and identities for the inertial frame)."""
    check_frame(frame)
    steps = len(result.time)
    if frame == "inertial":
        return np.tile(np.eye(3), (steps, 1, 1)), np.zeros((steps, 3))
    motion = spin(result)
    return axis_rotation(motion["normal"], -motion["angle"]), motion["centre"]


def in_frame(result: Result, frame: str) -> Result:
    """The run with its tile arrays in `frame` (module docstring); the inertial frame returns it unchanged."""
    require_sheet_run(result, f"the {frame} frame")
    check_frame(frame)
    if frame == "inertial":
        return result
    motion = spin(result)
    Q = axis_rotation(motion["normal"], -motion["angle"])
    c, cdot, n, rate = motion["centre"], motion["centre_velocity"], motion["normal"], motion["rate"]
    arm = result.tile_centres - c[:, None, :]
    frame_velocity = rate[:, None, None] * np.cross(n[:, None, :], arm)
    relative = result.tile_velocities - cdot[:, None, :] - frame_velocity
    spin_vector = (rate[:, None] * n)[:, None, :]
    rotations = Q[:, None] @ sheet.rotation_xyz(result.tile_angles)
    return dataclasses.replace(
        result,
        tile_centres=c[:, None, :] + turn(Q, arm),
        tile_velocities=cdot[:, None, :] + turn(Q, relative),
        tile_angular_velocities=turn(Q, result.tile_angular_velocities - spin_vector),
        tile_angles=sheet.angles_xyz(rotations),
    )


def turn(Q: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """Vectors (T, N, 3) turned by the rotations Q (T, 3, 3) of their samples."""
    return np.einsum("tij,tkj->tki", Q, vectors)
