"""The sheet's defects and initial state (model "sheet", :mod:`lightsail_mbs.model.sheet`): the 1-D sine on
the chain's exact-chord construction, the doubly sinusoidal and the seeded random 2-D defects, the
tiles' initial centres and orientations, and the seeded offsets of a perturbed start.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.model import shapes
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.sheet_grid import flat_centres, quaternion_rotation, require_sheet, tilt_quaternion

PERTURBATION_SEED = 20240917  # the seeded tile offsets of a perturbed start (solvers' perturbation option)


def multimode_coefficients(p: SailParameters):
    """Seeded random 2-D defect w = Σ_kl a_kl sin(2πν_k x/L + φ_kl) sin(2πν_l y/W + ψ_kl), ν_k = k/2.

    k, l = 1…K (K = defect_mode_count); a_kl = (ν_k² + ν_l²)^(−β/2) |g_kl| with g standard normal
    (β = defect_spectrum), phases uniform in [0, 2π), from numpy's default generator seeded with
    defect_seed; scaled so that the RMS of w over the sail is a₀/2, the RMS of the doubly sinusoidal
    defect of amplitude a₀ (as the chain's multi-mode defect has the RMS of the paper's sine).
    Returns (ν (K,), a (K, K), φ (K, K), ψ (K, K))."""
    rng = np.random.default_rng(p.defect_seed)
    K = p.defect_mode_count
    nu = 0.5 * np.arange(1, K + 1)
    a = (nu[:, None] ** 2 + nu[None, :] ** 2) ** (-0.5 * p.defect_spectrum) * np.abs(rng.standard_normal((K, K)))
    phx = rng.uniform(0, 2 * np.pi, (K, K))
    phy = rng.uniform(0, 2 * np.pi, (K, K))
    xs = np.linspace(0, p.length, 257)
    ys = np.linspace(0, p.width, 257)
    w = _multimode(p, (nu, a, phx, phy), xs[:, None], ys[None, :])
    rms = math.sqrt(np.trapezoid(np.trapezoid(w * w, ys, axis=1), xs) / (p.length * p.width))
    return nu, a * (0.5 * p.defect_amplitude / rms), phx, phy


def _multimode(p, coefficients, x, y, derivative=None):
    nu, a, phx, phy = coefficients
    kx = 2 * np.pi * nu / p.length
    ky = 2 * np.pi * nu / p.width
    x = np.asarray(x, float)[..., None, None]
    y = np.asarray(y, float)[..., None, None]
    ax = kx[:, None] * x + phx
    ay = ky[None, :] * y + phy
    if derivative is None:
        terms = np.sin(ax) * np.sin(ay)
    elif derivative == "x":
        terms = kx[:, None] * np.cos(ax) * np.sin(ay)
    else:
        terms = ky[None, :] * np.sin(ax) * np.cos(ay)
    return (a * terms).sum(axis=(-1, -2))


def defect_surface(p: SailParameters):
    """(w, w_x, w_y) of a 2-D defect (defect_mode_y set) as functions of (x, y): the doubly sinusoidal
    w = a₀ sin(2πν x/L) sin(2πν_y y/W), or with defect_seed the seeded 2-D multi-mode defect."""
    if p.defect_seed is not None:
        coefficients = multimode_coefficients(p)
        return (
            lambda x, y: _multimode(p, coefficients, x, y),
            lambda x, y: _multimode(p, coefficients, x, y, "x"),
            lambda x, y: _multimode(p, coefficients, x, y, "y"),
        )
    kx = 2 * np.pi * p.defect_mode / p.length
    ky = 2 * np.pi * p.defect_mode_y / p.width
    a0 = p.defect_amplitude
    return (
        lambda x, y: a0 * np.sin(kx * x) * np.sin(ky * y),
        lambda x, y: a0 * kx * np.cos(kx * x) * np.sin(ky * y),
        lambda x, y: a0 * ky * np.sin(kx * x) * np.cos(ky * y),
    )


def initial_state(p: SailParameters) -> tuple[np.ndarray, np.ndarray]:
    """Tile centres (N, 3) and rotation matrices (N, 3, 3) of the initial (defect) shape, at rest
    (initial_quaternions, whose quaternions carry the small rotations without round-off of 1)."""
    centres, q = initial_quaternions(p)
    return centres, quaternion_rotation(q)


def initial_quaternions(p: SailParameters) -> tuple[np.ndarray, np.ndarray]:
    """Tile centres (N, 3) and unit quaternions (N, 4, scalar first) of the initial (defect) shape.

    1-D defects (defect_mode_y None): every column of tiles is a slice of the chain
    (shapes.initial_state: hinge points on the profile, every chord exactly a long), the tile along its
    chord, turned about y by −θ_i (θ the chain's angle from +x towards its transverse axis, here +z):
    q = (cos(θ/2), 0, −sin(θ/2), 0).
    2-D defects: centres on the surface above the flat grid points, each tile turned by the twist-free
    rotation that takes ẑ to the surface normal (−w_x, −w_y, 1)/|…| (tilt_quaternion)."""
    require_sheet(p)
    flat = flat_centres(p)
    count = flat.shape[0]
    identity = np.tile([1.0, 0.0, 0.0, 0.0], (count, 1))
    if p.defect_amplitude == 0:
        return flat, identity
    if p.defect_mode_y is None:
        chain = shapes.initial_state(p)
        i = np.tile(np.arange(p.n), p.ny)
        centres = np.column_stack([chain.x[i], flat[:, 1], chain.y[i]])
        half = 0.5 * chain.theta[i]
        q = np.column_stack([np.cos(half), 0 * half, -np.sin(half), 0 * half])
        return centres, q
    w, wx, wy = defect_surface(p)
    x, y = flat[:, 0], flat[:, 1]
    centres = np.column_stack([x, y, w(x, y)])
    return centres, tilt_quaternion(np.column_stack([-wx(x, y), -wy(x, y), np.ones_like(x)]))


def perturbed(p: SailParameters, centres: np.ndarray, perturbation: float) -> np.ndarray:
    """The centres with seeded random offsets along z of RMS `perturbation` (m; PERTURBATION_SEED, the
    same for both solvers): a start perturbed at a chosen level, e.g. round-off."""
    if perturbation == 0:
        return centres
    rng = np.random.default_rng(PERTURBATION_SEED)
    out = np.array(centres, float)
    out[:, 2] += perturbation * rng.standard_normal(out.shape[0])
    return out
