"""The Doppler term (model/terms/doppler.py) against physics: the factor every kernel applies is the closed-form
trajectory's (1 − β)/(1 + β) at the run's proper time; it scales exactly the beam's loads; with β held constant
a run is the run at the intensity I₀ D(β₀); and both solvers agree on Doppler-shifted chains run to failure,
the paper's soft torsion sail at a high intensity and the journey's heated, tension-relieved snapshot case."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters, paper_case, solve
from lightsail_mbs.base.constants import SPEED_OF_LIGHT as C
from lightsail_mbs.model import relativity, sheet, terms
from lightsail_mbs.model.terms import doppler
from lightsail_mbs.solvers.exudyn.tree import ChainLayout, generalized_force
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.solvers.reduced.kinematics import ChainModel

rng = np.random.default_rng(25)
TIMES = (0.0, 0.37, 2.0, 1e3, 1e6)  # s of the run (proper time)
CASES = {
    "mirror": SailParameters(model="rigid", n=8, intensity=1e9, initial_beta=0.1),
    "gaussian-partial": SailParameters(
        model="rigid", n=9, intensity=3e10, beam_waist=0.5, reflectivity=0.6, absorptivity=0.3, initial_beta=0.3
    ),
    "payload": SailParameters(
        model="rigid", n=12, intensity=1e9, payload_mass=2e-4, payload_stem=0.2, initial_beta=0.2
    ),
}


def closed_form_factor(p, time):
    """(1 − β)/(1 + β) at the proper time τ₀ + τ of the constant-power trajectory of the case's craft (sail and
    payload, intercepting P = Ī L W), τ₀ its proper time at β₀."""
    craft = p.density * p.thickness * p.length * p.width + p.payload_mass
    trajectory = relativity.Trajectory(p.mean_intensity * p.length * p.width, craft, p.normal_momentum)
    start = trajectory.proper_time(p.initial_beta)
    return relativity.intensity_factor(trajectory.beta_at_proper_time(start + time))


@pytest.mark.parametrize("name", CASES)
def test_the_factor_each_kernel_applies_is_the_trajectorys(name):
    """D(τ) of the term's block, and the ratio of each solver's loads at τ to the same case's at rest (β₀ = 0,
    τ = 0): the reduced right-hand side's accelerations of a rigid chain at rest (q̈ = M⁻¹Q, linear in the
    loads, the payload's own frame force included) and the Exudyn tree's generalized forces."""
    p = CASES[name]
    still = p.replace(initial_beta=0.0)
    model, layout = ChainModel.from_params(p), ChainLayout.of(p)
    q = np.concatenate([[0.1, -0.2], rng.uniform(-0.3, 0.3, p.n)])
    y = np.concatenate([q, np.zeros(q.size)])
    at_rest = ChainDynamics(ChainModel.from_params(still)).rhs(0.0, y)[q.size :]
    q_tree = np.zeros(layout.size)
    q_tree[:2] = q[:2]
    q_tree[layout.angle_index] = np.diff(q[2:], prepend=0.0)  # θ₁, then the relative angles
    tree_rest = generalized_force(still, layout)(q_tree).copy()
    for time in TIMES:
        expected = closed_form_factor(p, time)
        assert doppler.factor(doppler.constants(p, "chain"), time) == pytest.approx(expected, rel=1e-12, abs=0)
        reduced = ChainDynamics(model).rhs(time, y)[q.size :]
        np.testing.assert_allclose(reduced, expected * at_rest, rtol=1e-12, atol=1e-12 * np.abs(at_rest).max())
        tree = generalized_force(p, layout)(q_tree, None, time)
        np.testing.assert_allclose(tree, expected * tree_rest, rtol=1e-12, atol=1e-12 * np.abs(tree_rest).max())
    assert closed_form_factor(p, 0.0) == pytest.approx((1 - p.initial_beta) / (1 + p.initial_beta), rel=1e-15)


def test_the_factor_is_the_integrated_trajectorys():
    """β(τ) of the closed form against d(γβ)/dτ·c = g₀ D γ (proper acceleration g₀ D, dt = γ dτ) integrated."""
    from scipy.integrate import solve_ivp

    trajectory = relativity.Trajectory(1e9, 1e-3, 2.0)
    g0 = C / trajectory.time_constant
    tau = np.linspace(0.0, 3 * trajectory.time_constant, 7)

    def rate(_, u):
        beta = u / np.sqrt(1 + u * u)
        return g0 / C * relativity.intensity_factor(beta) * np.sqrt(1 + u * u)

    u = solve_ivp(rate, (0, tau[-1]), [0.0], t_eval=tau, rtol=1e-12, atol=1e-14, method="DOP853").y[0]
    np.testing.assert_allclose(trajectory.beta_at_proper_time(tau), relativity.speed_from_u(u), rtol=1e-9, atol=0)


def test_the_term_scales_the_beams_loads_and_nothing_else():
    """With the velocity term, a body force (chain) or a dead pressure (sheet) active: the sum at τ is D(τ) times
    the beam's terms at rest plus the loads of other origin unscaled."""
    time = 0.8
    chain = SailParameters(n=7, intensity=1e9, velocity_terms=True, body_force=0.4, initial_beta=0.25)
    x, theta, vx, vy = np.sort(rng.uniform(0, 1, 7)), *rng.uniform(-0.3, 0.3, (3, 7))
    factor = doppler.factor(doppler.constants(chain, "chain"), time)
    beam = terms.chain_forces(chain.replace(initial_beta=0.0, body_force=0.0), x, theta, None, vx, vy)
    got = terms.chain_forces(chain, x, theta, None, vx, vy, time=time)
    np.testing.assert_allclose(got[0], factor * beam[0] + chain.slice_mass * 0.4, rtol=1e-13)
    np.testing.assert_allclose(got[1], factor * beam[1], rtol=1e-13)
    plate = SailParameters(model="sheet", n=3, ny=2, intensity=1e9, pressure=0.3, initial_beta=0.25)
    centres = sheet.flat_centres(plate) + rng.normal(0, 0.01, (6, 3))
    normals = rng.normal(0, 0.1, (6, 3)) + [0, 0, 1]
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    factor = doppler.factor(doppler.constants(plate, "sheet"), time)
    beam = terms.tile_forces(plate.replace(initial_beta=0.0, pressure=0.0), centres, normals)
    pressure = terms.tile_forces(plate.replace(intensity=0.0, initial_beta=0.0), centres, normals)
    np.testing.assert_allclose(
        terms.tile_forces(plate, centres, normals, time=time), factor * beam + pressure, rtol=1e-13
    )


def test_initial_beta_is_checked():
    for bad in (-0.1, 1.0, math.nan, math.inf):
        with pytest.raises(ParameterError, match="initial_beta"):
            SailParameters(initial_beta=bad)
    with pytest.raises(
        ParameterError, match=r"initial_beta=0.1 is invalid: allowed 0.0 with an optical table \(.*wavelength"
    ):
        SailParameters(n=8, optics="mirror", initial_beta=0.1)
    with pytest.raises(ParameterError, match=r"reflectivity=0.9 is invalid: allowed 1.0 with an optical table"):
        SailParameters(n=8, optics="mirror", reflectivity=0.9)
    with pytest.raises(ParameterError, match=r"velocity_terms=True is invalid: allowed off with an optical table"):
        SailParameters(n=8, optics="mirror", velocity_terms=True)
    with pytest.raises(ParameterError, match="--wavelengths"):
        SailParameters(n=8, optics="mirror", initial_beta=0.1)  # the message says what to do instead
    assert SailParameters().to_dict().get("initial_beta", 0.0) == 0.0


# ---- runs to failure --------------------------------------------------------------------------------------------
HOT = 1e5  # the soft torsion sail at 1e5 × the paper's intensity: I₀ = 1e13 W/m², g₀ = 6.7e7 m/s²
BETA = 0.1


def soft_at_high_intensity():
    """The paper's soft torsion sail at I₀ = 1e13 W/m² (lab) from β₀ = 0.1, and its run time (the paper's 6 s
    scaled by the growth time ∝ 1/√I₀; samples every 20 µs, given: the default follows g₀): over its failure
    time of 7.35 ms, g₀ t/c = 1.6e-3, so the sail-frame intensity falls by 2 D₀ g₀ t/c = 0.27 %."""
    p = paper_case("torsion-soft")
    p = p.replace(intensity=p.intensity * HOT, initial_beta=BETA)
    return p, RunSettings(t_final=6.0 / math.sqrt(HOT), output_interval=2e-5)


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_with_beta_held_constant_a_run_is_the_run_at_the_dimmed_intensity(solver, monkeypatch):
    """The trajectory's rate r set to 0 in the term's block (a test-only limit: β stays β₀): the run fails when
    the run at I₀ D(β₀) does, to 1e-9 (reduced) and 2e-9 (Exudyn). The two loads differ in their last bits
    (F + (D₀ − 1)F against F at I₀ D₀), and Exudyn's failure time moves by 4e-10 when the intensity moves by
    one ulp (measured): its generalized-α runs at a Newton tolerance 1e-6 of its default, where the
    difference is 1.3e-9 (4e-8 at the default). Exudyn's defaults follow the case's g₀ (step ∝ √(L/g₀),
    tolerances ∝ f₀), the lab's here: both runs get the dimmed case's step and tolerances."""
    from lightsail_mbs.solvers.exudyn.chain import default_abs_tol, default_step_size

    p, settings = soft_at_high_intensity()
    start = float(relativity.intensity_factor(p.initial_beta))
    dimmed = p.replace(intensity=p.intensity * start, initial_beta=0.0)
    options, tolerance = {}, 1e-9
    if solver == "exudyn":
        step = default_step_size(dimmed, settings)
        options = {"step_size": step, "newton_abs_tol": 1e-6 * default_abs_tol(dimmed), "newton_rel_tol": 1e-14}
        tolerance = 2e-9
    expected = solve(dimmed, solver, settings, uncertainty=False, **options)
    monkeypatch.setattr(doppler, "constants", lambda case, family: np.array([start, 0.0]))
    held = solve(p, solver, settings, uncertainty=False, **options)
    assert held.failure_time == pytest.approx(expected.failure_time, rel=tolerance)


def test_both_sheet_solvers_give_the_same_doppler_delay():
    """A soft 4 × 4 sheet at 1e13 W/m² from β₀ = 0.1 (g₀ t_f/c = 1.2e-3): the Doppler term delays its failure
    (by 3.4e-4 of t_f) against the constant intensity of the start, and both sheet solvers give the failure
    time to 1e-6 and the delay to 1e-3 of itself."""
    from lightsail_mbs.model.theory import at_start

    p = SailParameters(model="sheet", n=4, ny=4, youngs_modulus=4.5e9, intensity=1e13, initial_beta=BETA)
    settings = RunSettings(t_final=6.0 / math.sqrt(HOT), output_interval=2e-5)
    times = {}
    for solver in ("reduced", "exudyn"):
        runs = [solve(case, solver, settings, uncertainty=False) for case in (p, at_start(p))]
        times[solver] = [run.failure_time for run in runs]
    shifts = {solver: (t[0] - t[1]) / t[1] for solver, t in times.items()}
    assert times["exudyn"][0] == pytest.approx(times["reduced"][0], rel=1e-6)
    assert shifts["reduced"] > 1e-4
    assert shifts["exudyn"] == pytest.approx(shifts["reduced"], rel=1e-3)


def test_simulate_takes_initial_beta(tmp_path, capsys):
    """`lightsail-mbs simulate --initial-beta` runs the Doppler term: the saved case holds β₀, and the soft sail
    at 1e13 W/m² fails when the library's run of that case does."""
    from lightsail_mbs import Result
    from lightsail_mbs.cli import main

    p, settings = soft_at_high_intensity()
    args = ["simulate", "--model", "torsion", "--youngs-modulus", "4.5e9", "--intensity", "1e13"]
    args += ["--initial-beta", str(BETA), "--t-final", str(settings.t_final), "--output-interval", "2e-5"]
    assert main([*args, "--solver", "reduced", "--quiet", "--out", str(tmp_path / "run")]) == 0
    saved = Result.load(tmp_path / "run.npz")
    assert saved.params.initial_beta == BETA
    expected = solve(p, "reduced", settings).failure_time
    assert saved.failure_time == pytest.approx(expected, rel=1e-12)
