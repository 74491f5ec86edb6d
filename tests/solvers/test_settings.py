"""Run control (RunSettings): validation, the sample grid, the paper's runs, and solve()'s use of it."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from lightsail_mbs import ParameterError, RunSettings, SailParameters, paper_settings, solve
from tests.strategies import BAD_VALUES, EXAMPLES, check_property, log_uniform


@pytest.mark.parametrize(
    "field, value, words",
    [
        ("t_final", 0.0, "t_final"),
        ("t_final", -1.0, "> 0"),
        ("t_final", float("nan"), "finite"),
        ("failure_ratio", 1.0, "> 1"),
        ("failure_ratio", float("inf"), "failure_ratio"),
        ("output_interval", 10.0, "output_interval"),
        ("output_interval", 0.0, "output_interval ≤ t_final"),
        ("stop_at_failure", 1, "stop_at_failure"),
    ],
)
def test_bad_value_names_the_field_and_range(field, value, words):
    with pytest.raises(ParameterError) as err:
        RunSettings(**{field: value})
    assert field in str(err.value) and words in str(err.value)


def test_defaults_and_replace_validates_again():
    s = RunSettings()
    assert (s.t_final, s.output_interval, s.stop_at_failure, s.failure_ratio) == (6.0, None, True, 2.0)
    assert s.replace(t_final=0.5).t_final == 0.5 and s.t_final == 6.0
    with pytest.raises(ParameterError, match="output_interval"):
        s.replace(t_final=0.5, output_interval=1.0)


def test_sample_interval_default():
    assert RunSettings(t_final=6.0).sample_interval == pytest.approx(1e-3)
    assert RunSettings(t_final=0.01).sample_interval == pytest.approx(1e-5)
    assert RunSettings(t_final=0.01, output_interval=2e-3).sample_interval == 2e-3


def test_sample_times_include_zero_and_t_final():
    np.testing.assert_allclose(
        RunSettings(t_final=0.05, output_interval=0.01).sample_times(), np.arange(6) * 0.01, rtol=0, atol=1e-15
    )
    uneven = RunSettings(t_final=0.025, output_interval=0.01).sample_times()  # Δt does not divide t_final
    np.testing.assert_allclose(uneven, [0.0, 0.01, 0.02, 0.025], rtol=0, atol=1e-15)
    default = RunSettings().sample_times()
    assert default.size == 6001 and default[0] == 0.0 and default[-1] == pytest.approx(6.0, rel=1e-14)


def test_dict_round_trip_and_unknown_key():
    s = RunSettings(t_final=0.2, output_interval=1e-3, stop_at_failure=False, failure_ratio=3.0)
    assert RunSettings.from_dict(s.to_dict()) == s
    with pytest.raises(ParameterError, match="amplitude"):
        RunSettings.from_dict({"t_final": 1.0, "amplitude": 1e-5})


def test_paper_settings_of_the_named_cases():
    assert paper_settings("rigid") == RunSettings(t_final=0.01)
    for name in ("torsion-stable", "torsion-soft", "tnt-stable", "tnt-soft"):
        assert paper_settings(name) == RunSettings(t_final=6.0)
    assert paper_settings("rigid", stop_at_failure=False).stop_at_failure is False
    with pytest.raises(ParameterError, match="case"):
        paper_settings("nope")


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_solve_runs_with_the_settings_and_keeps_them(solver):
    settings = RunSettings(t_final=0.02, output_interval=5e-3, failure_ratio=3.0)
    r = solve(SailParameters(n=4), solver, settings, uncertainty=False)
    assert r.settings == settings
    np.testing.assert_allclose(r.time, settings.sample_times(), rtol=0, atol=1e-12)


def test_solve_defaults_to_the_default_settings():
    r = solve(SailParameters(n=4), "reduced", uncertainty=False)
    assert r.settings == RunSettings() and r.time[-1] == pytest.approx(6.0)


def test_solve_rejects_what_is_not_a_run_settings():
    with pytest.raises(ParameterError, match="settings"):
        solve(SailParameters(n=4), "reduced", {"t_final": 0.01}, uncertainty=False)
    with pytest.raises(ParameterError, match="solver"):
        solve(SailParameters(n=4), "euler", RunSettings(t_final=0.01), uncertainty=False)


@st.composite
def any_settings_kwargs(draw) -> dict:
    t_final = draw(log_uniform(-6, 5))
    kwargs = dict(
        t_final=t_final,
        output_interval=draw(st.one_of(st.none(), st.floats(1e-9, 1.0).map(lambda f: f * t_final))),
        stop_at_failure=draw(st.booleans()),
        failure_ratio=draw(st.floats(1.0, 100.0)),
    )
    for name in draw(st.lists(st.sampled_from(sorted(kwargs)), max_size=2, unique=True)):
        kwargs[name] = draw(BAD_VALUES)
    return kwargs


@pytest.mark.parametrize("examples", EXAMPLES)
def test_any_run_settings_are_accepted_or_refused_naming_a_field(examples):
    """Property: RunSettings accepts a value set (and then its sample grid is finite, increasing, from 0
    to t_final, at most MAX_SAMPLES + 1 long) or raises ParameterError naming a field."""
    from lightsail_mbs.solvers.settings import MAX_SAMPLES

    @given(any_settings_kwargs())
    def accepted_or_refused(kwargs):
        try:
            s = RunSettings(**kwargs)
        except ParameterError as exc:
            assert any(str(exc).startswith(f"{name}=") for name in kwargs), str(exc)
        else:
            if s.t_final / s.sample_interval < 1e5:
                times = s.sample_times()
                assert times[0] == 0 and times[-1] == pytest.approx(s.t_final) and np.all(np.diff(times) > 0)
                assert times[-1] <= s.t_final  # a solver integrating to t_final reaches every sample
                assert times.size <= MAX_SAMPLES + 1
            assert RunSettings.from_dict(s.to_dict()) == s

    check_property(accepted_or_refused, examples)


def test_last_sample_never_lies_past_t_final():
    """Δt = t_final/3 in floating point: 3Δt rounds past t_final; the grid ends at t_final (found by the
    property test of solve: the reduced solver lost its last sample)."""
    t_final = 0.0008501973527864822
    settings = RunSettings(t_final=t_final, output_interval=0.0002833991175954941)
    assert 3 * settings.output_interval > t_final
    times = settings.sample_times()
    assert times.size == 4 and times[-1] == t_final
    r = solve(SailParameters(model="rigid", n=2, intensity=1e7), "reduced", settings, uncertainty=False)
    assert r.error is None and r.time.size == 4
