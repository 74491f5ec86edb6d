"""The radiation load and the frame force, one load model shared by every solver of chain and sheet.

Paper Eq. (11), a uniform beam on perfect reflectors: f_i = (2I₀/c) A cos²θ_i n_i with
A = l W and n_i = (−sin θ_i, cos θ_i), applied at the slice centre.

Generalised to a flat facet of specular reflectivity R, absorptivity α and
transmissivity 1 − R − α, lit by a beam of local intensity I travelling along the unit vector b̂
(standard non-ideal flat-sail model, e.g. McInnes, *Solar Sailing*, 1999, Sec. 2.6, without
diffuse reflection and thermal emission):

    f = (I A / c) cos θ [ 2R cos θ n + α b̂ ],        cos θ = n·b̂                 (radiation_forces)

The intercepted power is I A cos θ; absorbed photons push along the beam, specularly reflected ones
along the unit normal n with twice their normal momentum, transmitted ones not at all. For R = 1,
α = 0 this is exactly Eq. (11). The law is the same for a slice of the chain (2-D: b̂ = ŷ,
n = (−sin θ, cos θ)) and for a tile of the sheet (3-D: b̂ = ẑ, n = R_tile ẑ); :func:`facet_forces`
is that one law for facets of any dimension (the sheet's tiles use it; the chain's
:func:`net_slice_forces` writes it with the half angle, and the tests hold the two to each other).

The beam profile is uniform (the paper) or Gaussian: I₀ exp(−2(x − x_c)²/w²) across the chain's
length, and the round I₀ exp(−2((x − x_c)² + (y − y_c)²)/w²) on the sheet.

The frame force. The solvers work in the frame accelerating with the flat sail at
g₀ = (2R + α) Ī/(c ρ h) (parameters.nominal_acceleration, Ī the beam's mean intensity over the
flat sail), so every facet also carries the d'Alembert force −m g₀ b̂ = −(2R + α) Ī A/c b̂.

The net force, computed without cancellation. On a flat facet in the mean intensity the load
and the frame force cancel exactly; what deforms the sail is their small remainder, for the paper's
mirror −(3/2) f₀ θ² b̂, about 1e-8 f₀ at its slopes. Summed in floating point, f₀ cos³θ − m g₀ keeps
that remainder with only ~8 of its 16 digits, and the lost digits act as a random force at every
wavelength that the sail's unstable short waves amplify (docs: validation, round-off budget). So
:func:`facet_forces` writes the net force with the cancellation done analytically. With n_⊥ the
normal's components across the beam and n_b = cos θ its component along it (|n| = 1),

    1 − cos θ = |n_⊥|² / (1 + cos θ),      1 − cos³θ = (1 − cos θ)(1 + cos θ + cos²θ),

    f_⊥ = (I A/c) 2R cos²θ n_⊥
    f_b = −(I A/c) [2R (1 − cos³θ) + α (1 − cos θ)] + (2R + α)(A/c)(I − Ī)

Every term is computed to a few ulps of itself from the small components n_⊥ (for the chain
n_⊥ = −sin θ, and |n_⊥|²/(1 + cos θ) = 2 sin²(θ/2); for a tile, n_⊥ are entries of its rotation
matrix, computed without cancellation by both sheet solvers). The last term is the beam's
non-uniformity; it is exactly 0 for the uniform beam (I = Ī), and for a Gaussian beam it is a
physical O(f₀) force that no cancellation threatens. For the mirror in a uniform beam
f_b = −f₀ (1 − cos θ)(1 + cos θ + cos²θ), f₀ = 2 I₀ A/c.

:func:`net_facet_force` is the same formula for one facet, compiled (numba); the tests hold it to
:func:`facet_forces`. For the chain, :func:`net_slice_forces` and its compiled twin :func:`net_slice_force`
write it with n_⊥ = −sin θ and 1 − cos θ = 2 sin²(θ/2). The solvers apply these laws through the physics
terms (:mod:`lightsail_mbs.model.terms`: the radiation term, and the frame term for a payload's share).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.kernels import njit

if TYPE_CHECKING:  # annotations only: the case imports this module (through model/optics.py), not the reverse
    from lightsail_mbs.model.parameters import SailParameters


def intensity(p: SailParameters, x: np.ndarray) -> np.ndarray:
    """I(x): I₀ for the uniform beam, I₀ exp(−2(x − x_c)²/w²) for the Gaussian beam (W/m²)."""
    x = np.asarray(x, float)
    if p.uniform_beam:
        return np.full_like(x, p.intensity)
    return p.intensity * np.exp(-2.0 * ((x - p.beam_centre) / p.beam_waist) ** 2)


def sheet_intensity(p: SailParameters, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """I(x, y) on the sheet: I₀, or the round Gaussian I₀ exp(−2((x − x_c)² + (y − y_c)²)/w²) (W/m²)."""
    x = np.asarray(x, float)
    if p.uniform_beam:
        return np.full_like(x, p.intensity)
    r2 = (x - p.beam_centre) ** 2 + (np.asarray(y, float) - p.sheet_beam_centre_y) ** 2
    return p.intensity * np.exp(-2.0 * r2 / p.beam_waist**2)


def facet_forces(
    normal_across: np.ndarray,
    normal_along: np.ndarray,
    local_intensity: np.ndarray,
    mean_intensity: float,
    area: float,
    reflectivity: float,
    absorptivity: float,
) -> tuple[np.ndarray, np.ndarray]:
    """The net force (radiation + frame force) on flat facets, with the cancellation done analytically.

    Parameters
    ----------
    normal_across : ndarray (..., k)
        The unit normal's components across the beam (k = 1 for a chain slice, 2 for a sheet tile).
    normal_along : ndarray (...)
        Its component along the beam, cos θ.
    local_intensity : ndarray (...)
        I at each facet (W/m²).
    mean_intensity : float
        Ī, the beam's mean over the flat sail, which sets the frame's acceleration (W/m²).
    area : float
        The facet's area A (m²).
    reflectivity, absorptivity : float
        R and α of the facet.

    Returns
    -------
    (f_across (..., k), f_along (...)) in N (module docstring).
    """
    across = np.asarray(normal_across, float)
    c = np.asarray(normal_along, float)
    s2 = np.sum(across * across, axis=-1)
    # 1 − cos θ from the small components; directly where the facet faces away (no cancellation there)
    one_minus_cos = np.where(c > 0, s2 / np.where(c > 0, 1.0 + c, 1.0), 1.0 - c)
    area_c = area / SPEED_OF_LIGHT
    local = np.broadcast_to(np.asarray(local_intensity, float), c.shape)
    push = local * area_c
    two_r = 2.0 * reflectivity
    f_across = (push * two_r * c * c)[..., None] * across
    f_along = -push * (two_r * one_minus_cos * (1.0 + c + c * c) + absorptivity * one_minus_cos)
    f_along = f_along + (two_r + absorptivity) * area_c * (local - mean_intensity)
    return f_across, f_along


def radiation_forces(p: SailParameters, x: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(f_x, f_y) of the radiation alone on each slice centre at abscissa x and angle θ, inertial
    directions (N): f = (I A / c) cos θ [2R cos θ n + α ŷ] with n = (−sin θ, cos θ); Eq. (11) for R = 1,
    α = 0. The chain solvers use :func:`net_slice_forces` (this load plus the frame force, their
    cancellation done analytically)."""
    c = np.cos(theta)
    s = np.sin(theta)
    if p.uniform_beam and p.reflectivity == 1.0 and p.absorptivity == 0.0:
        mag = p.flat_force * c * c  # Eq. (11) exactly
        return -mag * s, mag * c
    scale = intensity(p, x) * p.slice_length * p.width / SPEED_OF_LIGHT * c
    normal = 2.0 * p.reflectivity * c * scale
    return -normal * s, normal * c + p.absorptivity * scale


def frame_force(p: SailParameters) -> float:
    """y-component of the d'Alembert force −m g₀ on each slice in the accelerating frame (N); without a
    payload −m g₀ = −(2R + α) Ī A/c, the form :func:`net_slice_forces` cancels analytically."""
    return -p.slice_mass * p.nominal_acceleration


def frame_force_excess(p: SailParameters) -> float:
    """(2R + α) Ī A/c − m g₀ on each slice (N): the net form's frame force minus the craft's. Exactly 0
    without a payload; with a payload of mass m_p the craft accelerates at g₀ M/(M + m_p), and the
    difference, a physical O(f₀) push that the stem carries, is added to the net force."""
    if p.payload_mass == 0:
        return 0.0
    return p.normal_momentum * p.mean_intensity * p.slice_length * p.width / SPEED_OF_LIGHT + frame_force(p)


def net_slice_forces(p: SailParameters, x: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The net force on each slice centre in the accelerating frame, radiation load plus the frame force
    −(2R + α) Ī A/c ŷ, with their cancellation done analytically (module docstring); the numpy form of the
    radiation term (model/terms/radiation.py)."""
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
def net_facet_force(n1, n2, nb, local_intensity, mean_intensity, area_c, reflectivity, absorptivity):
    """(f₁, f₂, f_b) of :func:`facet_forces` for one facet with unit normal (n₁, n₂, n_b), beam along b
    (compiled); area_c = A/c."""
    if nb > 0.0:
        one_minus_cos = (n1 * n1 + n2 * n2) / (1.0 + nb)
    else:
        one_minus_cos = 1.0 - nb
    push = local_intensity * area_c
    two_r = 2.0 * reflectivity
    across = push * two_r * nb * nb
    fb = -push * (two_r * one_minus_cos * (1.0 + nb + nb * nb) + absorptivity * one_minus_cos)
    fb += (two_r + absorptivity) * area_c * (local_intensity - mean_intensity)
    return across * n1, across * n2, fb


@njit(cache=True)
def net_slice_force(theta, cos_theta, sin_theta, local_intensity, mean_intensity, area_c, reflectivity, absorptivity):
    """(f_x, f_y) of :func:`net_slice_forces` for one slice (compiled); area_c = l W / c."""
    half = math.sin(0.5 * theta)
    one_minus_cos = 2.0 * half * half
    push = local_intensity * area_c
    two_r = 2.0 * reflectivity
    fx = -push * two_r * cos_theta * cos_theta * sin_theta
    fy = -push * (two_r * one_minus_cos * (1.0 + cos_theta + cos_theta * cos_theta) + absorptivity * one_minus_cos)
    fy += (two_r + absorptivity) * area_c * (local_intensity - mean_intensity)
    return fx, fy


@njit(cache=True)
def gaussian_intensity(x, peak, centre, waist):
    """I(x) of the Gaussian beam for one abscissa (compiled); waist = inf gives the uniform peak."""
    if math.isinf(waist):
        return peak
    d = (x - centre) / waist
    return peak * math.exp(-2.0 * d * d)


@njit(cache=True)
def round_gaussian_intensity(x, y, peak, centre_x, centre_y, waist):
    """I(x, y) of the sheet's round Gaussian beam at one point (compiled); waist = inf: the uniform peak."""
    if math.isinf(waist):
        return peak
    dx = (x - centre_x) / waist
    dy = (y - centre_y) / waist
    return peak * math.exp(-2.0 * (dx * dx + dy * dy))
