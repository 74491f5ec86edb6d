"""Stability boundaries by bracketing and bisection, every evaluation a case of a resumable sweep.

For a one-parameter family of cases ``make_params(value)`` (e.g. the Young's modulus at a given
thickness) the boundary between stable and failed runs is bracketed — the bracket grows
geometrically (its log-width doubles per step) until its ends differ — then bisected in log space
until ``hi / lo ≤ factor``. Several boundaries advance at once on one
:class:`~lightsail_mbs.sweep.Sweep`, each taking its next step as soon as its own cases are back, so
all cores (or a cluster) stay busy; every case goes through the store, so a rerun finds every case it
already computed and a killed bisection resumes without recomputing (the path of each boundary depends
only on its own outcomes). With ``points_per_round = k`` each step evaluates k interior points at
once, shrinking the bracket's log-width k + 1 times — for clusters with more workers than boundaries.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.studies.sweep import Case, Sweep, solve_case


def default_stable(record: dict) -> bool | None:
    """Stable when the run did not fail; a solver error is "unknown" (None) unless the run had
    already failed (amplitude ≥ failure_ratio · a₀) before it."""
    if record.get("failed") is True:
        return False
    if record["status"] == "error":
        return None
    return not record["failed"]


@dataclass
class Boundary:
    """One bisected boundary: ``stable_value`` and ``unstable_value`` bracket it.

    status: "converged" (bracket ≤ factor wide), "unbracketed" (no sign change within
    ``max_expansions`` expansions) or "error" (a case's stability could not be decided).
    evaluations: (value, stable, key) in the order evaluated; ``monotone`` False if a step saw
    more than one stable/unstable change (then the change nearest the lower end was kept).
    """

    label: object
    stable_value: float | None = None
    unstable_value: float | None = None
    status: str = "running"
    message: str = ""
    monotone: bool = True
    steps: int = 0
    evaluations: list = field(default_factory=list)

    @property
    def bracket(self) -> tuple[float, float] | None:
        if self.stable_value is None or self.unstable_value is None:
            return None
        return tuple(sorted((self.stable_value, self.unstable_value)))

    @property
    def value(self) -> float | None:
        """The boundary estimate: geometric mean of the bracket (log bisection)."""
        b = self.bracket
        return None if b is None else math.sqrt(b[0] * b[1])


@dataclass
class BoundaryProblem:
    """The family ``make_params(value)`` and an initial guess ``lo < hi`` (both > 0)."""

    make_params: Callable
    lo: float
    hi: float


class _Search:
    """State of one bracketing/bisection; asks for values and takes their stability."""

    def __init__(self, label, problem: BoundaryProblem, *, factor, log, stable_above, points_per_round, max_expansions):
        if not (0 < problem.lo < problem.hi and math.isfinite(problem.hi)):
            raise ParameterError(
                f"bracket ({problem.lo!r}, {problem.hi!r}) of {label!r} is invalid: allowed 0 < lo < hi < inf"
            )
        self.problem, self.factor, self.log = problem, factor, log
        self.stable_above, self.k, self.max_expansions = stable_above, points_per_round, max_expansions
        self.lo, self.hi = float(problem.lo), float(problem.hi)
        self.s_lo = self.s_hi = None
        self.expansions = 0
        self.out = Boundary(label)

    def _between(self, fraction: float) -> float:
        if self.log:
            return self.lo * (self.hi / self.lo) ** fraction
        return self.lo + (self.hi - self.lo) * fraction

    def wanted(self) -> list[float]:
        if self.out.status != "running":
            return []
        if self.s_lo is None or self.s_hi is None:
            return [v for v, s in ((self.lo, self.s_lo), (self.hi, self.s_hi)) if s is None]
        if self.s_lo == self.s_hi:  # not bracketed: step outward, doubling the (log-)width
            below = self.s_lo == self.stable_above
            value = self._between(-2.0) if below else self._between(3.0)
            if value <= 0:
                self.stop("unbracketed", f"{'stable' if self.s_lo else 'unstable'} down to {self.lo:.6g}")
                return []
            return [value]
        return [self._between(j / (self.k + 1)) for j in range(1, self.k + 1)]

    def take(self, values: list[float], stable: list[bool | None], keys: list[str], errors: list[str | None]) -> None:
        self.out.steps += 1
        self.out.evaluations += list(zip(values, stable, keys))
        for v, s, e in zip(values, stable, errors):
            if s is None:
                self.stop("error", f"stability unknown at {v:.6g}: {e}")
                return
        if self.s_lo is None or self.s_hi is None:
            known = dict(zip(values, stable))
            self.s_lo = known.get(self.lo, self.s_lo)
            self.s_hi = known.get(self.hi, self.s_hi)
        elif self.s_lo == self.s_hi:
            v, s = values[0], stable[0]
            if v < self.lo:
                self.lo, self.hi, self.s_lo, self.s_hi = v, self.lo, s, self.s_lo
            else:
                self.lo, self.hi, self.s_lo, self.s_hi = self.hi, v, self.s_hi, s
            self.expansions += 1
        else:
            points = [(self.lo, self.s_lo), *zip(values, stable), (self.hi, self.s_hi)]
            changes = [i for i in range(1, len(points)) if points[i][1] != points[i - 1][1]]
            self.out.monotone &= len(changes) == 1
            i = changes[0]
            (self.lo, self.s_lo), (self.hi, self.s_hi) = points[i - 1], points[i]
        if self.s_lo is None or self.s_hi is None:
            return
        if self.s_lo != self.s_hi:
            self._record_bracket()
            if self.hi / self.lo <= self.factor:
                self.stop("converged", "")
        elif self.expansions >= self.max_expansions:
            self.stop(
                "unbracketed",
                f"{'stable' if self.s_lo else 'unstable'} over "
                f"[{self.lo:.6g}, {self.hi:.6g}] after {self.expansions} expansions",
            )

    def remaining(self) -> int:
        """A guess of the evaluations still to come (for the progress bar's total and ETA)."""
        if self.out.status != "running":
            return 0
        known = self.s_lo is not None and self.s_hi is not None
        outward = known and self.s_lo == self.s_hi
        ratio = (self.hi / self.lo) ** (2 if outward else 1) if self.log else self.hi / self.lo
        steps = math.ceil(math.log(max(math.log(ratio) / math.log(self.factor), 1.0)) / math.log(self.k + 1))
        return (0 if known else 2) + outward + self.k * steps

    def _record_bracket(self) -> None:
        if self.s_lo != self.s_hi:
            self.out.stable_value, self.out.unstable_value = (self.lo, self.hi) if self.s_lo else (self.hi, self.lo)

    def stop(self, status: str, message: str) -> None:
        self.out.status, self.out.message = status, message


def bisect_boundaries(
    problems: dict,
    *,
    store_dir,
    solver: str = "exudyn",
    settings: RunSettings | None = None,
    options: dict | None = None,
    stable: Callable[[dict], bool | None] = default_stable,
    factor: float = 1.5,
    log: bool = True,
    stable_above: bool = True,
    points_per_round: int = 1,
    max_expansions: int = 6,
    workers: int | None = None,
    scheduler=None,
    progress: bool = True,
    case_function: Callable = solve_case,
) -> dict:
    """Bisect several boundaries in lock-step; returns ``{label: Boundary}``.

    problems: ``{label: BoundaryProblem(make_params, lo, hi)}`` (make_params runs in this process and
        may be a lambda). stable(record) -> True | False | None (unknown: stops that boundary).
    stable_above: the stable side is at large values (True for E and T); used only to expand a bracket
        whose ends agree. factor: stop when hi/lo ≤ factor (> 1).
    """
    if not factor > 1:
        raise ParameterError(f"factor={factor!r} is invalid: allowed > 1")
    if not (isinstance(points_per_round, int) and points_per_round >= 1):
        raise ParameterError(f"points_per_round={points_per_round!r} is invalid: allowed an integer ≥ 1")
    searches = [
        _Search(
            label,
            problem,
            factor=factor,
            log=log,
            stable_above=stable_above,
            points_per_round=points_per_round,
            max_expansions=max_expansions,
        )
        for label, problem in problems.items()
    ]
    with Sweep(
        store_dir,
        workers=workers,
        scheduler=scheduler,
        progress=progress,
        case_function=case_function,
        label="bisection",
    ) as sweep:
        waiting: dict[str, list] = {}  # case key -> [(search, value)] in submission order

        def step(search: _Search) -> None:
            """Submit the cases of the search's next step."""
            search.answers = {}
            for value in search.wanted():
                try:
                    case = Case(
                        search.problem.make_params(value),
                        solver,
                        dict(options or {}),
                        settings=settings or RunSettings(),
                    )
                except ParameterError as exc:
                    search.out.evaluations.append((value, None, None))
                    search.stop("error", f"no case at {value:.6g}: {exc}")
                    return
                search.answers[value] = None
                waiting.setdefault(case.key, []).append((search, value))
                sweep.submit(case)

        for search in searches:
            step(search)
        while finished := sweep.wait():
            for case, record in finished:
                search, value = waiting[case.key].pop(0)
                if search.out.status != "running":
                    continue
                search.answers[value] = record
                if None not in search.answers.values():
                    values, records = list(search.answers), list(search.answers.values())
                    search.take(
                        values,
                        [stable(r) for r in records],
                        [r["key"] for r in records],
                        [r.get("error") for r in records],
                    )
                    step(search)
            sweep.set_total(sweep.bar.n + sum(s.remaining() for s in searches))
    return {search.out.label: search.out for search in searches}


def bisect_boundary(make_params: Callable, lo: float, hi: float, **kwargs) -> Boundary:
    """One boundary; keyword arguments as :func:`bisect_boundaries`."""
    return bisect_boundaries({None: BoundaryProblem(make_params, lo, hi)}, **kwargs)[None]
