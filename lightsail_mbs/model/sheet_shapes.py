"""The sheet's defects and initial state (model "sheet", :mod:`lightsail_mbs.model.sheet`): the 1-D sine on
the chain's exact-chord construction, the doubly sinusoidal and the seeded random 2-D defects, the billowed
start on a spherical cap, the tiles' initial centres and orientations (with the case's film, model.film), the
shapes the springs rest in, and the seeded offsets of a perturbed start.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.model import film, planforms, shapes
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
    q = (cos(θ/2), 0, −sin(θ/2), 0). On a mesh that is not a grid (another planform) there are no columns:
    the centres lie on the chain's profile w(x) (sine or seeded multi-mode, line_defect), each tile turned
    to its slope, as for a 2-D defect.
    2-D defects: centres on the surface above the flat grid points, each tile turned by the twist-free
    rotation that takes ẑ to the surface normal (−w_x, −w_y, 1)/|…| (tilt_quaternion).

    A film (film_rms > 0, model.film): on a sheet of ny ≥ 2 tiles across, its surface h(x, y) is added to
    the shape — every centre moves by z += h at its (x, y), every tile turns to the normal of the combined
    surface, (−(w_x + h_x), −h_y, 1) with w_x the chain's chord slope tan θ_i for a 1-D defect. A strip
    (ny = 1) carries one tile across its width, as the chain carries one slice: it sees the film's line
    scan along x (film_profile, the chain's), so that a strip with a 1-D defect starts exactly as the
    torsion chain of the same sail and film (as_strip); a 2-D defect on a strip adds the line scan h(x).

    Billowed (billow_radius finite): the tiles on the spherical cap (cap), the defect and film as a surface
    over the flat x, y displaced along the cap's normal (billowed_quaternions); a strip's columns are then
    not the chain's exact chords."""
    require_sheet(p)
    flat = flat_centres(p)
    spectrum = film.of_case(p)
    if not math.isinf(p.billow_radius):
        return billowed_quaternions(p, flat, spectrum)
    if p.defect_amplitude == 0 and spectrum is None:
        return flat, np.tile([1.0, 0.0, 0.0, 0.0], (flat.shape[0], 1))
    if p.defect_mode_y is None and planforms.mesh_of(p).grid is not None:
        strip = p.ny == 1  # the chain's construction carries the line scan itself
        chain = shapes.initial_state(p if strip or spectrum is None else p.replace(film_rms=0.0))
        i = np.tile(np.arange(p.n), p.ny)
        centres = np.column_stack([chain.x[i], flat[:, 1], chain.y[i]])
        if strip or spectrum is None:
            half = 0.5 * chain.theta[i]
            return centres, np.column_stack([np.cos(half), 0 * half, -np.sin(half), 0 * half])
        slope_x, slope_y = np.tan(chain.theta[i]), np.zeros(centres.shape[0])
        heights, film_x, film_y = film_field(p, spectrum, centres[:, 0], centres[:, 1])
        centres[:, 2] += heights
        slope_x, slope_y = slope_x + film_x, slope_y + film_y
    else:
        w, slope_x, slope_y = surface_defect(p, flat, spectrum)
        centres = np.column_stack([flat[:, 0], flat[:, 1], w])
    return centres, tilt_quaternion(np.column_stack([-slope_x, -slope_y, np.ones_like(slope_x)]))


def surface_defect(p: SailParameters, flat: np.ndarray, spectrum) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(w, ∂w/∂x, ∂w/∂y) at the flat centres (N, 3) of the defect as a surface: the 1-D defect w(x)
    (line_defect), or the 2-D one (defect_surface), zero without a defect; plus the film (film_field)."""
    x, y = flat[:, 0], flat[:, 1]
    if p.defect_amplitude == 0:
        w, slope_x, slope_y = np.zeros(len(x)), np.zeros(len(x)), np.zeros(len(x))
    elif p.defect_mode_y is None:
        f, fx = line_defect(p)
        w, slope_x, slope_y = f(x), fx(x), np.zeros(len(x))
    else:
        f, fx, fy = defect_surface(p)
        w, slope_x, slope_y = f(x, y), fx(x, y), fy(x, y)
    if spectrum is not None:
        heights, film_x, film_y = film_field(p, spectrum, x, y)
        w, slope_x, slope_y = w + heights, slope_x + film_x, slope_y + film_y
    return w, slope_x, slope_y


def cap(p: SailParameters, flat: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(points (N, 3), unit normals (N, 3)): the flat centres laid on the spherical cap of radius R_c
    (billow_radius), the strip's billowed arc (model.shapes) one dimension up.

    The middle m = (L/2, W/2) is the apex; a point at distance r from it in the direction d̂ goes to geodesic
    distance r from the apex along the meridian d̂ (lengths along the meridians kept, the parallels
    shortened by sin(κr)/(κr)), at polar angle ψ = κr, κ = 1/R_c:

        P = m + d sinc(κr) + (cos ψ − 1)/κ ẑ,   ν = (κ d sinc(κr), cos ψ),   sinc t = sin t / t,

    with (cos ψ − 1)/κ = −2 sin²(ψ/2)/κ. R_c > 0 is concave towards the laser (the beam travels along +z;
    the edges lie upstream of the apex, as the strip's arc), its centre at m − R_c ẑ: |P − (m − R_c ẑ)| = |R_c|."""
    kappa = 1.0 / float(p.billow_radius)
    middle = np.array([0.5 * p.length, 0.5 * p.width])
    d = flat[:, :2] - middle
    psi = kappa * np.hypot(d[:, 0], d[:, 1])
    shrink = np.sinc(psi / np.pi)
    sag = -2.0 * np.sin(0.5 * psi) ** 2 / kappa
    points = np.column_stack([middle + d * shrink[:, None], sag])
    normals = np.column_stack([kappa * d * shrink[:, None], np.cos(psi)])
    return points, normals


def billowed_quaternions(p: SailParameters, flat: np.ndarray, spectrum) -> tuple[np.ndarray, np.ndarray]:
    """Tile centres (N, 3) and unit quaternions (N, 4) of the billowed sheet: on the cap (cap; each tile turned
    by the twist-free rotation from ẑ to the cap's normal), displaced along the normal by the defect and film
    (surface_defect, as functions of the flat x, y) and turned from the cap's tangent plane to their slope:
    q = q_cap ⊗ q_defect, q_defect the twist-free tilt to (−w_x, −w_y, 1)."""
    points, normals = cap(p, flat)
    q_cap = tilt_quaternion(normals)
    if p.defect_amplitude == 0 and spectrum is None:
        return points, q_cap
    w, slope_x, slope_y = surface_defect(p, flat, spectrum)
    q_defect = tilt_quaternion(np.column_stack([-slope_x, -slope_y, np.ones_like(w)]))
    return points + w[:, None] * normals, quaternion_product(q_cap, q_defect)


def quaternion_product(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a ⊗ b of quaternions (..., 4), scalar first: the rotation b, then a."""
    a0, av = a[..., :1], a[..., 1:]
    b0, bv = b[..., :1], b[..., 1:]
    return np.concatenate([a0 * b0 - np.sum(av * bv, axis=-1, keepdims=True), a0 * bv + b0 * av + np.cross(av, bv)], -1)


def rest_quaternions(p: SailParameters, reference: str, centres: np.ndarray, quaternions: np.ndarray):
    """The shape (centres, quaternions) in which springs of the given reference are at rest, or None for the
    flat sheet: "initial" the initial shape (given) when it is not flat; "flat" flat, or the cap without the
    defect for a billowed sheet made curved (billow_rest)."""
    billowed = not math.isinf(p.billow_radius)
    if reference == "initial":
        return (centres, quaternions) if (p.defect_amplitude > 0 or p.film_rms > 0 or billowed) else None
    if billowed and p.billow_rest:
        points, normals = cap(p, flat_centres(p))
        return points, tilt_quaternion(normals)
    return None


def line_defect(p: SailParameters):
    """(w, w_x) of the 1-D defect as functions of x: the paper's sine or the seeded multi-mode defect of the
    chain (shapes.sine_profile, shapes.multimode_coefficients)."""
    if p.defect_seed is None:
        k = 2.0 * np.pi * p.defect_mode / p.length
        return (lambda x: p.defect_amplitude * np.sin(k * x), lambda x: p.defect_amplitude * k * np.cos(k * x))
    nu, a, phase = shapes.multimode_coefficients(p)
    k = 2.0 * np.pi * nu / p.length
    return (
        lambda x: (a[:, None] * np.sin(k[:, None] * np.asarray(x)[None, :] + phase[:, None])).sum(axis=0),
        lambda x: (a[:, None] * k[:, None] * np.cos(k[:, None] * np.asarray(x)[None, :] + phase[:, None])).sum(axis=0),
    )


def film_field(p: SailParameters, spectrum: film.Film, x, y) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(h, ∂h/∂x, ∂h/∂y) of the case's film at the points (x, y) (m): its surface on a sheet of ny ≥ 2 tiles
    across (film_surface, the modes the nx × ny grid carries), its line scan along x on a strip (ny = 1:
    film_profile, the modes of the chain of n slices; ∂h/∂y = 0)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    if p.ny == 1:
        line = film.film_profile(spectrum, p.length, p.n, p.film_seed)
        return line(x), line.slope(x), np.zeros_like(x)
    surface = film.film_surface(spectrum, p.length, p.width, p.n, p.ny, p.film_seed)
    return surface(x, y), surface.slope_x(x, y), surface.slope_y(x, y)


def perturbed(p: SailParameters, centres: np.ndarray, perturbation: float) -> np.ndarray:
    """The centres with seeded random offsets along z of RMS `perturbation` (m; PERTURBATION_SEED, the
    same for both solvers): a start perturbed at a chosen level, e.g. round-off."""
    if perturbation == 0:
        return centres
    rng = np.random.default_rng(PERTURBATION_SEED)
    out = np.array(centres, float)
    out[:, 2] += perturbation * rng.standard_normal(out.shape[0])
    return out
