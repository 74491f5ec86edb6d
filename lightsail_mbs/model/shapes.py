"""Initial sail shapes: hinge points on the defect profile, every chord exactly one slice long.

Paper Eq. (1): w(x) = a₀ sin(2πνx/L), or a seeded multi-mode defect, plus an optional seeded
roughness at every wavelength the chain carries (roughness_profile). Hinge 0 is at (0, 0); hinge k+1 is the point of the
profile at chord distance c_k from hinge k, with c_k = l for rigid/torsion slices and
c_k = l + z_k (slice plus pre-stretched spring, z_k = T/k_s) for k < n−1 in the extensible
TnT model (Eqs 30–31 with l_s = 0). Slices lie along the chords, at rest.

**Billowed start** (SailParameters.billow_radius = R_c, finite): the sail starts on a circular arc
of radius |R_c|, signed curvature κ = 1/R_c. Sign convention: R_c > 0 is concave towards the laser
(the beam travels along +y; the middle of the sail lies downstream of its edges, as a sail billows
under the light), its centre of curvature C = (L/2, −R_c) on the laser side; R_c < 0 is convex
towards the laser, C downstream. Arc length s along the circle, the apex at s = L/2:

    b(s) = (L/2 + sin ψ/κ, (cos ψ − 1)/κ),   ψ = κ (s − L/2),   unit normal ν(s) = (sin ψ, cos ψ)

(ν is +y at the apex: a flat sail's +y). Without a defect the hinges lie on the circle with exact
chords: a chord c subtends Δs = 2|R_c| asin(c/(2|R_c|)) of arc, and the chain is centred on the apex.
With the defect, the profile is the arc displaced along its normal, P(u) = b(s₀ + u) + w(u) ν(s₀ + u),
u the arc length from hinge 0 (the paper's w(x) with x → u); hinge k+1 is the point of P at chord
distance c_k from hinge k (a root in u), so every chord is again exact. As R_c → ∞ both reduce to
the flat construction; the flat sail itself is built by the flat code path, unchanged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import film
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
    k = np.pi * np.arange(1, p.n + 1) / p.length
    a = roughness_coefficients(p, amplitude, seed)
    if amplitude == 0:
        return lambda x: 0.0 * np.asarray(x, float)
    return lambda x: (
        float(np.dot(a, np.sin(k * x)))
        if np.ndim(x) == 0
        else (a[:, None] * np.sin(k[:, None] * np.asarray(x)[None, :])).sum(axis=0)
    )


def roughness_coefficients(p: SailParameters, amplitude: float, seed: int) -> np.ndarray:
    """The sine coefficients amplitude · ξ_k, k = 1 … n, of roughness_profile(p, amplitude, seed) (m)."""
    return amplitude * (np.random.default_rng(seed).standard_normal(p.n) / np.sqrt(p.n))


def defect_profile(p: SailParameters, perturbation: float = 0.0):
    """The initial shape of a case: the paper's sine, or the multi-mode defect if defect_seed is set, plus
    the case's roughness (p.roughness, seed p.roughness_seed), its film (p.film_rms, …: the film's line
    scan on the modes the chain carries, model.film) and a perturbation roughness of amplitude
    `perturbation` (m, seed PERTURBATION_SEED: the conditioning probe of solvers.uncertainty)."""
    defect = sine_profile(p) if p.defect_seed is None else multimode_profile(p)
    spectrum = film.of_case(p)
    if not p.roughness and not perturbation and spectrum is None:
        return defect
    rough = roughness_profile(p, p.roughness, p.roughness_seed)
    probe = roughness_profile(p, perturbation, PERTURBATION_SEED)
    if spectrum is None:
        return lambda x: defect(x) + rough(x) + probe(x)
    heights = film.film_profile(spectrum, p.length, p.n, p.film_seed)
    return lambda x: defect(x) + rough(x) + probe(x) + heights(x)


PERTURBATION_SEED = 271828  # the seed of the conditioning probe's roughness (the same for every solver)


def initial_spring_extension(p: SailParameters) -> np.ndarray:
    """z_k = T / k_s for the extensible TnT chain (pre-tension), else zeros (length n − 1); for a heated film the
    equilibrium of its heated state at the start (model/heating.py: initial_extension)."""
    z = np.zeros(p.n - 1)
    if p.heated:
        from lightsail_mbs.model import heating

        return heating.initial_extension(p)
    if p.extensible:
        z[:] = p.tension / p.axial_stiffness
    return z


def chord_lengths(p: SailParameters) -> np.ndarray:
    """c_k: l for every slice, plus the pre-stretched spring z_k for k < n − 1 in the extensible TnT chain."""
    chords = np.full(p.n, p.slice_length)
    chords[:-1] += initial_spring_extension(p)
    return chords


def arc_point(p: SailParameters, s):
    """(b(s), ν(s)): the billowed arc's point and unit normal at arc length s (module docstring)."""
    kappa = 1.0 / p.billow_radius
    psi = kappa * (np.asarray(s, float) - 0.5 * p.length)
    base = np.stack([0.5 * p.length + np.sin(psi) / kappa, (np.cos(psi) - 1.0) / kappa], axis=-1)
    return base, np.stack([np.sin(psi), np.cos(psi)], axis=-1)


def billowed_hinge_points(p: SailParameters, profile=None, perturbation: float = 0.0) -> np.ndarray:
    """(n+1, 2) hinge points of the billowed sail (billow_radius finite) with exact chords: on the arc, or
    on the arc displaced along its normal by `profile` (default: defect_profile(p, perturbation), none if
    a₀ = 0 and there is no roughness)."""
    from scipy.optimize import brentq

    R = abs(p.billow_radius)
    chords = chord_lengths(p)
    if np.any(chords > 2 * R):
        raise ParameterError(
            f"billow_radius={p.billow_radius!r} is invalid: allowed |R_c| ≥ c/2 = {chords.max() / 2:g} m"
        )
    spans = 2.0 * R * np.arcsin(chords / (2.0 * R))
    s0 = 0.5 * (p.length - spans.sum())  # the chain centred on the apex s = L/2
    if profile is None and p.defect_amplitude == 0 and not p.roughness and not perturbation and not p.film_rms:
        return arc_point(p, s0 + np.concatenate([[0.0], np.cumsum(spans)]))[0]
    w = profile or defect_profile(p, perturbation)

    def point(u):
        base, normal = arc_point(p, s0 + u)
        return base + float(w(u)) * normal

    pts = np.zeros((p.n + 1, 2))
    pts[0] = point(0.0)
    u = 0.0
    for k, c in enumerate(chords):
        start = pts[k]

        def gap(v, start=start, c=c):
            return float(np.hypot(*(point(v) - start))) - c

        u = brentq(gap, u, u + 2.0 * c, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
        pts[k + 1] = point(u)
    return pts


def hinge_points(p: SailParameters, profile=None, perturbation: float = 0.0) -> np.ndarray:
    """(n+1, 2) hinge points on `profile` (default: defect_profile(p, perturbation)) with exact chord
    lengths; on the billowed arc when billow_radius is finite (billowed_hinge_points)."""
    if not np.isinf(p.billow_radius):
        return billowed_hinge_points(p, profile, perturbation)
    w = profile or defect_profile(p, perturbation)
    chords = chord_lengths(p)
    pts = np.zeros((p.n + 1, 2))
    pts[0] = (0.0, w(0.0))
    step = chords[0]  # first guess of each hinge: the previous chord's Δx
    for k, c in enumerate(chords):
        x0, y0 = pts[k]

        def gap(x, x0=x0, y0=y0, c=c):
            return math.hypot(x - x0, w(x) - y0) - c

        x1 = chord_end(gap, x0, x0 + c * (1 + 1e-9), x0 + min(step, c))
        step = x1 - x0
        pts[k + 1] = (x1, w(x1))
    return pts


def chord_end(gap, lo: float, hi: float, guess: float, xtol: float = 1e-15, rtol: float = 8.9e-16) -> float:
    """The root of gap(x) = |hinge(x) − hinge₀| − chord in (lo, hi] (gap(lo) < 0 ≤ gap(hi)), to
    |Δx| ≤ xtol + rtol·|x|: secant steps from hi and the guess, which converge superlinearly from a guess
    as close as the previous chord's; bracketed_root if a step leaves [lo, hi] or stalls."""
    a, f_a = hi, gap(hi)
    b, f_b = guess, gap(guess)
    for _ in range(12):
        if f_b == 0:
            return b
        if f_b == f_a:
            break
        x = b - f_b * (b - a) / (f_b - f_a)
        if not lo <= x <= hi:
            break
        if abs(x - b) <= xtol + rtol * abs(x):
            return x
        a, f_a, b, f_b = b, f_b, x, gap(x)
    return bracketed_root(gap, lo, hi)


def bracketed_root(f, lo: float, hi: float, xtol: float = 1e-15, rtol: float = 8.9e-16) -> float:
    """A root of f in [lo, hi] with f(lo) < 0 < f(hi), to |Δx| ≤ xtol + rtol·|x|: false position with the
    Illinois modification (superlinear), bisecting whenever a step fails to halve the bracket."""
    f_lo, f_hi = f(lo), f(hi)
    if f_lo >= 0 or f_hi <= 0:
        if f_lo == 0:
            return lo
        if f_hi == 0:
            return hi
        raise ValueError(f"f must change sign from [{lo}, {hi}]: f = {f_lo}, {f_hi}")
    side = 0
    for _ in range(200):
        width = hi - lo
        x = lo - f_lo * width / (f_hi - f_lo)
        if not lo < x < hi:
            x = 0.5 * (lo + hi)
        value = f(x)
        if value == 0:
            return x
        if value < 0:
            lo, f_lo = x, value
            if side == -1:
                f_hi *= 0.5
            side = -1
        else:
            hi, f_hi = x, value
            if side == 1:
                f_lo *= 0.5
            side = 1
        if hi - lo > 0.5 * width:  # a slow step: bisect once
            mid = 0.5 * (lo + hi)
            value = f(mid)
            if value == 0:
                return mid
            if value < 0:
                lo, f_lo = mid, value
            else:
                hi, f_hi = mid, value
            side = 0
        if hi - lo <= xtol + rtol * abs(lo):
            return 0.5 * (lo + hi)
    return 0.5 * (lo + hi)


def initial_state(p: SailParameters, profile=None, perturbation: float = 0.0) -> ChainState:
    """Slice centres and angles of the initial shape (slice k spans its hinge k to hinge k + l·e_k);
    perturbation: see defect_profile."""
    pts = hinge_points(p, profile, perturbation)
    d = np.diff(pts, axis=0)
    theta = np.arctan2(d[:, 1], d[:, 0])
    half = 0.5 * p.slice_length
    x = pts[:-1, 0] + half * np.cos(theta)
    y = pts[:-1, 1] + half * np.sin(theta)
    if p.initial_tilt != 0.0:
        x, y, theta = _tilted(p, x, y, theta)
    return ChainState(x=x, y=y, theta=theta, z=initial_spring_extension(p))


def _tilted(p: SailParameters, x, y, theta):
    """The shape turned by p.initial_tilt (counter-clockwise) about the craft's centre of mass, the payload
    (model/payload.py) included: a rigid tilt that leaves the centre of mass where it was."""
    m, mp = p.slice_mass, p.payload_mass
    gx, gy = m * x.sum(), m * y.sum()
    if mp > 0:
        px, py = stem_end(p.replace(initial_tilt=0.0), x, y, theta)
        gx, gy = gx + mp * px, gy + mp * py
    gx, gy = gx / (m * p.n + mp), gy / (m * p.n + mp)
    c, s = np.cos(p.initial_tilt), np.sin(p.initial_tilt)
    return gx + c * (x - gx) - s * (y - gy), gy + s * (x - gx) + c * (y - gy), theta + p.initial_tilt


def middle_slice(n: int) -> int:
    """j: the slice that holds the sail's middle (its centre for odd n, its right end for even n)."""
    return (n - 1) // 2


def stem_offset(p: SailParameters):
    """(j, ρ_e, ρ_p): the slice j that holds the sail's middle and the offset from its centre of the end of
    a stem of length payload_stem that leaves the middle along −ŷ, in slice j's axes at its initial angle
    on the untilted sail (model/payload.py welds the payload there)."""
    state = initial_state(p.replace(initial_tilt=0.0))  # the stem is fixed in the untilted sail's axes
    j = middle_slice(p.n)
    c, s = np.cos(state.theta[j]), np.sin(state.theta[j])
    half = 0.5 * p.slice_length
    mid_x, mid_y = state.x[j], state.y[j]
    if p.n % 2 == 0:  # the middle is slice j's right end
        mid_x, mid_y = mid_x + half * c, mid_y + half * s
    wx, wy = mid_x - state.x[j], mid_y - state.y[j] - p.payload_stem
    return j, c * wx + s * wy, -s * wx + c * wy


def stem_end(p: SailParameters, x, y, theta):
    """The stem's end (x_p, y_p) (stem_offset) from slice centres and angles (arrays (…, n)): where a payload
    sits."""
    j, along, across = stem_offset(p)
    along, across = float(along), float(across)
    x, y, theta = (np.asarray(v, float) for v in (x, y, theta))
    th = theta[..., j]
    c, s = np.cos(th), np.sin(th)
    return x[..., j] + along * c - across * s, y[..., j] + along * s + across * c


MIN_SLICES_PER_HALF_WAVE = 4  # fewer slices per half wavelength do not draw the defect's shape
MIN_CARRIED_FRACTION = 0.5  # a chain whose initial amplitude is below this fraction of a₀ misses the defect
PRECISION_FLOOR = 1e-12  # a₀/L below this is within ~1e4 ulps of the coordinates' round-off


def shortest_mode(p: SailParameters, mode: float) -> float:
    """The mode number of the defect's shortest wave in one direction: `mode` (ν or ν_y) for the sine,
    K/2 for a seeded multi-mode defect of K modes."""
    return mode if p.defect_seed is None else 0.5 * p.defect_mode_count


def defect_warnings(p: SailParameters, initial_amplitude: float, element: str = "slices") -> list[str]:
    """Why a chain of n slices may not carry the case's defect: too few slices per half wavelength of
    its shortest wave, an initial chain amplitude (analysis.amplitude of the initial state) far below
    a₀, or an a₀ so small against L that double precision barely resolves it. Empty when none applies.
    ``element`` names the n bodies along L in the messages ("tiles" for the sheet)."""
    a0 = p.defect_amplitude
    if a0 <= 0:
        return []
    notes = []
    shortest = shortest_mode(p, p.defect_mode)
    per_half_wave = p.n / (2.0 * shortest)
    if per_half_wave < MIN_SLICES_PER_HALF_WAVE:
        notes.append(
            f"n = {p.n} gives {per_half_wave:.3g} {element} per half wavelength of the defect (ν = "
            f"{shortest:g}); at least {MIN_SLICES_PER_HALF_WAVE} are needed to resolve it"
        )
    if p.defect_seed is None and initial_amplitude < MIN_CARRIED_FRACTION * a0:
        notes.append(
            f"the initial shape carries an amplitude of {initial_amplitude:.3g} m, {initial_amplitude / a0:.2g} "
            f"of the defect's a₀ = {a0:.3g} m: amplitude ratios measure round-off, not the defect"
        )
    if a0 < PRECISION_FLOOR * p.length:
        notes.append(
            f"a₀/L = {a0 / p.length:.2g} is below {PRECISION_FLOOR:g}: double precision (2.2e-16 L) "
            "carries the defect with few digits"
        )
    return notes
