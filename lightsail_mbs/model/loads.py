"""The radiation load and the frame force, one load model shared by both solvers.

Paper Eq. (11), a uniform beam on perfect reflectors: f_i = (2I₀/c) A cos²θ_i n_i with
A = l W and n_i = (−sin θ_i, cos θ_i), applied at the slice centre.

Generalised to a flat facet of specular reflectivity R, absorptivity α and
transmissivity 1 − R − α, lit by a beam travelling along +ŷ with local intensity I(x)
(standard non-ideal flat-sail model, e.g. McInnes, *Solar Sailing*, 1999, Sec. 2.6, without
diffuse reflection and thermal emission):

    f_i = (I(x_i) A / c) cos θ_i [ 2R cos θ_i n_i + α ŷ ]                          (radiation_forces)

The intercepted power is I A cos θ; absorbed photons push along the beam (ŷ), specularly
reflected ones along the normal with twice their normal momentum, transmitted ones not at all.
For R = 1, α = 0 this is exactly Eq. (11). The beam profile is uniform (the paper) or
Gaussian, I(x) = I₀ exp(−2(x − x_c)²/w²).

The frame force. The solvers work in the frame accelerating with the flat sail at
g₀ = (2R + α) Ī/(c ρ h) (parameters.nominal_acceleration, Ī the beam's mean intensity over the
flat sail), so every slice also carries the d'Alembert force −m g₀ ŷ = −(2R + α) Ī A/c ŷ.

The net force, computed without cancellation. On a flat slice in the mean intensity the load
and the frame force cancel exactly; what deforms the sail is their small remainder, for the paper's
mirror −(3/2) f₀ θ² ŷ, about 1e-8 f₀ at its slopes. Summed in floating point, f₀ cos³θ − m g₀ keeps
that remainder with only ~8 of its 16 digits, and the lost digits act as a random force at every
wavelength that the chain's unstable short waves amplify (docs: validation, round-off budget). So
:func:`applied_forces` writes the net force with the cancellation done analytically, using
1 − cos θ = 2 sin²(θ/2) and 1 − cos³θ = 2 sin²(θ/2)(1 + cos θ + cos²θ):

    f_x = −(I A/c) 2R cos²θ sin θ
    f_y = −(I A/c) [2R (1 − cos³θ) + α (1 − cos θ)] + (2R + α)(A/c)(I(x) − Ī)

Every term is computed to a few ulps of itself. The last one is the beam's non-uniformity; it is
exactly 0 for the uniform beam (I = Ī), and for a Gaussian beam it is a physical O(f₀) force that
no cancellation threatens. For the mirror in a uniform beam f_y = −f₀ 2 sin²(θ/2)(1 + cos θ +
cos²θ), f₀ = 2 I₀ A/c.

:func:`net_slice_force` is the same formula for one slice, compiled (numba); the solvers' compiled
right-hand sides and force functions call it, and the tests hold it to :func:`applied_forces`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from lightsail_mbs.model.parameters import SPEED_OF_LIGHT, SailParameters


def intensity(p: SailParameters, x: np.ndarray) -> np.ndarray:
    """I(x): I₀ for the uniform beam, I₀ exp(−2(x − x_c)²/w²) for the Gaussian beam (W/m²)."""
    x = np.asarray(x, float)
    if p.uniform_beam:
        return np.full_like(x, p.intensity)
    return p.intensity * np.exp(-2.0 * ((x - p.beam_center) / p.beam_waist) ** 2)


def radiation_forces(p: SailParameters, x: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(f_x, f_y) of the radiation alone on each slice centre at abscissa x and angle θ, inertial
    directions (N): f = (I A / c) cos θ [2R cos θ n + α ŷ] with n = (−sin θ, cos θ); Eq. (11) for R = 1,
    α = 0. The solvers use :func:`applied_forces` (this load plus the frame force, without cancellation)."""
    c = np.cos(theta)
    s = np.sin(theta)
    if p.uniform_beam and p.reflectivity == 1.0 and p.absorptivity == 0.0:
        mag = p.flat_force * c * c  # Eq. (11) exactly
        return -mag * s, mag * c
    scale = intensity(p, x) * p.slice_length * p.width / SPEED_OF_LIGHT * c
    normal = 2.0 * p.reflectivity * c * scale
    return -normal * s, normal * c + p.absorptivity * scale


def frame_force(p: SailParameters) -> float:
    """y-component of the d'Alembert force −m g₀ = −(2R + α) Ī A/c on each slice in the accelerating
    frame (N)."""
    return -(2.0 * p.reflectivity + p.absorptivity) * p.mean_intensity * p.slice_length * p.width / SPEED_OF_LIGHT


def applied_forces(p: SailParameters, x: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The net force on each slice centre in the accelerating frame, radiation load plus frame force (N),
    with their cancellation done analytically (module docstring); the load every solver applies."""
    theta = np.asarray(theta, float)
    c = np.cos(theta)
    s = np.sin(theta)
    half = np.sin(0.5 * theta)
    one_minus_cos = 2.0 * half * half
    area_c = p.slice_length * p.width / SPEED_OF_LIGHT
    local = intensity(p, np.broadcast_to(x, theta.shape))
    push = local * area_c
    two_r = 2.0 * p.reflectivity
    fx = -push * two_r * c * c * s
    fy = -push * (two_r * one_minus_cos * (1.0 + c + c * c) + p.absorptivity * one_minus_cos)
    fy = fy + (two_r + p.absorptivity) * area_c * (local - p.mean_intensity)
    return fx, fy


@njit(cache=True)
def net_slice_force(theta, cos_theta, sin_theta, local_intensity, mean_intensity, area_c, reflectivity, absorptivity):
    """(f_x, f_y) of :func:`applied_forces` for one slice (compiled); area_c = l W / c."""
    half = math.sin(0.5 * theta)
    one_minus_cos = 2.0 * half * half
    push = local_intensity * area_c
    two_r = 2.0 * reflectivity
    fx = -push * two_r * cos_theta * cos_theta * sin_theta
    fy = -push * (two_r * one_minus_cos * (1.0 + cos_theta + cos_theta * cos_theta) + absorptivity * one_minus_cos)
    fy += (two_r + absorptivity) * area_c * (local_intensity - mean_intensity)
    return fx, fy


@njit(cache=True)
def gaussian_intensity(x, peak, center, waist):
    """I(x) of the Gaussian beam for one abscissa (compiled); waist = inf gives the uniform peak."""
    if math.isinf(waist):
        return peak
    d = (x - center) / waist
    return peak * math.exp(-2.0 * d * d)
