"""Twin runs in worker processes, started while the base run still runs.

The twins of a default run (:mod:`~lightsail_mbs.solvers.uncertainty`, :mod:`lightsail_mbs.analysis.n_error`)
are independent runs, each a deterministic function of its case, settings and options. A :func:`session`
opens around a default run and runs them, on a machine of more than one core, in forked worker processes (one
per twin) concurrently with each other and, where their inputs are known before the base run ends, with it:

- **When it pays.** The twins go to workers when the base run takes CONCURRENT_AFTER of wall time or more
  (the session's clock starts with the default run; checked at each progress update of the base run, in the
  main thread, through ``progress.watcher``, and when it ends, :meth:`Session.base_ended`) and the machine had
  MIN_IDLE_CORES idle meanwhile (Linux's /proc/stat; the base run itself keeps one core busy). A quicker base run
  keeps its twins in this process, one after the other, as before: a worker costs CPU to start and collect (a
  fork, its pages copied as they are written, its Result pickled back: 11–13 ms for an answer-only twin, 40–70 ms
  with the 8.7 MB of trajectories of the paper's 6 s stable torsion chain), while the twins of a base run B cost
  T = 1.5–3 B of CPU and two cores save at most (B + T)/2 of wall time with them; so workers pay from a B of a
  few tens of ms (about 20 ms with three or four answer-only twins), and 0.05 s leaves a margin. On a machine
  with no idle core they only add that
  cost (every core busy, the twins' CPU time is the wait either way). A run of 0.01 s is not made slower.
- **Speculation.** At that moment the session starts the twins whose inputs do not depend on how the base run
  ends (``Session.speculation``, given the settings of the base run's current pass: the loose, probe and film
  twins, with the options the solver declares it will use, contract rule 10, standing for the base run's
  ``info``; and ``Session.extra``: the n-twins, at the loose twin's options). A twin the estimate may not need (the
  probe, where the film twin may stand for it) runs at a lower priority (``Job.niceness``): on a busy machine it
  takes what the others leave, and it is stopped when the estimate finds it not needed. Every twin is keyed by its
  inputs (pickled: case, settings, options); when the base run has ended, the estimate asks for the twins its rule
  names (:meth:`Session.take`), and gets the worker's Result when the key matches, else starts the twin then. The
  answers are therefore those of the same runs in this process, bit for bit; a wrong guess costs CPU on the other
  core, not the answer. A base pass rerun at finer sampling (:func:`~lightsail_mbs.solvers.events.located_run`)
  ends the speculation made for the pass before it.
- **Interrupts and errors.** Workers ignore Ctrl-C (SIGINT is blocked from before the fork until they ignore
  it) and die with this process (Linux: PR_SET_PDEATHSIG); the session terminates and joins every worker when it
  ends, normally or by an exception, KeyboardInterrupt included, so no process outlives it. A twin that ends with
  a solver error is a Result as in process; an exception in a worker is raised again here; a worker that dies
  is a RuntimeError.
- **Priority.** Every worker runs WORKER_NICENESS below this process (os.nice; the probe's Job.niceness below
  that): while the base run runs, its core is not shared on equal terms with three or four twins, whose answers
  wait for it anyway. Measured as whole processes on the quiet machine (eight default runs of the paper's
  Exudyn rows against the same at equal priority, 6 pairs): wall 0.945 of it (median; 0.92–1.09), a small gain
  within the noise of a single benchmark row; once the base run has ended the workers have the cores to
  themselves.
- **Progress.** A worker's runs draw their bars on the shared stderr, labelled 'twin'.
- **What comes back.** A twin whose run only its answer is read of (``Job.answer_only``: the loose, probe and film
  twins, the n-twins; not a tightened twin, which may be the run reported) sends its Result back without its
  trajectories (:func:`slimmed`).

Workers are forked (no re-import, the compiled kernels inherited). Where the OS has no fork, in a process that
multiprocessing started (a sweep's pool worker), outside the main thread or on one core, every twin runs in this
process.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import os
import pickle
import signal
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from lightsail_mbs.result import ARRAYS, TILE_ARRAYS, Result
from lightsail_mbs.solvers import progress as progress_module

CONCURRENT_AFTER = 0.05  # s of the base run's wall time after which its twins go to worker processes ...
WORKER_NICENESS = 5  # every worker's priority below this process's: the base run, which every answer waits for, first
MIN_IDLE_CORES = 0.5  # ... if the machine had this many cores idle on average meanwhile
_local = threading.local()  # .sessions: this thread's open sessions (one per default run; nested solves share it)


@dataclass
class Job:
    """One twin: ``fn(*args, **kwargs)``, keyed by what its answer depends on (`key`, pickled by :func:`job`)."""

    key: bytes
    fn: Callable
    args: tuple
    kwargs: dict = field(default_factory=dict)
    speculative: bool = False  # started for the base run's current pass (ended when it is rerun)
    niceness: int = 0  # its worker's priority further below WORKER_NICENESS: a twin that may not be needed
    answer_only: bool = False  # its worker sends its Result back without the trajectories (`slimmed`)


def job(identity: tuple, fn: Callable, *args, **kwargs) -> Job:
    """A Job whose key is `identity` pickled (options dicts sorted by name, so that their order does not count)."""
    parts = tuple(sorted(part.items()) if isinstance(part, dict) else part for part in identity)
    return Job(pickle.dumps(parts, protocol=pickle.HIGHEST_PROTOCOL), fn, args, kwargs)


def usable() -> bool:
    """Whether twins can go to forked workers here: fork exists, ≥ 2 cores, the main thread of a process that
    multiprocessing did not start (a sweep's pool worker has the cores in use already)."""
    import multiprocessing  # here, not at import: 20–30 ms that runs without twins do not need

    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:
        cores = os.cpu_count() or 1
    forks = "fork" in multiprocessing.get_all_start_methods()
    main = threading.current_thread() is threading.main_thread()  # progress.watcher is one per process
    return cores >= 2 and forks and main and multiprocessing.parent_process() is None


def machine_times() -> tuple[float, float] | None:
    """(idle, total) CPU time of the whole machine so far, in clock ticks (Linux: /proc/stat's first line, idle
    and I/O wait against all), or None where it cannot be read."""
    try:
        with open("/proc/stat") as stat:
            ticks = [float(value) for value in stat.readline().split()[1:]]
    except (OSError, ValueError):
        return None
    return ticks[3] + ticks[4], sum(ticks[:8])


def idle_cores(since: tuple[float, float] | None) -> float:
    """How many cores stood idle on average since `since` (machine_times); inf when it cannot be told."""
    now = machine_times()
    if since is None or now is None or now[1] <= since[1]:
        return math.inf
    return (now[0] - since[0]) / (now[1] - since[1]) * (os.cpu_count() or 1)


class Worker:
    """A forked process running one Job; its outcome comes back over a pipe: ("ok", value, cpu s) or ("error", …)."""

    def __init__(self, work: Job):
        import multiprocessing

        context = multiprocessing.get_context("fork")
        self.receiver, sender = context.Pipe(duplex=False)
        self.process = context.Process(target=_work, args=(sender, work), daemon=True)
        blocked = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        try:
            self.process.start()
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, blocked)
        sender.close()

    def result(self):
        """(value, CPU seconds of the worker's run); raises what the job raised."""
        try:
            status, value, cpu = self.receiver.recv()
        except EOFError:
            self.process.join()
            raise RuntimeError(f"a twin's worker process died (exit code {self.process.exitcode})") from None
        self.process.join()
        if status != "ok":
            raise value
        return value, cpu

    def stop(self) -> None:
        if self.process.is_alive():
            self.process.terminate()
        self.process.join()
        self.receiver.close()


def _work(sender, work: Job) -> None:
    """A worker's body: Ctrl-C ignored, no session or watcher of the parent's, its bars labelled "twin", the job
    timed by its CPU time."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    with contextlib.suppress(Exception):  # Linux: die with the parent (SIGKILL leaves no orphan running)
        import ctypes

        ctypes.CDLL(None).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG
    _local.sessions = []
    progress_module.watcher, progress_module.prefix = None, "twin "
    os.nice(WORKER_NICENESS + work.niceness)
    start = time.process_time()
    try:
        value = work.fn(*work.args, **work.kwargs)
    except BaseException as exc:  # sent back and raised again in the session
        sender.send(("error", exc, time.process_time() - start))
    else:
        sender.send(("ok", slimmed(value) if work.answer_only else value, time.process_time() - start))
    sender.close()


def slimmed(value):
    """A Result without its trajectories (each of its arrays of two or more dimensions, result.ARRAYS and
    result.TILE_ARRAYS, cut to no columns; its time, amplitude history, record and so its answer kept), else
    `value`: what a twin's estimate reads of its run, at a few kB where the whole Result of a 6 s chain pickles to
    megabytes (tens of ms of CPU on both sides)."""
    if not isinstance(value, Result):
        return value
    cut = {}
    for name in ARRAYS + TILE_ARRAYS:
        array = getattr(value, name, None)
        if getattr(array, "ndim", 0) >= 2:
            cut[name] = array[:, :0].copy()
    return dataclasses.replace(value, **cut)


class Session:
    """The twins of one default run (module docstring): where they run, and which are running."""

    def __init__(self, enabled: bool = True):
        self.start, self.cpu_start = time.perf_counter(), machine_times()
        self.enabled = enabled and threading.current_thread() is threading.main_thread()  # usable() once due
        self.concurrent = self.decided = False
        self.workers: dict[bytes, tuple[Job, Worker]] = {}
        self.speculation: Callable | None = None  # settings of the base pass -> (jobs, the loose twin's options)
        self.extra: list[Callable] = []  # the loose twin's options -> jobs (the n-twins)
        self.pass_settings = None
        self.speculated = self.extra_speculated = False

    def due(self) -> bool:
        """Whether twins go to workers: once the base run has taken CONCURRENT_AFTER (decided for good then, or
        when it ends: :meth:`base_ended`)."""
        if self.enabled and not self.decided and time.perf_counter() - self.start >= CONCURRENT_AFTER:
            self.concurrent, self.decided = usable() and idle_cores(self.cpu_start) >= MIN_IDLE_CORES, True
        return self.concurrent

    def base_ended(self) -> None:
        """The base run has ended: whether its twins go to workers is decided by the time it took."""
        self.due()
        self.decided = True

    def submit(self, work: Job) -> None:
        """Start `work` in a worker if twins go to workers now and no worker runs it already."""
        if self.due() and work.key not in self.workers:
            self.workers[work.key] = (work, Worker(work))

    def take(self, work: Job):
        """(value, CPU seconds) of `work`: from its worker (started now if none runs it and twins go to
        workers), else run here."""
        self.submit(work)
        if work.key in self.workers:
            _, worker = self.workers.pop(work.key)
            return worker.result()
        start = time.process_time()
        value = work.fn(*work.args, **work.kwargs)
        return value, time.process_time() - start

    def discard(self, work: Job) -> None:
        """Stop the worker of a twin that is no longer needed."""
        if work.key in self.workers:
            self.workers.pop(work.key)[1].stop()

    def base_pass(self, settings) -> None:
        """A pass of the base run starts at `settings`: the speculation of an earlier pass ends."""
        if settings != self.pass_settings:
            for work, _ in [entry for entry in self.workers.values() if entry[0].speculative]:
                self.discard(work)
            self.pass_settings, self.speculated = settings, False

    def tick(self) -> None:
        """Called at every progress update of the base run: once due, start the speculative twins. Never raises
        (an exception here would end the base run); on a failure it gives speculation up."""
        if self.speculated or self.speculation is None or not self.due():
            return
        self.speculated = True
        try:
            jobs, reference = self.speculation(self.pass_settings)
            for work in jobs:
                work.speculative = True
            if not self.extra_speculated and reference is not None:
                self.extra_speculated = True
                jobs = jobs + [work for make in self.extra for work in make(reference)]
            for work in jobs:
                self.submit(work)
        except Exception:  # noqa: BLE001 - speculation is an optimisation; the twins run when asked for
            self.speculation = None

    def watching(self, engine):
        """`engine` with its runs watched: each is a base pass (:meth:`base_pass`) with :meth:`tick` on its
        progress updates."""
        return _Watched(engine, self) if self.enabled else engine

    def close(self) -> None:
        """Terminate and join every worker still running (speculation not taken, or an interrupted run)."""
        while self.workers:
            _, (_, worker) = self.workers.popitem()
            worker.stop()


class _Watched:
    def __init__(self, engine, session: Session):
        self.engine, self.session = engine, session

    def run(self, params, settings, *, progress: bool = False, **options):
        self.session.base_pass(settings)
        progress_module.watcher = self.session.tick
        try:
            return self.engine.run(params, settings, progress=progress, **options)
        finally:
            progress_module.watcher = None


@contextlib.contextmanager
def session(enabled: bool = True):
    """This thread's open Session, or a new one (closed, its workers stopped, on leaving) when none is open."""
    sessions = _sessions()
    if sessions:
        yield sessions[-1]
        return
    opened = Session(enabled)
    sessions.append(opened)
    try:
        yield opened
    finally:
        sessions.remove(opened)
        opened.close()


def current() -> Session:
    """This thread's open Session; a disabled one (every twin in this process) when none is open."""
    sessions = _sessions()
    return sessions[-1] if sessions else Session(enabled=False)


def _sessions() -> list:
    if not hasattr(_local, "sessions"):
        _local.sessions = []
    return _local.sessions
