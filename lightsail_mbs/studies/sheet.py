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
* :func:`twin_verdict`, :func:`twin_runs` and :func:`twin_boundary` — the unlit-twin rule for sheets
  whose initial shape is not an equilibrium without the beam (a doubly curved defect under edge tension:
  the membrane force T∇²w ≠ 0 sets the unlit sheet oscillating about flat, and on free edges its modes
  add up to peaks above a₀: 1.05–1.4 a₀ at 4–128 T_cr,max for the paper's sail, docs: sheet). The twin
  is the same sheet with I₀ = 0 and the same start. The lit sail fails at the first output sample
  where its amplitude reaches twice the largest amplitude the twin has had up to then,
  a(t) ≥ 2 max_{s ≤ t} a_twin(s): the paper's rule
  measured against what the tensioned sheet does without the beam. Where the unlit sheet holds its
  shape (a_twin = a(0)) it is the paper's rule, sample for sample. The beam-driven part of the motion,
  the plane amplitude of z_lit − z_twin (:func:`twin_departure`), is reported beside it; it is not the
  rule, because a defect that changes shape as it grows departs from its start by a(0) before its
  amplitude doubles (4 % earlier for the soft strip: tests/studies/test_sheet.py), and an oscillating
  sheet whose frequency the beam shifts drifts out of phase with its twin without growing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lightsail_mbs import analysis
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import plate_theory, theory
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.result import Result
from lightsail_mbs.studies.bisection import Boundary, BoundaryProblem, bisect_boundaries
from lightsail_mbs.studies.sweep import Case, run_cases, run_sweep

WINDOW_RATIO = 1.5
FAILURE_TIME_LIMIT = 0.01  # relative: the cross-check's agreement on failure times
DEFLECTION_LIMIT = 1e-3  # in units of a₀: the cross-check's agreement on deflections
TWIN_STOP_RATIO = 4.0  # both twins run until a(t) ≥ 4 a(0): past twice any unlit peak below 2 a(0)
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


def twin_departure(lit: Result, unlit: Result) -> np.ndarray:
    """(T,) plane amplitude of the deflection difference z_lit − z_unlit over the tiles' (x, y), at the lit
    run's output samples (m; analysis.plane_amplitude of the points (x_lit, y_lit, z_lit − z_unlit)).

    Both runs must share their output times while the lit one runs; the unlit one must not end earlier."""
    if not (lit.is_sheet and unlit.is_sheet):
        raise ParameterError("runs are invalid here: allowed two sheet runs")
    n = len(lit.time)
    if len(unlit.time) < n or not np.allclose(unlit.time[:n], lit.time, rtol=0, atol=1e-9):
        raise ParameterError("unlit twin is invalid: allowed a run with the lit run's output times, at least as long")
    a, b = lit.tile_centres, unlit.tile_centres[:n]
    points = np.concatenate([a[..., :2], (a[..., 2] - b[..., 2])[..., None]], axis=-1)
    return analysis.plane_amplitude(points)


@dataclass
class TwinVerdict:
    """The unlit-twin rule on one case (module docstring).

    Attributes
    ----------
    failed : bool
        a(t) ≥ 2 max_{s ≤ t} a_twin(s) at some output sample of the lit run.
    failure_time : float or None
        The first such sample (s).
    lit_max_ratio : float
        Largest amplitude of the lit run, in units of a(0).
    unlit_max_ratio : float
        Largest amplitude of the unlit twin over its run, in units of a(0).
    max_departure : float
        Largest plane amplitude of z_lit − z_twin over the lit run, in units of a(0) (twin_departure).
    """

    failed: bool
    failure_time: float | None
    lit_max_ratio: float
    unlit_max_ratio: float
    max_departure: float


def twin_verdict(lit: Result, unlit: Result, ratio: float = 2.0) -> TwinVerdict:
    """The unlit-twin rule (module docstring): lit fails where a(t) ≥ ratio · max_{s ≤ t} a_twin(s)."""
    n = len(lit.time)
    departure = twin_departure(lit, unlit)
    envelope = np.maximum.accumulate(unlit.amplitude[:n])
    past = np.nonzero(lit.amplitude >= ratio * envelope)[0]
    a0 = lit.amplitude[0]
    return TwinVerdict(
        failed=bool(past.size),
        failure_time=float(lit.time[past[0]]) if past.size else None,
        lit_max_ratio=float(lit.amplitude.max() / a0),
        unlit_max_ratio=float(unlit.amplitude.max() / unlit.amplitude[0]),
        max_departure=float(departure.max() / a0),
    )


def twin_runs(lit: SailParameters, store_dir, settings: RunSettings, *, progress: bool = False):
    """(lit Result, unlit Result, TwinVerdict) of one case; both runs through the store, each until
    TWIN_STOP_RATIO·a(0) or t_final (settings' failure ratio replaced). The unlit twin is the same sheet
    with I₀ = 0 (its edge tension is kept in N/m)."""
    stop = settings.replace(failure_ratio=TWIN_STOP_RATIO)
    done = run_cases(
        [lit, lit.replace(intensity=0.0)],
        store_dir,
        stop,
        solver="reduced",
        workers=1,
        progress=progress,
        label="unlit twin",
    )
    (_, res_lit), (_, res_unlit) = done
    for record, result in done:
        if result is None or record.get("error"):
            raise RuntimeError(f"twin run failed: {record.get('error')}")
    stopped = res_lit.time[-1] < settings.t_final - 1e-9 and res_lit.amplitude[-1] < 2.0 * res_unlit.amplitude.max()
    if len(res_unlit.time) < len(res_lit.time) or stopped:
        raise RuntimeError(
            f"unlit twin reached {TWIN_STOP_RATIO} a(0) at {res_unlit.time[-1]:.4g} s, or its peaks exceed "
            f"{TWIN_STOP_RATIO / 2} a(0): the sheet is unstable without the beam, the twin rule does not apply"
        )
    return res_lit, res_unlit, twin_verdict(res_lit, res_unlit)


def twin_boundary(
    label,
    p: SailParameters,
    quantity: str,
    store_dir,
    *,
    settings: RunSettings | None = None,
    lo: float = 1.0,
    hi: float = 8.0,
    factor: float = 1.3,
    max_expansions: int = 6,
    progress: bool = True,
) -> tuple[Boundary, dict]:
    """The stable ratio E/E_cr,max or T/T_cr,max of sheet `p` under the unlit-twin rule, bisected in log
    space (one evaluation at a time: a bracket [lo, hi] grows by doubling its log-width until its ends
    differ, then is halved until hi/lo ≤ factor). Returns (Boundary with the ratios, {ratio: TwinVerdict}).
    Every run goes through the store at `store_dir`, so a rerun recomputes nothing."""
    settings = settings or RunSettings(t_final=6.0)
    out = Boundary(label)
    verdicts = {}

    def stable(ratio: float) -> bool:
        lit = with_ratio(p, quantity, ratio)
        _, _, v = twin_runs(lit, store_dir, settings)
        verdicts[ratio] = v
        out.evaluations.append((ratio, not v.failed, None))
        out.steps += 1
        if progress:
            state = "fails" if v.failed else "stable"
            print(
                f"twin {label}: {quantity} ratio {ratio:.4g} {state} (departure {v.max_departure:.3g} a0, "
                f"unlit peak {v.unlit_max_ratio:.3g} a0)",
                flush=True,
            )
        return not v.failed

    try:
        s_lo, s_hi = stable(lo), stable(hi)
        expansions = 0
        while s_lo == s_hi:
            if expansions >= max_expansions:
                out.status = "unbracketed"
                out.message = f"{'stable' if s_lo else 'unstable'} over [{lo:.6g}, {hi:.6g}]"
                return out, verdicts
            width = hi / lo
            if s_lo:  # stable at both ends: look below
                lo, hi, s_hi = lo / width**2, lo, s_lo
                s_lo = stable(lo)
            else:
                lo, hi, s_lo = hi, hi * width**2, s_hi
                s_hi = stable(hi)
            expansions += 1
        while hi / lo > factor:
            mid = math.sqrt(lo * hi)
            if stable(mid) == s_lo:
                lo = mid
            else:
                hi = mid
        out.stable_value, out.unstable_value = (hi, lo) if s_hi else (lo, hi)
        out.status = "converged"
    except (RuntimeError, ParameterError) as exc:
        out.status = "error"
        out.message = str(exc)
    return out, verdicts
