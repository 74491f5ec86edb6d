"""The error in n of a single run: two coarser twins and Richardson's estimate, folded into the run's ±.

A chain of n slices answers q(n) (the failure time, or the largest amplitude ratio of a sail that survives).
Where the case is well posed in n (:mod:`lightsail_mbs.analysis.resolvedness`), q(n) tends to a continuum
answer q_∞ as n grows; in the asymptotic regime q(n) = q_∞ + C n^(−p), so a twin at n_c < n gives

    q(n) − q_∞ = (q(n_c) − q(n)) / ((n/n_c)^p − 1)                                   (Richardson)

For a halved n and p = 1 this is the last change d₂ = q(n) − q(n/2). The order is not assumed higher than 1:
`converge` measures p = 0.92–1.00 on the paper's stiff and stable torsion sails and at E = E_cr,max, 2.2 on
the soft one (docs/convergence.md). Below the asymptotic regime the answers need not be monotone in n (at
E = E_cr,max the answer rises to a peak near n = 60 and then falls at first order: 2.771, 2.791, 2.788, 2.784 s at
n = 30, 60, 120, 240), and a single change can be small by accident. So two twins are run, at ⌊n/2⌋ and
⌊n/4⌋ (the base run's solver, options and run; no twins of their own), with d₁ = q(n/2) − q(n/4), and

    E_n = SAFETY · abs(d₂)                   when d₁ d₂ > 0 and abs(d₂) ≤ abs(d₁)/2 (monotone, order ≥ 1),
    E_n = SAFETY · max(abs(d₁), abs(d₂))     otherwise (not monotone, or slower than first order),

SAFETY = 2 as in the uncertainty's numerical part. In the first-order regime E_n is twice Richardson's estimate;
where the order is higher it overstates the error by 2 (2^p − 1). The twin at n/4 is run only where it carries
SLICES_PER_WAVE = 8 slices per wavelength of the defect's shortest wave (L/ν; a coarser chain does not draw the
defect, and its answer says nothing of the run's: the soft sail at n = 7 fails at 2.23 s); without it, and where
⌊n/4⌋ is below MIN_COARSE slices, E_n = SAFETY · abs(d₂) from the twin at n/2 alone. Measured against
`converge`'s answers (validation/n_error.md: the paper's well-posed chains at n = 30–240 and seeded random cases
at their own n), and against runs at 2n sampled 4× finer (validation/accuracy.md).

The estimate is added to the run's uncertainty, U = SAFETY · (E_int + S) + E_s + E_n
(:mod:`lightsail_mbs.solvers.uncertainty`), and recorded in ``Result.uncertainty["n_error"]``. It is made only
when the uncertainty is estimated and the verdict says well posed: an ill-posed run keeps its one-line
verdict and gets no n-error (it has no continuum answer to be near), and a case the verdict does not assess
(sheets, supported chains, n above its limit) says so. When the twin at n/2 gives the other verdict (it
survives where the run fails, or the reverse), E_n is infinite: the verdict itself changes with n; a twin at
n/4 with the other verdict is too coarse to carry the answer and is left out.

Cost: the base run at n/2 and at n/4, about half and a quarter of a base run or less (a solver's cost grows
at least in proportion to n), on top of the 3–8 runs of the uncertainty estimate.
"""

from __future__ import annotations

import math

from lightsail_mbs import solvers
from lightsail_mbs.model import shapes

SAFETY = 2.0  # E_n = SAFETY · (the change the twins show), as U's numerical part
MIN_COARSE = 4  # a twin of fewer slices is not run
SLICES_PER_WAVE = 2 * shapes.MIN_SLICES_PER_HALF_WAVE  # the twin at n/4: at least this many per defect wave
RULE = (
    "; + E_n where well posed in n: 2 |q(n) − q(n/2)| when q(n/4), q(n/2), q(n) are monotone with the last change at "
    "most half the one before, else 2 max(|q(n) − q(n/2)|, |q(n/2) − q(n/4)|)"
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


def estimate(value: float, half: float, quarter: float | None = None) -> float:
    """E_n from q(n), q(n/2) and, if run and of the same kind, q(n/4) (module docstring)."""
    last = value - half
    if quarter is None:
        return SAFETY * abs(last)
    before = half - quarter
    if last * before > 0 and abs(last) <= abs(before) / 2:
        return SAFETY * abs(last)
    return SAFETY * max(abs(last), abs(before))


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


def fold(params, solver: str, settings, options: dict, result, progress: bool = False) -> None:
    """Estimate the n-error of `result` (a run of `solver` with `options`, its uncertainty estimated and its
    resolvedness verdict recorded) from its twins at n/2 and n/4, record it in ``result.uncertainty["n_error"]``
    and add it to ``result.uncertainty["uncertainty"]`` (module docstring). Does nothing for a run without an
    estimate."""
    record = result.uncertainty
    if not record or not record.get("estimated"):
        return
    reason = why_not(params, result)
    if reason is not None:
        record["n_error"] = {"estimated": False, "reason": reason}
        return
    base = record["base"]
    twins, wall = {}, 0.0
    for size in twin_sizes(params):
        twin = solvers.solve(params.replace(n=size), solver, settings, progress=progress, uncertainty=False, **options)
        wall += twin.wall_time
        if twin.error is not None:
            record["n_error"] = {"estimated": False, "reason": f"the twin at n = {size} ended with {twin.error}"}
            result.wall_time += wall
            return
        failed = twin.failed
        twins[size] = (float(twin.failure_time) if failed else float(twin.max_amplitude_ratio), failed)
    sizes = sorted(twins, reverse=True)
    (half, half_failed), quarter = twins[sizes[0]], twins.get(sizes[-1]) if len(sizes) > 1 else None
    if half_failed != base["failed"]:
        error = math.inf
    else:
        usable = quarter is not None and quarter[1] == base["failed"]
        error = estimate(base["value"], half, quarter[0] if usable else None)
    record["n_error"] = {
        "estimated": True,
        "value": error,
        "n_coarse": sizes[0],
        "coarse_failed": half_failed,
        "twins": {str(size): {"value": value, "failed": failed} for size, (value, failed) in twins.items()},
        "wall_time": wall,
    }
    record["uncertainty_numerics"] = record["uncertainty"]
    record["uncertainty"] = record["uncertainty"] + error
    record["rule"] = record["rule"] + RULE
    result.wall_time += wall
