"""Sweeps of many cases: parallel on all cores or on a Dask cluster, resumable, failures recorded.

A sweep is a list of :class:`Case` (parameters, solver name, solver options), each with a stable
key (hash of the three). ``run_sweep`` skips every case whose record is already in the store, runs
the rest in parallel and writes each record the moment its case finishes
(:class:`~lightsail_mbs.store.CaseStore`), so a killed sweep restarted with the same cases
recomputes nothing it had finished. A case whose solver raises, returns ``Result.error`` or kills
its worker process is recorded with ``status="error"`` and the sweep goes on.

Where the cases run:
  * ``workers=1``: in this process, one after the other;
  * default: a local process pool with one worker per core (``concurrent.futures``);
  * ``scheduler="tcp://host:8786"`` (or a ``distributed.Client``): the same cases on a Dask cluster.
Records are written by this (the submitting) process, so cluster workers need no shared disk.
"""
from __future__ import annotations

import collections
import concurrent.futures as cf
import contextlib
import hashlib
import multiprocessing
import os
import sys
import time
import traceback
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from typing import Callable

from .parameters import ParameterError, SailParameters
from .result import Result
from .store import CaseStore, to_json

KEY_LENGTH = 20  # hex digits of the SHA-256 of a case's description


@dataclass(frozen=True)
class Case:
    """One run of a sweep: ``solve(params, solver, **options)``.

    ``save_result`` asks for the full Result (.npz) to be stored too; it is not part of the key.
    """

    params: SailParameters
    solver: str = "exudyn"
    options: dict = field(default_factory=dict)
    save_result: bool = False
    key: str = field(init=False, compare=False)

    def __post_init__(self):
        try:
            text = to_json(self.description())
        except TypeError as exc:
            raise ParameterError(f"options={self.options!r} is invalid: allowed JSON-serialisable "
                                 f"values only ({exc})") from None
        object.__setattr__(self, "key", hashlib.sha256(text.encode()).hexdigest()[:KEY_LENGTH])

    def description(self) -> dict:
        """What the key identifies: the full parameter dict, the solver and its options."""
        return {"parameters": self.params.to_dict(), "solver": self.solver, "options": self.options}


def solve_case(case: Case) -> Result:
    """The default case function: ``lightsail_mbs.solve(params, solver, **options)``, no progress bar."""
    from .solvers import solve
    return solve(case.params, case.solver, progress=False, **case.options)


def execute(case_function: Callable, case: Case) -> tuple[dict, Result | None]:
    """Run one case in a worker and build its record; never raises for a failing case.

    ``case_function(case)`` returns a Result (its ``summary()`` is recorded) or a summary dict.
    Returns ``(record, result)`` with ``result`` the Result if it is to be saved, else None.
    """
    start = time.perf_counter()
    result = None
    try:
        out = case_function(case)
    except Exception as exc:  # a failing case is a record, not a crash of the sweep
        record = {"status": "error", "error": f"{type(exc).__name__}: {exc}", "failed": None,
                  "traceback": traceback.format_exc(limit=-8)}
    else:
        if isinstance(out, Result):
            record = out.summary()
            result = out if case.save_result else None
        else:
            record = dict(out)
        record["error"] = record.get("error")
        record["status"] = "error" if record["error"] else "ok"
    record.update(_identity(case), case_wall_time=time.perf_counter() - start)
    return record, result


def _identity(case: Case) -> dict:
    return {"key": case.key, "solver": case.solver, "options": case.options,
            "parameters": case.params.to_dict()}


def _lost_record(case: Case, why: str) -> dict:
    return {"status": "error", "error": why, "failed": None, **_identity(case)}


def available_cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def run_sweep(cases, store_dir, *, workers: int | None = None, scheduler=None, progress: bool = True,
              case_function: Callable = solve_case, retry_errors: bool = False,
              label: str = "sweep") -> list[dict]:
    """Run every case not yet in the store at ``store_dir``; return the records in the order of ``cases``.

    workers: local processes (default: all cores; 1 runs in this process). Ignored with a scheduler.
    scheduler: a Dask scheduler address ("tcp://host:8786") or a ``distributed.Client``.
    case_function: a module-level (picklable) function of a Case returning a Result or a summary
        dict; default :func:`solve_case`.
    retry_errors: also rerun cases recorded with status "error" (e.g. after fixing a solver).
    Each record is the case's summary (``Result.summary()``) plus ``key``, ``status`` ("ok" |
    "error"), ``error``, ``options``, ``case_wall_time`` and, if saved, ``result_path``.
    """
    cases = list(cases)
    for case in cases:
        if not isinstance(case, Case):
            raise ParameterError(f"cases contains {case!r}: allowed Case objects only")
    if workers is not None and (not isinstance(workers, int) or isinstance(workers, bool) or workers < 1):
        raise ParameterError(f"workers={workers!r} is invalid: allowed an integer ≥ 1 or None (all cores)")
    store = CaseStore(store_dir)
    unique: dict[str, Case] = {}
    for case in cases:
        unique.setdefault(case.key, case)
    todo = [case for key, case in unique.items()
            if not store.has(key, with_result=case.save_result)
            or (retry_errors and store.load(key)["status"] == "error")]

    from tqdm import tqdm
    bar = tqdm(total=len(unique), initial=len(unique) - len(todo), desc=label, unit="case",
               file=sys.stderr, disable=not progress, dynamic_ncols=True, smoothing=0.1)
    errors = 0

    def finished(case: Case, record: dict, result: Result | None) -> None:
        nonlocal errors
        if result is not None:
            record["result_path"] = str(store.save_result(case.key, result).relative_to(store.directory))
        store.write(case.key, record)
        errors += record["status"] == "error"
        bar.set_postfix(errors=errors, refresh=False)
        bar.update(1)

    try:
        if todo:
            if scheduler is not None:
                _run_dask(todo, case_function, scheduler, finished)
            elif (workers or available_cores()) == 1:
                for case in todo:
                    finished(case, *execute(case_function, case))
            else:
                _run_pool(todo, case_function, min(workers or available_cores(), len(todo)), finished)
    finally:
        bar.close()
    return [store.load(case.key) for case in cases]


def _run_pool(todo, case_function, workers, finished) -> None:
    """Local processes, at most 2 cases in flight per worker. A case whose worker dies is rerun alone
    in a fresh pool; if it kills that one too, it is recorded as an error (the others are innocent).

    Workers are forked where the OS allows (no re-import of the caller's ``__main__``, so scripts
    without a ``__main__`` guard and functions defined in them work), else spawned.
    """
    method = "fork" if "fork" in multiprocessing.get_all_start_methods() else "spawn"
    context = multiprocessing.get_context(method)
    queue, suspects = collections.deque(todo), collections.deque()
    running: dict[cf.Future, tuple[Case, bool]] = {}   # future -> (case, running alone?)
    pool = cf.ProcessPoolExecutor(workers, mp_context=context)

    def submit(case: Case, alone: bool) -> None:
        running[pool.submit(execute, case_function, case)] = (case, alone)

    try:
        while queue or suspects or running:
            broken = False
            try:
                if suspects and not running:
                    submit(suspects[0], True)
                    suspects.popleft()
                while not suspects and queue and len(running) < 2 * workers:
                    submit(queue[0], False)
                    queue.popleft()
                done, _ = cf.wait(running, return_when=cf.FIRST_COMPLETED)
            except BrokenProcessPool:   # the pool broke while cases were being submitted
                done, broken = set(), True
            for future in done:
                case, alone = running.pop(future)
                try:
                    outcome = future.result()
                except BrokenProcessPool:
                    broken = True
                    if alone:
                        finished(case, _lost_record(case, "worker process died running this case"), None)
                    else:
                        suspects.append(case)
                else:
                    finished(case, *outcome)
            if broken:
                suspects.extend(case for case, _ in running.values())
                running.clear()
                pool.shutdown(wait=False, cancel_futures=True)
                pool = cf.ProcessPoolExecutor(workers, mp_context=context)
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown(wait=True)


@contextlib.contextmanager
def dask_client(scheduler):
    """A ``distributed.Client`` for a scheduler address (closed on exit), a given Client as is, or None."""
    if scheduler is None or not isinstance(scheduler, str):
        yield scheduler
        return
    from distributed import Client
    with Client(scheduler) as client:
        yield client


def _run_dask(todo, case_function, scheduler, finished) -> None:
    """The same cases on a Dask cluster; Dask itself retries cases whose worker died."""
    from distributed import as_completed
    with dask_client(scheduler) as client:
        futures = {client.submit(execute, case_function, case, pure=False): case for case in todo}
        try:
            for future in as_completed(futures):
                case = futures[future]
                try:
                    outcome = future.result()
                except Exception as exc:  # e.g. KilledWorker: the case took down every worker it ran on
                    outcome = (_lost_record(case, f"{type(exc).__name__}: {exc}"), None)
                finished(case, *outcome)
        except BaseException:
            client.cancel(list(futures))
            raise
