"""Twins in worker processes (solvers.twin_workers): the same answers as in process, bit for bit; tiny runs kept
in process; no worker outlives its run, Ctrl-C included; a worker's exception or death reaches the caller."""

import math
import os
import pickle
import time

import numpy as np
import pytest

import lightsail_mbs
from lightsail_mbs import paper_case, paper_settings
from lightsail_mbs.solvers import twin_workers

pytestmark = pytest.mark.skipif(not twin_workers.usable(), reason="no fork, or one core: twins run in process")

TIMES = ("wall_time", "cpu_time", "elapsed")


def values(record):
    """An uncertainty record without its timings (what the twins answered), pickled for a bitwise comparison."""
    if isinstance(record, dict):
        return {key: values(value) for key, value in record.items() if key not in TIMES}
    return record


class Started:
    """The workers started, and for each twin asked for whether a worker had started it already (before the base
    run ended, when the base run is the only thing run before the twins are asked for)."""

    def __init__(self, monkeypatch):
        self.jobs, self.taken = [], []
        original_init, original_take = twin_workers.Worker.__init__, twin_workers.Session.take

        def init(worker, work):
            self.jobs.append(work)
            original_init(worker, work)

        def take(session, work):
            self.taken.append(work.key in session.workers)
            return original_take(session, work)

        monkeypatch.setattr(twin_workers.Worker, "__init__", init)
        monkeypatch.setattr(twin_workers.Session, "take", take)


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_concurrent_default_run_gives_the_sequential_record_bit_for_bit(solver, monkeypatch):
    """The soft torsion sail (fails at 2.1 s, n-twins at 15 and 7): every twin started in a worker as the base
    run starts (CONCURRENT_AFTER = 0), against all of them in process; the records' answers and the reported
    trajectories are identical, and every twin the estimate took was started before the base run ended."""
    p, settings = paper_case("torsion-soft"), paper_settings("torsion-soft")
    monkeypatch.setattr(twin_workers, "CONCURRENT_AFTER", math.inf)
    sequential = lightsail_mbs.solve(p, solver, settings)
    started = Started(monkeypatch)
    monkeypatch.setattr(twin_workers, "CONCURRENT_AFTER", 0.0)
    monkeypatch.setattr(twin_workers, "MIN_IDLE_CORES", 0.0)
    concurrent = lightsail_mbs.solve(p, solver, settings)
    assert sequential.uncertainty["estimated"] and sequential.uncertainty["n_error"]["estimated"]
    assert pickle.dumps(values(concurrent.uncertainty)) == pickle.dumps(values(sequential.uncertainty))
    assert np.array_equal(concurrent.amplitude, sequential.amplitude) and np.array_equal(concurrent.x, sequential.x)
    twins = [name for name in ("loose", "probe", "film") if name in sequential.uncertainty]
    assert len(started.taken) == len(twins) + len(sequential.uncertainty["n_error"]["twins"])
    assert all(started.taken), "a twin started after the base run: its speculation did not match"
    for name in twins:  # each twin's CPU time is its worker's
        assert concurrent.uncertainty[name]["cpu_time"] > 0


def test_a_tiny_run_keeps_its_twins_in_process(monkeypatch):
    """The reduced solver's soft sail takes milliseconds: no worker is started at the default threshold."""
    p, settings = paper_case("torsion-soft"), paper_settings("torsion-soft")
    lightsail_mbs.solve(p, "reduced", settings, uncertainty=False)  # compiled kernels loaded
    started = Started(monkeypatch)
    start = time.perf_counter()
    result = lightsail_mbs.solve(p, "reduced", settings)
    if time.perf_counter() - start < twin_workers.CONCURRENT_AFTER:
        assert started.jobs == []
    assert result.uncertainty["estimated"]


def sleeper(seconds):
    time.sleep(seconds)
    return os.getpid()


def alive(pid) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    with open(f"/proc/{pid}/stat") as stat:  # a zombie (not yet reaped by anyone) counts as gone
        return stat.read().split(") ")[-1][0] != "Z"


def test_a_worker_returns_its_value_and_cpu_time_and_the_session_stops_what_was_not_taken():
    with twin_workers.session() as workers:
        workers.concurrent = workers.decided = True
        quick = twin_workers.job(("quick",), sleeper, 0.0)
        slow = twin_workers.job(("slow",), sleeper, 60.0)
        workers.submit(quick)
        workers.submit(slow)
        pid, cpu = workers.take(quick)
        assert pid != os.getpid() and 0 <= cpu < 1
        slow_pid = workers.workers[slow.key][1].process.pid
        assert alive(slow_pid)
    assert not alive(slow_pid) and not workers.workers


def test_ctrl_c_in_the_run_leaves_no_worker():
    """A KeyboardInterrupt raised while twins run (as Ctrl-C raises it in the main process: the workers ignore
    SIGINT) ends the session with every worker terminated."""
    pids = []
    with pytest.raises(KeyboardInterrupt), twin_workers.session() as workers:
        workers.concurrent = workers.decided = True
        for seconds in (60.0, 61.0):
            work = twin_workers.job(("sleep", seconds), sleeper, seconds)
            workers.submit(work)
            pids.append(workers.workers[work.key][1].process.pid)
        raise KeyboardInterrupt
    assert pids and not any(alive(pid) for pid in pids)


def raises():
    raise ValueError("inside the worker")


def dies():
    os._exit(3)


def test_a_workers_exception_is_raised_and_its_death_is_a_runtime_error():
    with twin_workers.session() as workers:
        workers.concurrent = workers.decided = True
        with pytest.raises(ValueError, match="inside the worker"):
            workers.take(twin_workers.job(("raises",), raises))
        with pytest.raises(RuntimeError, match="exit code 3"):
            workers.take(twin_workers.job(("dies",), dies))


def test_jobs_are_keyed_by_their_inputs_not_the_order_of_options():
    a = twin_workers.job(("twin", {"rtol": 1e-7, "perturbation": 0.0}), sleeper, 0.0)
    b = twin_workers.job(("twin", {"perturbation": 0.0, "rtol": 1e-7}), sleeper, 0.0)
    c = twin_workers.job(("twin", {"perturbation": 0.0, "rtol": 1.0000000000000002e-7}), sleeper, 0.0)
    assert a.key == b.key != c.key


def test_a_run_outside_the_main_thread_keeps_its_twins_in_process(monkeypatch):
    """The progress hook is one per process: a default run in another thread (a threaded scheduler's) starts no
    worker, and gives the record it gives in the main thread."""
    import threading

    p, settings = paper_case("torsion-soft"), paper_settings("torsion-soft")
    monkeypatch.setattr(twin_workers, "CONCURRENT_AFTER", 0.0)
    monkeypatch.setattr(twin_workers, "MIN_IDLE_CORES", 0.0)
    in_main = lightsail_mbs.solve(p, "reduced", settings)
    started, results = Started(monkeypatch), []
    thread = threading.Thread(target=lambda: results.append(lightsail_mbs.solve(p, "reduced", settings)))
    thread.start()
    thread.join()
    assert started.jobs == [] and started.taken == [False] * len(started.taken)
    assert pickle.dumps(values(results[0].uncertainty)) == pickle.dumps(values(in_main.uncertainty))


def test_every_run_draws_its_bar_the_workers_labelled_twin(monkeypatch, capfd):
    p, settings = paper_case("torsion-soft"), paper_settings("torsion-soft")
    monkeypatch.setattr(twin_workers, "CONCURRENT_AFTER", 0.0)
    monkeypatch.setattr(twin_workers, "MIN_IDLE_CORES", 0.0)
    result = lightsail_mbs.solve(p, "reduced", settings, progress=True)
    bars = capfd.readouterr().err.replace("\r", "\n")
    runs = 1 + sum(name in result.uncertainty for name in ("loose", "probe", "film"))
    runs += len(result.uncertainty["n_error"]["twins"])
    assert bars.count("twin reduced:") >= runs - 1 and "\nreduced:" in "\n" + bars


def test_workers_only_where_a_core_stood_idle(monkeypatch):
    """A machine whose cores were all busy during the base run keeps the twins in process; the idle cores
    measured over a sleep lie between 0 and the machine's cores."""
    since = twin_workers.machine_times()
    time.sleep(0.05)
    if since is not None:
        assert 0.0 <= twin_workers.idle_cores(since) <= os.cpu_count()
    p, settings = paper_case("torsion-soft"), paper_settings("torsion-soft")
    monkeypatch.setattr(twin_workers, "CONCURRENT_AFTER", 0.0)
    monkeypatch.setattr(twin_workers, "idle_cores", lambda since: 0.0)
    started = Started(monkeypatch)
    result = lightsail_mbs.solve(p, "reduced", settings)
    assert started.jobs == [] and result.uncertainty["estimated"]


def test_an_answer_only_twin_comes_back_without_its_trajectories():
    """A worker's answer-only Result (the loose, probe, film and n-twins) keeps the time, amplitude history and
    answer of the run in process, with no column of its trajectories: kilobytes, not the megabytes of 6 s of a
    chain, pickled back."""
    p, settings = paper_case("torsion-stable", n=10), paper_settings("torsion-stable")
    here = lightsail_mbs.solvers.solve(p, "reduced", settings, uncertainty=False)
    work = twin_workers.job(("answer only",), lightsail_mbs.solvers.solve, p, "reduced", settings, uncertainty=False)
    work.answer_only = True
    there, _ = twin_workers.Worker(work).result()
    assert np.array_equal(there.time, here.time) and np.array_equal(there.amplitude, here.amplitude)
    assert there.max_amplitude_ratio == here.max_amplitude_ratio and there.failed == here.failed
    assert there.x.shape == (here.time.size, 0) and there.omega.shape == (here.time.size, 0)
    assert len(pickle.dumps(there)) < len(pickle.dumps(here)) / 10
