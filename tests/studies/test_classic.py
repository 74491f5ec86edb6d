"""Classic validations (studies.classic, paper Appendices A–B): both solvers against exact discrete-chain results.

The numbers asserted are the headline checks of the validations; the full tables come from validation/*.py.
"""

import math

import numpy as np
import pytest

from lightsail_mbs.analysis import linear_stability as lin
from lightsail_mbs.analysis.statics import static_state
from lightsail_mbs.model import chain_theory as ct
from lightsail_mbs.solvers import RunSettings, solve
from lightsail_mbs.studies import classic

SOLVERS = ("exudyn", "reduced")


# ---- cantilever -----------------------------------------------------------------------------
@pytest.mark.parametrize("solver", SOLVERS)
def test_cantilever_static_tip_equals_the_discrete_closed_form(solver):
    p = classic.cantilever_case(30)
    tip = static_state(p, solver).y[-1]
    exact = ct.cantilever_tip_deflection(p.tip_load, p.length, classic.bending_stiffness(p), p.n)
    assert tip == pytest.approx(exact, rel=1e-6)


def test_clamped_slice_stays_put_in_the_static_solution():
    p = classic.cantilever_case(12)
    for solver in SOLVERS:
        state = static_state(p, solver)
        assert abs(state.theta[0]) < 1e-15 and abs(state.y[0]) < 1e-15
        assert state.x[0] == pytest.approx(0.5 * p.slice_length, rel=1e-14)


def test_cantilever_static_converges_at_first_order_to_euler_bernoulli():
    """The Exudyn chain's error against P L³/(3EI) is the closed form's, −3/n + …: fitted order → 1."""
    ns = [50, 100, 200, 400]
    errors, predicted = [], []
    for n in ns:
        p = classic.cantilever_case(n)
        eb = p.tip_load * p.length**3 / (3 * classic.bending_stiffness(p))
        errors.append(static_state(p, "exudyn").y[-1] / eb - 1)
        predicted.append(float(ct.cantilever_relative_error(n)))
    assert np.allclose(errors, predicted, rtol=1e-5)
    assert classic.fitted_order(ns, errors) == pytest.approx(classic.fitted_order(ns, predicted), abs=1e-4)
    assert classic.fitted_order(ns, errors) == pytest.approx(1.0, abs=0.03)


def test_cantilever_short_dynamic_run_oscillates_at_the_chain_frequency():
    """Exudyn, n = 30, first 0.5 s of the paper's ramp: the free vibration left by the ramp is at the
    clamped chain's f₁ (to the generalized-α period elongation ≈ (ω₁h)²/12 ≈ 1e-3 at h = 1e-4 s)."""
    p = classic.cantilever_case(30)
    settings = classic.CANTILEVER_RUN.replace(t_final=0.5, output_interval=1e-4)
    run = solve(p, "exudyn", settings, step_size=1e-4, uncertainty=False)
    assert run.error is None
    assert np.max(np.abs(run.x[:, 0] - 0.5 * p.slice_length)) < 1e-14 and np.max(np.abs(run.theta[:, 0])) < 1e-14
    fit = classic.plateau(p, run.time, run.y[:, -1], start=0.2)
    f1 = ct.chain_angular_frequencies(p)[0] / (2 * math.pi)
    assert fit.frequency == pytest.approx(f1, rel=2e-3)
    assert fit.amplitude == pytest.approx(classic.error_budget(p, settings)["vibration"], rel=2e-3)


@pytest.mark.slow
def test_cantilever_plateau_error_matches_the_paper_and_its_budget():
    """n = 30, 2 s: the paper's Eq. 44 error at t = 2 s is the static chain's discretisation error plus the
    load deficit, ± the ramp's free vibration; it lands next to the paper's 1.84e-7 m."""
    p = classic.cantilever_case(30)
    settings = classic.CANTILEVER_RUN.replace(output_interval=1e-4)
    budget = classic.error_budget(p, settings)
    for solver, options in (("exudyn", dict(step_size=5e-5)), ("reduced", dict(method="Radau", rtol=1e-8))):
        run = solve(p, solver, settings, **options, uncertainty=False)
        assert run.error is None
        error = classic.paper_error(p, run.x[-1], run.y[-1])
        assert abs(error - budget["discretisation"] - budget["load_deficit"]) <= budget["vibration_bound"]
        assert error == pytest.approx(1.84e-7, rel=0.05)
        f1 = ct.chain_angular_frequencies(p)[0] / (2 * math.pi)
        fit = classic.plateau(p, run.time, run.y[:, -1])
        assert fit.frequency == pytest.approx(f1, rel=5e-4)
        assert fit.amplitude == pytest.approx(budget["vibration"], rel=2e-3)


def test_runs_of_the_appendices():
    """Appendix A: 2 s; Appendix B: 50 ms sampled every 10 µs; neither stops at a 'failure' (they have no
    defect to double). The load deficit of the budget is P₀e^(−t/τ) at the run's end."""
    assert classic.CANTILEVER_RUN == RunSettings(t_final=2.0, stop_at_failure=False)
    assert classic.STRING_RUN == RunSettings(t_final=0.05, output_interval=1e-5, stop_at_failure=False)
    assert not classic.FREE_RUN.stop_at_failure
    p = classic.cantilever_case(12)
    two, one = classic.error_budget(p), classic.error_budget(p, RunSettings(t_final=1.0))
    assert two["load_deficit"] / one["load_deficit"] == pytest.approx(math.exp(-1.0 / 0.3), rel=1e-12)
    assert two["vibration"] == one["vibration"] and two["discretisation"] == one["discretisation"]


# ---- string ---------------------------------------------------------------------------------
def test_g3_continuous_string_frequency():
    """Eq. 45 with μ = ρπd²/4 and T = 72.485 N: 195.28 Hz (not the 196 Hz the paper aims at)."""
    ref = classic.string_references(classic.g3_string_case(20))
    mu = 7800 * math.pi * 0.43e-3**2 / 4
    assert ref["continuous"] == pytest.approx(math.sqrt(72.485 / mu) / (2 * 0.6477), rel=1e-12)
    assert ref["continuous"] == pytest.approx(195.28, abs=0.01)


def test_g3_section_matches_the_wire():
    p = classic.g3_string_case(10)
    d = classic.WIRE_DIAMETER
    assert p.width * p.thickness == pytest.approx(math.pi * d**2 / 4, rel=1e-14)
    assert p.second_moment_of_area == pytest.approx(math.pi * d**4 / 64, rel=1e-14)


def test_discrete_string_converges_to_the_continuous_string():
    """Inextensible: second order, +(π/n)²/24. Extensible: to the stretched string, plus a first-order
    part ≈ (T/EA)/n from the last slice, which has no spring after it."""
    ns = [10, 20, 40, 80, 160]
    for springs, limit, orders, last in (
        (False, "continuous", (1.95, 2.05), 2e-5),
        (True, "continuous_stretched", (1.5, 1.95), 3e-5),
    ):
        errs = []
        for n in ns:
            ref = classic.string_references(classic.g3_string_case(n, axial_springs=springs))
            errs.append(ref["discrete"] / ref[limit] - 1)
        if not springs:
            assert errs[0] == pytest.approx((math.pi / 10) ** 2 / 24, rel=0.02)
        assert all(e > 0 for e in errs) and errs[-1] < last
        assert orders[0] < classic.fitted_order(ns, errs) < orders[1]


@pytest.mark.parametrize("solver", SOLVERS)
def test_string_fundamental_from_the_time_series(solver):
    """Plucked half sine, n = 10, pinned ends: the fitted fundamental is the exact discrete chain's
    to far inside the required 0.1 %, and the supports hold."""
    p = classic.g3_string_case(10)
    options = dict(step_size=1e-5) if solver == "exudyn" else dict(method="Radau", rtol=1e-8)
    run = solve(p, solver, classic.STRING_RUN.replace(t_final=0.03), **options, uncertainty=False)
    assert run.error is None
    fit = classic.string_fit(run)
    assert fit.frequency == pytest.approx(classic.string_references(p)["discrete"], rel=1e-4)
    b = 0.5 * p.slice_length
    left_x = run.x[:, 0] - b * np.cos(run.theta[:, 0])
    left_y = run.y[:, 0] - b * np.sin(run.theta[:, 0])
    right_y = run.y[:, -1] + b * np.sin(run.theta[:, -1])
    assert np.max(np.abs(left_x)) < 1e-12 and np.max(np.abs(left_y)) < 1e-12
    assert np.max(np.abs(right_y - right_y[0])) < 1e-10


# ---- linearised modes -----------------------------------------------------------------------
def test_free_free_chain_modes_match_euler_bernoulli_and_each_other():
    p = classic.free_beam_case(30)
    ex = lin.elastic(lin.angular_frequencies(p, "exudyn"), p)[:3]
    red = lin.elastic(lin.angular_frequencies(p, "reduced"), p)[:3]
    eb = classic.beam_references(p, 3)
    assert np.allclose(ex, eb, rtol=5e-3) and np.allclose(red, eb, rtol=5e-3)
    assert np.allclose(ex, red, rtol=1e-6, atol=0)
    assert np.allclose(red, ct.chain_angular_frequencies(p)[2:5], rtol=1e-8, atol=0)


@pytest.mark.parametrize("solver", SOLVERS)
def test_tensioned_pinned_chain_matches_the_closed_form(solver):
    """ω_k² = (6T/ml)(1 − cos(kπ/n))/(2 + cos(kπ/n)): first five modes to 1e-6."""
    p = classic.g3_string_case(30, axial_springs=False, defect_amplitude=0.0)
    closed_form = ct.pinned_chain_angular_frequencies(p)[:5]
    assert np.allclose(lin.angular_frequencies(p, solver)[:5], closed_form, rtol=1e-6, atol=0)


@pytest.mark.parametrize("solver", SOLVERS)
def test_extensible_tensioned_chain_matches_its_exact_spectrum(solver):
    p = classic.g3_string_case(12, defect_amplitude=0.0)
    assert np.allclose(lin.angular_frequencies(p, solver)[:5], ct.chain_angular_frequencies(p)[:5], rtol=1e-6, atol=0)


@pytest.mark.parametrize("solver", SOLVERS)
def test_clamped_chain_modes(solver):
    p = classic.cantilever_case(15)
    assert np.allclose(lin.angular_frequencies(p, solver)[:3], ct.chain_angular_frequencies(p)[:3], rtol=1e-6, atol=0)
