"""The relativistic beam: Doppler factors against a Lorentz boost of the photon's four-momentum, and the closed-form
trajectory against the integrated equation of motion d(γβ)/dt = (2R + α)P/(mc²) (1 − β)/(1 + β)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from lightsail_mbs import ParameterError
from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.model import relativity


def boosted_photon(beta):
    """(energy, momentum) of a unit-energy photon along +x seen from a frame moving at +βc (a boost matrix)."""
    g = 1.0 / np.sqrt(1.0 - beta**2)
    boost = np.array([[g, -g * beta], [-g * beta, g]])
    return boost @ np.array([1.0, 1.0])


@pytest.mark.parametrize("beta", [0.0, 1e-6, 0.05, 0.2, 0.9])
def test_doppler_factors_follow_from_the_boost(beta):
    energy, momentum = boosted_photon(beta)
    assert energy == pytest.approx(momentum, rel=1e-12)
    # frequency scales as the energy; wavelength as its inverse; the photon rate (flux) as the energy too
    assert relativity.wavelength_factor(beta) == pytest.approx(1.0 / energy, rel=1e-12)
    assert relativity.intensity_factor(beta) == pytest.approx(energy**2, rel=1e-12)


def test_speeds_outside_zero_to_one_are_refused():
    for beta in (-0.1, 1.0, np.nan):
        with pytest.raises(ParameterError, match="beta"):
            relativity.intensity_factor(beta)


@pytest.mark.parametrize(("reflectivity", "absorptivity", "target"), [(1.0, 0.0, 0.2), (0.9, 0.05, 0.6)])
def test_the_closed_form_trajectory_matches_the_integrated_equation_of_motion(reflectivity, absorptivity, target):
    """Starshot-like numbers: 50 GW on a 3 g craft; the equation of motion for u = γβ and x integrated by
    DOP853 at rtol 1e-13 agrees with β(t) and x(β) of the closed form to 1e-9 at every output time."""
    trajectory = relativity.Trajectory(50e9, 3e-3, relativity.momentum_coefficient(reflectivity, absorptivity))
    t_end = float(trajectory.time(target))

    def rhs(_t, y):
        beta = relativity.speed_from_u(y[0])
        return [trajectory.rate(beta), SPEED_OF_LIGHT * beta]

    times = np.linspace(0.0, t_end, 41)
    sol = solve_ivp(rhs, (0.0, t_end), [0.0, 0.0], method="DOP853", t_eval=times, rtol=1e-13, atol=1e-16)
    beta_ode = relativity.speed_from_u(sol.y[0])
    beta_closed = np.array([trajectory.beta_at(t) for t in times])
    assert np.max(np.abs(beta_ode - beta_closed)) < 1e-9
    assert beta_closed[-1] == pytest.approx(target, abs=1e-14)
    distance = trajectory.distance(np.minimum(beta_ode, np.nextafter(1, 0)))
    assert np.max(np.abs(sol.y[1] - distance)) < 1e-9 * SPEED_OF_LIGHT * t_end


def test_proper_time_and_acceleration_are_those_of_the_trajectory():
    trajectory = relativity.Trajectory(1e10, 1e-3)
    betas = np.linspace(0.0, 0.3, 7)
    # dτ/dβ = (dt/dβ)/γ, by differences of t(β)
    h = 1e-6
    for b in betas[1:-1]:
        dt_db = (trajectory.time(b + h) - trajectory.time(b - h)) / (2 * h)
        dtau_db = (trajectory.proper_time(b + h) - trajectory.proper_time(b - h)) / (2 * h)
        assert dtau_db == pytest.approx(dt_db / relativity.lorentz_factor(b), rel=1e-8)
        # the proper acceleration is c γ³ dβ/dt
        g = SPEED_OF_LIGHT * relativity.lorentz_factor(b) ** 3 / dt_db
        assert g == pytest.approx(relativity.proper_acceleration(b, 1e10, 1e-3), rel=1e-8)


def test_the_newtonian_limit_and_the_inverse():
    trajectory = relativity.Trajectory(100.0, 1e-6)  # a lab-scale sail: 100 W on a milligram
    assert trajectory.time(1e-9) == pytest.approx(1e-9 * trajectory.time_constant, rel=1e-8)
    assert trajectory.time_constant == pytest.approx(1e-6 * SPEED_OF_LIGHT**2 / 200.0)
    for beta in (1e-12, 1e-5, 0.1, 0.5, 0.99):
        assert trajectory.beta_at(float(trajectory.time(beta))) == pytest.approx(beta, rel=1e-13)
