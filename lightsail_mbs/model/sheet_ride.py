"""A sheet riding the beam: the histories every sheet run records (Result.info["ride"]).

From the tiles' centres c_k, velocities and angular velocities ω_k (masses m_k) and the payload's centre
P (mass m_p, model.sheet_payload) at every sample:

* **lateral position** of the craft's centre of mass, G = (Σ m_k c_k + m_p P)/(Σ m_k + m_p), from the beam
  axis: (G_x − x_c, G_y − y_c) (m);
* **tilt**: n̂ the normal of the tiles' mass-weighted best-fit plane (the smallest principal axis of
  Σ m_k (c_k − c̄)(c_k − c̄)ᵀ, turned to n_z > 0); the angles of model.sheet_pose's Q that turn ẑ to it,
  α_x = atan2(−n_x, n_z) (the x axis towards the beam) and α_y = atan2(−n_y, n_z) (rad): the tilt of a
  rigidly turned flat sail is its initial_tilt, initial_tilt_y to first order;
* **spin rate** Ω = Σ m_k ω_k·n̂ / Σ m_k (rad/s), the tiles' mean rate about the normal
  (viz.spin_frame's);
* **shape amplitude**: the failure rule's plane amplitude (model.failure), Result.amplitude.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.sheet_grid import Tiles

HISTORIES = ("lateral_x", "lateral_y", "tilt_x", "tilt_y", "spin_rate")


def plane_normals(masses: np.ndarray, centres: np.ndarray) -> np.ndarray:
    """(T, 3) unit normals (n_z ≥ 0) of the mass-weighted best-fit planes of centres (T, N, 3)."""
    mean = np.einsum("k,tki->ti", masses, centres) / masses.sum()
    d = centres - mean[:, None]
    scatter = np.einsum("k,tki,tkj->tij", masses, d, d)
    _, vectors = np.linalg.eigh(scatter)
    normal = vectors[..., 0]
    return normal * np.where(normal[:, 2:3] < 0, -1.0, 1.0)


def histories(p: SailParameters, centres, angular_velocities, payload_centres=None) -> dict:
    """{name: (T,) array} of HISTORIES (module docstring) for tile centres and angular velocities (T, N, 3)
    and the payload's centres (T, 3) (None without a payload)."""
    masses = Tiles.of(p).masses
    centres = np.asarray(centres, float)
    total = np.einsum("k,tki->ti", masses, centres)
    mass = masses.sum()
    if payload_centres is not None and p.payload_mass > 0:
        total = total + p.payload_mass * np.asarray(payload_centres, float)
        mass += p.payload_mass
    g = total / mass
    normal = plane_normals(masses, centres)
    spin = np.einsum("k,tki,ti->t", masses, np.asarray(angular_velocities, float), normal) / masses.sum()
    return {
        "lateral_x": g[:, 0] - p.beam_centre,
        "lateral_y": g[:, 1] - p.sheet_beam_centre_y,
        "tilt_x": np.arctan2(-normal[:, 0], normal[:, 2]),
        "tilt_y": np.arctan2(-normal[:, 1], normal[:, 2]),
        "spin_rate": spin,
    }


def record(p: SailParameters, centres, angular_velocities, payload: dict) -> dict:
    """{"ride": {name: list}}: the histories as a run's info records them (payload: the run's payload record,
    model.sheet_payload.record)."""
    where = payload.get("payload_centre")
    ride = histories(p, centres, angular_velocities, None if where is None else np.array(where))
    return {"ride": {name: values.tolist() for name, values in ride.items()}}
