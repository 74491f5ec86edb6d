"""The film heated by the beam inside a run: its quasi-steady temperature and the tension a frame leaves it.

**What follows the moment.** With the case field ``heated`` (a TnT chain with a ``material``) the film's
temperature is the steady field of the sail-frame beam of each moment, I'(τ) = I₀ D(τ) times the beam's profile
(D the Doppler factor the run's beam loads follow: 1 at rest, the closed form or the world line in the run's
state, model/terms/doppler.py and model/world_line.py). The field is radiative equilibrium per slice for a
uniform beam and the conducting strip's steady field for a Gaussian one (:mod:`lightsail_mbs.model.thermal`):
absorptance A (``heat_absorptance`` or the material's; with an optical table that has a wavelength axis and
records absorption, its 1 − R − T at the sail-frame wavelength of D, as the snapshot journey reads it:
:func:`absorptance`), emissivities ε_f + ε_b and conductivity k of the material, surroundings at DEEP_SPACE. It
is quasi-steady because the film's thermal time ρ c_p h/(4εσT³) is
shorter than the beam's change time c/(2g₀) by orders of magnitude (docs/journey.md gives both for every case;
:func:`lag` the fraction by which T would trail).

**The tension it leaves.** A TnT chain held by a frame that does not expand (model/expansion.py) keeps
N(τ) = N₀ − E h W α_T ⟨ΔT(τ)⟩, ΔT counted from REFERENCE_TEMPERATURE, N₀ the case's ``tension`` (the pre-tension
of the cold film). The chain's n − 1 axial springs, k_s = (n − 1) E h W/L, each carry the compliance of a length
L/(n − 1) of film, half of each slice they join; heated by ΔT_i (the mean of those two slices' rises) its rest
length grows by L α_T ΔT_i/(n − 1), and the spring pulls with k_s (z_i − L α_T ΔT_i/(n − 1)). In the run the
follower end tension is N(τ), with ⟨ΔT⟩ the springs' mean, and the springs' rest lengths follow ΔT_i(τ). The
chain starts in the equilibrium of its heated state, z_i = N(0)/k_s + L α_T ΔT_i(0)/(n − 1)
(:func:`initial_extension`): for uniform heating N₀/k_s, the cold pre-stretch the frame holds; as T changes the
equilibrium moves with it (for uniform heating it stays there, and only the force changes).

**The table the kernels read.** The temperatures are solved once, before the run, on a grid of D uniform in
ln D from D₀ (the run's start) down to the speed FASTEST; the kernels interpolate linearly in ln D (:func:`at`).
Between grid points T ∝ I'^(1/4) is interpolated to ~1e-7 of itself (GRID points over ln D ∈ [ln D₀, −7.6]).
Layout: [points, ln D₀, step, N₀, E h W α_T, L α_T/(n − 1), then the springs' mean rise (points), then each
point's rises of the n − 1 springs (points × (n − 1)), then each point's largest slice temperature (points)].
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.base.kernels import njit
from lightsail_mbs.model import materials

# thermal and relativity are imported where they are used: the kernels' module (the chain solvers import it)
# loads neither scipy.optimize nor scipy.linalg
GRID = 2049  # points of the table in ln D
FASTEST = 0.999  # β of the table's lowest D
REFERENCE_TEMPERATURE = 293.15  # K: the film is tensioned at room temperature (the journey's default)
HEADER = 6
POINTS, TOP, STEP, TENSION, RELIEF, REST = range(HEADER)


def absorptance(p, factor: float = 1.0) -> float:
    """A at the Doppler factor D = factor: the case's heat_absorptance; else, for an optical table with a wavelength
    axis that records absorption (not lossless), its normal-incidence 1 − R − T at the sail-frame wavelength
    λ' = λ₀/√D (:meth:`~lightsail_mbs.model.optics.SpectralTable.normal_absorptance`, λ₀ the table's laser
    wavelength; held at the table's end beyond its range, where the run's loads are not finite and the run
    stops); else the material's at the beam's wavelength."""
    if p.heat_absorptance is not None:
        return p.heat_absorptance
    spectrum = _absorbing_spectrum(p)
    if spectrum is None:
        return materials.get(p.material).absorptance.value
    lo, hi = spectrum.range
    return spectrum.normal_absorptance(min(max(spectrum.wavelength / math.sqrt(factor), lo), hi))


def _absorbing_spectrum(p):
    """The case's optical table with a wavelength axis if it records absorption, else None."""
    if not p.optics_file:
        return None
    from lightsail_mbs.model import optics

    spectrum = optics.read_spectrum(p.optics, single=True)
    return None if spectrum is None or spectrum.lossless else spectrum


def profile(p) -> np.ndarray:
    """I(x)/I₀ at the slices' centres (1 for a uniform beam)."""
    from lightsail_mbs.model import thermal

    if p.uniform_beam:
        return np.ones(p.n)
    centres = (np.arange(p.n) + 0.5) * p.length / p.n
    return thermal.gaussian_flux(centres, 1.0, p.beam_waist, p.beam_centre)


def temperatures(p, factor: float) -> np.ndarray:
    """The slices' steady temperatures (K) under the lab intensity I₀ dimmed by D = factor."""
    from lightsail_mbs.model import thermal

    film = materials.get(p.material)
    flux = absorptance(p, factor) * p.intensity * factor * profile(p)
    if p.uniform_beam:
        return np.asarray(thermal.equilibrium_temperature(flux, film.emissivity))
    edges = np.linspace(0.0, p.length, p.n + 1)
    conductance = film.conductivity.value * p.thickness
    return thermal.steady_profile(edges, flux, conductance, film.emissivity)


def lag(p, factor: float) -> float:
    """The fraction by which T would trail its steady field at D = factor (thermal.lag at the hottest slice)."""
    from lightsail_mbs.model import thermal

    film = materials.get(p.material)
    hottest = float(temperatures(p, factor).max())
    capacity = p.density * film.heat_capacity.value * p.thickness
    change = thermal.change_time_scale(p.trajectory_acceleration * factor)
    return thermal.lag(float(thermal.time_scale(capacity, film.emissivity, hottest)), float(change), hottest)


def table(p) -> np.ndarray:
    """The table the kernels read (module docstring) for case p."""
    from lightsail_mbs.model import relativity

    film = materials.get(p.material)
    expansion = film.thermal_expansion.value
    top = math.log(float(relativity.intensity_factor(p.initial_beta)))
    bottom = math.log(float(relativity.intensity_factor(FASTEST)))
    step = (top - bottom) / (GRID - 1)
    slices = np.array([temperatures(p, math.exp(top - j * step)) for j in range(GRID)])
    rises = 0.5 * (slices[:, 1:] + slices[:, :-1]) - REFERENCE_TEMPERATURE  # the springs'
    relief = p.youngs_modulus * p.thickness * p.width * expansion
    head = [GRID, top, step, p.tension, relief, p.length * expansion / (p.n - 1)]
    return np.concatenate([head, rises.mean(axis=1), rises.ravel(), slices.max(axis=1)])


def initial_extension(p) -> np.ndarray:
    """z_i = N(0)/k_s + L α_T ΔT_i(0)/(n − 1) (m): the springs' extensions in the heated chain's equilibrium at the
    run's start (D₀ of initial_beta)."""
    heat = table(p)
    springs = p.n - 1
    rest = heat[REST] * heat[HEADER + GRID : HEADER + GRID + springs]
    return tension(heat, 0, 0.0) / p.axial_stiffness + rest


def cold_equivalent(p):
    """The case without heat whose end tension is the heated film's at the run's start, N(0) = N₀ − E h W α_T
    ⟨ΔT(0)⟩ (the state a linearisation at the start sees), or p itself when it is not heated. ValueError when
    the heat leaves the film in compression (N(0) < 0), which no cold case with a tension carries."""
    if not p.heated:
        return p
    start = float(tension(table(p), 0, 0.0))
    if start < 0:
        raise ValueError(f"the heated film starts in compression (end tension {start:.4g} N)")
    return p.replace(heated=False, heat_absorptance=None, tension=start)


@njit(cache=True)
def weights(heat, factor):
    """(j, f): D = factor lies between the table's points j and j + 1, a fraction f of the way in ln D
    (clamped to the table's ends)."""
    x = (heat[TOP] - math.log(factor)) / heat[STEP]
    last = int(heat[POINTS]) - 1
    if x <= 0.0:
        return 0, 0.0
    if x >= last:
        return last - 1, 1.0
    j = int(x)
    return j, x - j


@njit(cache=True)
def tension(heat, j, f):
    """N = N₀ − E h W α_T ⟨ΔT⟩ at the table's weights (j, f)."""
    mean = heat[HEADER + j] + f * (heat[HEADER + j + 1] - heat[HEADER + j])
    return heat[TENSION] - heat[RELIEF] * mean


@njit(cache=True)
def rest_extension(heat, n, j, f, i):
    """L α_T ΔT_i/(n − 1): the thermal growth of spring i's rest length at the table's weights (j, f)."""
    springs = n - 1
    at = HEADER + int(heat[POINTS]) + j * springs + i
    return heat[REST] * (heat[at] + f * (heat[at + springs] - heat[at]))


def at(heat: np.ndarray, n: int, factors) -> dict:
    """The table read at the Doppler factors D (an array): tension N (N), the springs' mean and the slices'
    largest temperatures (K), as the kernels read it."""
    factors = np.atleast_1d(np.asarray(factors, float))
    points = int(heat[POINTS])
    mean, hottest = heat[HEADER : HEADER + points], heat[HEADER + points * n :]
    out = {"tension": [], "temperature_mean": [], "temperature_max": []}
    for factor in factors:
        j, f = weights(heat, factor)
        out["tension"].append(tension(heat, j, f))
        out["temperature_mean"].append(REFERENCE_TEMPERATURE + mean[j] + f * (mean[j + 1] - mean[j]))
        out["temperature_max"].append(hottest[j] + f * (hottest[j + 1] - hottest[j]))
    return {k: np.array(v) for k, v in out.items()}
