"""The radiation load, one pure function of the chain state shared by both solvers.

Eq. (11): f_i = (2I₀/c) A cos²θ_i n_i with A = l W and n_i = (−sin θ_i, cos θ_i), applied
at the slice centre. In the frame accelerating with the flat sail at g₀ (Eq. 4, first
order) every slice also carries the d'Alembert body force −m g₀ ŷ, which cancels the load
on a flat slice exactly (f₀ = m g₀).
"""
from __future__ import annotations

import numpy as np

from .parameters import SailParameters


def radiation_forces(p: SailParameters, x: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(f_x, f_y) on each slice centre at abscissa x and angle θ, Eq. (11), inertial directions (N).

    The uniform beam of the paper does not depend on x; x is part of the signature so that
    beam profiles (issue 9) change this module only.
    """
    c = np.cos(theta)
    s = np.sin(theta)
    mag = p.flat_force * c * c
    return -mag * s, mag * c


def frame_force(p: SailParameters) -> float:
    """y-component of the d'Alembert force −m g₀ on each slice in the accelerating frame (N)."""
    return -p.slice_mass * p.nominal_acceleration


def applied_forces(p: SailParameters, x: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Radiation load plus frame force on each slice centre, as used by the solvers (N)."""
    fx, fy = radiation_forces(p, x, theta)
    return fx, fy + frame_force(p)
