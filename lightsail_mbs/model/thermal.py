"""Heat in the sail: absorbed beam power, radiative cooling from both faces, heat capacity and in-plane
conduction, per slice (or per ring of a disc).

**The balance.** An element of film of thickness h, density ρ, specific heat c_p, conductivity k, absorptance A
and emissivities ε_f, ε_b (front and back faces, total ε = ε_f + ε_b) in the sail-frame beam intensity I' obeys

    ρ c_p h ∂T/∂t = A I' − ε σ (T⁴ − T_env⁴) + k h ∇·∇T                       (per unit area)

where I' = I (1 − β)/(1 + β) is the intensity in the sail's rest frame (:mod:`lightsail_mbs.model.relativity`)
and T_env the temperature of the surroundings (deep space, 2.7 K).

**Radiative equilibrium** (no conduction, steady): T⁴ = A I'/(ε σ) + T_env⁴.

**One element's transient** (uniform beam, constant I'): with a⁴ = A I'/(εσ) + T_env⁴ (the equilibrium) and
κ = εσ/(ρ c_p h), dT/dt = −κ (T⁴ − a⁴). Since 1/(T⁴ − a⁴) = [1/(T² − a²) − 1/(T² + a²)]/(2a²), a primitive is

    G(T) = ln|(T − a)/(T + a)|/(4a³) − arctan(T/a)/(2a³),   and   t(T) = (G(T₀) − G(T))/κ.

**The thermal time scale.** Linearised about T, a deviation relaxes at the rate 4εσT³/(ρ c_p h), so

    τ_th = ρ c_p h / (4 ε σ T³).

Along the journey the sail-frame intensity I' ∝ (1 − β)/(1 + β), the acceleration g₀ ∝ I' and T ∝ I'^(1/4) change
on the proper-time scale c/(2g₀) (:func:`change_time_scale`); where τ_th is shorter by orders of magnitude the
temperature follows the beam: the quasi-steady field (the balance with ∂T/∂t = 0) is the sail's temperature.

**The steady field with conduction** (:func:`steady_profile`): k h ∇²T = εσ(T⁴ − T_env⁴) − A I'(r) on a strip
(x, the chain's slices as cells) or a disc (r, axisymmetric rings), insulated at its edges (an edge radiates
through a negligible area h), by finite volumes: each cell's absorbed and radiated power and the conducted flux
k h (T_j+1 − T_j)/Δ through each face (times the face's circumference 2πr for the disc), solved by Newton's
method on the tridiagonal Jacobian from the radiative equilibrium as the first guess. The conduction length
√(k h/(4εσT³)) says how far heat spreads before it is radiated (:func:`conduction_length`).
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import solve_banded
from scipy.optimize import brentq

from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.validation import ParameterError, check, finite

STEFAN_BOLTZMANN = 5.670374419e-8  # σ, W/(m²·K⁴): exact in the 2019 SI, 2π⁵k_B⁴/(15h³c²)
DEEP_SPACE = 2.725  # K: the cosmic microwave background, the default surroundings
GEOMETRIES = ("strip", "disc")


def equilibrium_temperature(absorbed_flux, emissivity: float, environment: float = DEEP_SPACE):
    """T = (A I'/(εσ) + T_env⁴)^(1/4) (K): radiative equilibrium of a film absorbing absorbed_flux = A I'
    (W/m²) and radiating with ε = ε_f + ε_b."""
    check("emissivity", emissivity, finite("emissivity", emissivity) > 0, "ε_f + ε_b > 0")
    q = np.asarray(absorbed_flux, float)
    check("absorbed_flux", absorbed_flux, bool(np.all(q >= 0)), "≥ 0 W/m²")
    return (q / (emissivity * STEFAN_BOLTZMANN) + environment**4) ** 0.25


def time_scale(areal_heat_capacity: float, emissivity: float, temperature) -> np.ndarray:
    """τ_th = ρ c_p h / (4 ε σ T³) (s): how fast the film's temperature follows its heat balance at T."""
    return areal_heat_capacity / (4.0 * emissivity * STEFAN_BOLTZMANN * np.asarray(temperature, float) ** 3)


def change_time_scale(proper_acceleration) -> np.ndarray:
    """c/(2g₀) (s, the sail's proper time): the time over which g₀ and I' change by the factor e along the
    journey. From I' ∝ (1 − β)/(1 + β): d ln I'/dτ = −2 (dβ/dτ)/(1 − β²) with dβ/dτ = g₀ (1 − β²)/c, so
    |d ln g₀/dτ| = 2 g₀/c; T ∝ I'^(1/4) changes four times slower, λ' ∝ I'^(−1/2) twice slower."""
    return SPEED_OF_LIGHT / (2.0 * np.asarray(proper_acceleration, float))


def lag(thermal_time: float, change_time: float, temperature: float, environment: float = DEEP_SPACE) -> float:
    """The fraction by which T trails its steady value when the beam changes on change_time: a first-order
    relaxation dT/dτ = (T_eq − T)/τ_th following T_eq(τ) lags by δT ≈ τ_th dT_eq/dτ, and from
    T_eq⁴ − T_env⁴ ∝ I' with |d ln I'/dτ| = 1/change_time, dT_eq/dτ = (T_eq⁴ − T_env⁴)/(4 T_eq³ change_time), so
    δT/T = (τ_th/change_time) (1 − (T_env/T)⁴)/4."""
    return float(thermal_time / change_time * (1.0 - (environment / temperature) ** 4) / 4.0)


def conduction_length(conductance: float, emissivity: float, temperature: float) -> float:
    """√(k h / (4 ε σ T³)) (m): the distance over which conduction (sheet conductance k h, W/K) spreads a
    temperature difference before the faces radiate it (the linearised steady balance's decay length)."""
    return float(np.sqrt(conductance / (4.0 * emissivity * STEFAN_BOLTZMANN * temperature**3)))


class Element:
    """One element of film (a slice or tile) in a uniform beam: areal heat capacity C = ρ c_p h (J/(m²·K)),
    total emissivity ε, absorbed flux q = A I' (W/m²), surroundings at T_env; its transient in closed form."""

    def __init__(self, areal_heat_capacity: float, emissivity: float, absorbed_flux: float, environment=DEEP_SPACE):
        check("areal_heat_capacity", areal_heat_capacity, finite("areal_heat_capacity", areal_heat_capacity) > 0, "> 0")
        self.capacity, self.emissivity = float(areal_heat_capacity), float(emissivity)
        self.flux, self.environment = float(absorbed_flux), float(environment)
        self.equilibrium = float(equilibrium_temperature(self.flux, self.emissivity, self.environment))
        self.rate = self.emissivity * STEFAN_BOLTZMANN / self.capacity  # κ, 1/(s·K³)

    def derivative(self, temperature):
        """dT/dt = (q − εσ(T⁴ − T_env⁴))/C (K/s)."""
        t4 = np.asarray(temperature, float) ** 4
        return (self.flux - self.emissivity * STEFAN_BOLTZMANN * (t4 - self.environment**4)) / self.capacity

    def _primitive(self, temperature):
        a = self.equilibrium
        return np.log(np.abs((temperature - a) / (temperature + a))) / (4 * a**3) - np.arctan(temperature / a) / (
            2 * a**3
        )

    def time_to(self, temperature: float, initial: float) -> float:
        """t (s) at which the element starting at `initial` reaches `temperature` (between it and equilibrium)."""
        a = self.equilibrium
        check(
            "temperature",
            temperature,
            (initial - a) * (temperature - a) > 0 and abs(temperature - a) <= abs(initial - a),
            f"between the initial {initial:g} K and the equilibrium {a:g} K (excluded)",
        )
        return float((self._primitive(initial) - self._primitive(temperature)) / self.rate)

    def temperature(self, time: float, initial: float) -> float:
        """T(t) (K) from `initial` at t = 0: the root of time_to(T) = t (Brent's method)."""
        a = self.equilibrium
        if time <= 0 or initial == a:
            return float(initial)
        edge = a + (initial - a) * 1e-15

        def f(T):
            return self.time_to(T, initial) - time if T != initial else -time

        if f(edge) < 0:  # within round-off of the equilibrium
            return a
        return brentq(f, edge, initial, xtol=1e-14 * a, rtol=4 * np.finfo(float).eps)


def _cells(edges: np.ndarray, geometry: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(cell areas per unit width or radian, face conductance factors, cell centres) of a strip or disc."""
    centres = 0.5 * (edges[1:] + edges[:-1])
    gaps = np.diff(centres)
    if geometry == "strip":
        return np.diff(edges), 1.0 / gaps, centres
    return 0.5 * np.diff(edges**2), edges[1:-1] / gaps, centres


def steady_profile(
    edges,
    absorbed_flux,
    conductance: float,
    emissivity: float,
    environment: float = DEEP_SPACE,
    geometry: str = "strip",
    tol: float = 1e-12,
) -> np.ndarray:
    """The steady temperatures (K) of the cells between `edges` (m, increasing; for the disc from r = 0) under
    absorbed_flux (W/m², one per cell): k h ∇²T = εσ(T⁴ − T_env⁴) − q, insulated edges (module docstring).
    conductance is the sheet conductance k h (W/K)."""
    check("geometry", geometry, geometry in GEOMETRIES, f"one of {', '.join(GEOMETRIES)}")
    edges = np.asarray(edges, float)
    check("edges", "…", edges.ndim == 1 and edges.size >= 3 and bool(np.all(np.diff(edges) > 0)), "increasing, ≥ 3")
    check("edges", edges[0], geometry == "strip" or edges[0] == 0.0, "starting at r = 0 for a disc")
    q = np.broadcast_to(np.asarray(absorbed_flux, float), (edges.size - 1,))
    area, face, _ = _cells(edges, geometry)
    g = conductance * face  # conductance between neighbouring cells (per unit width or radian)
    es = emissivity * STEFAN_BOLTZMANN
    T = np.asarray(equilibrium_temperature(q, emissivity, environment), float).copy()
    for _ in range(100):
        flow = np.zeros_like(T)
        flow[:-1] += g * (T[1:] - T[:-1])
        flow[1:] -= g * (T[1:] - T[:-1])
        residual = area * (q - es * (T**4 - environment**4)) + flow
        bands = np.zeros((3, T.size))
        bands[1] = -area * 4 * es * T**3
        bands[1, :-1] -= g
        bands[1, 1:] -= g
        bands[0, 1:] = g
        bands[2, :-1] = g
        step = solve_banded((1, 1), bands, -residual)
        T = T + step
        if np.max(np.abs(step)) <= tol * np.max(T):
            return T
    raise ParameterError("steady_profile: Newton's method did not converge in 100 steps (check the inputs)")


def gaussian_flux(positions, absorbed_peak: float, waist: float, centre: float = 0.0) -> np.ndarray:
    """A I'(x) = A I'₀ exp(−2 (x − x_c)²/w²) (W/m²): the absorbed flux of a Gaussian beam (the case's profile)."""
    return absorbed_peak * np.exp(-2.0 * (np.asarray(positions, float) - centre) ** 2 / waist**2)
