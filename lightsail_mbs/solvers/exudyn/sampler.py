"""The chain's post-step sampler for Exudyn (solvers.exudyn.chain): output samples from the steps, and the stop rule.

After every step the sampler keeps t, q, q̇, q̈; it interpolates the output samples the steps passed by the
quintic Hermite polynomial through both ends of each one's step (exact at a step end) and asks the run
skeleton's FailureMonitor (solvers.skeleton) for the first sample at or above the limit, every
``check_every`` samples (sooner when the amplitude's growth predicts failure before then) or after
STEPS_PER_CHECK steps, and at the end.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs.model import failure
from lightsail_mbs.solvers.exudyn.tree import ChainLayout
from lightsail_mbs.solvers.skeleton import FailureMonitor

STEPS_PER_CHECK = 100  # ... or after this many steps: a crumpling sail (steps shrinking) stops soon after failure


class Sampler:
    """The post-step function of a run: samples the output grid from the steps and applies the stop rule.

    After every step it keeps t, q, q̇, q̈; every ``check_every`` output samples (and at the end) it
    interpolates the samples the new steps passed, by the quintic Hermite polynomial through both ends
    of the step that holds each (exact at a step end), and asks the monitor for the first sample at or
    above the limit; it keeps the samples up to and including that one and returns False (stop).
    """

    def __init__(self, mbs, times: np.ndarray, layout: ChainLayout, monitor: FailureMonitor, check_every: int, bar):
        self.times, self.layout, self.monitor, self.bar = times, layout, monitor, bar
        self.check_every = max(1, int(check_every))
        data = mbs.systemData
        q0 = np.array(data.GetODE2Coordinates())
        self.steps_t = [0.0]
        self.steps_q = [q0]
        self.steps_v = [np.array(data.GetODE2Coordinates_t())]
        self.steps_a = [np.array(data.GetODE2Coordinates_tt())]
        self.q, self.v = [q0], [self.steps_v[0]]  # samples (rows)
        self.failed_at = None  # index of the first sample at or above the limit
        self.steps = 0
        self._next_check = min(self.check_every, times.size - 1)
        x, y, _, _ = layout.positions(q0)
        self._last = (0.0, failure.amplitude(x, y))  # time and amplitude of the last checked sample

    def __call__(self, mbs, t) -> bool:
        self.steps += 1
        data = mbs.systemData
        self.steps_t.append(float(t))
        self.steps_q.append(np.array(data.GetODE2Coordinates()))
        self.steps_v.append(np.array(data.GetODE2Coordinates_t()))
        self.steps_a.append(np.array(data.GetODE2Coordinates_tt()))
        if self.steps_t[-1] >= self.times[self._next_check] * (1 - 1e-13) or len(self.steps_t) > STEPS_PER_CHECK:
            self.bar.update(self.steps_t[-1])
            return not self.check()
        return True

    def _sample(self, final: bool = False) -> None:
        """Interpolate the output times passed by the kept steps (then forget all but the last step); at the
        end of the run (final), also the times within 1e-6 of a step past its last one (the grid's end, which
        steps accumulated in floating point may fall short of). A step whose record an interrupt (Ctrl-C)
        cut between its appends is dropped first."""
        kept_steps = (self.steps_t, self.steps_q, self.steps_v, self.steps_a)
        whole = min(len(kept) for kept in kept_steps)
        for kept in kept_steps:
            del kept[whole:]
        t = np.asarray(self.steps_t)
        k0 = len(self.q)
        reach = t[-1] + 1e-6 * (t[-1] - t[-2]) if final and t.size > 1 else t[-1] * (1 + 1e-13) + 1e-300
        k1 = int(np.searchsorted(self.times, reach, side="right"))
        if k1 > k0:
            times = self.times[k0:k1]
            step = np.clip(np.searchsorted(t, times * (1 - 1e-13), side="left"), 1, t.size - 1)
            q, v = hermite(
                (t[step - 1], *(np.asarray(a)[step - 1] for a in (self.steps_q, self.steps_v, self.steps_a))),
                (t[step], *(np.asarray(a)[step] for a in (self.steps_q, self.steps_v, self.steps_a))),
                times,
            )
            self.q.extend(q)
            self.v.extend(v)
        for kept in kept_steps:
            del kept[:-1]

    def check(self, final: bool = False) -> bool:
        """Sample, then check the new samples; True (and the samples cut after it) at the first one at or
        above the limit. final: the run has ended (see _sample)."""
        if self.failed_at is not None:
            return True
        checked = len(self.q)
        self._sample(final)
        every = self.check_every
        if self.monitor.active and len(self.q) > checked:
            x, y, _, _ = self.layout.positions(np.asarray(self.q[checked:]))
            amplitude = np.atleast_1d(failure.amplitude(x, y))
            over = self.monitor.first_failure(amplitude)
            if over is not None:
                self.failed_at = checked + over
                del self.q[self.failed_at + 1 :]
                del self.v[self.failed_at + 1 :]
                return True
            every = self._samples_to_next_check(self.times[len(self.q) - 1], float(amplitude[-1]))
        self._next_check = min(len(self.q) - 1 + every, self.times.size - 1)
        return False

    def _samples_to_next_check(self, t: float, amplitude: float) -> int:
        """check_every, or fewer when the amplitude, growing exponentially at the rate measured since the
        last check, would reach the limit within twice that many samples: then half the predicted time to
        the limit (at least one sample), so the run stops within a few steps of failure instead of
        integrating the crumpling sail past it."""
        t_last, a_last = self._last
        self._last = (t, amplitude)
        if not (amplitude > a_last > 0 and t > t_last):
            return self.check_every
        rate = math.log(amplitude / a_last) / (t - t_last)
        to_limit = math.log(self.monitor.limit / amplitude) / rate
        dt = self.times[1] - self.times[0] if self.times.size > 1 else to_limit
        return int(max(1, min(self.check_every, math.floor(0.5 * to_limit / dt))))

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(time, q, q̇) of the samples taken."""
        rows = len(self.q)
        return self.times[:rows], np.asarray(self.q), np.asarray(self.v)


def hermite(start, end, times) -> tuple[np.ndarray, np.ndarray]:
    """q and q̇ at `times` within the step [t₀, t₁] from (t, q, q̇, q̈) at both ends: the quintic Hermite
    polynomial and its derivative (error O(h⁶) in q, O(h⁵) in q̇)."""
    t0, q0, v0, a0 = start
    t1, q1, v1, a1 = end
    h = np.asarray(t1 - t0, float).reshape(-1, 1)
    s = np.clip((np.asarray(times) - np.asarray(t0).reshape(-1)) / h[:, 0], 0.0, 1.0)[:, None]
    s2, s3 = s * s, s * s * s
    s4, s5 = s3 * s, s3 * s2
    q = (
        (1 - 10 * s3 + 15 * s4 - 6 * s5) * q0
        + (s - 6 * s3 + 8 * s4 - 3 * s5) * (h * v0)
        + 0.5 * (s2 - 3 * s3 + 3 * s4 - s5) * (h * h * a0)
        + (10 * s3 - 15 * s4 + 6 * s5) * q1
        + (-4 * s3 + 7 * s4 - 3 * s5) * (h * v1)
        + 0.5 * (s3 - 2 * s4 + s5) * (h * h * a1)
    )
    v = (
        (-30 * s2 + 60 * s3 - 30 * s4) * ((q0 - q1) / h)
        + (1 - 18 * s2 + 32 * s3 - 15 * s4) * v0
        + 0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4) * (h * a0)
        + (-12 * s2 + 28 * s3 - 15 * s4) * v1
        + 0.5 * (3 * s2 - 8 * s3 + 5 * s4) * (h * a1)
    )
    return list(q), list(v)
