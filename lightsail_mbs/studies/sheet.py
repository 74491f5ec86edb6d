"""Studies of the sheet: the two solvers side by side, and stability boundaries in units of the strip's.

* :func:`compare_deflections` and :func:`crosscheck` — both sheet solvers on the same cases (through the
  store, so a rerun recomputes nothing): failure times, and the largest difference of the tile
  deflections (offsets from the best-fit plane, the failure rule's quantity) over the common output
  samples while both amplitudes are below WINDOW_RATIO × a(0) (past that the instability amplifies
  any difference by e every ~0.1 s), in units of a₀.
* :func:`stability_boundaries` — the stiffness that keeps a sheet from failing within a run, bisected
  in log space through the store (studies.bisection), as ratios to the paper's strip scales:
  E/E_cr,max (Eq. 8, with the defect's ν along x) or the edge tension T/T_cr,max with
  T_cr,max = ½(2I₀/c)a₀ per metre of edge (Eq. 10 per width).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lightsail_mbs.model import plate_theory, theory
from lightsail_mbs.model.parameters import ParameterError, SailParameters
from lightsail_mbs.result import Result
from lightsail_mbs.solvers.settings import RunSettings
from lightsail_mbs.studies.bisection import BoundaryProblem, bisect_boundaries
from lightsail_mbs.studies.sweep import Case, run_sweep

WINDOW_RATIO = 1.5
FAILURE_TIME_LIMIT = 0.01  # relative: the cross-check's agreement on failure times
DEFLECTION_LIMIT = 1e-3  # in units of a₀: the cross-check's agreement on deflections
QUANTITIES = {
    "modulus": ("youngs_modulus", theory.critical_modulus_max),
    "edge_tension": ("edge_tension", plate_theory.critical_tension_per_width),
}


def compare_deflections(a: Result, b: Result, window_ratio: float = WINDOW_RATIO) -> tuple[float, float]:
    """(max |Δ deflection| / a₀, end of the window in s) over the output times the two sheet runs share,
    while both amplitudes are < window_ratio × their initial value (a₀ = a's initial amplitude)."""
    if not (a.is_sheet and b.is_sheet):
        raise ParameterError("runs are invalid here: allowed two sheet runs")
    ia = np.clip(np.searchsorted(a.time, b.time - 1e-9), 0, len(a.time) - 1)
    shared = np.abs(a.time[ia] - b.time) < 1e-9 * max(1.0, float(b.time[-1]))
    ia, ib = ia[shared], np.nonzero(shared)[0]
    inside = (a.amplitude[ia] < window_ratio * a.amplitude[0]) & (b.amplitude[ib] < window_ratio * b.amplitude[0])
    outside = np.nonzero(~inside)[0]
    stop = outside[0] if outside.size else len(ia)
    if stop == 0:
        return float("nan"), float(a.time[0])
    difference = np.abs(a.deflection()[ia[:stop]] - b.deflection()[ib[:stop]])
    return float(difference.max() / a.amplitude[0]), float(a.time[ia[stop - 1]])


@dataclass(frozen=True)
class SheetCase:
    """One cross-check case: the sail, its run, and each solver's options."""

    name: str
    params: SailParameters
    settings: RunSettings
    exudyn_options: dict
    reduced_options: dict


@dataclass
class CrossCheckRow:
    name: str
    exudyn: Result
    reduced: Result
    failure_difference: float | None  # |t_e/t_r − 1|; None unless both failed
    deflection_difference: float  # max |Δw|/a₀ in the window
    window_end: float  # s

    @property
    def verdicts_agree(self) -> bool:
        return self.exudyn.failed == self.reduced.failed

    @property
    def passed(self) -> bool:
        times = self.failure_difference is None or self.failure_difference <= FAILURE_TIME_LIMIT
        return self.verdicts_agree and times and self.deflection_difference <= DEFLECTION_LIMIT


def crosscheck(cases: list[SheetCase], store_dir, *, workers: int | None = None, progress: bool = True):
    """Run every case with both solvers through the store (Results saved) and compare them; returns
    [CrossCheckRow]. Each case runs in its own worker process."""
    jobs = []
    for case in cases:
        jobs.append(Case(case.params, "exudyn", dict(case.exudyn_options), True, case.settings))
        jobs.append(Case(case.params, "reduced", dict(case.reduced_options), True, case.settings))
    records = run_sweep(jobs, store_dir, workers=workers, progress=progress, label="sheet cross-check")
    rows = []
    for k, case in enumerate(cases):
        runs = []
        for record in records[2 * k : 2 * k + 2]:
            if "result_path" not in record:
                raise RuntimeError(f"{case.name}: {record['solver']} run failed: {record.get('error')}")
            runs.append(Result.load(Path(store_dir) / record["result_path"]))
        ex, re = runs
        ft = None
        if ex.failed and re.failed:
            ft = abs(ex.failure_time / re.failure_time - 1.0)
        deflection, window = compare_deflections(ex, re)
        rows.append(CrossCheckRow(case.name, ex, re, ft, deflection, window))
    return rows


def with_ratio(p: SailParameters, quantity: str, ratio: float) -> SailParameters:
    """The sheet with E = ratio·E_cr,max or T = ratio·T_cr,max (per metre of edge)."""
    if quantity not in QUANTITIES:
        raise ParameterError(f"quantity={quantity!r} is invalid: allowed one of {', '.join(QUANTITIES)}")
    name, scale = QUANTITIES[quantity]
    return p.replace(**{name: float(ratio) * scale(p)})


def stability_boundaries(
    cases: dict,
    quantity: str,
    store_dir,
    *,
    solver: str = "reduced",
    settings: RunSettings | None = None,
    options: dict | None = None,
    lo: float = 1.0,
    hi: float = 8.0,
    factor: float = 1.25,
    workers: int | None = None,
    progress: bool = True,
) -> dict:
    """Bisect the stable ratio E/E_cr,max or T/T_cr,max of each case ({label: SailParameters}) in log
    space until hi/lo ≤ factor; every run through the store at `store_dir`. Returns {label: Boundary}
    (studies.bisection) whose values are ratios. The stiffness scale is each case's own (E_cr,max
    with its a₀, ν, h, I₀), so a strip and a sheet of the same sail share it."""
    problems = {label: BoundaryProblem(lambda r, p=p: with_ratio(p, quantity, r), lo, hi) for label, p in cases.items()}
    return bisect_boundaries(
        problems,
        store_dir=store_dir,
        solver=solver,
        settings=settings or RunSettings(),
        options=options,
        factor=factor,
        workers=workers,
        progress=progress,
    )
