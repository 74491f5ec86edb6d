"""Exact results for the discrete chain and its continuum limits (validations of Appendices A–B).

The chain: n rigid slices of length l = L/n, mass m, centroidal inertia J, joined at hinges
0…n (hinge k−1 is the left end of slice k), torsional springs k_T = EI/l at the interior
hinges 1…n−1 (Eq. 23). Everything linear here is written in the transverse hinge displacements
w_0…w_n about the straight chain; a rigid slice k then has the centre displacement
(1 − α_k) w_{k−1} + α_k w_k and the rotation θ_k = (w_k − w_{k−1})/s_k, where s_k is the
hinge-to-hinge length (l, or l + z₀ for an extensible TnT slice followed by its pre-stretched
spring, Eqs 30–31 with l_s = 0) and α_k = (l/2)/s_k.

Energies to second order (exact linearisation of the chain, no discretisation error on top):

    kinetic     ½ Σ_k [ m ((1−α_k) ẇ_{k−1} + α_k ẇ_k)² + J θ̇_k² ]
    bending     ½ k_T Σ_{k=1}^{n−1} (θ_{k+1} − θ_k)²
    tension     ½ Σ_k (T/s_k) (w_k − w_{k−1})²        (geometric stiffness of the axial force T)

For s_k = l, J = m l²/12 the slice mass matrix is the consistent mass of a linear element,
(m/6)[[2, 1], [1, 2]], and for the pinned chain (w_0 = w_n = 0) the sine vectors
w_j = sin(jkπ/n) diagonalise both matrices: with x = kπ/n,

    ω_k² = [ (T/l)(2 − 2cos x) + (k_T/l²)(2 − 2cos x)² ] / [ (m/6)(4 + 2cos x) ]
         = (6T/(m l)) (1 − cos x)/(2 + cos x) + (12 k_T/(m l²)) (1 − cos x)²/(2 + cos x),

the tensioned (string) and simply supported (beam) chains. For x → 0 they tend to the continuous
string ω = kπ√(T/μ)/L from above, relative error +x²/24 (second order), and to the beam
ω = (kπ)²√(EI/μ)/L² from below, relative error −x⁴/1440: the x² terms of (1 − cos x)² and of the
consistent mass cancel, so the rigid-slice beam chain converges at FOURTH order.

Boundary conditions (SailParameters.boundary): "free" (all w free), "cantilever" (slice 1
clamped: w_0 = w_1 = 0, paper Appendix A), "pinned" (w_0 = w_n = 0: hinge 0 pinned, hinge n on a
roller that lets the end tension through, see parameters.BOUNDARIES).

Static cantilever (Appendix A, Fig. 13b): slice 1 clamped, a transverse load P at the centre of
slice n (x_P = L − l/2). The spring at hinge j (x = j l) carries the moment P (x_P − j l) and turns
by that over k_T; the tip deflection is the sum of those rotations times their arms:

    y_tip = Σ_{j=1}^{n−1} P (x_P − j l)² / k_T = (P L³ / EI) (n − 1)(2n − 1)(2n − 3) / (12 n³)
          = (P L³ / 3EI) [1 − 3/n + 11/(4n²) − 3/(4n³)],

converging to the Euler–Bernoulli tip deflection P L³/(3EI) at FIRST order (error −3/n): the
clamp sits at x = 0 but the first spring at x = l, and the load acts l/2 short of the tip.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import eigh
from scipy.optimize import brentq

from lightsail_mbs.model.parameters import SailParameters

# ---- static cantilever --------------------------------------------------------------------


def cantilever_tip_deflection(load: float, length: float, bending_stiffness: float, n: int) -> float:
    """Static deflection (m) of the centre of slice n of the clamped chain under the load P there:
    (P L³/EI)(n − 1)(2n − 1)(2n − 3)/(12 n³) (module docstring; linear in P)."""
    return load * length**3 / bending_stiffness * (n - 1) * (2 * n - 1) * (2 * n - 3) / (12.0 * n**3)


def cantilever_deflection(load: float, length: float, bending_stiffness: float, n: int) -> np.ndarray:
    """Static deflections (m) of all n slice centres x_i = (i − ½) l of the clamped chain (load P at
    the centre of slice n): y_i = Σ_{j<i} P (x_P − j l)(x_i − j l)/k_T, k_T = EI/l."""
    l = length / n
    x_load = length - 0.5 * l
    hinges = l * np.arange(1, n)  # springs at hinges 1…n−1
    centres = l * (np.arange(1, n + 1) - 0.5)
    turn = load * (x_load - hinges) * l / bending_stiffness  # Δθ_j = M_j / k_T
    arms = np.clip(centres[:, None] - hinges[None, :], 0.0, None)
    return arms @ turn


def euler_bernoulli_cantilever(
    load: float, length: float, bending_stiffness: float, x, load_position: float | None = None
) -> np.ndarray:
    """Euler–Bernoulli deflection (m) of a cantilever clamped at x = 0 under a transverse load P at
    a (default the tip L): P x²(3a − x)/(6EI) for x ≤ a, P a²(3x − a)/(6EI) beyond (paper Eq. 42,
    sign: deflection along the load)."""
    a = length if load_position is None else float(load_position)
    x = np.asarray(x, float)
    inner = load * x**2 * (3 * a - x) / (6 * bending_stiffness)
    outer = load * a**2 * (3 * x - a) / (6 * bending_stiffness)
    return np.where(x <= a, inner, outer)


def cantilever_relative_error(n) -> np.ndarray:
    """y_tip(chain)/(P L³/3EI) − 1 = −3/n + 11/(4n²) − 3/(4n³) (first order in 1/n)."""
    n = np.asarray(n, float)
    return -3.0 / n + 11.0 / (4 * n**2) - 3.0 / (4 * n**3)


def ramp_residual_amplitude(static: float, omega: float, time_constant: float) -> float:
    """Amplitude of the free vibration left by the ramp of Eq. (43) in an undamped oscillator
    ÿ + ω² y = ω² y_s (1 − e^(−t/τ)), y(0) = ẏ(0) = 0: y_s / (τ √(ω² + τ⁻²)) (≈ y_s/(ωτ))."""
    return static / (time_constant * math.sqrt(omega**2 + time_constant**-2))


def tip_ramp_vibration(p: SailParameters) -> tuple[np.ndarray, np.ndarray]:
    """(ω_k, a_k): the free vibration the ramped tip load of Eq. (43) leaves at the centre of slice n of
    the linearised chain, mode by mode: a_k = c_k / (τ √(ω_k² + τ⁻²)) (ramp_residual_amplitude), c_k the
    static tip deflection carried by mode k (mass-normalised modes φ_k: c_k = P φ_k(tip)² / ω_k²)."""
    M, K = chain_matrices(p)
    w2, modes = eigh(K, M)
    alpha = 0.5  # the last slice has no spring after it: centre = mid-segment
    tip = np.zeros(K.shape[0])
    tip[-2:] = [1.0 - alpha, alpha]
    static = p.tip_load * (tip @ modes) ** 2 / w2
    tau = p.tip_load_time_constant
    return np.sqrt(w2), static / (tau * np.sqrt(w2 + tau**-2))


# ---- linearised chain ---------------------------------------------------------------------

BOUNDARY_FIXED = {"free": lambda n: [], "cantilever": lambda n: [0, 1], "pinned": lambda n: [0, n]}


def chain_matrices(p: SailParameters, *, tension: float | None = None, segments=None):
    """(M, K) of the chain of p linearised about the straight state, in the free hinge
    displacements (module docstring; the fixed ones of p.boundary removed).

    tension: axial force T carried by every segment (default: p.tension for the pinned boundary,
    where the roller passes it through, else 0: free ends carry no axial force at rest).
    segments: hinge-to-hinge lengths s_k (default l, or l + T/k_s before every spring of an
    extensible chain).
    """
    n, l, m, J = p.n, p.slice_length, p.slice_mass, p.slice_inertia
    if tension is None:
        tension = p.tension if p.boundary == "pinned" else 0.0
    if segments is None:
        segments = np.full(n, l)
        if p.extensible:
            segments[:-1] += p.tension / p.axial_stiffness
    s = np.asarray(segments, float)
    alpha = 0.5 * l / s
    M = np.zeros((n + 1, n + 1))
    K = np.zeros((n + 1, n + 1))
    for k in range(n):  # slice k+1 spans hinges k, k+1
        centre = np.array([1.0 - alpha[k], alpha[k]])
        turn = np.array([-1.0, 1.0]) / s[k]
        M[k : k + 2, k : k + 2] += m * np.outer(centre, centre) + J * np.outer(turn, turn)
        K[k : k + 2, k : k + 2] += tension * s[k] * np.outer(turn, turn)
    k_T = p.torsional_stiffness
    for k in range(1, n):  # spring at hinge k: θ_{k+1} − θ_k
        bend = np.zeros(n + 1)
        bend[k - 1 : k + 2] = [1.0 / s[k - 1], -1.0 / s[k - 1] - 1.0 / s[k], 1.0 / s[k]]
        K += k_T * np.outer(bend, bend)
    free = np.setdiff1d(np.arange(n + 1), BOUNDARY_FIXED[p.boundary](n))
    return M[np.ix_(free, free)], K[np.ix_(free, free)]


def chain_angular_frequencies(p: SailParameters, **kwargs) -> np.ndarray:
    """ω (rad/s), ascending, of the linearised transverse chain (chain_matrices); rigid-body modes
    of a free chain appear as zeros (its axial rigid translation is not included)."""
    return chain_modes(p, **kwargs)[0]


def chain_modes(p: SailParameters, **kwargs) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(ω, Φ, M): the linearised chain's angular frequencies (ascending), its mode shapes in the free
    hinge displacements as columns, mass-normalised (Φᵀ M Φ = 1), and M (chain_matrices)."""
    M, K = chain_matrices(p, **kwargs)
    w2, shapes = eigh(K, M)
    return np.sqrt(np.clip(w2, 0.0, None)), shapes, M


def rayleigh_decay_rate(p: SailParameters, omega) -> np.ndarray:
    """σ = β ω²/2 (1/s): the amplitude decay rate e^(−σt) of the mode at ω under material damping
    c = β k on every spring (damping matrix β K, so the modes stay uncoupled); the damped
    frequency is ω √(1 − (βω/2)²)."""
    return 0.5 * p.stiffness_damping * np.asarray(omega, float) ** 2


def pinned_chain_angular_frequencies(p: SailParameters, tension: float | None = None) -> np.ndarray:
    """Closed form ω_k (rad/s), k = 1…n−1, of the inextensible pinned chain with tension T and
    torsional springs k_T (module docstring): the exact spectrum of chain_matrices for s_k = l."""
    T = p.tension if tension is None else tension
    x = np.arange(1, p.n) * np.pi / p.n
    m, l = p.slice_mass, p.slice_length
    c = np.cos(x)
    w2 = 6 * T / (m * l) * (1 - c) / (2 + c) + 12 * p.torsional_stiffness / (m * l * l) * (1 - c) ** 2 / (2 + c)
    return np.sqrt(w2)


# ---- continuum ----------------------------------------------------------------------------


def string_frequency(tension: float, line_density: float, length: float, mode: int = 1) -> float:
    """f_k = (k / 2L) √(T/μ) (Hz): the continuous string fixed at both ends (paper Eq. 45)."""
    return mode / (2.0 * length) * math.sqrt(tension / line_density)


def free_free_beam_roots(count: int) -> np.ndarray:
    """β_k L of the Euler–Bernoulli free–free beam: roots of cos(βL) cosh(βL) = 1 (4.7300, 7.8532, …)."""
    f = lambda b: math.cos(b) * math.cosh(b) - 1.0  # noqa: E731
    return np.array(
        [
            brentq(
                lambda b: f(b) / math.cosh(b),
                (k + 0.5) * math.pi - 0.49 * math.pi,
                (k + 0.5) * math.pi + 0.49 * math.pi,
                xtol=1e-14,
            )
            for k in range(1, count + 1)
        ]
    )


def cantilever_beam_roots(count: int) -> np.ndarray:
    """β_k L of the Euler–Bernoulli cantilever: roots of cos(βL) cosh(βL) = −1 (1.8751, 4.6941, …)."""
    f = lambda b: math.cos(b) + 1.0 / math.cosh(b)  # noqa: E731
    return np.array(
        [
            brentq(f, (k - 0.5) * math.pi - 0.49 * math.pi, (k - 0.5) * math.pi + 0.49 * math.pi, xtol=1e-14)
            for k in range(1, count + 1)
        ]
    )


def beam_angular_frequencies(roots, bending_stiffness: float, line_density: float, length: float) -> np.ndarray:
    """ω_k = (β_k L)² √(EI / (μ L⁴)) (rad/s) of an Euler–Bernoulli beam with those roots."""
    return np.asarray(roots, float) ** 2 * math.sqrt(bending_stiffness / (line_density * length**4))
