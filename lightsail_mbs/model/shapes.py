"""Initial sail shapes: hinge points on the defect profile, every chord exactly one slice long.

Paper Eq. (1): w(x) = a₀ sin(2πνx/L), or a seeded multi-mode defect, plus an optional seeded
roughness at every wavelength the chain carries (roughness_profile). Hinge 0 is at (0, 0); hinge k+1 is the point of the
profile at chord distance c_k from hinge k, with c_k = l for rigid/torsion slices and
c_k = l + z_k (slice plus pre-stretched spring, z_k = T/k_s) for k < n−1 in the extensible
TnT model (Eqs 30–31 with l_s = 0). Slices lie along the chords, at rest.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from lightsail_mbs.model.parameters import SailParameters


@dataclass(frozen=True)
class ChainState:
    """Slice centres (x, y), angles θ from +x, spring extensions z (length n−1, zeros if inextensible)."""

    x: np.ndarray
    y: np.ndarray
    theta: np.ndarray
    z: np.ndarray


def sine_profile(p: SailParameters):
    """w(x) = a₀ sin(2πνx/L), Eq. (1)."""
    k = 2.0 * np.pi * p.defect_mode / p.length
    return lambda x: p.defect_amplitude * np.sin(k * x)


def multimode_coefficients(p: SailParameters) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Modes ν_k = k/2 (k = 1…K), amplitudes a_k and phases φ_k of a random defect.

    a_k = ν_k^(−β) abs(g_k) with g_k standard normal and φ_k uniform in [0, 2π), drawn from
    numpy's default generator seeded with params.defect_seed, then scaled so that the RMS
    of w over 0 ≤ x ≤ L equals a₀/√2, the RMS of the paper's sine of amplitude a₀.
    """
    rng = np.random.default_rng(p.defect_seed)
    nu = 0.5 * np.arange(1, p.defect_mode_count + 1)
    a = nu ** (-p.defect_spectrum) * np.abs(rng.standard_normal(nu.size))
    phase = rng.uniform(0.0, 2.0 * np.pi, nu.size)
    x = np.linspace(0.0, p.length, 4097)
    w = (a[:, None] * np.sin(2 * np.pi * nu[:, None] * x / p.length + phase[:, None])).sum(axis=0)
    rms = np.sqrt(np.trapezoid(w * w, x) / p.length)
    return nu, a * (p.defect_amplitude / np.sqrt(2.0) / rms), phase


def multimode_profile(p: SailParameters):
    """w(x) = Σ_k a_k sin(2πν_k x/L + φ_k): a seeded random multi-mode defect."""
    nu, a, phase = multimode_coefficients(p)
    k = 2.0 * np.pi * nu / p.length
    return lambda x: (
        float(np.dot(a, np.sin(k * x + phase)))
        if np.ndim(x) == 0
        else (a[:, None] * np.sin(k[:, None] * np.asarray(x)[None, :] + phase[:, None])).sum(axis=0)
    )


def roughness_profile(p: SailParameters, amplitude: float, seed: int):
    """w_r(x) = amplitude · Σ_{k=1…n} ξ_k sin(kπx/L), ξ_k ~ N(0, 1/n) from numpy's default generator seeded
    with `seed`: a seeded roughness with the same expected amplitude at every wavelength 2L/k the chain of
    n slices carries, down to 2l, and the RMS over 0 ≤ x ≤ L of a sine of amplitude `amplitude` (in
    expectation). Zero for amplitude 0."""
    xi = np.random.default_rng(seed).standard_normal(p.n) / np.sqrt(p.n)
    k = np.pi * np.arange(1, p.n + 1) / p.length
    a = amplitude * xi
    if amplitude == 0:
        return lambda x: 0.0 * np.asarray(x, float)
    return lambda x: (
        float(np.dot(a, np.sin(k * x)))
        if np.ndim(x) == 0
        else (a[:, None] * np.sin(k[:, None] * np.asarray(x)[None, :])).sum(axis=0)
    )


def defect_profile(p: SailParameters, perturbation: float = 0.0):
    """The initial shape of a case: the paper's sine, or the multi-mode defect if defect_seed is set, plus
    the case's roughness (p.roughness, seed p.roughness_seed) and a perturbation roughness of amplitude
    `perturbation` (m, seed PERTURBATION_SEED: the conditioning probe of solvers.uncertainty)."""
    defect = sine_profile(p) if p.defect_seed is None else multimode_profile(p)
    if not p.roughness and not perturbation:
        return defect
    rough = roughness_profile(p, p.roughness, p.roughness_seed)
    probe = roughness_profile(p, perturbation, PERTURBATION_SEED)
    return lambda x: defect(x) + rough(x) + probe(x)


PERTURBATION_SEED = 271828  # the seed of the conditioning probe's roughness (the same for every solver)


def initial_spring_extension(p: SailParameters) -> np.ndarray:
    """z_k = T / k_s for the extensible TnT chain (pre-tension), else zeros (length n − 1)."""
    z = np.zeros(p.n - 1)
    if p.extensible:
        z[:] = p.tension / p.axial_stiffness
    return z


def hinge_points(p: SailParameters, profile=None, perturbation: float = 0.0) -> np.ndarray:
    """(n+1, 2) hinge points on `profile` (default: defect_profile(p, perturbation)) with exact chord lengths."""
    w = profile or defect_profile(p, perturbation)
    z = initial_spring_extension(p)
    chords = np.full(p.n, p.slice_length)
    chords[:-1] += z
    pts = np.zeros((p.n + 1, 2))
    pts[0] = (0.0, w(0.0))
    for k, c in enumerate(chords):
        x0, y0 = pts[k]

        def gap(x, x0=x0, y0=y0, c=c):
            return np.hypot(x - x0, w(x) - y0) - c

        x1 = brentq(gap, x0, x0 + c * (1 + 1e-9), xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
        pts[k + 1] = (x1, w(x1))
    return pts


def initial_state(p: SailParameters, profile=None, perturbation: float = 0.0) -> ChainState:
    """Slice centres and angles of the initial shape (slice k spans its hinge k to hinge k + l·e_k);
    perturbation: see defect_profile."""
    pts = hinge_points(p, profile, perturbation)
    d = np.diff(pts, axis=0)
    theta = np.arctan2(d[:, 1], d[:, 0])
    half = 0.5 * p.slice_length
    x = pts[:-1, 0] + half * np.cos(theta)
    y = pts[:-1, 1] + half * np.sin(theta)
    return ChainState(x=x, y=y, theta=theta, z=initial_spring_extension(p))


MIN_SLICES_PER_HALF_WAVE = 4  # fewer slices per half wavelength do not draw the defect's shape
MIN_CARRIED_FRACTION = 0.5  # a chain whose initial amplitude is below this fraction of a₀ misses the defect
PRECISION_FLOOR = 1e-12  # a₀/L below this is within ~1e4 ulps of the coordinates' round-off


def defect_warnings(p: SailParameters, initial_amplitude: float) -> list[str]:
    """Why a chain of n slices may not carry the case's defect: too few slices per half wavelength of
    its shortest wave, an initial chain amplitude (analysis.amplitude of the initial state) far below
    a₀, or an a₀ so small against L that double precision barely resolves it. Empty when none applies."""
    a0 = p.defect_amplitude
    if a0 <= 0:
        return []
    notes = []
    shortest = p.defect_mode if p.defect_seed is None else 0.5 * p.defect_mode_count
    per_half_wave = p.n / (2.0 * shortest)
    if per_half_wave < MIN_SLICES_PER_HALF_WAVE:
        notes.append(
            f"n = {p.n} gives {per_half_wave:.3g} slices per half wavelength of the defect (ν = "
            f"{shortest:g}); at least {MIN_SLICES_PER_HALF_WAVE} are needed to resolve it"
        )
    if p.defect_seed is None and initial_amplitude < MIN_CARRIED_FRACTION * a0:
        notes.append(
            f"the chain carries an initial amplitude of {initial_amplitude:.3g} m, {initial_amplitude / a0:.2g} "
            f"of the defect's a₀ = {a0:.3g} m: amplitude ratios measure round-off, not the defect"
        )
    if a0 < PRECISION_FLOOR * p.length:
        notes.append(
            f"a₀/L = {a0 / p.length:.2g} is below {PRECISION_FLOOR:g}: double precision (2.2e-16 L) "
            "carries the defect with few digits"
        )
    return notes
