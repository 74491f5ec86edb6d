"""The failure located by event (solvers.events): the location error bound on samples of known curves, the
refinement of runs whose failure falls between coarse samples, and sampling that follows the case's time
scales."""

import math

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, paper_case, solve
from lightsail_mbs.model import failure
from lightsail_mbs.result import with_uncertainty
from lightsail_mbs.solvers import events

# A Starshot-like sail: 3.2 m of 100 nm glass in a 1e10 W/m² Gaussian beam as wide as the sail; it cups
# within microseconds, a thousand times faster than the 1 ms default output interval.
STARSHOT = SailParameters(
    model="torsion",
    length=3.2,
    width=3.2,
    thickness=100e-9,
    density=2200.0,
    youngs_modulus=70e9,
    intensity=1e10,
    defect_amplitude=1e-6,
    beam_waist=1.6,
)


def exponential_samples(rate: float, interval: float, t_end: float):
    time = interval * np.arange(int(t_end / interval) + 1)
    return time, np.exp(rate * time)


@pytest.mark.parametrize("interval", [0.1, 0.05, 0.013, 0.01])
def test_location_error_bounds_the_linear_root_of_an_exponential(interval):
    """a(t) = e^{σt} doubles at ln 2/σ: the line through the bracketing samples misses it by less than the
    bound E_loc, and by no less than an eighth of it (the bound is the line's own error, not a blanket)."""
    rate = 3.0
    time, amplitude = exponential_samples(rate, interval, 1.0)
    k = failure.crossing(amplitude, 2.0)
    t_lin = time[k - 1] + (2.0 - amplitude[k - 1]) / (amplitude[k] - amplitude[k - 1]) * interval
    exact = math.log(2.0) / rate
    bound = events.location_error(time, amplitude, 2.0)
    assert abs(t_lin - exact) <= bound <= 8 * abs(t_lin - exact)


def test_unresolved_brackets_have_no_location():
    """A crossing before the second sample, or across which the amplitude jumps, is unresolved (inf); a run
    that does not fail has no location error."""
    assert events.location_error(np.array([0.0, 1.0, 2.0]), np.array([1.0, 5.0, 9.0]), 2.0) == math.inf
    jump = np.array([1.0, 1.2, 1.4, 30.0])
    assert events.location_error(np.arange(4.0), jump, 2.0) == math.inf
    assert events.location_error(np.arange(3.0), np.array([1.0, 1.5, 1.9]), 2.0) is None


def test_peak_error_bounds_the_maximum_between_samples():
    """a(t) = 1 + 0.5 sin t sampled every 0.3 (peak at π/2 between samples): the largest sample plus the
    bound reaches the true maximum 1.5, and not by much more."""
    time = 0.3 * np.arange(12)
    amplitude = 1.0 + 0.5 * np.sin(time)
    bound = events.peak_error(amplitude)
    assert amplitude.max() + bound >= 1.5 > amplitude.max()
    assert bound < 4 * (1.5 - amplitude.max())


def test_default_sampling_follows_a_fast_case_and_leaves_the_paper_alone():
    slow = RunSettings(t_final=6.0)
    assert events.default_sampling(paper_case("torsion-soft"), slow) == (slow, None)
    fast = RunSettings(t_final=1e-3)
    cupping = events.time_scales(STARSHOT)["cupping"]
    assert 1e-6 < cupping < 1e-5
    settings, note = events.default_sampling(STARSHOT, fast)
    assert settings.output_interval == pytest.approx(cupping / events.SAMPLES_PER_TIME_SCALE)
    assert "cupping" in note
    capped, note = events.default_sampling(STARSHOT, RunSettings(t_final=6.0))
    assert capped.output_interval > cupping / events.SAMPLES_PER_TIME_SCALE and "memory cap" in note


def test_starshot_failure_is_the_same_at_every_output_interval_and_in_both_solvers():
    """The sail cups 65,000-fold within the first default sample: the failure time is located by reruns
    at finer intervals, and the same to its ± with the default interval and with 10× and 100× finer ones;
    Exudyn agrees within the two error bars."""
    runs = [solve(STARSHOT, "reduced")]
    interval = events.default_sampling(STARSHOT, RunSettings())[0].sample_interval
    for finer in (10, 100):
        runs.append(solve(STARSHOT, "reduced", RunSettings(output_interval=interval / finer)))
    runs.append(solve(STARSHOT, "exudyn"))
    reference = runs[0]
    assert reference.failed and 5e-6 < reference.failure_time < 8e-6
    assert reference.info["sampling"]["refinements"] >= 1
    for other in runs[1:]:
        assert other.failed
        gap = abs(other.failure_time - reference.failure_time)
        assert gap <= other.failure_time_uncertainty + reference.failure_time_uncertainty
        assert gap <= 1e-5 * reference.failure_time
    assert reference.settings == RunSettings()  # the settings asked for; the sampling used is in info


def test_failure_before_the_first_default_sample_is_refined():
    """The paper's soft sail in a 0.5 m Gaussian beam fails before the first 1 ms sample; without a
    refinement the line through samples 0 and 1 put it at 7.8e-5 s. Located, it agrees with a run sampled
    10,000 times finer, and its error bar (location only: no twins) covers the difference."""
    p = paper_case("torsion-soft", beam_waist=0.5)
    located = solve(p, "reduced", RunSettings(t_final=0.01), uncertainty=False)
    fine = solve(p, "reduced", RunSettings(t_final=0.01, output_interval=1e-7), uncertainty=False)
    assert located.info["sampling"]["refinements"] >= 1 and fine.info["sampling"]["refinements"] == 0
    bound = located.info["sampling"]["location_error"] + fine.info["sampling"]["location_error"]
    assert abs(located.failure_time - fine.failure_time) <= bound < 1e-6 * located.failure_time
    assert 4e-4 < located.failure_time < 4.5e-4
    assert "location only" in located.answer_text()


@pytest.mark.parametrize("uncertainty", [False, True])
def test_the_memory_cap_stops_a_refinement_and_says_so(monkeypatch, uncertainty):
    """With the uncertainty estimate too: the Result it reports (the base run, or the fallback's tightest twin)
    carries the sampling's warnings of the base run, once."""
    monkeypatch.setattr(events, "SAMPLE_MEMORY", 2e4)
    p = paper_case("torsion-soft", beam_waist=0.5)
    r = solve(p, "reduced", RunSettings(t_final=0.01), uncertainty=uncertainty)
    assert sum("memory cap" in note for note in r.warnings) == 1
    assert r.info["sampling"]["location_error"] > events.LOCATE_RTOL * r.failure_time


def test_small_and_large_numbers_print_in_scientific_notation_with_their_digits():
    assert with_uncertainty(6.2948312e-6, 4.1e-11) == "(6.29483 ± 0.00005)e-06"
    assert with_uncertainty(2.111214, 3e-6) == "2.111214 ± 0.000003"
    assert with_uncertainty(123456.7, 3.0) == "(1.23457 ± 0.00003)e+05"


def test_a_failure_that_the_finer_rerun_does_not_reproduce_is_kept_and_flagged():
    """A solver whose finer-sampled rerun does not fail (as Exudyn's sheet near its connector round-off floor,
    its step following the output interval): the refinement's run ends at about twice the failure time, so
    reporting it would call the sail a survivor of a run cut short. The coarse run's failure is kept, its
    location error stays in the record, and one warning says the failure is not confirmed."""
    from lightsail_mbs.solvers import contract

    p = paper_case("torsion-soft", beam_waist=0.5)
    engine = contract.lookup("reduced", p)
    settings = RunSettings(t_final=0.01)

    class FlakyWhenFine:
        def run(self, params, run_settings, progress=False, **options):
            if run_settings.t_final < settings.t_final:  # a refinement: a run that grows no more
                params = params.replace(intensity=params.intensity * 1e-6)
            return engine.run(params, run_settings, progress=progress, **options)

    result, kept = events.located_run(FlakyWhenFine(), p, settings, {})
    assert result.failed and result.params == p and kept.t_final == settings.t_final
    assert result.info["sampling"]["refinements"] == 1
    assert result.info["sampling"]["location_error"] > events.LOCATE_RTOL * result.failure_time
    assert sum("not confirmed" in w for w in result.warnings) == 1
