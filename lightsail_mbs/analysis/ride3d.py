"""A sheet run read as beam riding in 3-D: lateral position, tilt, spin rate and shape amplitude, and the
verdict rides / drifts out / crumples.

Every sheet run records its histories (model.sheet_ride: ``Result.info["ride"]``); a run saved without them
(an older file) has them computed here from its tile arrays and its payload record. The verdict follows the
planar strip's (:func:`lightsail_mbs.analysis.beam_riding.flexible_ride`): "crumples" once the deformation
δ reaches ``crumple`` (m), else "drifts out" once the craft's
centre of mass is ``drift_factor`` beam waists from the beam axis (a Gaussian beam; the radial distance
√(X² + Y²)), else "rides"; ``decided_at`` is the first sample that decides it. The deformation is the
largest distance of a tile centre from the initial shape moved rigidly onto the sample (the mass-weighted
least-squares rotation and translation, Kabsch's): a billowed sail's own cap is no deformation, whereas the
shape amplitude (the failure rule's plane amplitude, reported beside it) counts the cap's sag.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import check, finite
from lightsail_mbs.model import sheet_ride as ride_model
from lightsail_mbs.model.sheet_grid import Tiles

VERDICTS = ("rides", "drifts out", "crumples")


@dataclass
class SheetRide:
    """A sheet run's beam-riding histories (module docstring) and its verdict; arrays (T,) or (T, 2)."""

    time: np.ndarray
    lateral: np.ndarray  # (T, 2): X, Y of the craft's centre of mass from the beam axis (m)
    tilt: np.ndarray  # (T, 2): α_x, α_y (rad)
    spin_rate: np.ndarray  # Ω (rad/s)
    amplitude: np.ndarray  # shape amplitude (m): the failure rule's plane amplitude
    deformation: np.ndarray  # δ (m): the largest distance from the rigidly moved initial shape
    verdict: str
    decided_at: float | None

    @property
    def distance(self) -> np.ndarray:
        """√(X² + Y²) (m): the centre of mass's distance from the beam axis."""
        return np.hypot(self.lateral[:, 0], self.lateral[:, 1])


def histories(result) -> dict:
    """The run's ride histories {name: (T,) array}: recorded, or computed from its arrays."""
    recorded = result.info.get("ride")
    if recorded is not None:
        return {name: np.asarray(recorded[name], float) for name in ride_model.HISTORIES}
    payload = result.info.get("payload_centre")
    return ride_model.histories(
        result.params,
        result.tile_centres,
        result.tile_angular_velocities,
        None if payload is None else np.asarray(payload, float),
    )


def deformation(masses: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """(T,) δ: the largest distance of the centres (T, N, 3) from the first sample's, moved rigidly onto each
    sample (mass-weighted Kabsch fit)."""
    w = masses / masses.sum()
    mean = np.einsum("k,tki->ti", w, centres)
    x = centres - mean[:, None]
    x0 = x[0]
    H = np.einsum("k,ki,tkj->tij", w, x0, x)  # Σ w x₀ xᵀ
    U, _, Vt = np.linalg.svd(H)
    sign = np.sign(np.linalg.det(np.einsum("tij,tjk->tik", U, Vt)))
    Vt[:, 2] *= sign[:, None]
    rotation = np.einsum("tji,tkj->tik", Vt, U)  # R = V Uᵀ maps x₀ onto x
    fitted = np.einsum("tij,kj->tki", rotation, x0)
    return np.max(np.linalg.norm(x - fitted, axis=-1), axis=1)


def classify(time, distance, deformation, width: float, crumple: float) -> tuple[str, float | None]:
    """(verdict, decided_at) of histories (T,): "crumples" at the first sample where the deformation reaches
    crumple (m), "drifts out" at the first where the distance from the axis reaches width (m; inf: never),
    whichever comes first (crumples on a tie), else ("rides", None)."""
    firsts = []
    crumpled = np.flatnonzero(np.asarray(deformation) >= crumple)
    if crumpled.size:
        firsts.append((int(crumpled[0]), "crumples"))
    if math.isfinite(width):
        drifted = np.flatnonzero(np.asarray(distance) >= width)
        if drifted.size:
            firsts.append((int(drifted[0]), "drifts out"))
    if not firsts:
        return "rides", None
    k, verdict = min(firsts)
    return verdict, float(time[k])


def sheet_ride(result, crumple: float = 0.01, drift_factor: float = 1.0) -> SheetRide:
    """The beam-riding histories and verdict of a sheet run (module docstring)."""
    check("result", "a chain run", result.is_sheet, "a sheet run (model 'sheet')")
    crumple, drift_factor = finite("crumple", crumple), finite("drift_factor", drift_factor)
    check("crumple", crumple, crumple > 0, "> 0 m")
    check("drift_factor", drift_factor, drift_factor > 0, "> 0")
    h = histories(result)
    lateral = np.column_stack([h["lateral_x"], h["lateral_y"]])
    tilt = np.column_stack([h["tilt_x"], h["tilt_y"]])
    amplitude = np.asarray(result.amplitude, float)
    delta = deformation(Tiles.of(result.params).masses, np.asarray(result.tile_centres, float))
    distance = np.hypot(lateral[:, 0], lateral[:, 1])
    verdict, when = classify(result.time, distance, delta, drift_factor * result.params.beam_waist, crumple)
    return SheetRide(np.asarray(result.time), lateral, tilt, h["spin_rate"], amplitude, delta, verdict, when)
