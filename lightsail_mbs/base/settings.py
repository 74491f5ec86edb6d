"""Run control: how long a run lasts, where it is sampled and when it stops.

The physical case (:class:`~lightsail_mbs.model.parameters.SailParameters`) says what the sail is; a
:class:`RunSettings` says how one run of it is watched. Every solver takes both, and the Result keeps
both, so a run can be repeated exactly. Numerical settings that belong to one solver (a step size, a
tolerance, an integration method) are that solver's keyword options.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.validation import ParameterError, check, finite

FIELDS = ("t_final", "output_interval", "stop_at_failure", "failure_ratio")
MAX_SAMPLES = 10_000_000  # output samples of one run (each holds 6n + 2(n − 1) + 2 numbers)


@dataclass(frozen=True)
class RunSettings:
    """How one run is watched.

    Parameters
    ----------
    t_final : float
        End of the run (s); the run ends earlier at failure when ``stop_at_failure``.
    output_interval : float or None
        Spacing of the output samples (s); None: min(1 ms, t_final/1000).
    stop_at_failure : bool
        End the run at the first output sample whose amplitude reaches ``failure_ratio`` times the
        initial amplitude.
    failure_ratio : float
        The sail has failed when amplitude(t) ≥ failure_ratio · amplitude(0) (the paper: 2).
    """

    t_final: float = 6.0
    output_interval: float | None = None
    stop_at_failure: bool = True
    failure_ratio: float = 2.0

    def __post_init__(self):
        v = finite("t_final", self.t_final)
        check("t_final", v, v > 0, "> 0")
        if self.output_interval is not None:
            v = finite("output_interval", self.output_interval)
            check("output_interval", v, 0 < v <= self.t_final, f"0 < output_interval ≤ t_final={self.t_final}")
        samples = self.t_final / self.sample_interval
        if self.output_interval is None:
            check(
                "t_final",
                self.t_final,
                samples <= MAX_SAMPLES,
                f"≤ {MAX_SAMPLES * 1e-3:g} s with the default 1 ms output interval ({MAX_SAMPLES:.0e} samples; "
                "set a longer output_interval)",
            )
        check(
            "output_interval",
            self.output_interval,
            samples <= MAX_SAMPLES,
            f"≥ t_final/{MAX_SAMPLES:.0e} = {self.t_final / MAX_SAMPLES:.3g} s ({samples:.3g} output samples)",
        )
        check("stop_at_failure", self.stop_at_failure, isinstance(self.stop_at_failure, bool), "True or False")
        v = finite("failure_ratio", self.failure_ratio)
        check("failure_ratio", v, v > 1, "> 1")

    @property
    def sample_interval(self) -> float:
        """The output interval actually used (s)."""
        if self.output_interval is not None:
            return float(self.output_interval)
        return min(1e-3, self.t_final / 1000.0)

    def sample_times(self) -> np.ndarray:
        """Output times 0, Δt, 2Δt, … up to t_final, with t_final appended when Δt does not divide it and
        the last one set to t_final when Δt divides it up to round-off (s)."""
        dt = self.sample_interval
        times = dt * np.arange(int(math.floor(self.t_final / dt + 1e-9)) + 1)
        if times[-1] > self.t_final:  # k·Δt rounded past t_final: the run ends at t_final
            times[-1] = self.t_final
        elif times[-1] < self.t_final * (1 - 1e-12):
            times = np.append(times, self.t_final)
        return times

    def replace(self, **changes) -> RunSettings:
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)

    def to_dict(self) -> dict:
        return dataclasses.asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> RunSettings:
        unknown = sorted(set(d) - set(FIELDS))
        if unknown:
            raise ParameterError(f"settings {unknown[0]!r} is invalid: allowed {', '.join(FIELDS)}")
        return cls(**d)
