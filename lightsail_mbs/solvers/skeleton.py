"""The run skeleton every solver follows: sample grid, failure monitor and stop rule, progress.

A solver module exposes ``run(params, settings, *, progress=False, **options) -> Result`` and keeps to
this contract (see :func:`lightsail_mbs.solvers.solve`):

1. It starts from rest in ``shapes.initial_state(params)``, in the frame accelerating at g₀.
2. Its output is sampled on ``settings.sample_times()`` (t = 0 included) and nowhere else.
3. It stops at the first output sample whose amplitude reaches ``settings.failure_ratio`` × the initial
   amplitude when ``settings.stop_at_failure`` (a :class:`FailureMonitor` decides; a flat sail has no
   failure to stop at), else at ``settings.t_final``.
4. A failure of the method (no convergence, a too small step, a non-finite state) ends the run and is
   recorded in ``Result.error`` with the trajectory up to there; it never raises.
5. It returns a :class:`~lightsail_mbs.result.Result` built by ``Result.from_trajectory`` with its
   settings and statistics in ``Result.info``.

:func:`collect_samples` is the sampling loop of the solvers whose integrators hand back the state at
requested output times (the reduced solver's compiled and scipy integrators); Exudyn's solver drives
its own loop and uses the monitor from its post-step function.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Callable

import numpy as np

from lightsail_mbs.base.settings import RunSettings

FINISHED = "finished"  # status of an integrator that has reached t_final


class FailureMonitor:
    """The stop rule of a run: failure when amplitude ≥ failure_ratio · amplitude(0).

    ``active`` is False when the settings do not stop at failure or the sail starts flat
    (amplitude(0) = 0: nothing can double).
    """

    def __init__(self, initial_amplitude: float, settings: RunSettings):
        self.limit = settings.failure_ratio * float(initial_amplitude)
        self.active = bool(settings.stop_at_failure and self.limit > 0)

    def first_failure(self, amplitudes: np.ndarray) -> int | None:
        """Index of the first amplitude at or above the limit; None if none is, or when inactive."""
        if not self.active:
            return None
        above = np.nonzero(np.asarray(amplitudes) >= self.limit)[0]
        return int(above[0]) if above.size else None


def collect_samples(
    advance: Callable,
    y0: np.ndarray,
    sample_times: np.ndarray,
    monitor: FailureMonitor,
    amplitude_of: Callable,
    bar,
    chunk: int,
):
    """Drive an integrator over the sample grid; returns (list of state batches (size, k), error or None).

    advance(times) -> (batch, t, status): the states at the first k ≥ 0 of the requested output times
    (columns), the integrator's time and its status: None (going on), FINISHED, or an error message.
    At most ``chunk`` times are requested per call. The run ends at the first sample the monitor
    flags (kept), at an error (the samples before it kept) or when the grid is done.
    amplitude_of(batch) -> amplitude of each column.
    """
    states, error, next_sample = [y0[:, None]], None, 1
    while next_sample < sample_times.size:
        batch, t, status = advance(sample_times[next_sample : next_sample + chunk])
        if batch.shape[1]:
            states.append(batch)
            next_sample += batch.shape[1]
            stop = monitor.first_failure(amplitude_of(batch))
            if stop is not None:
                states[-1] = batch[:, : stop + 1]
                break
        if status not in (None, FINISHED):
            error = status
            break
        bar.update(t)
        if status == FINISHED:
            break
    return states, error


@contextlib.contextmanager
def interrupts_propagate():
    """Ctrl-C (SIGINT) during a run ends it with KeyboardInterrupt, even when the engine caught it.

    Exudyn turns an exception raised in a Python user function, KeyboardInterrupt included, into a
    solver error and returns normally; without this the interrupted run would come back as a Result
    with an error (and a sweep would record it and go on). Active only in the main thread while
    Python's own SIGINT handler is installed; elsewhere it does nothing.
    """
    if threading.current_thread() is not threading.main_thread() or (
        signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    ):
        yield
        return
    received = []

    def handler(signum, frame):
        received.append(signum)
        signal.default_int_handler(signum, frame)

    signal.signal(signal.SIGINT, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, signal.default_int_handler)
    if received:
        raise KeyboardInterrupt
