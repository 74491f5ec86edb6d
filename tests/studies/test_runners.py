"""Where sweep cases run (studies.runners), under faults: a worker killed with SIGKILL in the middle of a case,
in the local process pool and in a local Dask cluster; the number of workers.

The cases are real runs of both solvers (tests.sweep_fake.real_cases) through ``held_solve``, which marks
each execution with its process id and pauses first, so a test can kill the process running a case. Every
sweep must finish, lose no case, recompute no case that had finished, and leave records equal to an
uninterrupted sweep's bit for bit except the fields that are measured times (RECORD_TIMINGS).
"""

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from lightsail_mbs.result import ARRAYS, Result
from lightsail_mbs.studies.store import CaseStore
from lightsail_mbs.studies.sweep import run_sweep
from tests import sweep_fake
from tests.sweep_fake import HOLD, MARKERS, executions, held_solve, real_cases

# Fields of a record that are measured, not computed, and so differ between two runs of the same case:
# the solver's wall time (Result.wall_time, "wall_time"), the worker's wall time for the whole case
# ("case_wall_time") and the moment the Result was made (provenance "created"), and the state of the
# checkout when it was made (provenance "git_commit", "git_dirty": a commit or an edited file during the
# test changes them, not the numbers). Everything else — the summary, failure time, amplitudes, solver
# statistics, code version, parameters — must be equal.
RECORD_TIMINGS = ("wall_time", "case_wall_time")
PROVENANCE_NOT_COMPUTED = ("created", "git_commit", "git_dirty")


def comparable(record: dict) -> str:
    """The record without its measured times, as canonical JSON (exact: floats by their repr)."""
    out = {k: v for k, v in record.items() if k not in RECORD_TIMINGS}
    out["provenance"] = {k: v for k, v in out.get("provenance", {}).items() if k not in PROVENANCE_NOT_COMPUTED}
    return json.dumps(out, sort_keys=True)


def assert_same_records(store, records, reference_store, reference):
    """Records equal but for their timings, and their saved Results equal array for array, bit for bit."""
    for record, ref in zip(records, reference):
        mine, theirs = json.loads(comparable(record)), json.loads(comparable(ref))
        differing = sorted(k for k in mine.keys() | theirs.keys() if mine.get(k) != theirs.get(k))
        assert not differing, {k: (mine.get(k), theirs.get(k)) for k in differing}
    assert len(records) == len(reference)
    for record, ref in zip(records, reference):
        mine, theirs = Result.load(store / record["result_path"]), Result.load(reference_store / ref["result_path"])
        for name in ARRAYS:
            assert getattr(mine, name).tobytes() == getattr(theirs, name).tobytes(), (record["key"], name)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The uninterrupted sweep: every case in this process, one after the other."""
    store = tmp_path_factory.mktemp("reference")
    return store, run_sweep(real_cases(), store, workers=1, progress=False)


def sweep_and_kill_one_worker(store, markers, scheduler=None):
    """Run the held sweep in a fresh process; once a case has finished, SIGKILL the process running another
    case (the worker, not the sweep). Returns (exit status, stderr, killed case key, keys finished before)."""
    args = [sys.executable, sweep_fake.__file__, "held", str(store), "2"] + ([scheduler] if scheduler else [])
    proc = subprocess.Popen(args, stderr=subprocess.PIPE, text=True, env={**os.environ, MARKERS: str(markers)})
    hold = float(os.environ[HOLD])
    victim, finished, deadline = None, set(), time.monotonic() + 120
    try:
        while victim is None:
            assert proc.poll() is None and time.monotonic() < deadline, "no case to kill"
            finished = set(CaseStore(store).keys()) if store.exists() else set()
            # a case started less than hold/2 ago is surely still in its pause: its process is running it
            fresh = [
                name.split(".")
                for name in os.listdir(markers)
                if name.split(".")[0] not in finished and time.time() - (markers / name).stat().st_mtime < hold / 2
            ]
            if finished and fresh:
                victim = fresh[0][0]
                os.kill(int(fresh[0][1]), signal.SIGKILL)
            time.sleep(0.01)
        _, err = proc.communicate(timeout=300)
    finally:
        if proc.poll() is None:
            proc.kill()
    return proc.returncode, err, victim, finished


def check_recovered(store, markers, victim, finished, reference):
    """No case lost, none finished recomputed, the killed one rerun, records as without the kill; and a rerun
    of the sweep recomputes nothing. Returns (cases lost, stale or changed records served)."""
    cases = real_cases()
    records = [CaseStore(store).load(c.key) for c in cases]
    counts = executions(markers)
    lost = sum(r["status"] != "ok" or not CaseStore(store).has(r["key"], with_result=True) for r in records)
    assert lost == 0
    assert all(counts[key] == 1 for key in finished), counts  # nothing that had finished was recomputed
    assert counts[victim] >= 2  # the killed case ran again
    assert_same_records(store, records, *reference)
    before = executions(markers)
    os.environ[MARKERS] = str(markers)
    try:
        again = run_sweep(cases, store, workers=2, progress=False, case_function=held_solve)
    finally:
        del os.environ[MARKERS]
    assert executions(markers) == before  # the rerun computes nothing
    assert again == records
    served_stale = sum(comparable(r) != comparable(ref) for r, ref in zip(again, reference[1]))
    return lost, served_stale


def test_a_pool_worker_killed_mid_case_loses_nothing(tmp_path, markers, reference, monkeypatch):
    monkeypatch.setenv(HOLD, "0.3")
    code, err, victim, finished = sweep_and_kill_one_worker(tmp_path / "store", markers)
    assert code == 0, err
    assert 1 <= len(finished) < len(real_cases())
    assert check_recovered(tmp_path / "store", markers, victim, finished, reference) == (0, 0)


@pytest.mark.slow
def test_a_dask_worker_killed_mid_case_loses_nothing(tmp_path, markers, reference, monkeypatch):
    """A local cluster of two worker processes on 127.0.0.1, started and stopped here; Dask reschedules the
    killed worker's case on the other (or the restarted) worker."""
    distributed = pytest.importorskip("distributed")
    monkeypatch.setenv(HOLD, "0.3")
    monkeypatch.setenv(MARKERS, str(markers))  # the cluster's workers are started with this environment
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster:
        code, err, victim, finished = sweep_and_kill_one_worker(
            tmp_path / "store", markers, scheduler=cluster.scheduler_address
        )
        pids = {int(name.split(".")[1]) for name in os.listdir(markers)}
    assert code == 0, err
    for pid in pids:  # the cluster's processes are gone with it
        with pytest.raises(ProcessLookupError):
            os.kill(pid, 0)
    monkeypatch.delenv(MARKERS)
    assert check_recovered(tmp_path / "store", markers, victim, finished, reference) == (0, 0)


def test_one_and_two_workers_give_identical_records(tmp_path, reference):
    two = run_sweep(real_cases(), tmp_path, workers=2, progress=False)
    assert_same_records(tmp_path, two, *reference)
    assert {r["solver"] for r in two} == {"exudyn", "reduced"} and all(r["status"] == "ok" for r in two)
