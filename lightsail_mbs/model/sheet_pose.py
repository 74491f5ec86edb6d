"""The sheet's initial pose and motion: tilted about both in-plane axes, spinning, with its payload.

Every body (the tiles, then the payload when there is one, model.sheet_payload) starts from the case's
initial shape (model.sheet_shapes) turned as one rigid body about the craft's centre of mass G (payload
included) by

    Q = R_y(−α_x) R_x(α_y),    α_x = ``initial_tilt``, α_y = ``initial_tilt_y``,

R_x, R_y the right-handed rotations about the global x and y axes: α_x > 0 turns the sail's x axis towards
the beam (+z; the chain's counter-clockwise tilt, the chain's y being the sheet's z), α_y > 0 its y axis.
A centre c goes to G + Q(c − G), an orientation q to q_Q ⊗ q. The sail's spin (model.sheet_spin: the
velocities ω × (c − c_m) and angular velocity ω of its rigid rotation about its normal) turns with it:
v → Q v, ω → Q ω; the payload, on the spin axis of a symmetric sail, spins with it (v = ω × (P₀ − c_m)).

The connector law is objective (δ = A₀ᵀ(p₁ − p₀) and the angles of A₀ᵀA₁ do not change when both bodies
turn alike), and the followers are body-fixed, so the sheet's springs are built from the untilted shape
and the turned start is the same elastic state: a tilted unlit sheet is at rest as the untilted one.
The beam's offset needs no field of its own: the beam axis is at (beam_centre, beam_centre_y), the sail's
middle at (L/2, W/2).
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.model import sheet_spin
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.sheet_grid import Tiles
from lightsail_mbs.model.sheet_shapes import quaternion_product


def tilt_quaternion(p: SailParameters) -> np.ndarray:
    """q_Q (4,) of Q = R_y(−α_x) R_x(α_y) (scalar first)."""
    ax, ay = -0.5 * p.initial_tilt, 0.5 * p.initial_tilt_y
    about_y = np.array([math.cos(ax), 0.0, math.sin(ax), 0.0])
    about_x = np.array([math.cos(ay), math.sin(ay), 0.0, 0.0])
    return quaternion_product(about_y[None], about_x[None])[0]


def tilt_matrix(p: SailParameters) -> np.ndarray:
    """Q (3, 3) (module docstring)."""
    cx, sx = math.cos(p.initial_tilt), math.sin(p.initial_tilt)
    cy, sy = math.cos(p.initial_tilt_y), math.sin(p.initial_tilt_y)
    about_y = np.array([[cx, 0.0, -sx], [0.0, 1.0, 0.0], [sx, 0.0, cx]])  # R_y(−α_x)
    about_x = np.array([[1.0, 0.0, 0.0], [0.0, cy, -sy], [0.0, sy, cy]])  # R_x(α_y)
    return about_y @ about_x


def body_masses(p: SailParameters, payload=None) -> np.ndarray:
    """(N [+ 1],): the tiles' masses, then the payload's."""
    masses = Tiles.of(p).masses
    return masses if payload is None else np.append(masses, payload.mass)


def initial_motion(p: SailParameters, centres: np.ndarray, quaternions: np.ndarray, payload=None, shape=None):
    """(centres, quaternions, velocities, angular velocities) of every body at t = 0, global axes: the tiles'
    (centres, quaternions: the untilted start) and the payload's (model.sheet_payload), tilted and spinning
    (module docstring); arrays (N [+ 1], 3) and (N [+ 1], 4). shape: None, or (centres, quaternions) of every
    body to start from instead of the initial ones (the spun equilibrium, spin_equilibrium)."""
    tiles = len(centres)
    if shape is not None:
        centres, quaternions = shape[0][:tiles], shape[1][:tiles]
    centres = np.asarray(centres, float)
    quaternions = np.asarray(quaternions, float)
    velocities, omega = sheet_spin.spin_velocities(p, centres)
    if payload is not None:
        spin = sheet_spin.spin_vector(p)
        start, turned = (payload.start, payload.quaternion) if shape is None else (shape[0][tiles], shape[1][tiles])
        centres = np.vstack([centres, start])
        quaternions = np.vstack([quaternions, turned])
        lever = start - sheet_spin.spin_centre(p, centres[:-1])
        velocities = np.vstack([velocities, np.cross(spin, lever)])
        omega = np.vstack([omega, spin])
    if p.initial_tilt == 0 and p.initial_tilt_y == 0:
        return centres, quaternions, velocities, omega
    masses = body_masses(p, payload)
    g = masses @ centres / masses.sum()
    Q = tilt_matrix(p)
    turned = g + (centres - g) @ Q.T
    q = quaternion_product(np.broadcast_to(tilt_quaternion(p), quaternions.shape), quaternions)
    return turned, q, velocities @ Q.T, omega @ Q.T
