"""Heat: radiative equilibrium, one element's transient against scipy's integrator and quadrature, and a Gaussian
spot's steady profile on a conducting disc against an independent boundary-value solution."""

import numpy as np
import pytest
from scipy.integrate import quad, solve_bvp, solve_ivp

from lightsail_mbs import ParameterError
from lightsail_mbs.model import materials, thermal
from lightsail_mbs.model.thermal import STEFAN_BOLTZMANN as SIGMA

SIN = materials.get("silicon-nitride")


@pytest.mark.parametrize("flux", [1e-3, 1.0, 1e4, 1e6])
def test_radiative_equilibrium_balances_absorbed_and_radiated_power(flux):
    T = thermal.equilibrium_temperature(flux, SIN.emissivity)
    radiated = SIN.emissivity * SIGMA * (T**4 - thermal.DEEP_SPACE**4)
    assert radiated == pytest.approx(flux, rel=1e-9)
    element = thermal.Element(SIN.density.value * SIN.heat_capacity.value * 1e-7, SIN.emissivity, flux)
    assert abs(element.derivative(T)) * element.capacity < 1e-9 * flux


@pytest.mark.parametrize("initial", [3.0, 2000.0])
def test_one_elements_transient_matches_the_integrated_ode_and_quadrature(initial):
    """A 100 nm silicon-nitride slice in 1e4 W/m² absorbed (A = 1e-5 of 1 GW/m²), heated from 3 K or cooled from
    2000 K: the closed form T(t) against DOP853 at rtol 1e-12 to 1e-6, and t(T) against quadrature of dt = dT/Ṫ."""
    C = SIN.density.value * SIN.heat_capacity.value * 1e-7
    element = thermal.Element(C, SIN.emissivity, 1e4)
    tau = float(thermal.time_scale(C, SIN.emissivity, element.equilibrium))
    times = np.linspace(0.0, 8 * tau, 17)
    sol = solve_ivp(lambda t, y: element.derivative(y), (0, times[-1]), [initial], method="DOP853", t_eval=times,
                    rtol=1e-12, atol=1e-12)  # fmt: skip
    closed = np.array([element.temperature(t, initial) for t in times])
    assert np.max(np.abs(closed - sol.y[0]) / sol.y[0]) < 1e-6
    target = 0.5 * (initial + element.equilibrium)
    by_quadrature, _ = quad(lambda T: 1.0 / element.derivative(T), initial, target, epsrel=1e-12)
    assert element.time_to(target, initial) == pytest.approx(by_quadrature, rel=1e-9)


def test_a_transient_target_beyond_the_equilibrium_is_refused():
    element = thermal.Element(0.25, 0.2, 1e4)
    with pytest.raises(ParameterError, match="temperature"):
        element.time_to(element.equilibrium + 1.0, 3.0)


def _bvp_disc(radius, flux, conductance, emissivity, peak):
    """The disc's steady profile by scipy's collocation solver, written independently of steady_profile: in
    θ = T/T₀ (εσT₀⁴ = the peak absorbed flux) and s = r/R, θ'' + θ'/s = R²/(k h T₀) (εσT₀⁴θ⁴ − q(sR)) (T_env⁴
    neglected, 1e-11 of it), θ'(0) = θ'(1) = 0, the 1/s term as solve_bvp's singular term S y/s. Returns T(r)."""
    T0 = (peak / (emissivity * SIGMA)) ** 0.25
    scale = radius**2 / (conductance * T0)

    def rhs(s, y):
        return np.vstack([y[1], scale * (peak * y[0] ** 4 - flux(s * radius))])

    s = np.linspace(0.0, 1.0, 201)
    guess = (flux(s * radius) / peak + 1e-3) ** 0.25
    sol = solve_bvp(rhs, lambda a, b: np.array([a[1], b[1]]), s, np.vstack([guess, 0 * s]),
                    S=np.array([[0.0, 0.0], [0.0, -1.0]]), tol=1e-8, max_nodes=100000)  # fmt: skip
    assert sol.success, sol.message
    return lambda r: T0 * sol.sol(np.asarray(r) / radius)[0]


def test_a_gaussian_spots_steady_profile_on_a_conducting_disc_matches_an_independent_solution():
    """A 1 cm-waist spot of 1e4 W/m² absorbed peak on a 4 cm silicon disc (k h = 1.48e-5 W/K at 100 nm):
    conduction spreads heat over ~ the conduction length, comparable to the waist; the finite-volume profile
    (400 rings) agrees with the collocation solution within 1 % everywhere, and both differ from the
    conduction-free equilibrium by more than that."""
    radius, waist, conductance, emissivity = 0.04, 0.01, 148.0 * 1e-5, 0.1

    def flux(r):
        return thermal.gaussian_flux(r, 1e4, waist)

    edges = np.linspace(0.0, radius, 401)
    T = thermal.steady_profile(edges, flux(0.5 * (edges[1:] + edges[:-1])), conductance, emissivity, geometry="disc")
    reference = _bvp_disc(radius, flux, conductance, emissivity, 1e4)(0.5 * (edges[1:] + edges[:-1]))
    assert np.max(np.abs(T - reference) / reference) < 0.01
    local = thermal.equilibrium_temperature(flux(0.5 * (edges[1:] + edges[:-1])), emissivity)
    assert np.max(np.abs(local - reference) / reference) > 0.05  # conduction matters in this case
    assert thermal.conduction_length(conductance, emissivity, float(T[0])) > 0.2 * waist


def test_the_strip_conserves_energy_and_a_uniform_beam_gives_the_equilibrium():
    edges = np.linspace(0.0, 1.0, 31)
    centres = 0.5 * (edges[1:] + edges[:-1])
    q = thermal.gaussian_flux(centres, 1e4, 0.2, 0.5)
    T = thermal.steady_profile(edges, q, 1e-4, 0.2)
    widths = np.diff(edges)
    radiated = np.sum(widths * 0.2 * SIGMA * (T**4 - thermal.DEEP_SPACE**4))
    assert radiated == pytest.approx(np.sum(widths * q), rel=1e-10)
    uniform = thermal.steady_profile(edges, 1e4, 1e-4, 0.2)
    assert np.allclose(uniform, thermal.equilibrium_temperature(1e4, 0.2), rtol=1e-12)


def test_the_change_time_scale_is_that_of_the_doppler_factor():
    """d ln g₀/dτ = −2g₀/c along the constant-power trajectory, by differences of the closed form."""
    from lightsail_mbs.model.relativity import Trajectory

    trajectory = Trajectory(5e10, 3e-3)
    beta, h = 0.1, 1e-6
    tau = [float(trajectory.proper_time(b)) for b in (beta - h, beta + h)]
    g = [float(trajectory.proper_acceleration(b)) for b in (beta - h, beta + h)]
    rate = (np.log(g[1]) - np.log(g[0])) / (tau[1] - tau[0])
    g0 = float(trajectory.proper_acceleration(beta))
    assert -1.0 / rate == pytest.approx(float(thermal.change_time_scale(g0)), rel=1e-7)


def test_the_lag_estimate_matches_a_film_following_a_falling_beam():
    """The absorbed flux falls as exp(−τ/τ_c) (the Doppler factor's rate); after the start-up transient the
    integrated film trails its steady temperature by the fraction thermal.lag gives, within 2 % of it."""
    C, eps, q0, tc = 0.25, 0.2, 1e4, 5.0
    element = thermal.Element(C, eps, q0)

    def rhs(t, y):
        q = q0 * np.exp(-t / tc)
        return [(q - eps * SIGMA * (y[0] ** 4 - thermal.DEEP_SPACE**4)) / C]

    t_end = 2.0
    sol = solve_ivp(rhs, (0, t_end), [element.equilibrium], method="DOP853", rtol=1e-12, atol=1e-12)
    steady = float(thermal.equilibrium_temperature(q0 * np.exp(-t_end / tc), eps))
    measured = (sol.y[0, -1] - steady) / steady
    tau = float(thermal.time_scale(C, eps, steady))
    assert tau < 0.01 * tc
    assert measured == pytest.approx(thermal.lag(tau, tc, steady), rel=0.02)
