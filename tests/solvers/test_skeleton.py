"""The run skeleton every solver keeps: the failure monitor (stop rule) and the sampling loop
collect_samples, driven here by a fake integrator whose state is its own amplitude."""

import numpy as np
import pytest

from lightsail_mbs import RunSettings
from lightsail_mbs.solvers.skeleton import FINISHED, FailureMonitor, collect_samples


# ---- FailureMonitor -------------------------------------------------------------------------
def test_flat_sail_has_no_failure_to_stop_at():
    monitor = FailureMonitor(0.0, RunSettings())
    assert not monitor.active and monitor.first_failure(np.array([0.0, 1.0, 1e3])) is None


def test_no_stop_when_the_settings_say_so():
    monitor = FailureMonitor(1e-5, RunSettings(stop_at_failure=False))
    assert not monitor.active and monitor.first_failure(np.array([1e-5, 1.0])) is None


def test_first_index_at_or_above_the_limit():
    monitor = FailureMonitor(2.0, RunSettings(failure_ratio=3.0))
    assert monitor.active and monitor.limit == 6.0
    assert monitor.first_failure(np.array([2.0, 5.9, 6.0, 7.0, 1.0])) == 2  # at the limit counts
    assert monitor.first_failure(np.array([2.0, 6.5, 6.0])) == 1
    assert monitor.first_failure(np.array([2.0, 5.999999])) is None
    assert monitor.first_failure(np.array([])) is None


# ---- collect_samples ------------------------------------------------------------------------
class Bar:
    """A progress bar that remembers what it was told."""

    def __init__(self):
        self.times = []

    def update(self, t):
        self.times.append(t)


class FakeIntegrator:
    """State y = [e^{rate·t}] (size 1): advance(times) returns the states at the first `per_call` of the
    requested times. ``error_at`` / ``finish_at``: the call (1-based) that returns that status."""

    def __init__(self, rate=1.0, per_call=None, error_at=None, finish_at=None):
        self.rate, self.per_call, self.error_at, self.finish_at = rate, per_call, error_at, finish_at
        self.requests = []

    def __call__(self, times):
        self.requests.append(np.array(times))
        times = times[: self.per_call]
        call = len(self.requests)
        status = "boom at t = 0.5" if call == self.error_at else FINISHED if call == self.finish_at else None
        t = float(times[-1]) if times.size else 0.0
        return np.exp(self.rate * times)[None, :], t, status


def collect(integrator, settings, initial=1.0, chunk=3):
    times = settings.sample_times()
    monitor = FailureMonitor(initial, settings)
    bar = Bar()
    states, error = collect_samples(integrator, np.array([initial]), times, monitor, lambda b: b[0], bar, chunk)
    return np.concatenate(states, axis=1)[0], error, bar, times


def test_stops_at_the_first_flagged_sample_and_keeps_it():
    settings = RunSettings(t_final=1.0, output_interval=0.1)  # e^t ≥ 2 first at t = 0.7
    fake = FakeIntegrator()
    y, error, _, times = collect(fake, settings)
    assert error is None and y.size == 8
    np.testing.assert_allclose(y, np.exp(times[:8]))
    assert y[-1] >= 2.0 > y[-2]
    assert len(fake.requests) == 3 and all(r.size <= 3 for r in fake.requests)  # chunks of ≤ 3 times
    np.testing.assert_allclose(np.concatenate(fake.requests), times[1:10])  # nothing asked twice


def test_runs_the_whole_grid_without_failure():
    settings = RunSettings(t_final=1.0, output_interval=0.1, stop_at_failure=False)
    fake = FakeIntegrator(per_call=2)  # hands back fewer than asked
    y, error, bar, times = collect(fake, settings)
    assert error is None and y.size == times.size == 11
    np.testing.assert_allclose(y, np.exp(times))
    assert bar.times[-1] == pytest.approx(1.0)


def test_an_error_ends_the_run_with_the_samples_before_it():
    settings = RunSettings(t_final=1.0, output_interval=0.1, stop_at_failure=False)
    fake = FakeIntegrator(per_call=2, error_at=3)
    y, error, bar, times = collect(fake, settings)
    assert error == "boom at t = 0.5"
    assert y.size == 1 + 3 * 2 and len(fake.requests) == 3  # the failing call's samples are kept
    np.testing.assert_allclose(y, np.exp(times[:7]))
    assert len(bar.times) == 2  # no progress after the error


def test_an_error_without_samples_keeps_the_earlier_ones():
    settings = RunSettings(t_final=1.0, output_interval=0.1, stop_at_failure=False)
    fake = FakeIntegrator(per_call=0, error_at=1)
    y, error, _, _ = collect(fake, settings)
    assert error == "boom at t = 0.5" and y.size == 1 and y[0] == 1.0


def test_stops_when_the_integrator_has_finished():
    settings = RunSettings(t_final=1.0, output_interval=0.1, stop_at_failure=False)
    fake = FakeIntegrator(per_call=2, finish_at=2)
    y, error, bar, times = collect(fake, settings)
    assert error is None and len(fake.requests) == 2  # not asked again after FINISHED
    assert y.size == 1 + 2 * 2
    np.testing.assert_allclose(y, np.exp(times[:5]))
    assert bar.times == pytest.approx([0.2, 0.4])
