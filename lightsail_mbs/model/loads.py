"""The radiation load, one pure function of the chain state shared by both solvers.

Paper Eq. (11), a uniform beam on perfect reflectors: f_i = (2I₀/c) A cos²θ_i n_i with
A = l W and n_i = (−sin θ_i, cos θ_i), applied at the slice centre.

Generalised to a flat facet of specular reflectivity R, absorptivity α and
transmissivity 1 − R − α, lit by a beam travelling along +ŷ with local intensity I(x)
(standard non-ideal flat-sail model, e.g. McInnes, *Solar Sailing*, 1999, Sec. 2.6, without
diffuse reflection and thermal emission):

    f_i = (I(x_i) A / c) cos θ_i [ 2R cos θ_i n_i + α ŷ ]

The intercepted power is I A cos θ; absorbed photons push along the beam (ŷ), specularly
reflected ones along the normal with twice their normal momentum, transmitted ones not at all.
For R = 1, α = 0 this is exactly Eq. (11). The beam profile is uniform (the paper) or
Gaussian, I(x) = I₀ exp(−2(x − x_c)²/w²).

In the frame accelerating with the flat sail at g₀ (parameters.nominal_acceleration) every
slice also carries the d'Alembert body force −m g₀ ŷ.
"""

from __future__ import annotations

import numpy as np

from lightsail_mbs.model.parameters import SPEED_OF_LIGHT, SailParameters


def intensity(p: SailParameters, x: np.ndarray) -> np.ndarray:
    """I(x): I₀ for the uniform beam, I₀ exp(−2(x − x_c)²/w²) for the Gaussian beam (W/m²)."""
    x = np.asarray(x, float)
    if p.uniform_beam:
        return np.full_like(x, p.intensity)
    return p.intensity * np.exp(-2.0 * ((x - p.beam_center) / p.beam_waist) ** 2)


def radiation_forces(p: SailParameters, x: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(f_x, f_y) on each slice centre at abscissa x and angle θ, inertial directions (N).

    f = (I A / c) cos θ [2R cos θ n + α ŷ] with n = (−sin θ, cos θ); Eq. (11) for R = 1, α = 0.
    """
    c = np.cos(theta)
    s = np.sin(theta)
    if p.uniform_beam and p.reflectivity == 1.0 and p.absorptivity == 0.0:
        mag = p.flat_force * c * c  # Eq. (11) exactly
        return -mag * s, mag * c
    scale = intensity(p, x) * p.slice_length * p.width / SPEED_OF_LIGHT * c
    normal = 2.0 * p.reflectivity * c * scale
    return -normal * s, normal * c + p.absorptivity * scale


def frame_force(p: SailParameters) -> float:
    """y-component of the d'Alembert force −m g₀ on each slice in the accelerating frame (N)."""
    return -p.slice_mass * p.nominal_acceleration


def applied_forces(p: SailParameters, x: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Radiation load plus frame force on each slice centre, as used by the solvers (N)."""
    fx, fy = radiation_forces(p, x, theta)
    return fx, fy + frame_force(p)
