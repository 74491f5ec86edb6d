"""The error in n of a single run: coarser twins and Richardson's estimate, folded into the run's ±.

A chain of n slices answers q(n) (the failure time, or the largest amplitude ratio of a sail that survives).
Where the case is well posed in n (:mod:`lightsail_mbs.analysis.resolvedness`), q(n) tends to a continuum
answer q_∞ as n grows; in the asymptotic regime q(n) = q_∞ + C n^(−p), so a twin at n_c < n gives

    q(n) − q_∞ = (q(n_c) − q(n)) / ((n/n_c)^p − 1)                                   (Richardson)

For a halved n and p = 1 this is the last change d₂ = q(n) − q(n/2). The order is not assumed higher than 1:
`converge` measures p = 0.92–1.00 on the paper's stiff and stable torsion sails and at E = E_cr,max, 2.2 on
the soft one (docs/convergence.md). Below the asymptotic regime the answers need not be monotone in n (at
E = E_cr,max the answer rises to a peak near n = 60 and then falls at first order: 2.771, 2.791, 2.788, 2.784 s at
n = 30, 60, 120, 240), and a single change can be small by accident. So the twins are run at ⌊n/2⌋ and, where
it still draws the defect (SLICES_PER_WAVE = 8 slices per wavelength of its shortest wave, L/ν), at ⌊n/4⌋ (the
base run's solver, options and run; no twins of their own), with d₁ = q(n/2) − q(n/4), and

    E_n = SAFETY · abs(d₂)                   when d₁ d₂ > 0 and 1 ≤ log₂(d₁/d₂) ≤ MAX_ORDER (a power law of
                                             order 1 to 8: the changes shrink as the asymptotic regime's do),
    E_n = SAFETY · max(abs(d₁), abs(d₂))     otherwise (not monotone, slower than first order, a collapse of
                                             the last change too sudden for a power law, or an amplitude
                                             ratio of exactly 1 — the initial amplitude never exceeded — in
                                             one of the three),
    E_n = SAFETY · abs(d₂)                   without the twin at n/4,

SAFETY = 2 as in the uncertainty's numerical part: in the first-order regime E_n is twice Richardson's estimate.

For a sail that survives, the answer q = max_t r(t) of its amplitude ratio r(t) = a(t)/a(0) is a peak: the
first rise of the defect, or a recurrence, when the waves it excites come back into phase. Their frequencies
depend on n, so with n the recurrences move in time as well as in height, and the change of q between n/2 and n
can vanish by accident while the chain at 2n recurs higher (a seeded tension-stabilised chain: 1.0251, 1.0190,
1.0392, 1.0501 at n = 34, 68, 136, 272), or q is clipped at exactly 1 — the amplitude first falls, and its
recurrences stay just below the initial amplitude (0.977, 0.9995 at n = 45, 91) — while at 2n they pass it
(1.0143). So E_n of a largest amplitude ratio is at least the rise its recurrences may make above q. With
R(t) = max r(s) over t₀ ≤ s ≤ t, the largest recurrence up to t (t₀: the first sample from which r rises, its
first local minimum; R is the running maximum of the whole history when r rises from the start), each run's
own, and the twin at n/2's R_c compared at the same times t ≥ both t₀:

    E_rec = max(0, max_t [R(t) + SAFETY · abs(R(t) − R_c(t))] − q)

R(t) is the answer of the run stopped at t without its initial value, and its change R − R_c the change of that
answer with n, at every run length, not at t_final alone, and without the clip at 1. A recurrence far below q
adds nothing (a rigid sail's, 0.3–0.6 of the initial amplitude, cannot reach 1.0 within its error); one near q
adds its doubled change.
Without the twin at n/4, for a failure time whose fastest-growing wave sits at the grid scale (at most
GRID_SCALE_SLICES slices per wavelength, a case the verdict still calls well posed), E_n is at least the verdict's
spectral estimate t_f · abs(σ(n) − σ(2n))/σ(2n): there the one coarser twin carries even fewer of the waves that
grow. With the twin at n/4 the spectral estimate adds nothing the twins miss and is erratic (0.44 t_f on the soft
sail at n = 60, 28× its distance from the converged answer), so it is not used.

Measured (validation/n_error.md, validation/accuracy.md): against `converge`'s converged answers on the paper's
well-posed chains at n = 30–240 and seeded random cases at their own n, and against runs at 2n sampled 4× finer
on the 96 seeded cases of the accuracy report (and 64 more with the reduced solver alone): 31 of 31, 53 of 53 for
each solver, and 35 of 36. Without the recurrences' rise: 29 of 31, 51 of 53 and 34 of 36, every miss a surviving
membrane's largest amplitude ratio. The twin at n/4 is left out where it does not draw the defect (the soft
sail at n = 7 fails at 2.23 s, at n = 15 at 2.03 s, at n = 30 at 2.11 s: its answer says nothing of the run's).

The estimate is added to the run's uncertainty, U = SAFETY · (E_int + S) + E_s + E_n
(:mod:`lightsail_mbs.solvers.uncertainty`), and recorded in ``Result.uncertainty["n_error"]``. It is made only
when the uncertainty is estimated and the verdict says well posed: an ill-posed run keeps its one-line
verdict and gets no n-error (it has no continuum answer to be near), and a case the verdict does not assess
(sheets, supported chains, n above its limit) says so. When the twin at n/2 gives the other verdict (it
survives where the run fails, or the reverse), E_n is infinite: the verdict itself changes with n; a twin at
n/4 with the other verdict is too coarse to carry the answer and is left out.

Cost: the base run at n/2 and at n/4, about half and a quarter of a base run or less (a solver's cost grows
at least in proportion to n), on top of the 3–4 twin runs of the uncertainty estimate. They run where those run
(:mod:`lightsail_mbs.solvers.twin_workers`): in worker processes, started beside a long base run with the loose
twin's options as the solver declares them (`jobs`), or in this process after a short one.
"""

from __future__ import annotations

import math

import numpy as np

from lightsail_mbs import solvers
from lightsail_mbs.analysis import resolvedness
from lightsail_mbs.model import shapes
from lightsail_mbs.solvers import twin_workers

SAFETY = 2.0  # E_n = SAFETY · (the change the twins show), as U's numerical part
MIN_COARSE = 4  # a twin of fewer slices is not run
SLICES_PER_WAVE = 2 * shapes.MIN_SLICES_PER_HALF_WAVE  # the twin at n/4: at least this many per defect wave
MAX_ORDER = 8.0  # a faster collapse of the last change is no power law (studies.convergence.ORDER_MAX)
GRID_SCALE_SLICES = 2.5  # a fastest wave this short is the grid-scale zig-zag: the spectral estimate applies
RULE = (
    "; + E_n where well posed in n: 2 |q(n) − q(n/2)| when q(n/4), q(n/2), q(n) shrink as a power law of order 1–8 "
    "(or without the twin at n/4), else 2 max(|q(n) − q(n/2)|, |q(n/2) − q(n/4)|); without the twin at n/4, for "
    "a failure time at the grid scale, at least t_f δσ/σ; for a largest amplitude ratio, at least the rise its "
    "recurrences may make above it, max_t [R + 2 |R − R(n/2)|] − q (R(t): the running maximum of a(t)/a(0) from its "
    "first local minimum)"
)


def twin_sizes(params) -> list[int]:
    """The twins' numbers of slices (module docstring): ⌊n/2⌋ if at least MIN_COARSE, and ⌊n/4⌋ if it also
    carries SLICES_PER_WAVE slices per wavelength of the defect's shortest wave."""
    half, quarter = params.n // 2, params.n // 4
    if half < MIN_COARSE:
        return []
    if quarter >= max(MIN_COARSE, SLICES_PER_WAVE * shapes.shortest_mode(params, params.defect_mode)):
        return [half, quarter]
    return [half]


def estimate(value: float, half: float, quarter: float | None = None, ratio: bool = False) -> float:
    """E_n from q(n), q(n/2) and, if run and of the same kind, q(n/4) (module docstring); `ratio`: the answers
    are largest amplitude ratios (one of exactly 1 is clipped, not a power law's)."""
    last = value - half
    if quarter is None:
        return SAFETY * abs(last)
    before = half - quarter
    clipped = ratio and 1.0 in (value, half, quarter)
    if not clipped and last * before > 0 and abs(before) / 2**MAX_ORDER <= abs(last) <= abs(before) / 2:
        return SAFETY * abs(last)
    return SAFETY * max(abs(last), abs(before))


def recurrences(ratio: np.ndarray) -> np.ndarray:
    """R(t) of an amplitude-ratio history (module docstring): its running maximum from the first sample from which
    it rises (its first local minimum; the first sample when it rises from the start), NaN before."""
    ratio = np.asarray(ratio, float)
    rising = np.nonzero(np.diff(ratio) > 0)[0]
    start = int(rising[0]) if rising.size else ratio.size - 1
    late = np.full(ratio.shape, np.nan)
    late[start:] = np.maximum.accumulate(ratio[start:])
    return late


def recurrence_rise(time, amplitude, coarse_time, coarse_amplitude) -> float:
    """E_rec (module docstring): how far the recurrences of a sail that survives, its amplitude history
    (`time`, `amplitude`) at n against the twin's at n/2, may rise above its largest amplitude ratio."""
    ratio = np.asarray(amplitude, float) / amplitude[0]
    coarse = np.interp(time, coarse_time, np.asarray(coarse_amplitude, float) / coarse_amplitude[0])
    late, coarse_late = recurrences(ratio), recurrences(coarse)
    both = np.isfinite(late) & np.isfinite(coarse_late)
    if not both.any():
        return 0.0
    reach = late[both] + SAFETY * np.abs(late[both] - coarse_late[both])
    return max(0.0, float(reach.max() - ratio.max()))


def spectral_floor(verdict: dict, value: float, failed: bool) -> float:
    """The verdict's spectral n-error t_f δσ/σ for a failure time whose fastest wave is at the grid scale (at most
    GRID_SCALE_SLICES slices per wavelength), else 0 (module docstring)."""
    slices, relative = verdict.get("slices_per_wavelength"), verdict.get("relative_n_error")
    if not failed or slices is None or relative is None or slices > GRID_SCALE_SLICES:
        return 0.0
    return value * relative


def why_not(params, result) -> str | None:
    """Why no n-error is estimated for `result`, or None."""
    verdict = result.info.get("resolvedness") or {}
    if not verdict.get("assessed"):
        return verdict.get("reason") or "the case's resolvedness in n is not assessed"
    if not verdict.get("well_posed"):
        return "ill-posed in n: the answer has no continuum limit to be near"
    if not twin_sizes(params):
        return f"n = {params.n} is too small for a twin at n/2 (at least {MIN_COARSE} slices)"
    return None


def job(params, size: int, solver: str, settings, options: dict, progress: bool) -> twin_workers.Job:
    """The twin at `size` slices: the base run's solver, settings and `options` (the reference run's), alone."""
    twin = params.replace(n=size)
    identity = ("n-twin", twin, solver, settings, progress, options)
    work = twin_workers.job(
        identity, solvers.solve, twin, solver, settings, progress=progress, uncertainty=False, **options
    )
    work.answer_only = True  # fold reads its answer, time and amplitude history
    return work


def jobs(params, solver: str, settings, options: dict, progress: bool) -> list[twin_workers.Job]:
    """The n-twins `fold` will ask for when the run has an uncertainty estimate and `options` are its reference
    run's (for twin_workers.Session.extra: started beside the base run); none where `why_not` holds for any run."""
    try:
        verdict = resolvedness.assess(params)
    except Exception:  # noqa: BLE001 - not assessed: fold says why; nothing to start
        return []
    if not verdict.well_posed:
        return []
    return [job(params, size, solver, settings, options, progress) for size in twin_sizes(params)]


def fold(params, solver: str, settings, options: dict, result, progress: bool = False) -> None:
    """Estimate the n-error of `result` (a run of `solver` with `options`, its uncertainty estimated and its
    resolvedness verdict recorded) from its twins at n/2 and n/4, record it in ``result.uncertainty["n_error"]``
    and add it to ``result.uncertainty["uncertainty"]`` (module docstring). The twins run at the options of the
    run the estimate names as its reference (``result.uncertainty["reference"]``: the loose twin, or the base
    run), and their answers are compared with that run's. Does nothing for a run without an estimate."""
    record = result.uncertainty
    if not record or not record.get("estimated"):
        return
    reason = why_not(params, result)
    if reason is not None:
        record["n_error"] = {"estimated": False, "reason": reason}
        return
    reference = record[record.get("reference", "base")]
    twins, histories, wall, cpu = {}, {}, 0.0, 0.0
    workers = twin_workers.current()
    jobs = {size: job(params, size, solver, settings, reference["options"], progress) for size in twin_sizes(params)}
    for work in jobs.values():
        workers.submit(work)
    for size, work in jobs.items():
        twin, twin_cpu = workers.take(work)
        wall, cpu = wall + twin.wall_time, cpu + twin_cpu
        if twin.error is not None:
            record["n_error"] = {"estimated": False, "reason": f"the twin at n = {size} ended with {twin.error}"}
            result.wall_time += wall
            return
        failed = twin.failed
        twins[size] = (float(twin.failure_time) if failed else float(twin.max_amplitude_ratio), failed)
        histories[size] = (twin.time, twin.amplitude)
    sizes = sorted(twins, reverse=True)
    (half, half_failed), quarter = twins[sizes[0]], twins.get(sizes[-1]) if len(sizes) > 1 else None
    rise = None
    if half_failed != reference["failed"]:
        error = math.inf
    else:
        usable = quarter is not None and quarter[1] == reference["failed"]
        error = estimate(reference["value"], half, quarter[0] if usable else None, ratio=not reference["failed"])
        if not usable:
            error = max(error, spectral_floor(result.info["resolvedness"], reference["value"], reference["failed"]))
        if not reference["failed"]:
            rise = recurrence_rise(result.time, result.amplitude, *histories[sizes[0]])
            error = max(error, rise)
    record["n_error"] = {
        "estimated": True,
        "value": error,
        "n_coarse": sizes[0],
        "coarse_failed": half_failed,
        "recurrence_rise": rise,
        "twins": {str(size): {"value": value, "failed": failed} for size, (value, failed) in twins.items()},
        "wall_time": wall,
        "cpu_time": cpu,
    }
    record["uncertainty_numerics"] = record["uncertainty"]
    record["uncertainty"] = record["uncertainty"] + error
    record["rule"] = record["rule"] + RULE
    result.wall_time += wall
