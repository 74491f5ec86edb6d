"""Monte Carlo over random multi-mode defects or over films: failure probability and failure times.

For each value of a swept parameter (E or T), N seeded cases (seeds 0…N−1) run through the sweep engine, each
finished case written to the store. What the seed draws (``over``):

* ``"defect"``: the multi-mode defect (shapes.multimode_profile, SailParameters.defect_seed);
* ``"film"``: the case's film (model.film, SailParameters.film_seed; the case needs film_rms > 0), its defect
  left as the case states it: the spread of the answer over films of one spectrum.

Per value we report the failure probability with its 95 % Wilson score interval, and the failure-time
distribution of the failed runs (median, quartiles, 5–95 % range, mean with its 95 % Student-t interval).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.studies.sweep import Case, run_sweep, solve_case

SWEEPABLE = ("youngs_modulus", "tension", "thickness", "intensity", "defect_amplitude")
SEEDED = {"defect": "defect_seed", "film": "film_seed"}  # what a Monte Carlo draws: the field its seeds set


def wilson_interval(failures: int, trials: int, confidence: float = 0.95) -> tuple[float, float]:
    """Wilson score interval for a binomial proportion (Wilson 1927)."""
    from statistics import NormalDist

    if trials == 0:
        return (0.0, 1.0)
    z = NormalDist().inv_cdf(0.5 + confidence / 2)
    p = failures / trials
    centre = (p + z * z / (2 * trials)) / (1 + z * z / trials)
    half = z / (1 + z * z / trials) * np.sqrt(p * (1 - p) / trials + z * z / (4 * trials * trials))
    return (max(0.0, centre - half), min(1.0, centre + half))


@dataclass(frozen=True)
class MonteCarloRow:
    value: float
    runs: int
    failures: int
    errors: int
    probability: float
    probability_low: float
    probability_high: float
    failure_time_median: float | None
    failure_time_q25: float | None
    failure_time_q75: float | None
    failure_time_mean: float | None
    failure_time_mean_halfwidth: float | None
    failure_time_q05: float | None
    failure_time_q95: float | None


def cases(
    base: SailParameters,
    parameter: str,
    values,
    seeds: int,
    solver: str = "exudyn",
    options: dict | None = None,
    settings: RunSettings | None = None,
    over: str = "defect",
) -> list[Case]:
    """The sweep: every (value, seed) pair, seeds 0…seeds−1 of the defect or of the film (`over`, SEEDED)."""
    if parameter not in SWEEPABLE:
        raise ParameterError(f"parameter={parameter!r} is invalid: allowed one of {', '.join(SWEEPABLE)}")
    if not isinstance(seeds, int) or seeds < 1:
        raise ParameterError(f"seeds={seeds!r} is invalid: allowed an integer ≥ 1")
    if over not in SEEDED:
        raise ParameterError(f"over={over!r} is invalid: allowed one of {', '.join(SEEDED)}")
    if over == "film" and not base.film_rms > 0:
        raise ParameterError(f"film_rms={base.film_rms!r} is invalid: allowed > 0 (m) for a Monte Carlo over films")
    return [
        Case(
            base.replace(**{parameter: float(v), SEEDED[over]: s}),
            solver,
            dict(options or {}),
            settings=settings or RunSettings(),
        )
        for v in values
        for s in range(seeds)
    ]


def summarise(values, seeds: int, records: list[dict]) -> list[MonteCarloRow]:
    """Group the records (in the order of `cases`) by value and summarise each group."""
    from scipy import stats

    rows = []
    for i, value in enumerate(values):
        group = records[i * seeds : (i + 1) * seeds]
        ok = [r for r in group if r["status"] == "ok"]
        times = np.array([r["failure_time"] for r in ok if r["failed"]], float)
        k = times.size
        low, high = wilson_interval(k, len(ok))
        half = float(stats.t.ppf(0.975, k - 1) * times.std(ddof=1) / np.sqrt(k)) if k > 1 else None
        q = np.percentile(times, [25, 50, 75, 5, 95]) if k else [None] * 5
        rows.append(
            MonteCarloRow(
                float(value),
                len(ok),
                k,
                len(group) - len(ok),
                k / len(ok) if ok else float("nan"),
                low,
                high,
                _f(q[1]),
                _f(q[0]),
                _f(q[2]),
                _f(times.mean()) if k else None,
                half,
                _f(q[3]),
                _f(q[4]),
            )
        )
    return rows


def run(
    base: SailParameters,
    parameter: str,
    values,
    seeds: int,
    store_dir,
    *,
    solver: str = "exudyn",
    settings: RunSettings | None = None,
    options: dict | None = None,
    workers: int | None = None,
    scheduler=None,
    progress: bool = True,
    case_function=solve_case,
    over: str = "defect",
) -> list[MonteCarloRow]:
    """Run (or resume) the Monte Carlo sweep over defects or films (`over`) and summarise it per value."""
    values = [float(v) for v in values]
    records = run_sweep(
        cases(base, parameter, values, seeds, solver, options, settings, over),
        store_dir,
        workers=workers,
        scheduler=scheduler,
        progress=progress,
        case_function=case_function,
        label="monte carlo",
    )
    return summarise(values, seeds, records)


def _f(v):
    return None if v is None else float(v)
