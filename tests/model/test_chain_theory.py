"""Exact discrete-chain results (chain_theory) against independent computations, and the sine fit."""

import math

import numpy as np
import pytest

from lightsail_mbs.analysis.frequencies import fit_sinusoid
from lightsail_mbs.model import chain_theory as ct
from lightsail_mbs.model.parameters import SailParameters

BEAM = dict(
    model="torsion",
    length=1.0,
    width=0.1,
    thickness=0.2,
    density=7800.0,
    youngs_modulus=200e9,
    intensity=0.0,
    defect_amplitude=0.0,
)
STRING = dict(
    model="tnt",
    axial_springs=False,
    boundary="pinned",
    length=0.6477,
    width=3.9e-4,
    thickness=3.7e-4,
    density=7800.0,
    youngs_modulus=210e9,
    tension=72.485,
    intensity=0.0,
    defect_amplitude=0.0,
)


@pytest.mark.parametrize("n", [2, 3, 10, 57])
def test_cantilever_closed_form_equals_linear_solve(n):
    """(n−1)(2n−1)(2n−3)/(12n³) P L³/EI = the tip deflection of K w = F from the assembled matrices."""
    p = SailParameters(n=n, boundary="cantilever", **BEAM)
    EI = p.youngs_modulus * p.second_moment_of_area
    _, K = ct.chain_matrices(p)
    load = np.zeros(K.shape[0])
    load[-2:] = 0.5 * 100.0  # P at the centre of slice n: half on each of its hinges
    w = np.linalg.solve(K, load)
    tip = 0.5 * (w[-2] + w[-1]) if n > 2 else 0.5 * w[-1]
    assert tip == pytest.approx(ct.cantilever_tip_deflection(100.0, 1.0, EI, n), rel=1e-12)
    assert ct.cantilever_deflection(100.0, 1.0, EI, n)[-1] == pytest.approx(tip, rel=1e-12)


def test_cantilever_error_expansion_and_first_order():
    n = np.array([100, 1000, 10000])
    exact = ct.cantilever_tip_deflection(1.0, 1.0, 1.0, n) * 3.0 - 1.0
    assert np.allclose(exact, ct.cantilever_relative_error(n), rtol=1e-12, atol=0)
    order = -np.diff(np.log(np.abs(exact))) / np.diff(np.log(n))
    assert np.allclose(order, 1.0, atol=0.005)


def test_euler_bernoulli_cantilever_shape():
    assert ct.euler_bernoulli_cantilever(3.0, 2.0, 5.0, 2.0) == pytest.approx(3.0 * 8 / 15)
    x = np.linspace(0, 1, 5)
    assert np.allclose(ct.euler_bernoulli_cantilever(1.0, 1.0, 1.0, x, load_position=1.0), x**2 * (3 - x) / 6)


@pytest.mark.parametrize("bending", [False, True])
def test_pinned_closed_form_is_the_spectrum_of_the_matrices(bending):
    """ω_k² = (6T/ml)(1−cos x)/(2+cos x) [+ 12k_T/(ml²)(1−cos x)²/(2+cos x)] for the pinned chain."""
    p = SailParameters(n=25, bending=bending, **STRING)
    assert np.allclose(ct.chain_angular_frequencies(p), ct.pinned_chain_angular_frequencies(p), rtol=1e-12)


def test_consistent_mass_of_a_rigid_slice():
    p = SailParameters(n=4, **STRING)
    M, _ = ct.chain_matrices(p)
    m = p.slice_mass
    assert np.allclose(M[0, :2], m / 6 * np.array([4, 1]), rtol=1e-13)


def test_discrete_string_and_beam_converge_at_second_and_fourth_order():
    for n in (20, 200):
        p = SailParameters(n=n, **STRING)
        mu = p.density * p.width * p.thickness
        f1 = ct.pinned_chain_angular_frequencies(p)[0] / (2 * math.pi)
        f_string = ct.string_frequency(p.tension, mu, p.length)
        assert f1 / f_string - 1 == pytest.approx((math.pi / n) ** 2 / 24, rel=0.01)
    p = SailParameters(n=200, boundary="pinned", **BEAM)
    w = ct.pinned_chain_angular_frequencies(p)[0]
    EI, mu = p.youngs_modulus * p.second_moment_of_area, p.density * p.width * p.thickness
    assert w / ct.beam_angular_frequencies([math.pi], EI, mu, 1.0)[0] - 1 == pytest.approx(
        -((math.pi / 200) ** 4) / 1440, rel=0.01
    )


def test_beam_roots():
    assert np.allclose(ct.free_free_beam_roots(3), [4.7300407, 7.8532046, 10.9956078], atol=1e-7)
    assert np.allclose(ct.cantilever_beam_roots(2), [1.8751041, 4.6940911], atol=1e-7)


def test_free_free_chain_converges_to_euler_bernoulli():
    errors = []
    for n in (10, 20, 40):
        p = SailParameters(n=n, **BEAM)
        w = ct.chain_angular_frequencies(p)[2:5]  # two rigid modes first
        EI, mu = p.youngs_modulus * p.second_moment_of_area, p.density * p.width * p.thickness
        errors.append(abs(w[0] / ct.beam_angular_frequencies(ct.free_free_beam_roots(1), EI, mu, 1.0)[0] - 1))
    assert errors[0] > errors[1] > errors[2] and errors[2] < 1e-5


def test_ramp_residual_amplitude_matches_an_integrated_oscillator():
    from scipy.integrate import solve_ivp

    omega, tau, ys = 50.0, 0.3, 2.0
    sol = solve_ivp(
        lambda t, y: [y[1], omega**2 * (ys * -np.expm1(-t / tau) - y[0])],
        (0, 3),
        [0, 0],
        rtol=1e-11,
        atol=1e-13,
        dense_output=True,
    )
    t = np.linspace(2.5, 3, 2001)
    forced = ys * (1 - np.exp(-t / tau) * omega**2 / (omega**2 + tau**-2))  # particular solution
    fit = fit_sinusoid(t, sol.sol(t)[0] - forced)
    assert fit.amplitude == pytest.approx(ct.ramp_residual_amplitude(ys, omega, tau), rel=1e-6)
    assert fit.frequency == pytest.approx(omega / (2 * math.pi), rel=1e-8)


def test_tip_ramp_vibration_sums_to_the_static_tip_and_matches_one_mode():
    p = SailParameters(n=20, boundary="cantilever", tip_load=100.0, tip_load_time_constant=0.3, **BEAM)
    omega, amplitude = ct.tip_ramp_vibration(p)
    static = amplitude * 0.3 * np.sqrt(omega**2 + 0.3**-2)
    EI = p.youngs_modulus * p.second_moment_of_area
    assert static.sum() == pytest.approx(ct.cantilever_tip_deflection(100.0, 1.0, EI, 20), rel=1e-10)
    assert amplitude[0] < ct.ramp_residual_amplitude(static.sum(), omega[0], 0.3)
    assert amplitude[0] == pytest.approx(ct.ramp_residual_amplitude(static[0], omega[0], 0.3), rel=1e-12)
