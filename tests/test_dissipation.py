"""Material damping (issue 9): c = β k on every spring, the modal decay rate it predicts, and the
heat it generates balancing the loss of mechanical energy."""
import numpy as np
import pytest

from lightsail_mbs import ParameterError, SailParameters, analysis, solve
from lightsail_mbs.model import chain_theory as ct
from lightsail_mbs.analysis.sinefit import fit_damped_sinusoid

# free vibration of a stiff 10-slice torsion chain: first elastic mode 13.7 rad/s, ζ₁ = 2.1 %
FREE = dict(model="torsion", n=10, youngs_modulus=4.5e15, intensity=0.0, stiffness_damping=3e-3)


def test_stiffness_damping_adds_beta_k_to_every_damper():
    p = SailParameters(model="tnt", youngs_modulus=1e9, tension=1e-3, bending=True, torsional_damping=1e-9,
                       axial_damping=2.0, stiffness_damping=1e-4)
    assert p.torsional_damper == pytest.approx(1e-9 + 1e-4 * p.torsional_stiffness, rel=1e-15)
    assert p.axial_damper == pytest.approx(2.0 + 1e-4 * p.axial_stiffness, rel=1e-15)
    assert SailParameters(model="rigid", torsional_damping=1.0, stiffness_damping=1.0).torsional_damper == 0.0
    assert p.replace(axial_springs=False).axial_damper == 0.0
    with pytest.raises(ParameterError, match="stiffness_damping"):
        SailParameters(stiffness_damping=-1e-3)


@pytest.mark.parametrize("solver, tolerance", [("reduced", 1e-6), ("exudyn", 2e-4)])
def test_damped_first_mode_decays_at_rayleigh_rate(solver, tolerance):
    """The first elastic modal coordinate Φ₁ᵀ M w(t) decays as e^(−σt), σ = β ω₁²/2, and rings at
    ω₁ √(1 − ζ₁²) (Exudyn: generalized-α's own period and damping errors, O(h²), set the tolerance)."""
    p = SailParameters(**FREE, t_final=2.0)
    omega, modes, mass = ct.chain_modes(p)
    result = solve(p, solver)
    fit = fit_damped_sinusoid(result.time, analysis.hinge_heights(result) @ mass @ modes[:, 2])
    sigma = ct.rayleigh_decay_rate(p, omega[2])
    damped = omega[2] * np.sqrt(1 - (p.stiffness_damping * omega[2] / 2) ** 2)
    assert fit.decay_rate == pytest.approx(sigma, rel=tolerance)
    assert 2 * np.pi * fit.frequency == pytest.approx(damped, rel=tolerance)


@pytest.mark.parametrize("solver, options", [("reduced", {}), ("exudyn", {"step_size": 2e-5})])
def test_dissipated_energy_equals_loss_of_mechanical_energy(solver, options):
    """E_mech(t) + D(t) = E_mech(0) to 1e-6 E_mech(0) while 98 % of the energy turns into heat
    (Simpson quadrature on 0.1 ms samples; Exudyn's generalized-α needs 20 µs steps for it)."""
    result = solve(SailParameters(**FREE, t_final=0.5, output_interval=1e-4), solver, **options)
    energy = analysis.mechanical_energy(result)
    heat = result.dissipated_energy
    assert heat[-1] > 0.95 * energy[0]
    assert np.abs(energy + heat - energy[0]).max() <= 1e-6 * energy[0]
    assert result.summary()["dissipated_energy"] == heat[-1]


def test_undamped_run_dissipates_nothing():
    result = solve(SailParameters(**{**FREE, "stiffness_damping": 0.0}, t_final=0.1), "reduced")
    assert np.all(result.dissipated_energy == 0.0)


def test_dissipation_scenario_heat_rises_with_tension(tmp_path):
    """scenarios/dissipation.py (quick): only damped runs make heat, and in the stable regime the mean
    power rises with the tension (through the frequency, P ∝ β ω² × energy)."""
    from lightsail_mbs.cli.reproduce import load_scenario
    rows = load_scenario("dissipation").run(tmp_path, quick=True, workers=1, progress=False)
    assert (tmp_path / "dissipation.png").exists() and (tmp_path / "dissipation.csv").exists()
    assert all(r["heat_J"] == 0.0 for r in rows if r["beta_s"] == 0.0)
    stable = [r for r in rows if r["beta_s"] > 0 and not r["failed"] and r["T_over_T_cr"] >= 10]
    powers = [r["mean_power_W"] for r in sorted(stable, key=lambda r: r["T_N"])]
    assert len(powers) >= 3 and all(b > a > 0 for a, b in zip(powers, powers[1:]))
