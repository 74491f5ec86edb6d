"""The uncertainty and conditioning of a run (solvers.uncertainty): both solvers agree where the question is
well posed, flag it where it is not, and the error bar covers the run's own discretisation error in time. The
solver template's runs (lightsail_mbs.solvers.solve): the n-error that lightsail_mbs.solve adds is
tests/analysis/test_n_error.py's."""

import math

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, paper_case
from lightsail_mbs.model import theory
from lightsail_mbs.result import Result, with_uncertainty
from lightsail_mbs.solvers import film_twin, solve, twin_options, uncertainty

exudyn = pytest.importorskip("exudyn")

RUN = RunSettings(t_final=3.0)


def thin_bright(**changes) -> SailParameters:
    """Beyond the paper: torsion n = 50, h = 0.5 µm, ρ = 1400 kg/m³, I₀ = 0.3 GW/m², a₀ = 5 µm, ν = 5/2,
    E = 0.01 E_cr,max (before the net-force load the solvers disagreed by 1.2 % here)."""
    base = dict(
        model="torsion", n=50, thickness=0.5e-6, density=1400.0, intensity=3e8, defect_amplitude=5e-6, defect_mode=2.5
    )
    modulus = 0.01 * theory.critical_modulus_max(SailParameters(**base))
    return SailParameters(**{**base, "youngs_modulus": modulus, **changes})


def test_solvers_agree_on_a_well_conditioned_case_beyond_the_paper():
    p = thin_bright()
    runs = [solve(p, solver, RUN) for solver in ("exudyn", "reduced")]
    for r in runs:
        assert r.failed and r.well_conditioned is True
        assert 0 < r.failure_time_uncertainty < 1e-4 * r.failure_time
    a, b = (r.failure_time for r in runs)
    assert abs(a - b) <= 1e-3 * b
    assert abs(a - b) <= sum(r.failure_time_uncertainty for r in runs)


@pytest.mark.parametrize("solver", ["exudyn", "reduced"])
def test_ill_conditioned_case_is_flagged_and_says_why(solver):
    """ν = 3/2 at E = 0.0036 E_cr,max: a roughness of 1e-12 a₀ moves the failure time by percent."""
    p = thin_bright(defect_mode=1.5)
    r = solve(p, solver, RUN)
    assert r.failed and r.well_conditioned is False
    assert r.uncertainty["sensitivity"] > 1e-4 * r.failure_time
    assert r.failure_time_uncertainty >= 2 * r.uncertainty["sensitivity"]
    explanation = r.uncertainty["explanation"]
    assert explanation.startswith("ill-conditioned") and "roughness" in explanation and "n" in explanation
    assert "(ill-conditioned)" in r.answer_text()


@pytest.mark.parametrize(
    "case, kind, t_final",
    [("torsion-soft", "failure_time", 2.5), ("tnt-stable", "max_amplitude_ratio", 1.0)],
)
def test_uncertainty_covers_the_difference_to_a_sixteenth_step(case, kind, t_final):
    """Generalized-α asked for a step h reports its run at h, its error bar from the loose twin at 2h; the answer
    at a sixteenth of that step, h/16, lies within the reported uncertainty."""
    p = paper_case(case, n=20)
    settings = RunSettings(t_final=t_final)
    h = 2e-3
    reported = solve(p, "exudyn", settings, step_size=h)
    fine = solve(p, "exudyn", settings, step_size=h / 16, uncertainty=False)
    u = reported.uncertainty
    assert u["quantity"] == kind and u["reported"] == "base" and u["reference"] == "loose"
    steps = {"base": h, "loose": 2 * h, "probe": h, "film": 2 * h}  # the probe where the film twin does not stand in
    ran = [name for name in steps if name in u]
    assert [u[name]["options"]["step_size"] for name in ran] == pytest.approx([steps[name] for name in ran])
    assert reported.info["step_size"] == pytest.approx(h)
    value = reported.failure_time if kind == "failure_time" else reported.max_amplitude_ratio
    fine_value = fine.failure_time if kind == "failure_time" else fine.max_amplitude_ratio
    assert value == u["value"] == u["base"]["value"]
    assert abs(fine_value - value) <= u["uncertainty"]
    assert abs(fine_value - value) > 0  # a real difference, not an exact repeat


def test_reported_answer_is_the_base_run():
    """With the estimate on, the answer is the one a sweep (the base run alone) gets: the same run."""
    p, settings = paper_case("torsion-soft", n=10), RunSettings(t_final=3.0)
    alone = solve(p, "reduced", settings, uncertainty=False)
    reported = solve(p, "reduced", settings)
    assert reported.failure_time == alone.failure_time
    assert np.array_equal(reported.amplitude, alone.amplitude)
    u = reported.uncertainty
    assert u["loose"]["options"]["rtol"] == pytest.approx(twin_options.loosening(alone.info) * alone.info["rtol"])
    assert u["cpu_time"] >= u["base"]["cpu_time"] > 0


def test_estimate_is_saved_and_loaded(tmp_path):
    r = solve(paper_case("torsion-soft", n=10), "reduced", RunSettings(t_final=3.0))
    summary = r.summary()
    assert summary["failure_time_uncertainty"] == r.failure_time_uncertainty > 0
    assert summary["well_conditioned"] is r.well_conditioned
    back = Result.load(r.save(tmp_path / "run"))
    assert back.uncertainty == r.uncertainty
    assert back.failure_time_uncertainty == r.failure_time_uncertainty
    assert back.answer_text() == r.answer_text()


def test_opting_out_says_so():
    r = solve(paper_case("torsion-soft", n=10), "reduced", RunSettings(t_final=0.1), uncertainty=False)
    assert r.uncertainty is None and r.well_conditioned is None and r.failure_time_uncertainty is None
    assert r.summary()["uncertainty"] is None


def test_not_estimated_for_a_flat_sail():
    r = solve(paper_case("torsion-stable", n=6, defect_amplitude=0.0), "reduced", RunSettings(t_final=0.01))
    assert r.uncertainty["estimated"] is False and "flat" in r.uncertainty["explanation"]


def test_loose_twin_options():
    assert twin_options.loosened({}, {"rtol": 1e-7}) == {"rtol": pytest.approx(1e-6)}
    assert twin_options.loosened({}, {"rtol": 1e-8, "method": "DOP853"}) == {"rtol": pytest.approx(3e-8)}
    loose = twin_options.loosened({"step_size": 1e-3}, {"rtol": 1e-7, "method": "generalized-alpha"})
    assert loose["step_size"] == pytest.approx(2e-3) and loose["rtol"] == pytest.approx(4e-7)
    # a fixed-step solver without an rtol (Exudyn's sheet): the step × 2, its Newton tolerances × 4
    info = {"method": "generalized-alpha", "step_size": 1e-3, "newton_rel_tol": 1e-8, "newton_abs_tol": 1e-12}
    assert twin_options.loosened({}, info) == {
        "step_size": pytest.approx(2e-3),
        "newton_rel_tol": pytest.approx(4e-8),
        "newton_abs_tol": pytest.approx(4e-12),
    }


def test_tight_twin_options():
    info = {"rtol": 1e-7}
    assert twin_options.tightened({}, info) == {"rtol": 1e-8}
    tight = twin_options.tightened({"step_size": 1e-3, "atol": 1e-9}, info)
    assert tight["step_size"] == pytest.approx(1e-3 / math.sqrt(10)) and tight["atol"] == pytest.approx(1e-10)
    quarter = twin_options.tightened({"step_size": 1e-3}, {"rtol": 1e-7, "method": "generalized-alpha"})
    assert quarter["step_size"] == pytest.approx(2.5e-4) and quarter["rtol"] == pytest.approx(1e-7 / 16)
    assert twin_options.tightened({}, {"rtol": 1e-8, "method": "DOP853"})["rtol"] == pytest.approx(1e-10)


def test_twin_sequences():
    assert twin_options.sequence({"method": "generalized-alpha", "rtol": 1e-7}) == [("half", 4.0), ("tight", 16.0)]
    assert twin_options.sequence({"method": "DOP853", "rtol": 1e-8}) == [("tight", 100.0)]
    assert twin_options.sequence({"method": "Radau", "rtol": 1e-6}) == [("tight", 10.0)]
    # a fixed-step solver without an rtol (Exudyn's sheet): the twin's step is the base run's / √F
    info = {"method": "generalized-alpha", "step_size": 1e-3, "newton_rel_tol": 1e-8, "newton_abs_tol": 1e-12}
    half = twin_options.tightened({}, info, 4.0)
    assert half == {"step_size": pytest.approx(5e-4), "newton_rel_tol": 2.5e-9, "newton_abs_tol": 2.5e-13}
    # a Newton tolerance stops at the floor the base run reports (Exudyn's sheet: its connectors' round-off)
    floored = {**info, "newton_abs_tol_floor": 5e-13}
    assert twin_options.tightened({}, floored, 4.0)["newton_abs_tol"] == 5e-13
    assert twin_options.tightened({}, floored, 16.0)["step_size"] == pytest.approx(2.5e-4)
    assert twin_options.held_at_floor(twin_options.tightened({}, floored, 4.0), floored) == ["newton_abs_tol"]
    assert twin_options.tightened({"newton_abs_tol": 1e-12}, floored, 16.0)["newton_abs_tol"] == 5e-13
    assert twin_options.held_at_floor(half, info) == []


class FakeSolver:
    """A solver whose failure time is a given function of its step (None: the step fails): the rule's bookkeeping
    in isolation."""

    def __init__(self, failure_time, film_shift=0.1):
        self.failure_time, self.film_shift = failure_time, film_shift  # a film moves t_f by film_shift

    def run(self, params, settings, progress=False, step_size=1e-3, perturbation=0.0):
        from types import SimpleNamespace

        t_f = self.failure_time(step_size)
        info = {"method": "generalized-alpha", "step_size": step_size}
        error = None if t_f is not None else "Newton did not converge"
        t_f = (t_f or 1.0) + (1e-9 if perturbation else 0.0) + (self.film_shift if params.film_rms else 0.0)
        time, amplitude = np.array([0.0, 0.5 * t_f, t_f]), np.array([1.0, 1.5, 2.0])  # a line: located exactly
        return SimpleNamespace(
            error=error,
            time=time,
            amplitude=amplitude,
            failed=True,
            failure_time=t_f,
            info=info,
            wall_time=1.0,
            uncertainty=None,
            warnings=[],
        )


def nearest(answers):
    return lambda h: answers[min(answers, key=lambda k: abs(k - h))]


def test_reported_run_is_the_base_and_its_error_bar_the_change_to_the_loose_twin():
    """Answers at h and 2h: E_int is their difference, S the probe's change against the base run (both at h)."""
    solver = FakeSolver(nearest({1e-3: 1.0, 2e-3: 1.0 + 3e-6}))
    p = paper_case("torsion-soft", n=10)
    base = solver.run(p, RUN)
    reported = uncertainty.assess(solver, p, RUN, {}, base)
    u = reported.uncertainty
    assert reported is base and u["reported"] == "base" and u["reference"] == "loose"
    assert u["integration_error"] == pytest.approx(3e-6)
    assert u["sensitivity"] == pytest.approx(1e-9)
    assert u["uncertainty"] == pytest.approx(2 * (3e-6 + 1e-9))
    assert u["film_sensitivity"]["shift"] == pytest.approx(0.1) and u["sensitivity_from"] == "probe"
    assert reported.wall_time == pytest.approx(4.0)  # base, the loose twin, the film twin and the probe


def test_a_film_that_does_not_move_the_answer_stands_for_the_probe():
    """The film moves t_f by 1e-6 (defect-dominated): the probe is not run, and S is the film's change times c, the
    probe's largest amplitude over the film's mode by mode, which is far below 1 (a probe of 1e-12 a₀ against 1 nm)."""
    solver = FakeSolver(nearest({1e-3: 1.0, 2e-3: 1.0 + 3e-6}), film_shift=1e-6)
    p = paper_case("torsion-soft", n=10)
    reported = uncertainty.assess(solver, p, RUN, {}, solver.run(p, RUN))
    u = reported.uncertainty
    c = film_twin.probe_ratio(p, uncertainty.PROBE_LEVEL * p.displacement_scale)
    assert "probe" not in u and u["sensitivity_from"] == "film" and u["well_conditioned"]
    assert u["sensitivity"] == pytest.approx(c * 1e-6, rel=1e-6) and 0 < c < 1e-4
    assert u["uncertainty"] == pytest.approx(2 * (3e-6 + c * 1e-6))
    assert "from the film twin's change" in u["explanation"]
    assert reported.wall_time == pytest.approx(3.0)  # base, the loose twin and the film twin


def test_a_base_run_the_loose_twin_finds_inaccurate_is_tightened():
    """The loose twin at 2h lies 5e-3 from the base run (more than ACCURACY): the twin at h/2 runs and is reported,
    E_int the sum of the two differences; the probe runs at the base run's step, the film twin at the loose one."""
    solver = FakeSolver(nearest({1e-3: 1.0, 2e-3: 1.0 + 5e-3, 5e-4: 1.0 - 1e-4}))
    p = paper_case("torsion-soft", n=10)
    base = solver.run(p, RUN)
    reported = uncertainty.assess(solver, p, RUN, {}, base)
    u = reported.uncertainty
    assert u["reported"] == "half" and u["reference"] == "loose" and reported.failure_time == pytest.approx(1 - 1e-4)
    assert u["integration_error"] == pytest.approx(5e-3 + 1e-4)
    assert "step_size" not in u["probe"]["options"] and u["sensitivity"] == pytest.approx(1e-9)  # the base run's
    assert u["film"]["options"]["step_size"] == pytest.approx(2e-3)
    assert reported.wall_time == pytest.approx(5.0)  # base, loose, h/2, the film twin and the probe


def test_a_loose_twin_that_fails_falls_back_to_the_tightened_sequence():
    """The loose twin's step is too large (a solver error): the twins at h/2 and h/4 are run instead, E_int is
    the sum of the sequence's two differences, whatever their order, and the tightest run is reported."""
    answers = {1e-3: 1.0, 5e-4: 1.0 - 2e-6, 2.5e-4: 1.0 + 5e-6, 2e-3: None}
    solver = FakeSolver(nearest(answers))
    p = paper_case("torsion-soft", n=10)
    base = solver.run(p, RUN)
    reported = uncertainty.assess(solver, p, RUN, {}, base)
    u = reported.uncertainty
    assert reported is not base and reported.failure_time == pytest.approx(1.0 + 5e-6)
    assert u["reported"] == "tight" and u["reference"] == "base" and u["loose"]["error"]
    assert u["integration_error"] == pytest.approx(2e-6 + 7e-6)
    assert u["sensitivity"] == pytest.approx(1e-9)
    assert u["uncertainty"] == pytest.approx(2 * (9e-6 + 1e-9))
    assert reported.wall_time == pytest.approx(6.0)  # base, loose, h/2, h/4, the film twin and the probe


@pytest.mark.parametrize(
    "value, u, text",
    [
        (2.111215, 3e-6, "2.111215 ± 0.000003"),
        (2.111215, 1.3e-3, "2.1112 ± 0.0013"),
        (2.111215, 9e-4, "2.1112 ± 0.0009"),
        (1.473, 0.06, "1.47 ± 0.06"),
        (123.4, 56.0, "120 ± 60"),
        (1.2, math.inf, "1.2 ± inf"),
        (1.2, None, "1.2"),
    ],
)
def test_value_with_uncertainty_text(value, u, text):
    assert with_uncertainty(value, u) == text


def test_exudyn_sheet_estimate_falls_back_to_refining_its_step():
    """Exudyn's sheet has no rtol and caps its step at the output interval: its loose twin runs at the base
    run's step (the same answer), so the estimate falls back to the twins at h/2 and h/4."""
    from lightsail_mbs.solvers.exudyn.sheet import default_step_size

    p = SailParameters(model="sheet", n=4, ny=3, youngs_modulus=4.5e9)
    settings = RunSettings(t_final=0.3)
    reported = solve(p, "exudyn", settings)
    u = reported.uncertainty
    h = default_step_size(p, settings)
    assert u["loose"]["value"] == u["base"]["value"] and u["reference"] == "base"
    assert u["half"]["options"]["step_size"] == pytest.approx(h / 2)
    assert reported.info["step_size"] == pytest.approx(h / 4) and u["reported"] == "tight"
    assert u["integration_error"] > 0 and u["uncertainty"] >= 2 * u["integration_error"]
    # at the physical membrane the base run's Newton tolerance is the connectors' round-off floor already:
    # the twins keep it (below it Newton does not converge) and the explanation says so
    floor = reported.info["newton_abs_tol_floor"]
    assert u["base"]["options"] == {} and reported.info["newton_abs_tol"] == floor
    assert u["held_at_floor"] == ["newton_abs_tol"] and "round-off floor" in u["explanation"]


def test_generalized_alpha_loose_twin_loosens_the_newton_solve_as_f_squared():
    """The loose twin (rtol × 4: the step × 2) solves its steps to Newton tolerances × 16."""
    from lightsail_mbs.solvers.exudyn import chain

    p = paper_case("tnt-stable", n=10)
    settings = RunSettings(t_final=0.2)
    reported = solve(p, "exudyn", settings)
    loose = reported.uncertainty["loose"]["options"]
    assert reported.uncertainty["reported"] == "base" and loose == {"rtol": pytest.approx(4 * chain.DEFAULT_RTOL)}
    twin = solve(p, "exudyn", settings, uncertainty=False, **loose)
    assert twin.info["newton_rel_tol"] == pytest.approx(chain.NEWTON_REL_TOL * 16)
    assert twin.info["newton_abs_tol"] == pytest.approx(chain.default_abs_tol(p) * 16)


@pytest.mark.slow
def test_extensible_survivor_whose_error_the_newton_tolerance_sets():
    """A seeded extensible membrane (validation/accuracy.md, case 50): at Exudyn's default tolerances its
    answer is 1.2e-5 off, flat over the steps h, h/2, h/4 while the Newton tolerances only follow rtol; with
    them ∝ rtol² the loose twin (rtol × 4: Newton × 16) moves by more than that, and the error bar covers it."""
    p = SailParameters(
        model="tnt",
        n=41,
        thickness=1.971448458051086e-07,
        density=2990.084748249741,
        youngs_modulus=183632441599.29428,
        tension=5.934949691801659e-06,
        intensity=18019557.154378325,
        defect_amplitude=7.591858284061386e-06,
        defect_mode=2.5,
        axial_springs=True,
    )
    settings = RunSettings(t_final=6.471781218517266, output_interval=0.016179453046293164)
    reference = solve(p, "reduced", settings, rtol=1e-11, uncertainty=False).max_amplitude_ratio
    reported = solve(p, "exudyn", settings)
    base = reported.uncertainty["base"]["value"]
    assert abs(base - reference) > 1e-5 * reference  # the default tolerances' error this test is about
    assert reported.max_amplitude_ratio == base
    assert abs(reported.max_amplitude_ratio - reference) <= reported.max_amplitude_ratio_uncertainty


def test_a_sail_that_never_exceeds_its_initial_amplitude_says_so():
    """A 6 × 6 doubly sinusoidal sheet (E = 4.5e11 Pa, E_m = 4.5e9 Pa) whose amplitude only falls over
    0.2 s: its largest ratio is the initial 1 in every twin, printed as such rather than '1 ± 0'."""
    p = SailParameters(model="sheet", n=6, ny=6, defect_mode_y=1.5, youngs_modulus=4.5e11, membrane_modulus=4.5e9)
    r = solve(p, "reduced", RunSettings(t_final=0.2))
    assert not r.failed and r.max_amplitude_ratio == 1.0 and r.max_amplitude_ratio_uncertainty == 0.0
    assert "never exceeded its initial value" in r.answer_text() and "±" not in r.answer_text()
