"""Maps of the 3-D beam-riding verdict (rides / drifts out / crumples) of sheet runs over two of a case's
fields, through the sweep engine (:mod:`lightsail_mbs.studies.sweep`: resumable, every finished case
written to the store at once, local processes or a Dask cluster).

Every cell is a :class:`~lightsail_mbs.studies.sweep.Case` run by :func:`ride_case`, whose record is the
run's summary plus ``"ride3d"``: the histories the verdict is read from (time, the centre of mass's
distance from the beam axis, the deformation δ of analysis.ride3d, the tilt's size and the spin rate).
The verdict itself is read from the record by :func:`cell_of` with the map's thresholds
(:func:`lightsail_mbs.analysis.ride3d.classify`, the rule of ``sheet_ride``), so that one store serves
any crumple or drift threshold. Beside the verdict each cell carries the growth of the distance,
log(largest distance in the last fifth / in the first fifth) over the time between them (1/s), which
tells how far a cell that still rides at the end of its run is from drifting.

:func:`ride_case` runs the solver once (``engine.run``): the ride does not use the failure time, so a
run is not repeated at finer output intervals to locate it as ``solve`` does, and no twin runs estimate
its uncertainty; the run still ends at the first sample where its plane amplitude reaches the settings'
failure_ratio (a crumpled sail), which the verdict reads as deformation. The plane amplitude also jumps
when a rigid sail tilts past 45° (model.failure.plane_offsets takes for the normal the principal axis
nearest z, which is then an in-plane one), so a run can end before its t_final with neither threshold
reached: such a cell is "tips over" when its tilt has passed TIPPED, else "stopped" (no verdict).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lightsail_mbs.analysis.ride3d import classify, sheet_ride
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError, check, finite
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.studies.sweep import Case, run_sweep

RIDE = "ride3d"  # the record's entry of ride histories
TIPPED = math.pi / 4  # rad: past this tilt the failure rule's plane is another principal axis of the sail


def ride_histories(result) -> dict:
    """{name: list} of the run's ride histories that a map's verdict needs (module docstring)."""
    ride = sheet_ride(result)
    return {
        "time": ride.time.tolist(),
        "distance": ride.distance.tolist(),
        "deformation": ride.deformation.tolist(),
        "tilt": np.hypot(ride.tilt[:, 0], ride.tilt[:, 1]).tolist(),
        "spin_rate": np.asarray(ride.spin_rate, float).tolist(),
    }


def ride_case(case: Case) -> dict:
    """The sweep's case function of a ride map: the case's solver run once (module docstring), its
    summary and, under ``"ride3d"``, its ride histories."""
    from lightsail_mbs.solvers import contract

    engine = contract.lookup(case.solver, case.params)
    engine.check_options(case.options)
    result = engine.run(case.params, case.settings, **case.options)
    record = result.summary()
    record[RIDE] = ride_histories(result)
    return record


@dataclass
class RideCell:
    """One cell of a map: its case's key, the verdict and when it was decided (s; None: rides), the growth
    of the distance from the axis (1/s), the largest distance (m) and deformation (m), and the end of
    its run (s); status "error" (with the solver's message) for a run that failed."""

    key: str
    verdict: str | None
    decided_at: float | None
    growth: float
    max_distance: float
    max_deformation: float
    t_end: float
    status: str = "ok"
    error: str | None = None

    def as_dict(self) -> dict:
        return dict(self.__dict__)


def growth_rate(time, distance) -> float:
    """log(largest distance in the last fifth of the samples / in the first fifth) over the time between
    the fifths (1/s); nan for a run too short to have two fifths."""
    time, distance = np.asarray(time, float), np.asarray(distance, float)
    fifth = max(len(time) // 5, 1)
    if len(time) < 2 * fifth or time[-1] <= time[fifth]:
        return math.nan
    first, last = distance[:fifth].max(), distance[-fifth:].max()
    return math.log(last / first) / (time[-1] - time[fifth]) if first > 0 and last > 0 else math.nan


def cell_of(record: dict, waist: float, crumple: float, drift_factor: float = 1.0) -> RideCell:
    """The cell of a ride record (ride_case's) under the thresholds of analysis.ride3d.sheet_ride; a run the
    failure rule ended early without a verdict: "tips over" or "stopped" (module docstring)."""
    if record.get("status") == "error" or RIDE not in record:
        error = record.get("error") or f"the record holds no {RIDE!r} histories (not made by ride_case)"
        return RideCell(record["key"], None, None, math.nan, math.nan, math.nan, math.nan, "error", error)
    h = {name: np.asarray(values, float) for name, values in record[RIDE].items()}
    verdict, when = classify(h["time"], h["distance"], h["deformation"], drift_factor * waist, crumple)
    t_final = (record.get("settings") or {}).get("t_final", h["time"][-1])
    if verdict == "rides" and h["time"][-1] < t_final * (1 - 1e-9):  # ended early by the failure rule
        tipped = np.flatnonzero(h["tilt"] >= TIPPED)
        verdict, when = ("tips over", float(h["time"][tipped[0]])) if tipped.size else ("stopped", None)
    return RideCell(
        record["key"],
        verdict,
        when,
        growth_rate(h["time"], h["distance"]),
        float(h["distance"].max()),
        float(h["deformation"].max()),
        float(h["time"][-1]),
    )


def grid(base: SailParameters, x: tuple[str, list], y: tuple[str, list], make: Callable | None = None) -> dict:
    """{(x value, y value): case} of a map: axes (name, values); make(base, x_value, y_value) builds a cell's
    case (default: base with the two fields of those names replaced)."""
    (x_name, xs), (y_name, ys) = x, y
    if make is None:

        def make(p, u, v):
            return p.replace(**{x_name: u, y_name: v})

    return {(u, v): make(base, u, v) for v in ys for u in xs}


def ride_map(
    cases: dict,
    *,
    store_dir,
    settings: RunSettings,
    solver: str = "reduced",
    options: dict | None = None,
    crumple: float = 0.05,
    drift_factor: float = 1.0,
    workers: int | None = None,
    scheduler=None,
    progress: bool = True,
    label: str = "ride map",
) -> dict:
    """{cell: RideCell} of {cell: sheet case} (e.g. :func:`grid`'s), every case run by :func:`ride_case`
    on one sweep of the store at store_dir (a cell already there is read, not run); options: the solver's.
    crumple (m), drift_factor (beam waists): the verdict's thresholds (analysis.ride3d.sheet_ride)."""
    crumple, drift_factor = finite("crumple", crumple), finite("drift_factor", drift_factor)
    check("crumple", crumple, crumple > 0, "> 0 m")
    check("drift_factor", drift_factor, drift_factor > 0, "> 0")
    for p in cases.values():
        if not (isinstance(p, SailParameters) and p.model == "sheet"):
            raise ParameterError(f"cases={p!r} is invalid: allowed sheet cases (SailParameters with model 'sheet')")
    runs = {cell: Case(p, solver, options=dict(options or {}), settings=settings) for cell, p in cases.items()}
    records = run_sweep(
        list(runs.values()),
        store_dir,
        workers=workers,
        scheduler=scheduler,
        progress=progress,
        case_function=ride_case,
        label=label,
    )
    return {
        cell: cell_of(record, cases[cell].beam_waist, crumple, drift_factor)
        for cell, record in zip(runs, records, strict=True)
    }
