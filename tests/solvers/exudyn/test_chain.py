"""The Exudyn solver: kinematics and loads against Exudyn's own evaluation, equilibrium of the
flat sail, energy conservation and step convergence in free vibration, the paper's verdicts."""

import numpy as np
import pytest

exu = pytest.importorskip("exudyn")

from lightsail_mbs import ParameterError, RunSettings, SailParameters, analysis, paper_case, paper_settings, solve  # noqa: E402
from lightsail_mbs.model import shapes, terms  # noqa: E402
from lightsail_mbs.solvers.exudyn import chain as exudyn_chain  # noqa: E402
from lightsail_mbs.solvers.exudyn.tree import ChainLayout  # noqa: E402
from tests.references import assert_held  # noqa: E402

rng = np.random.default_rng(11)

CASES = {
    "rigid": SailParameters(model="rigid", n=7, intensity=1e9),
    "torsion": SailParameters(n=6, youngs_modulus=4.5e9, intensity=1e9),
    "tnt-extensible": SailParameters(model="tnt", n=5, tension=1e-3, youngs_modulus=1e11, bending=True, intensity=1e9),
    "tnt-inextensible": SailParameters(model="tnt", n=6, tension=1e-3, axial_springs=False, intensity=1e9),
    "gaussian-absorbing": SailParameters(
        n=6, youngs_modulus=4.5e9, intensity=1e9, beam_waist=0.4, reflectivity=0.7, absorptivity=0.2
    ),
}


def random_coordinates(layout: ChainLayout) -> np.ndarray:
    q = rng.normal(0.0, 0.3, layout.size)
    q[layout.stretch_index] = rng.normal(0.0, 1e-3, layout.stretch_index.size)
    return q


def exudyn_state(p, q):
    """Exudyn's own link positions/angles and ODE2 right-hand side at coordinates q, q̇ = 0."""
    from exudyn.itemInterface import SensorKinematicTree

    SC, mbs, layout, _, _ = exudyn_chain.build(p)
    links = layout.angle_index
    centre = [0.5 * p.slice_length, 0.0, 0.0]
    sensors = [
        [
            mbs.AddSensor(
                SensorKinematicTree(
                    objectNumber=0, linkNumber=int(k), localPosition=centre, storeInternal=True, outputVariableType=kind
                )
            )
            for k in links
        ]
        for kind in (exu.OutputVariableType.Position, exu.OutputVariableType.Rotation)
    ]
    mbs.Assemble()
    solver = exu.MainSolverImplicitSecondOrder()
    solver.InitializeSolver(mbs, exudyn_chain.simulation_settings(RunSettings().t_final, 1e-4, 1e-10, 1e-15))
    mbs.systemData.SetODE2Coordinates(q, configuration=exu.ConfigurationType.Current)
    mbs.systemData.SetODE2Coordinates_t(np.zeros(layout.size), configuration=exu.ConfigurationType.Current)
    position = np.array([mbs.GetSensorValues(s) for s in sensors[0]])
    angle = np.array([mbs.GetSensorValues(s)[2] for s in sensors[1]])
    solver.ComputeODE2RHS(mbs)
    rhs = np.asarray(solver.GetSystemResidual())[: layout.size]
    return layout, position, angle, rhs


def virtual_work_forces(p, layout, q, eps=1e-7):
    """Q_j = Σ F·∂r/∂q_j of terms.chain_forces at the centres and the end tensions (central differences),
    minus the springs' −k q."""

    def points(q):
        x, y, th, _ = layout.positions(q)
        h = 0.5 * p.slice_length
        left = np.array([x[0] - h * np.cos(th[0]), y[0] - h * np.sin(th[0])])
        right = np.array([x[-1] + h * np.cos(th[-1]), y[-1] + h * np.sin(th[-1])])
        return x, y, left, right

    x, y, th, _ = layout.positions(q)
    fx, fy = terms.chain_forces(p, x, th)
    e1 = np.array([np.cos(th[0]), np.sin(th[0])])
    en = np.array([np.cos(th[-1]), np.sin(th[-1])])
    Q = np.zeros(layout.size)
    for j in range(layout.size):
        dq = np.zeros(layout.size)
        dq[j] = eps
        xp, yp, lp, rp = points(q + dq)
        xm, ym, lm, rm = points(q - dq)
        Q[j] = (fx @ (xp - xm) + fy @ (yp - ym) + p.tension * (en @ (rp - rm) - e1 @ (lp - lm))) / (2 * eps)
    Q[layout.angle_index[1:]] -= p.torsional_stiffness * q[layout.angle_index[1:]]
    if p.extensible:
        Q[layout.stretch_index] -= p.axial_stiffness * q[layout.stretch_index]
    return Q


@pytest.mark.parametrize("name", CASES)
def test_kinematics_match_exudyn_links(name):
    p = CASES[name]
    q = random_coordinates(ChainLayout.of(p))
    layout, position, angle, _ = exudyn_state(p, q)
    x, y, theta, z = layout.positions(q)
    np.testing.assert_allclose(position[:, 0], x, rtol=0, atol=1e-14)
    np.testing.assert_allclose(position[:, 1], y, rtol=0, atol=1e-14)
    np.testing.assert_allclose(np.angle(np.exp(1j * (angle - theta))), 0.0, atol=1e-13)


@pytest.mark.parametrize("name", CASES)
def test_exudyn_load_equals_the_terms_forces(name):
    """Exudyn's generalized forces at a random state are the virtual work of terms.chain_forces
    (radiation + frame force), the follower tensions and the springs."""
    p = CASES[name]
    q = random_coordinates(ChainLayout.of(p))
    layout, _, _, rhs = exudyn_state(p, q)
    expected = virtual_work_forces(p, layout, q)
    scale = np.abs(expected).max()
    np.testing.assert_allclose(rhs, expected, rtol=0, atol=1e-7 * scale)


def test_initial_state_is_the_shape_at_rest():
    p = SailParameters(model="tnt", n=12, tension=1e-4, youngs_modulus=1e11)
    r = solve(p, "exudyn", RunSettings(t_final=0.01), uncertainty=False)
    s0 = shapes.initial_state(p)
    np.testing.assert_allclose(r.x[0], s0.x, atol=1e-15)
    np.testing.assert_allclose(r.y[0], s0.y, atol=1e-15)
    np.testing.assert_allclose(r.z[0], s0.z, rtol=1e-12)
    assert not np.abs(r.vx[0]).any() and not np.abs(r.omega[0]).any()


def test_flat_sail_stays_flat_and_put():
    """Uniform beam on a flat sail: radiation f₀ balances the frame force m g₀ exactly
    (stiff sail: a soft one is unstable and amplifies round-off)."""
    p = SailParameters(n=10, defect_amplitude=0.0, youngs_modulus=4.5e13)
    r = solve(p, "exudyn", RunSettings(t_final=0.5, stop_at_failure=False), uncertainty=False)
    assert r.error is None and r.time[-1] == pytest.approx(0.5)
    assert np.abs(r.y).max() < 1e-12
    assert np.abs(r.x - r.x[0]).max() < 1e-12
    assert np.abs(r.theta).max() < 1e-12
    assert r.amplitude.max() < 1e-12


@pytest.mark.parametrize("model", ["torsion", "tnt"])
def test_free_vibration_conserves_energy_and_converges(model):
    """I₀ = 0, no damping, no tension: ½mΣv² + ½JΣω² + ½k_TΣΔθ² (+ ½k_sΣz²) is constant, and
    its drift (generalized-α, ρ∞ = 0.9) shrinks with the step size."""
    p = SailParameters(
        model=model, n=8, intensity=0.0, defect_amplitude=5e-3, defect_mode=1.5, youngs_modulus=4.5e13, bending=True
    )
    settings = RunSettings(t_final=0.2, output_interval=1e-3, stop_at_failure=False)
    drift = []
    for h in (4e-4, 2e-4):
        r = solve(p, "exudyn", settings, step_size=h, newton_rel_tol=1e-12, newton_abs_tol=1e-18, uncertainty=False)
        assert r.error is None
        energy = analysis.mechanical_energy(r)
        assert energy.max() > 0
        drift.append(np.abs(energy - energy[0]).max() / energy.max())
    assert drift[0] < 1e-6
    assert drift[1] < 0.5 * drift[0]  # second order: ≈ 1/4


def test_soft_torsion_fails_near_two_seconds():
    """Paper Fig. 7: E = 4.5e9 Pa < E_cr,max fails 'after merely 2 seconds': at the dated reference, to
    Exudyn's measured step error (tests/references.py), and the run stops at the first sample past it."""
    settings = paper_settings("torsion-soft")
    r = solve(paper_case("torsion-soft"), "exudyn", settings, uncertainty=False)
    assert r.error is None
    assert_held("soft_torsion_failure_time_exudyn", r.failure_time)
    assert r.time[-2] < r.failure_time <= r.time[-1] == pytest.approx(r.failure_time, abs=settings.sample_interval)


@pytest.mark.parametrize("options", [{}, {"method": "generalized-alpha", "step_size": 1e-3}])
def test_stop_rule_is_the_first_output_sample_at_or_past_the_limit(options):
    """Output every 40 ms, steps far shorter: the run ends at the first output sample whose amplitude
    reaches twice the initial one, keeps it, and holds the same samples as the run that goes on."""
    p = paper_case("torsion-soft")
    settings = RunSettings(t_final=2.4, output_interval=0.04)
    r = exudyn_chain.run(p, settings, **options)  # the solver's own rule (solve() would then refine the sampling)
    on = exudyn_chain.run(p, settings.replace(stop_at_failure=False), **options)
    limit = 2.0 * r.amplitude[0]
    assert r.error is None and r.failed
    assert r.amplitude[-1] >= limit and np.all(r.amplitude[:-1] < limit)
    k = r.time.size - 1
    assert r.time[-1] == pytest.approx(k * 0.04, abs=1e-12)
    np.testing.assert_array_equal(r.theta, on.theta[: k + 1])
    assert on.time[-1] == pytest.approx(2.4)


def test_runs_on_past_failure_when_asked():
    r = solve(paper_case("torsion-soft"), "exudyn", RunSettings(t_final=2.2, stop_at_failure=False), uncertainty=False)
    assert r.error is None and r.failed and r.time[-1] == pytest.approx(2.2)
    assert r.max_amplitude_ratio > 2.0


def test_rigid_mode_three_halves_fails_at_a_trough():
    r = solve(paper_case("rigid", defect_mode=1.5), "exudyn", paper_settings("rigid"), uncertainty=False)
    assert r.failed and r.failure_time < 0.01
    k = int(np.searchsorted(r.time, r.failure_time))
    assert analysis.fails_at_trough(r.x[k], r.y[k])


def test_rigid_mode_one_half_does_not_fail():
    r = solve(paper_case("rigid", defect_mode=0.5), "exudyn", paper_settings("rigid"), uncertainty=False)
    assert r.error is None and not r.failed and r.time[-1] == pytest.approx(0.01)


def test_bad_options_name_themselves():
    p, settings = SailParameters(n=4), RunSettings(t_final=0.01)
    with pytest.raises(ParameterError, match="step_size"):
        solve(p, "exudyn", settings, step_size=-1.0, uncertainty=False)
    with pytest.raises(ParameterError, match="newton_rel_tol"):
        solve(p, "exudyn", settings, newton_rel_tol=float("nan"), uncertainty=False)
    with pytest.raises(ParameterError, match="option 'tolerance' is invalid for the exudyn chain solver"):
        solve(p, "exudyn", settings, tolerance=1e-3, uncertainty=False)


def test_impossible_newton_is_recorded_not_raised():
    """Zero tolerances cannot be met: the run ends with Result.error and the arrays so far."""
    p = SailParameters(n=6, youngs_modulus=4.5e9)
    r = solve(p, "exudyn", RunSettings(t_final=0.05), newton_rel_tol=0.0, newton_abs_tol=0.0, uncertainty=False)
    assert r.info["method"] == "generalized-alpha"
    assert r.error
    assert r.time.shape[0] == r.x.shape[0] >= 1


# ---- long runs -----------------------------------------------------------------------------
@pytest.mark.slow
def test_stable_torsion_does_not_fail_over_six_seconds():
    r = solve(paper_case("torsion-stable"), "exudyn", paper_settings("torsion-stable"), uncertainty=False)
    assert r.error is None and not r.failed and r.time[-1] == pytest.approx(6.0)


@pytest.mark.slow
@pytest.mark.parametrize("mode", [1, 1.5, 2, 2.5, 3, 3.5, 4, 4.5, 5])
def test_rigid_modes_fail_at_troughs(mode):
    r = solve(paper_case("rigid", defect_mode=mode), "exudyn", paper_settings("rigid"), uncertainty=False)
    assert r.failed and r.failure_time < 0.01
    k = int(np.searchsorted(r.time, r.failure_time))
    assert analysis.fails_at_trough(r.x[k], r.y[k])


@pytest.mark.slow
@pytest.mark.parametrize("modulus, springs", [(1e11, True), (1e10, True), (1e11, False)])
def test_tnt_verdicts_do_not_hinge_on_modulus(modulus, springs):
    stable = solve(
        paper_case("tnt-stable", youngs_modulus=modulus, axial_springs=springs),
        "exudyn",
        paper_settings("tnt-stable"),
        uncertainty=False,
    )
    assert stable.error is None and not stable.failed and stable.time[-1] == pytest.approx(6.0)
    soft = solve(
        paper_case("tnt-soft", youngs_modulus=modulus, axial_springs=springs),
        "exudyn",
        paper_settings("tnt-soft"),
        uncertainty=False,
    )
    assert soft.error is None and 1.5 <= soft.failure_time <= 2.5


@pytest.mark.slow
def test_soft_torsion_failure_time_converges():
    """Halving the step and the Newton tolerances moves the failure time by < 1 %."""
    p, settings = paper_case("torsion-soft"), paper_settings("torsion-soft")
    h = exudyn_chain.default_step_size(p, settings)
    coarse = solve(p, "exudyn", settings, uncertainty=False)
    fine = solve(
        p,
        "exudyn",
        settings,
        step_size=h / 2,
        newton_rel_tol=exudyn_chain.NEWTON_REL_TOL / 2,
        newton_abs_tol=exudyn_chain.default_abs_tol(p) / 2,
        uncertainty=False,
    )
    assert fine.failure_time == pytest.approx(coarse.failure_time, rel=1e-2)


def test_the_last_sample_is_kept_when_the_steps_fall_short_of_t_final_by_round_off():
    """33,200 steps of t_final/33,200 accumulate to just below t_final in floating point: the grid's last
    sample (t_final) is still taken, from the last step (contract rule 4)."""
    p = SailParameters(model="rigid", n=11, intensity=0.0, tip_load=1e-9, tip_load_time_constant=1e-4)
    settings = RunSettings(t_final=1e-5, output_interval=1e-5 / 33200, stop_at_failure=False)
    result = exudyn_chain.run(p, settings, step_size=1e-5 / 33200)
    assert result.error is None
    np.testing.assert_allclose(result.time, settings.sample_times(), rtol=0, atol=1e-18)
