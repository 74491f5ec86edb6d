"""Fine stability maps (paper Figs 9 and 12): per thickness and mode, the bisected stable/failed
boundary of E (torsion) or T (TnT) next to the analytic E_cr,max (Eq. 8) or T_cr,max (Eq. 10).

Each boundary is bracketed around the analytic value (analytic / span … analytic · span, widened
if needed) and bisected in log space by :func:`lightsail_mbs.bisection.bisect_boundaries` until the
bracket is at most ``factor`` wide; every run is a resumable case of the sweep store.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import theory
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.studies.bisection import BoundaryProblem, bisect_boundaries
from lightsail_mbs.studies.sweep import solve_case

# the swept parameter of each model and its analytic critical value
SWEPT = theory.STIFFNESS


@dataclass
class MapRow:
    """One boundary: the bracket [stable_value, unstable_value] (either order), its geometric mean
    ``boundary`` and ``ratio`` = boundary / analytic; ``points`` are all (value, stable) evaluated."""

    thickness: float
    mode: float
    t_final: float
    analytic: float
    stable_value: float | None
    unstable_value: float | None
    status: str
    message: str = ""
    points: list = field(default_factory=list)

    @property
    def boundary(self) -> float | None:
        if self.stable_value is None or self.unstable_value is None:
            return None
        return math.sqrt(self.stable_value * self.unstable_value)

    @property
    def ratio(self) -> float | None:
        b = self.boundary
        return None if b is None else b / self.analytic

    def as_dict(self) -> dict:
        return {
            "thickness_m": self.thickness,
            "mode": self.mode,
            "t_final_s": self.t_final,
            "analytic": self.analytic,
            "stable_value": self.stable_value,
            "unstable_value": self.unstable_value,
            "boundary": self.boundary,
            "ratio": self.ratio,
            "status": self.status,
            "evaluations": len(self.points),
        }


def boundary_map(
    base: SailParameters,
    cases,
    *,
    store_dir,
    settings: RunSettings,
    solver: str = "exudyn",
    factor: float = 1.5,
    span: float = 30.0,
    workers=None,
    scheduler=None,
    progress: bool = True,
    options: dict | None = None,
    max_expansions: int = 1,
    case_function: Callable = solve_case,
) -> list[MapRow]:
    """Bisect the boundary of ``base`` (model torsion: E; tnt: T) at every (thickness, mode) of
    ``cases``; one row per case, in their order, each run with ``settings``. All boundaries advance at
    once on one sweep.
    max_expansions: widenings of a bracket whose ends agree (each doubles its log-width; one
    takes the lower end from analytic/span to analytic/span³ — no stiffness to speak of).
    case_function: how a case runs (default: the named solver; tests pass a stand-in).
    """
    if base.model not in SWEPT:
        raise ParameterError(f"model={base.model!r} is invalid: allowed one of {', '.join(SWEPT)} for a map")
    if not span > 1:
        raise ParameterError(f"span={span!r} is invalid: allowed > 1")
    name, critical = SWEPT[base.model]
    problems, analytic = {}, {}
    for h, nu in cases:
        p = base.replace(thickness=float(h), defect_mode=float(nu))
        a = float(critical(p))
        analytic[(float(h), float(nu))] = a
        problems[(float(h), float(nu))] = BoundaryProblem(
            lambda value, p=p: p.replace(**{name: float(value)}), a / span, a * span
        )
    found = bisect_boundaries(
        problems,
        store_dir=store_dir,
        solver=solver,
        settings=settings,
        options=options,
        factor=factor,
        workers=workers,
        scheduler=scheduler,
        progress=progress,
        max_expansions=max_expansions,
        case_function=case_function,
    )
    return [
        MapRow(
            h,
            nu,
            settings.t_final,
            analytic[(h, nu)],
            b.stable_value,
            b.unstable_value,
            b.status,
            b.message,
            [(v, s) for v, s, _ in b.evaluations],
        )
        for (h, nu), b in found.items()
    ]
