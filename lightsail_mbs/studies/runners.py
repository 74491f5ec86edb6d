"""Where the cases of a sweep run: in this process, a local process pool, or a Dask cluster.

A runner takes cases at any time (``submit``) and hands back finished ones (``wait``: blocks until at
least one is done; ``[]`` when none is left), each as ``(case, record, result)`` from :func:`execute`,
which runs in the worker and never raises for a failing case.
"""

from __future__ import annotations

import collections
import concurrent.futures as cf
import contextlib
import multiprocessing
import os
import signal
import time
import traceback
from collections.abc import Callable
from concurrent.futures.process import BrokenProcessPool

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.result import Result

SCHEDULER_TIMEOUT = 10.0  # s to wait for a Dask scheduler to answer


def execute(case_function: Callable, case) -> tuple[dict, Result | None]:
    """Run one case (a :class:`~lightsail_mbs.studies.sweep.Case`) and build its record; never raises for a
    failing case.

    ``case_function(case)`` returns a Result (its ``summary()`` is recorded) or a summary dict.
    Returns ``(record, result)`` with ``result`` the Result if it is to be saved, else None.
    """
    start = time.perf_counter()
    result = None
    try:
        out = case_function(case)
    except Exception as exc:  # a failing case is a record, not a crash of the sweep
        record = {
            "status": "error",
            "error": f"{type(exc).__name__}: {exc}",
            "failed": None,
            "traceback": traceback.format_exc(limit=-8),
        }
    else:
        if isinstance(out, Result):
            record = out.summary()
            result = out if case.save_result else None
        else:
            record = dict(out)
        record["error"] = record.get("error")
        record["status"] = "error" if record["error"] else "ok"
    record.update(identity(case), case_wall_time=time.perf_counter() - start)
    return record, result


def identity(case) -> dict:
    """What every record says about its case."""
    return {
        "key": case.key,
        "solver": case.solver,
        "options": case.options,
        "parameters": case.params.to_dict(),
        "settings": case.settings.to_dict(),
    }


def lost_record(case, why: str) -> dict:
    """The record of a case whose worker died (no summary)."""
    return {"status": "error", "error": why, "failed": None, **identity(case)}


def available_cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


@contextlib.contextmanager
def dask_client(scheduler, timeout: float = SCHEDULER_TIMEOUT):
    """A ``distributed.Client`` for a scheduler address (closed on exit), a given Client as is, or None.

    ParameterError naming the address, before any case runs, when no scheduler answers there within
    ``timeout`` seconds or the address is not one Dask understands."""
    if scheduler is None or not isinstance(scheduler, str):
        yield scheduler
        return
    from distributed import Client

    try:
        client = Client(scheduler, timeout=timeout)
    except ValueError as exc:
        raise ParameterError(
            f"scheduler={scheduler!r} is invalid: allowed a Dask scheduler address such as tcp://host:8786 ({exc})"
        ) from None
    except Exception as exc:  # refused, timed out, or something that does not speak Dask's protocol
        raise ParameterError(
            f"scheduler={scheduler!r} is invalid: no Dask scheduler answered there within {timeout:g} s "
            f"({type(exc).__name__}: {exc})"
        ) from None
    with client:
        yield client


def make_runner(case_function: Callable, *, workers: int | None = None, client=None):
    """Dask if a client is given, in this process for one worker, else a pool of ``workers`` (default:
    all cores)."""
    if client is not None:
        return DaskRunner(case_function, client)
    if (workers or available_cores()) == 1:
        return SerialRunner(case_function)
    return PoolRunner(case_function, workers or available_cores())


class SerialRunner:
    """One case after the other in this process (a crashing solver takes the sweep down with it)."""

    def __init__(self, case_function):
        self.case_function = case_function
        self.queue = collections.deque()

    def submit(self, case) -> None:
        self.queue.append(case)

    def wait(self) -> list:
        if not self.queue:
            return []
        case = self.queue.popleft()
        return [(case, *execute(self.case_function, case))]

    def close(self, cancel: bool = False) -> None:
        self.queue.clear()


class PoolRunner:
    """Local processes, at most 2 cases in flight per worker.

    A case whose worker dies is rerun alone in a fresh pool; if it kills that one too, it is recorded
    as an error (the cases that ran beside it are innocent and rerun). Workers are forked where the OS
    allows (no re-import of the caller's ``__main__``: scripts without a ``__main__`` guard, and
    functions defined in them, work), else spawned.
    """

    def __init__(self, case_function, workers: int):
        self.case_function = case_function
        self.workers = workers
        method = "fork" if "fork" in multiprocessing.get_all_start_methods() else "spawn"
        self.context = multiprocessing.get_context(method)
        self.queue, self.suspects = collections.deque(), collections.deque()
        self.running: dict[cf.Future, tuple[object, bool]] = {}  # future -> (case, running alone?)
        self.pool = self._new_pool()

    def _new_pool(self) -> cf.ProcessPoolExecutor:
        return cf.ProcessPoolExecutor(self.workers, mp_context=self.context, initializer=_ignore_interrupts)

    def submit(self, case) -> None:
        self.queue.append(case)

    def _start(self, queue: collections.deque, alone: bool) -> None:
        future = self.pool.submit(_execute_interruptibly, self.case_function, queue[0])
        self.running[future] = (queue.popleft(), alone)

    def wait(self) -> list:
        finished = []
        while not finished and (self.queue or self.suspects or self.running):
            broken = False
            try:
                if self.suspects and not self.running:
                    self._start(self.suspects, alone=True)
                while not self.suspects and self.queue and len(self.running) < 2 * self.workers:
                    self._start(self.queue, alone=False)
                done, _ = cf.wait(self.running, return_when=cf.FIRST_COMPLETED)
            except BrokenProcessPool:  # the pool broke while cases were being submitted
                done, broken = set(), True
            for future in done:
                case, alone = self.running.pop(future)
                try:
                    finished.append((case, *future.result()))
                except BrokenProcessPool:
                    broken = True
                    if alone:
                        finished.append((case, lost_record(case, "worker process died running this case"), None))
                    else:
                        self.suspects.append(case)
            if broken:
                self.suspects.extend(case for case, _ in self.running.values())
                self.running.clear()
                self.pool.shutdown(wait=False, cancel_futures=True)
                self.pool = self._new_pool()
        return finished

    def close(self, cancel: bool = False) -> None:
        self.pool.shutdown(wait=not cancel, cancel_futures=True)


def _ignore_interrupts() -> None:
    """Pool workers ignore Ctrl-C while idle (no traceback from a worker waiting for work); the sweep's
    own process handles it and shuts the pool down."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _execute_interruptibly(case_function: Callable, case):
    """:func:`execute` in a pool worker with Ctrl-C raising KeyboardInterrupt while the case runs (sent
    back to the sweep as the case's outcome, never recorded)."""
    signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        return execute(case_function, case)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)


class DaskRunner:
    """Cases on a Dask cluster, submitted at once; Dask itself retries cases whose worker died."""

    def __init__(self, case_function, client):
        self.case_function = case_function
        self.client = client
        self.futures: dict = {}

    def submit(self, case) -> None:
        self.futures[self.client.submit(execute, self.case_function, case, pure=False)] = case

    def wait(self) -> list:
        if not self.futures:
            return []
        from distributed import wait

        done, _ = wait(list(self.futures), return_when="FIRST_COMPLETED")
        finished = []
        for future in done:
            case = self.futures.pop(future)
            try:
                finished.append((case, *future.result()))
            except Exception as exc:  # e.g. KilledWorker: the case took down every worker it ran on
                finished.append((case, lost_record(case, f"{type(exc).__name__}: {exc}"), None))
        return finished

    def close(self, cancel: bool = False) -> None:
        if cancel and self.futures:
            self.client.cancel(list(self.futures))
        self.futures.clear()
