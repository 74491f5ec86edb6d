"""Energy of a run (model.energy): mechanical energy of a state, and material damping — the modal decay
rate c = β k predicts and the heat it generates balancing the loss of mechanical energy."""

import numpy as np
import pytest

from lightsail_mbs import Result, RunSettings, SailParameters, analysis, solve
from lightsail_mbs.analysis.frequencies import fit_damped_sinusoid
from lightsail_mbs.model import chain_theory as ct

# free vibration of a stiff 10-slice torsion chain: first elastic mode 13.7 rad/s, ζ₁ = 2.1 %
FREE = dict(model="torsion", n=10, youngs_modulus=4.5e15, intensity=0.0, stiffness_damping=3e-3)


@pytest.mark.parametrize("solver, tolerance", [("reduced", 1e-6), ("exudyn", 2e-4)])
def test_damped_first_mode_decays_at_rayleigh_rate(solver, tolerance):
    """The first elastic modal coordinate Φ₁ᵀ M w(t) decays as e^(−σt), σ = β ω₁²/2, and rings at
    ω₁ √(1 − ζ₁²) (Exudyn: generalized-α's own period and damping errors, O(h²), set the tolerance)."""
    p = SailParameters(**FREE)
    omega, modes, mass = ct.chain_modes(p)
    result = solve(p, solver, RunSettings(t_final=2.0), uncertainty=False)
    fit = fit_damped_sinusoid(result.time, analysis.hinge_heights(result) @ mass @ modes[:, 2])
    sigma = ct.rayleigh_decay_rate(p, omega[2])
    damped = omega[2] * np.sqrt(1 - (p.stiffness_damping * omega[2] / 2) ** 2)
    assert fit.decay_rate == pytest.approx(sigma, rel=tolerance)
    assert 2 * np.pi * fit.frequency == pytest.approx(damped, rel=tolerance)


@pytest.mark.parametrize("solver, options", [("reduced", {}), ("exudyn", {"step_size": 2e-5})])
def test_dissipated_energy_equals_loss_of_mechanical_energy(solver, options):
    """E_mech(t) + D(t) = E_mech(0) to 1e-6 E_mech(0) while 98 % of the energy turns into heat
    (Simpson quadrature on 0.1 ms samples; Exudyn's generalized-α needs 20 µs steps for it)."""
    result = solve(
        SailParameters(**FREE), solver, RunSettings(t_final=0.5, output_interval=1e-4), **options, uncertainty=False
    )
    energy = analysis.mechanical_energy(result)
    heat = result.dissipated_energy
    assert heat[-1] > 0.95 * energy[0]
    assert np.abs(energy + heat - energy[0]).max() <= 1e-6 * energy[0]
    assert result.summary()["dissipated_energy"] == heat[-1]


def test_undamped_run_dissipates_nothing():
    result = solve(
        SailParameters(**{**FREE, "stiffness_damping": 0.0}), "reduced", RunSettings(t_final=0.1), uncertainty=False
    )
    assert np.all(result.dissipated_energy == 0.0)


def test_mechanical_energy_of_a_synthetic_state():
    p = SailParameters(n=3, youngs_modulus=1e12)
    t = np.array([0.0])
    theta = np.array([[0.0, 0.1, 0.3]])
    vx = np.array([[1.0, 0.0, 0.0]])
    omega = np.array([[0.0, 2.0, 0.0]])
    r = Result.from_trajectory(p, "test", t, [[0, 1, 2]], [[0, 0, 0]], theta, vx, 0 * vx, omega)
    expected = 0.5 * p.slice_mass * 1.0 + 0.5 * p.slice_inertia * 4.0 + 0.5 * p.torsional_stiffness * (0.01 + 0.04)
    assert analysis.mechanical_energy(r)[0] == pytest.approx(expected, rel=1e-14)
