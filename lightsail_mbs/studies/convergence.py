"""Convergence of a run's answer in the number of slices n: is the chain fine enough to answer the question?

A chain of n slices is a discretisation of the sail; its answer — the failure time t_f, or for a sail
that survives the run the largest amplitude ratio max a(t)/a₀ — moves with n. :func:`converge` runs one
case at increasing n (reduced solver) and reports, per n:

* the answer and its change from the previous n;
* the tolerance noise: the change of the answer when the run is repeated at a ten times tighter rtol
  (the solver's own error, amplified by the instability; a change in n below it is not resolved);
* the method, steps and CPU time of the run.

Fit (:func:`power_law_fit`): through the last three sizes n₁ < n₂ < n₃, a power law
t(n) = t_∞ + C n^(−p). With d₁ = t(n₂) − t(n₁), d₂ = t(n₃) − t(n₂) the order p solves

    d₁/d₂ = (n₁^(−p) − n₂^(−p)) / (n₂^(−p) − n₃^(−p))

(p = log₂(d₁/d₂) for doubling sizes; found by bisection otherwise), then C = d₂/(n₃^(−p) − n₂^(−p)),
t_∞ = t(n₃) − C n₃^(−p), and the n needed for 1 %, |C| n^(−p) ≤ 0.01 |t_∞|: n₁% = (|C|/(0.01 |t_∞|))^(1/p).
The fit is refused ("not converging", with no limit and no n for 1 %) when d₁ and d₂ differ in sign or
|d₂| ≥ |d₁| (the changes do not shrink); when the answers over the last four sizes are not monotone in n (a
power law is, and the size before the fitted three tests it); when the order is above ORDER_MAX (absurd for a
chain whose slices converge at second or fourth order); when the extrapolation abs(t_∞ − t(n₃)) exceeds the change
abs(t(n₃) − t(n₁)) already seen over the fitted sizes (for doubling sizes: p < 1/2, a limit the data do not
support); and when the limit is unphysical (a failure time ≤ 0, an amplitude ratio below 1). The answer is
called converged to the noise when |d₂| is below the tolerance noise. Beside an accepted fit, the direct
reading: the smallest n from which every finer answer stays within 1 % of the finest one.

A sheet (model "sheet") is refined in both directions: n tiles along L and, for ny > 1, ny = round(n W/L)
across (square tiles); a sheet of one row (ny = 1) stays one row. Its in-house solver has one method
(Radau), so the tolerance-noise run repeats it at rtol/10.

Every run carries the resolvedness verdict of :mod:`lightsail_mbs.analysis.resolvedness` (the growth-rate
spectrum at its initial state, at n and 2n). The study is ill-posed in n when the verdict at its largest
assessed size says so: the fastest-growing wave sits at the grid scale, a finer chain adds faster-growing
waves and the failure time falls once they outgrow the defect — a falling (or still rising) sequence can
mimic a slow power law, so no fit is offered; the verdict says which way the failure time moved. Where no
size is assessed (sheets, n above the verdict's limit) a chain or sheet without bending stiffness is
flagged, as every wavelength down to the slice is then unstable under a compressive load.
Whether such a sail survives can still be robust in n.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model.parameters import SailParameters

ONE_PERCENT = 0.01
DEFAULT_FACTOR = 2.0
ORDER_MAX = 8.0  # a fitted order above this is absurd for the chain's second- and fourth-order errors
MONOTONE_SIZES = 4  # the fit's three sizes and the one before must give answers monotone in n
CONVERGED = ("power law", "converged to the tolerance noise")


@dataclass
class ConvergenceRow:
    """One n of a convergence study.

    Parameters
    ----------
    n : int
        Number of slices.
    value : float or None
        The answer: the failure time (s) when the run failed, else the largest amplitude ratio
        (None if the run ended in a solver error before either).
    kind : str
        "failure_time" or "max_amplitude_ratio".
    change : float or None
        value − the previous n's value (same kind), None for the first.
    tolerance_noise : float or None
        abs(value at rtol/10 − value) (None when not measured).
    method : str
        The reduced solver's integrator at this n (Result.info["method"]).
    steps : int
        Accepted steps of the run.
    cpu_time : float
        CPU time of the run at the default tolerance (s, this process).
    error : str or None
        A solver failure, recorded.
    ny : int or None
        Tiles across the width (a sheet), None for a chain.
    resolvedness : dict or None
        The run's resolvedness verdict (Result.info["resolvedness"]: well_posed, growth_rate,
        slices_per_wavelength, …).
    """

    n: int
    value: float | None
    kind: str
    change: float | None
    tolerance_noise: float | None
    method: str
    steps: int
    cpu_time: float
    error: str | None = None
    ny: int | None = None
    resolvedness: dict | None = None

    @property
    def size(self) -> str:
        """'n' of a chain, 'n×ny' of a sheet."""
        return str(self.n) if self.ny is None else f"{self.n}×{self.ny}"


@dataclass
class PowerLawFit:
    """t(n) = limit + C n^(−order) through the last three sizes (module docstring); None fields when refused.

    Parameters
    ----------
    limit : float or None
        t_∞, the extrapolated answer.
    order : float or None
        p, the order of convergence in n.
    n_for_one_percent : float or None
        n at which abs(t(n) − t_∞) = 1 % of abs(t_∞).
    verdict : str
        "power law", "converged to the tolerance noise", "not converging (…)", "not converging: ill-posed in n
        (…)" or "fewer than three sizes".
    """

    limit: float | None
    order: float | None
    n_for_one_percent: float | None
    verdict: str


@dataclass
class ConvergenceStudy:
    """The rows of a study, the fit, the direct reading of n for 1 % and the case."""

    params: SailParameters
    settings: RunSettings
    rows: list[ConvergenceRow]
    fit: PowerLawFit
    empirical_n_for_one_percent: int | None
    ill_posed: bool
    notes: list[str] = field(default_factory=list)

    @property
    def tolerance_noise(self) -> float | None:
        """The largest tolerance noise of the rows (None when not measured)."""
        noises = [r.tolerance_noise for r in self.rows if r.tolerance_noise is not None]
        return max(noises) if noises else None

    def to_dict(self) -> dict:
        return {
            "parameters": self.params.to_dict(),
            "settings": self.settings.to_dict(),
            "rows": [asdict(r) for r in self.rows],
            "fit": asdict(self.fit),
            "empirical_n_for_one_percent": self.empirical_n_for_one_percent,
            "ill_posed": self.ill_posed,
            "tolerance_noise": self.tolerance_noise,
            "notes": self.notes,
        }


def geometric_sizes(n_start: int, n_max: int, factor: float = DEFAULT_FACTOR) -> list[int]:
    """n_start, n_start·factor, … (rounded) up to n_max, with n_max itself last when the sequence misses it."""
    if n_start < 2:
        raise ParameterError(f"n_start={n_start!r} is invalid: allowed ≥ 2")
    if n_max < n_start:
        raise ParameterError(f"n_max={n_max!r} is invalid: allowed ≥ n_start={n_start}")
    if not factor > 1:
        raise ParameterError(f"factor={factor!r} is invalid: allowed > 1")
    sizes, n = [], float(n_start)
    while round(n) <= n_max:
        if not sizes or round(n) > sizes[-1]:
            sizes.append(round(n))
        n *= factor
    if sizes[-1] != n_max and n_max / sizes[-1] > math.sqrt(factor):
        sizes.append(n_max)
    return sizes


def answer(result) -> tuple[float | None, str]:
    """(value, kind) of a run: its failure time if it failed, else its largest amplitude ratio."""
    if result.failure_time is not None:
        return result.failure_time, "failure_time"
    if result.error:
        return None, "max_amplitude_ratio"
    return result.max_amplitude_ratio, "max_amplitude_ratio"


def _order_equation(p: float, n1: float, n2: float, n3: float) -> float:
    return (n1**-p - n2**-p) / (n2**-p - n3**-p)


def power_law_fit(sizes, values, noise: float = 0.0, kind: str = "failure_time") -> PowerLawFit:
    """The three-point power-law fit of the module docstring through the last three (n, value), refused when
    the changes do not shrink, the last four values are not monotone, or the fit is unphysical (`kind`: the
    answer's kind, "failure_time" or "max_amplitude_ratio")."""
    if len(values) < 3 or any(v is None for v in values[-3:]):
        return PowerLawFit(None, None, None, "fewer than three sizes")
    (n1, n2, n3), (t1, t2, t3) = sizes[-3:], values[-3:]
    d1, d2 = t2 - t1, t3 - t2
    if abs(d2) <= noise:
        return PowerLawFit(t3, None, None, "converged to the tolerance noise")
    if d1 * d2 <= 0 or abs(d2) >= abs(d1):
        return PowerLawFit(None, None, None, "not converging (the changes do not shrink)")
    recent = values[-MONOTONE_SIZES:]
    steps = [b - a for a, b in zip(recent, recent[1:])]
    if None in recent or any(step * steps[-1] <= 0 for step in steps):
        shown = ", ".join(f"{v:.4g}" for v in recent if v is not None)
        return PowerLawFit(None, None, None, f"not converging (not monotone in n: {shown})")
    ratio = d1 / d2
    lo, hi = 1e-6, 1.0
    if _order_equation(lo, n1, n2, n3) >= ratio:
        return PowerLawFit(None, None, None, "not converging (slower than any power law)")
    while _order_equation(hi, n1, n2, n3) < ratio and hi < 64:
        lo, hi = hi, 2 * hi
    if _order_equation(hi, n1, n2, n3) < ratio:
        return PowerLawFit(None, None, None, "not converging (order above 64)")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if _order_equation(mid, n1, n2, n3) < ratio:
            lo = mid
        else:
            hi = mid
    p = 0.5 * (lo + hi)
    c = d2 / (n3**-p - n2**-p)
    limit = t3 - c * n3**-p
    refused = unphysical_fit(limit, p, values[-3:], kind)
    if refused:
        return PowerLawFit(None, None, None, f"not converging ({refused})")
    n_one = (abs(c) / (ONE_PERCENT * abs(limit))) ** (1 / p) if limit != 0 else None
    return PowerLawFit(limit, p, n_one, "power law")


def unphysical_fit(limit: float, order: float, fitted, kind: str) -> str | None:
    """Why a fitted limit and order are not to be believed (module docstring), or None."""
    if order > ORDER_MAX:
        return f"fitted order p = {order:.3g} is above {ORDER_MAX:g}"
    if abs(limit - fitted[-1]) > abs(fitted[-1] - fitted[0]):
        return (
            f"the fitted limit {limit:.4g} lies further from the finest answer than the fitted answers span "
            f"(order p = {order:.2g})"
        )
    if kind == "failure_time" and limit <= 0:
        return f"unphysical fit: a failure time of {limit:.4g} s"
    if kind == "max_amplitude_ratio" and limit < 1:
        return f"unphysical fit: an amplitude ratio of {limit:.4g} below 1"
    return None


def empirical_n_for_one_percent(sizes, values) -> int | None:
    """The smallest n from which every finer value stays within 1 % of the finest one."""
    if len(values) < 2 or values[-1] is None:
        return None
    finest = values[-1]
    found = None
    for n, v in zip(reversed(sizes), reversed(values)):
        if v is None or abs(v - finest) > ONE_PERCENT * abs(finest):
            break
        found = n
    return found


def converge(
    params: SailParameters,
    settings: RunSettings,
    sizes,
    *,
    noise: bool = True,
    budget: float | None = None,
    progress=None,
    **options,
) -> ConvergenceStudy:
    """Run the case at each n of `sizes` (increasing) with the reduced solver; rows, fit and verdict.

    Parameters
    ----------
    params : SailParameters
        The case; its n is replaced by each size.
    settings : RunSettings
        The run (the answer is its failure time, or the largest amplitude ratio over it).
    sizes : sequence of int
        The numbers of slices, increasing (e.g. :func:`geometric_sizes`).
    noise : bool
        Repeat every run at a ten times tighter rtol to measure the tolerance noise.
    budget : float, optional
        Stop before the next size once one run has taken more than budget/4 CPU seconds (the next one
        would take about 2–4× longer).
    progress : callable, optional
        Called with each ConvergenceRow as it is finished.
    **options
        Options of the reduced solver (rtol, method, …).
    """
    from lightsail_mbs.analysis.runs import solve
    from lightsail_mbs.solvers.contract import lookup

    sizes = [int(n) for n in sizes]
    if len(sizes) < 1 or any(b <= a for a, b in zip(sizes, sizes[1:])) or sizes[0] < 2:
        raise ParameterError(f"sizes={sizes!r} is invalid: allowed increasing numbers of slices ≥ 2")
    if budget is not None and not budget > 0:
        raise ParameterError(f"budget={budget!r} is invalid: allowed > 0 (CPU seconds)")
    is_sheet = params.model == "sheet"
    if is_sheet and "method" in options:
        if options["method"] not in (None, "auto"):
            raise ParameterError(f"method={options['method']!r} is invalid for a sheet: its solver is Radau only")
        options = {k: v for k, v in options.items() if k != "method"}
    rows: list[ConvergenceRow] = []
    notes: list[str] = []
    for n in sizes:
        ny = (1 if params.ny == 1 else max(1, round(n * params.width / params.length))) if is_sheet else None
        case = params.replace(n=n, ny=ny) if is_sheet else params.replace(n=n)
        start = time.process_time()
        result = solve(case, "reduced", settings, uncertainty=False, **options)
        cpu = time.process_time() - start
        value, kind = answer(result)
        method = result.info.get("method", "Radau" if is_sheet else "")
        tolerance_noise = None
        if noise and value is not None:
            rtol = options.get("rtol") or result.info.get("rtol")
            rtol = rtol or lookup("reduced", case).default_options(case, settings, **options)["rtol"]
            tight_options = (
                {**options, "rtol": rtol / 10} if is_sheet else {**options, "method": method, "rtol": rtol / 10}
            )
            tight = solve(case, "reduced", settings, uncertainty=False, **tight_options)
            tight_value, tight_kind = answer(tight)
            if tight_value is not None and tight_kind == kind:
                tolerance_noise = abs(tight_value - value)
            else:
                tolerance_noise = math.inf
                notes.append(f"n = {n}: the run at rtol/10 gives a different kind of answer ({tight_kind})")
        previous = rows[-1] if rows else None
        change = None
        if previous is not None and previous.value is not None and value is not None and previous.kind == kind:
            change = value - previous.value
        row = ConvergenceRow(n, value, kind, change, tolerance_noise, method, result.info.get("steps", 0), cpu, ny=ny)
        row.error, row.resolvedness = result.error, result.info.get("resolvedness")
        rows.append(row)
        if progress is not None:
            progress(row)
        if result.error:
            notes.append(f"n = {n}: {result.error}; the study stops here")
            break
        if budget is not None and cpu > budget / 4 and n != sizes[-1]:
            notes.append(f"stopped after n = {n}: its run took {cpu:.3g} s CPU, over a quarter of the budget")
            break
    kinds = {r.kind for r in rows[-3:]}
    values = [r.value for r in rows]
    ill_posed, why = ill_posed_in_n(params, rows)
    if ill_posed:
        fit = PowerLawFit(None, None, None, f"not converging: ill-posed in n ({why}; {ill_posed_trend(rows)})")
    elif len(kinds) > 1:
        fit = PowerLawFit(None, None, None, "not converging (fails at some n, survives at others)")
    else:
        noises = [r.tolerance_noise for r in rows[-2:] if r.tolerance_noise is not None]
        fit = power_law_fit([r.n for r in rows], values, max(noises) if noises else 0.0, rows[-1].kind)
    converged = len(kinds) == 1 and fit.verdict in CONVERGED
    empirical = empirical_n_for_one_percent([r.n for r in rows], values) if converged else None
    return ConvergenceStudy(params, settings, rows, fit, empirical, ill_posed, notes)


def ill_posed_trend(rows: list[ConvergenceRow]) -> str:
    """How the answer of an ill-posed study moves with n, read from its rows: the failure time falling (or
    rising) at every refinement of the last three sizes, or neither."""
    last = rows[-3:]
    changes = [r.change for r in last[1:]]
    if not changes or any(r.kind != "failure_time" for r in last) or None in changes:
        return "answer is not a limit"
    if all(c < 0 for c in changes):
        return "failure time keeps falling"
    if all(c > 0 for c in changes):
        return "failure time still rising over these sizes"
    return "failure time moves both ways"


def ill_posed_in_n(params: SailParameters, rows: list[ConvergenceRow]) -> tuple[bool, str]:
    """(ill-posed?, why) from the resolvedness verdict of the largest assessed size (module docstring); without
    one, from the bending stiffness."""
    assessed = [r for r in rows if r.resolvedness and r.resolvedness.get("assessed")]
    if assessed:
        row = assessed[-1]
        verdict = row.resolvedness
        if verdict["well_posed"]:
            return False, ""
        return True, (
            f"at n = {row.size} the fastest-growing wave sits at the grid scale: "
            f"{verdict['slices_per_wavelength']:.3g} slices per wavelength, growth rate "
            f"{verdict['growth_rate']:.3g} /s, {verdict['rate_ratio']:.3g}× at 2n"
        )
    stiffness = params.youngs_modulus if params.model == "sheet" else params.torsional_stiffness
    if stiffness == 0.0:
        return True, "no bending stiffness: every wavelength down to l is unstable"
    return False, ""


def _fmt(value, spec: str = ".6g") -> str:
    if value is None:
        return "—"
    if isinstance(value, float) and math.isinf(value):
        return "∞"
    return format(value, spec)


def wave_text(verdict: dict | None) -> str:
    """A row's resolvedness verdict in a table cell: the fastest-growing wave and whether it is resolved."""
    if not verdict or not verdict.get("assessed"):
        return "not assessed"
    if not verdict["growth_rate"]:
        return "none grows"
    state = "well posed" if verdict["well_posed"] else "grid scale: ill-posed"
    if verdict["well_posed"] and verdict.get("resolved") is False:  # the run's warning: not resolved in n
        state = "well posed, not resolved"
    return f"{verdict['slices_per_wavelength']:.3g} sl., σ = {verdict['growth_rate']:.3g} /s ({state})"


def markdown_table(study: ConvergenceStudy) -> str:
    """The rows of a study as a Markdown table, then the fit and the verdict."""
    unit = {"failure_time": "t_f (s)", "max_amplitude_ratio": "max a/a₀"}
    lines = [
        "| n | answer | value | change vs previous n | tolerance noise | fastest-growing wave | method | steps "
        "| CPU (s) |",
        "|---:|---|---:|---:|---:|---|---|---:|---:|",
    ]
    for r in study.rows:
        lines.append(
            f"| {r.size} | {unit[r.kind]} | {_fmt(r.value)} | {_fmt(r.change, '+.2e')} "
            f"| {_fmt(r.tolerance_noise, '.1e')} | {wave_text(r.resolvedness)} | {r.method} | {r.steps} "
            f"| {r.cpu_time:.3g} |"
        )
    fit = study.fit
    noise = f"largest tolerance noise {_fmt(study.tolerance_noise, '.1e')}."
    lines.append("")
    if fit.verdict in CONVERGED:
        lines.append(
            f"Fit: {fit.verdict}; limit {_fmt(fit.limit)}, order p = {_fmt(fit.order, '.2f')}, "
            f"n for 1 % (fit) = {_fmt(fit.n_for_one_percent, '.0f')}, "
            f"n for 1 % (within 1 % of the finest from there on) = {_fmt(study.empirical_n_for_one_percent)}; " + noise
        )
    else:
        lines.append(f"Fit: {fit.verdict}: no limit and no n for 1 % are given; " + noise)
    lines.extend(f"Note: {note}" for note in study.notes)
    return "\n".join(lines)
