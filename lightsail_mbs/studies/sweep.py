"""Sweeps of many cases: parallel on all cores or on a Dask cluster, resumable, failures recorded.

A sweep is a list of :class:`Case` (parameters, solver name, solver options), each with a stable
key (hash of the three). ``run_sweep`` skips every case whose record is already in the store, runs
the rest in parallel and writes each record the moment its case finishes
(:class:`~lightsail_mbs.studies.store.CaseStore`), so a killed sweep restarted with the same cases
recomputes nothing it had finished. A case whose solver raises, returns ``Result.error`` or kills
its worker process is recorded with ``status="error"`` and the sweep goes on.

Where the cases run (:mod:`lightsail_mbs.studies.runners`):

* ``workers=1``: in this process, one after the other;
* default: a local process pool with one worker per core (``concurrent.futures``);
* ``scheduler="tcp://host:8786"`` (or a ``distributed.Client``): the same cases on a Dask cluster.

Records are written by this (the submitting) process, so cluster workers need no shared disk.
:class:`Sweep` is the live form: submit cases at any time and collect them as they finish (the
stability bisections of :mod:`lightsail_mbs.studies.bisection` choose each case from the previous ones).
"""

from __future__ import annotations

import hashlib
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.model.records import stored
from lightsail_mbs.result import Result
from lightsail_mbs.studies.runners import available_cores, dask_client, make_runner
from lightsail_mbs.studies.store import CaseStore, to_json

__all__ = ["Case", "Sweep", "run_sweep", "run_cases", "solve_case", "available_cores", "dask_client"]

KEY_LENGTH = 20  # hex digits of the SHA-256 of a case's description


@dataclass(frozen=True)
class Case:
    """One run of a sweep: ``solve(params, solver, settings, uncertainty=uncertainty, **options)``.

    ``save_result`` asks for the full Result (.npz) to be stored too; it is not part of the key.
    ``uncertainty``: sweeps run without the twin runs of the uncertainty estimate by default (their
    records say ``"uncertainty": null``); True asks for it (and is part of the key).
    """

    params: SailParameters
    solver: str = "exudyn"
    options: dict = field(default_factory=dict)
    save_result: bool = False
    settings: RunSettings = field(default_factory=RunSettings)
    uncertainty: bool = False
    key: str = field(init=False, compare=False)

    def __post_init__(self):
        try:
            text = to_json(self.description())
        except TypeError as exc:
            raise ParameterError(
                f"options={self.options!r} is invalid: allowed JSON-serialisable values only ({exc})"
            ) from None
        object.__setattr__(self, "key", hashlib.sha256(text.encode()).hexdigest()[:KEY_LENGTH])

    def description(self) -> dict:
        """What the key identifies: the case and its run settings in one parameter dict (under the
        field names of the store's key format, model.records.stored; with an optical table file, the digest of its
        content, so that a rewritten table is a new case), the solver and its options."""
        parameters = stored(self.params.to_dict())
        parameters.update(self.settings.to_dict())
        if self.params.optics_file:
            parameters["optics_sha256"] = self.params.optics_digest
        description = {"parameters": parameters, "solver": self.solver, "options": self.options}
        if self.uncertainty:
            description["uncertainty"] = True
        return description


def solve_case(case: Case) -> Result:
    """The default case function: ``lightsail_mbs.solve(params, solver, settings, **options)``, no progress bar,
    with the uncertainty estimate only if the case asks for it."""
    from lightsail_mbs.solvers import solve

    return solve(case.params, case.solver, case.settings, progress=False, uncertainty=case.uncertainty, **case.options)


class Sweep:
    """A live sweep on a store: ``submit`` cases at any time, ``wait`` for finished ones.

    Used as a context manager (it owns the worker pool or the Dask connection). A case already in the
    store comes back from the next ``wait`` without running; every other finished case is written to
    the store (Result first if ``save_result``, then its record, atomically) before ``wait`` returns
    it. A case submitted again while it runs is run once and returned once per submission.

    Parameters
    ----------
    workers
        local processes (default: all cores; 1 runs in this process). Ignored with a scheduler.
    scheduler
        a Dask scheduler address ("tcp://host:8786") or a ``distributed.Client``.
    progress
        a progress bar on stderr.
    case_function
        a module-level (picklable) function of a Case returning a Result or a summary dict; default
        :func:`solve_case`.
    retry_errors
        also rerun cases recorded with status "error" (e.g. after fixing a solver).
    label
        the progress bar's name.
    """

    def __init__(
        self,
        store_dir,
        *,
        workers: int | None = None,
        scheduler=None,
        progress: bool = True,
        case_function: Callable = solve_case,
        retry_errors: bool = False,
        label: str = "sweep",
    ):
        if workers is not None and (not isinstance(workers, int) or isinstance(workers, bool) or workers < 1):
            raise ParameterError(f"workers={workers!r} is invalid: allowed an integer ≥ 1 or None (all cores)")
        self.store = CaseStore(store_dir)
        self.workers, self.scheduler, self.progress = workers, scheduler, progress
        self.case_function, self.retry_errors, self.label = case_function, retry_errors, label
        self.errors = 0
        self._ready: list[tuple[Case, dict]] = []
        self._waiting: dict[str, list[Case]] = {}  # key -> submissions of a case now running

    def __enter__(self) -> Sweep:
        from tqdm import tqdm

        self._client_context = dask_client(self.scheduler)
        client = self._client_context.__enter__()
        self._runner = make_runner(self.case_function, workers=self.workers, client=client)
        self.bar = tqdm(
            total=0,
            desc=self.label,
            unit="case",
            file=sys.stderr,
            disable=not self.progress,
            dynamic_ncols=True,
            smoothing=0.1,
        )
        return self

    def __exit__(self, kind, value, tb) -> None:
        try:
            self._runner.close(cancel=kind is not None)
        finally:
            self.bar.close()
            self._client_context.__exit__(kind, value, tb)

    def done(self, case: Case) -> bool:
        """Is the case finished in the store (with its Result if asked; not an error, if retrying them)?"""
        if not self.store.has(case.key, with_result=case.save_result):
            return False
        return not (self.retry_errors and self.store.load(case.key)["status"] == "error")

    def submit(self, case: Case) -> None:
        if not isinstance(case, Case):
            raise ParameterError(f"case={case!r} is invalid: allowed a Case")
        if case.key in self._waiting:
            self._waiting[case.key].append(case)
        elif self.done(case):
            self._ready.append((case, self.store.load(case.key)))
            self._count_found()
        else:
            self._waiting[case.key] = [case]
            self._runner.submit(case)
        self.set_total(self.bar.total)

    def _count_found(self) -> None:
        """One more case done without computing: counted, but kept out of the rate and the ETA."""
        self.bar.n += 1
        if not self.bar.disable:
            self.bar.initial += 1
            self.bar.last_print_n += 1

    def set_total(self, total: int) -> None:
        """Tell the progress bar how many cases to expect in all (at least those found or submitted); it is
        drawn again when the sweep next waits, once for any number of submissions."""
        self.bar.total = max(total, self.bar.n + sum(map(len, self._waiting.values())))

    def wait(self) -> list[tuple[Case, dict]]:
        """Block until some submitted cases are finished; return them as (case, record); [] if none is left."""
        if not self.bar.disable:
            self.bar.refresh()
        if self._ready:
            ready, self._ready = self._ready, []
            return ready
        finished = []
        for case, record, result in self._runner.wait():
            if result is not None:
                path = self.store.save_result(case.key, result)
                record["result_path"] = str(path.relative_to(self.store.directory))
            record = self.store.write(case.key, record)
            self.errors += record["status"] == "error"
            submissions = self._waiting.pop(case.key)
            finished += [(c, record) for c in submissions]
            self.bar.set_postfix(errors=self.errors, refresh=False)
            self.bar.update(len(submissions))
        return finished


def run_sweep(cases, store_dir, *, workers: int | None = None, **options) -> list[dict]:
    """Run every case not yet in the store at ``store_dir``; return the records in the order of ``cases``.

    workers: local processes (default: all cores, at most one per case; 1 runs in this process); options:
    those of :class:`Sweep` (scheduler, progress, case_function, retry_errors, label).
    Each record is the case's summary (``Result.summary()``) plus ``key``, ``status`` ("ok" |
    "error"), ``error``, ``options``, ``case_wall_time`` and, if saved, ``result_path``.
    """
    cases = list(cases)
    unique = {getattr(case, "key", id(case)): case for case in cases}
    with Sweep(store_dir, workers=_fewer(workers, len(unique)), **options) as sweep:
        sweep.set_total(len(unique))
        for case in unique.values():
            sweep.submit(case)
        records = {}
        while finished := sweep.wait():
            records.update((case.key, record) for case, record in finished)
    return [records[case.key] for case in cases]


def _fewer(workers: int | None, cases: int) -> int | None:
    """No more local workers than cases (at least one)."""
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        return workers  # let Sweep reject it with its message
    return max(1, min(workers or available_cores(), cases))


def run_cases(
    params_list,
    store_dir,
    settings,
    *,
    solver: str = "exudyn",
    workers=None,
    scheduler=None,
    label: str = "cases",
    progress: bool = True,
    options: dict | None = None,
) -> list[tuple[dict, Result | None]]:
    """Run (or find in the store) every case with its full Result saved; return (record, Result) pairs
    in order. settings: one RunSettings for every case, or one per case; options: the solver's, for every
    case. A case whose solver failed comes back with its record and, if any, its partial Result."""
    if isinstance(settings, RunSettings):
        settings = [settings] * len(params_list)
    cases = [
        Case(p, solver, options=dict(options or {}), save_result=True, settings=s)
        for p, s in zip(params_list, settings, strict=True)
    ]
    records = run_sweep(cases, store_dir, workers=workers, scheduler=scheduler, label=label, progress=progress)
    out = []
    for record in records:
        path = record.get("result_path")
        out.append((record, Result.load(Path(store_dir) / path) if path else None))
    return out
