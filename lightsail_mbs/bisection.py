"""Stability boundaries by bracketing and bisection, every evaluation a case of a resumable sweep.

For a one-parameter family of cases ``make_params(value)`` (e.g. the Young's modulus at a given
thickness) the boundary between stable and failed runs is bracketed — the bracket grows
geometrically (its log-width doubles per step) until its ends differ — then bisected in log space
until ``hi / lo ≤ factor``. Several boundaries advance in lock-step, one batch of cases per round
through :func:`~lightsail_mbs.sweep.run_sweep`, so all cores (or a cluster) stay busy, and a rerun
finds every case it already computed in the store: a killed bisection resumes without recomputing.
With ``points_per_round = k`` each round evaluates k interior points, shrinking the bracket
(log-width) by k + 1 per round — for clusters with more workers than boundaries.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

from .parameters import ParameterError
from .sweep import Case, dask_client, run_sweep, solve_case


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
    evaluations: (value, stable, key) in the order evaluated; ``monotone`` False if a round saw
    more than one stable/unstable change (then the change nearest the lower end was kept).
    """

    label: object
    stable_value: float | None = None
    unstable_value: float | None = None
    status: str = "running"
    message: str = ""
    monotone: bool = True
    rounds: int = 0
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

    def __init__(self, label, problem: BoundaryProblem, *, factor, log, stable_above, points_per_round,
                 max_expansions):
        if not (0 < problem.lo < problem.hi and math.isfinite(problem.hi)):
            raise ParameterError(f"bracket ({problem.lo!r}, {problem.hi!r}) of {label!r} is invalid: "
                                 "allowed 0 < lo < hi < inf")
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
        if self.s_lo == self.s_hi:   # not bracketed: step outward, doubling the (log-)width
            below = self.s_lo == self.stable_above
            value = self._between(-2.0) if below else self._between(3.0)
            if value <= 0:
                self.stop("unbracketed", f"{'stable' if self.s_lo else 'unstable'} down to {self.lo:.6g}")
                return []
            return [value]
        return [self._between(j / (self.k + 1)) for j in range(1, self.k + 1)]

    def take(self, values: list[float], stable: list[bool | None], keys: list[str],
             errors: list[str | None]) -> None:
        self.out.rounds += 1
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
            self._record_bracket()
            self.stop("unbracketed", f"{'stable' if self.s_lo else 'unstable'} over "
                                      f"[{self.lo:.6g}, {self.hi:.6g}] after {self.expansions} expansions")

    def _record_bracket(self) -> None:
        if self.s_lo != self.s_hi:
            self.out.stable_value, self.out.unstable_value = ((self.lo, self.hi) if self.s_lo
                                                              else (self.hi, self.lo))

    def stop(self, status: str, message: str) -> None:
        self.out.status, self.out.message = status, message


def bisect_boundaries(problems: dict, *, store_dir, solver: str = "exudyn", options: dict | None = None,
                      stable: Callable[[dict], bool | None] = default_stable, factor: float = 1.5,
                      log: bool = True, stable_above: bool = True, points_per_round: int = 1,
                      max_expansions: int = 6, workers: int | None = None, scheduler=None,
                      progress: bool = True, case_function: Callable = solve_case) -> dict:
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
    searches = {label: _Search(label, problem, factor=factor, log=log, stable_above=stable_above,
                               points_per_round=points_per_round, max_expansions=max_expansions)
                for label, problem in problems.items()}
    with dask_client(scheduler) as client:   # one connection for all rounds
        _advance(searches, store_dir, solver, options, stable,
                 dict(workers=workers, scheduler=client, progress=progress, case_function=case_function))
    return {label: search.out for label, search in searches.items()}


def _advance(searches: dict, store_dir, solver, options, stable, run_options: dict) -> None:
    """Rounds until every search has stopped: each round, one sweep of the values all searches want."""
    round_number = 0
    while True:
        batch = []   # (search, value, case)
        for search in searches.values():
            for value in search.wanted():
                try:
                    case = Case(search.problem.make_params(value), solver, dict(options or {}))
                except ParameterError as exc:
                    search.out.evaluations.append((value, None, None))
                    search.stop("error", f"no case at {value:.6g}: {exc}")
                    break
                batch.append((search, value, case))
        batch = [item for item in batch if item[0].out.status == "running"]
        if not batch:
            break
        round_number += 1
        records = run_sweep([case for _, _, case in batch], store_dir, label=f"bisection round {round_number}",
                            **run_options)
        for search in searches.values():
            mine = [(v, r) for (s, v, _), r in zip(batch, records) if s is search]
            if mine:
                search.take([v for v, _ in mine], [stable(r) for _, r in mine], [r["key"] for _, r in mine],
                            [r.get("error") for _, r in mine])


def bisect_boundary(make_params: Callable, lo: float, hi: float, **kwargs) -> Boundary:
    """One boundary; keyword arguments as :func:`bisect_boundaries`."""
    return bisect_boundaries({None: BoundaryProblem(make_params, lo, hi)}, **kwargs)[None]
