"""Sweep engine: keys, resume after a real kill, failures recorded, Dask = local, bisection.

The cases run the fake solver of tests/sweep_fake.py (fails iff E < E_cr,max, Eq. 8), so every
expected outcome is known in closed form and the tests take seconds.
"""
import os
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import pytest

from lightsail_mbs import ParameterError, Result, SailParameters
from lightsail_mbs.model import theory
from lightsail_mbs.studies.bisection import (BoundaryProblem, bisect_boundaries, bisect_boundary, default_stable)
from lightsail_mbs.studies.store import CaseStore
from lightsail_mbs.studies.sweep import Case, run_sweep

sys.path.insert(0, str(Path(__file__).parent))
from sweep_fake import fake_case, small_sweep  # noqa: E402

OUTCOME = ("key", "status", "failed", "failure_time", "error", "parameters", "options", "solver")


def executions(marker_dir) -> Counter:
    """How many times each case key was executed (one marker file per execution)."""
    return Counter(name.split(".")[0] for name in os.listdir(marker_dir))


def outcomes(records):
    return [{k: r.get(k) for k in OUTCOME} for r in records]


@pytest.fixture
def markers(tmp_path):
    path = tmp_path / "markers"
    path.mkdir()
    return path


def test_key_identifies_parameters_solver_and_options():
    p = SailParameters(thickness=1e-6)
    assert Case(p, "fake").key == Case(SailParameters(thickness=1e-6, bending=True), "fake").key
    assert Case(p, "fake").key == Case(p, "fake", save_result=True).key
    keys = {Case(p, "fake").key, Case(p, "reduced").key, Case(p, "fake", {"rtol": 1e-8}).key,
            Case(p.replace(thickness=2e-6), "fake").key}
    assert len(keys) == 4
    with pytest.raises(ParameterError, match="options"):
        Case(p, "fake", {"bad": object()})


def test_sweep_records_outcomes_and_skips_finished_cases(tmp_path, markers, capsys):
    cases = small_sweep(markers)
    records = run_sweep(cases + cases[:2], tmp_path / "store", workers=2, progress=True,
                        case_function=fake_case)
    assert "12/12" in capsys.readouterr().err                          # progress: cases done / total
    assert len(records) == 14 and records[12] == records[0]          # duplicates computed once
    assert set(executions(markers).values()) == {1} and len(executions(markers)) == 12
    for case, record in zip(cases, records):
        assert record["key"] == case.key and record["status"] == "ok"
        assert record["failed"] == (case.params.youngs_modulus < theory.critical_modulus_max(case.params))
    assert {r["failed"] for r in records} == {True, False}
    assert sorted(CaseStore(tmp_path / "store").keys()) == sorted(c.key for c in cases)
    again = run_sweep(cases, tmp_path / "store", workers=2, progress=False, case_function=fake_case)
    assert again == records[:12] and sum(executions(markers).values()) == 12


def test_failing_cases_are_recorded_and_the_sweep_goes_on(tmp_path, markers):
    options = dict(marker_dir=str(markers), raise_modes=[2.0], error_modes=[2.5], crash_modes=[3.0])
    modes = [1.0, 2.0, 1.5, 2.5, 3.0, 0.5, 1.0]
    cases = [Case(SailParameters(mode=m, youngs_modulus=1e12 * (i + 1)), "fake", options)
             for i, m in enumerate(modes)]
    records = run_sweep(cases, tmp_path / "store", workers=2, progress=False, case_function=fake_case)
    status = {r["parameters"]["mode"]: (r["status"], r["error"]) for r in records}
    assert status[2.0][0] == "error" and "fake solver blew up" in status[2.0][1]
    assert status[2.5] == ("error", "fake divergence")
    assert status[3.0] == ("error", "worker process died running this case")
    assert all(status[m] == ("ok", None) for m in (0.5, 1.0, 1.5))
    assert executions(markers)[cases[4].key] >= 2                      # rerun alone before blamed
    # errors are final unless asked: a rerun skips them, retry_errors reruns exactly them
    run_sweep(cases, tmp_path / "store", workers=1, progress=False, case_function=fake_case)
    before = executions(markers)
    run_sweep(cases[:4], tmp_path / "store", workers=1, progress=False, case_function=fake_case,
              retry_errors=True)
    rerun = executions(markers) - before
    assert set(rerun) == {cases[1].key, cases[3].key}


def test_default_case_function_goes_through_solve(tmp_path):
    [record] = run_sweep([Case(SailParameters(), "no-such-solver")], tmp_path, workers=1, progress=False)
    assert record["status"] == "error" and "ParameterError" in record["error"] and "solver" in record["error"]


def test_full_results_are_saved_when_asked(tmp_path, markers):
    stiff, soft = (SailParameters(youngs_modulus=e) for e in (1e16, 1e10))
    options = dict(marker_dir=str(markers), as_result=True)
    cases = [Case(stiff, "fake", options), Case(soft, "fake", options, save_result=True)]
    records = run_sweep(cases, tmp_path, workers=2, progress=False, case_function=fake_case)
    assert [r["failed"] for r in records] == [False, True] and "result_path" not in records[0]
    saved = Result.load(tmp_path / records[1]["result_path"])
    assert saved.params == soft and saved.failed and saved.failure_time == records[1]["failure_time"]
    # a record without its requested Result is not finished: asking for the Result reruns that case only
    run_sweep([Case(stiff, "fake", options, save_result=True)] + cases[1:], tmp_path, workers=1,
              progress=False, case_function=fake_case)
    assert executions(markers) == Counter({cases[0].key: 2, cases[1].key: 1})


def test_killed_sweep_resumes_without_recomputing(tmp_path, markers):
    script = Path(__file__).with_name("sweep_fake.py")
    store = tmp_path / "store"
    args = [sys.executable, str(script), str(store), str(markers), "0.25"]
    proc = subprocess.Popen(args, start_new_session=True, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 30
        while len(list(store.glob("*.json"))) < 4:
            assert proc.poll() is None and time.monotonic() < deadline, "sweep did not get going"
            time.sleep(0.02)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)   # the script and its pool workers, mid-sweep
        proc.wait()
    finished = set(CaseStore(store).keys())
    assert 4 <= len(finished) < 12
    resumed = run_sweep(small_sweep(markers, 0.25), store, workers=2, progress=False, case_function=fake_case)
    counts = executions(markers)
    assert all(counts[key] == 1 for key in finished)                  # nothing finished was recomputed
    assert set(counts) == {r["key"] for r in resumed}
    reference = run_sweep(small_sweep(markers, 0.25), tmp_path / "reference", workers=2, progress=False,
                          case_function=fake_case)
    assert outcomes(resumed) == outcomes(reference)


def test_dask_cluster_gives_the_local_results(tmp_path, markers):
    distributed = pytest.importorskip("distributed")
    cases = small_sweep(markers)
    local = run_sweep(cases, tmp_path / "local", workers=2, progress=False, case_function=fake_case)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                                  dashboard_address=None, protocol="tcp://", host="127.0.0.1") as cluster:
        remote = run_sweep(cases, tmp_path / "dask", scheduler=cluster.scheduler_address, progress=False,
                           case_function=fake_case)
        remote_boundary = bisect_boundary(lambda e: SailParameters(youngs_modulus=e), 1e8, 1e20,
                                          store_dir=tmp_path / "dask", solver="fake", progress=False,
                                          scheduler=cluster.scheduler_address, case_function=fake_case)
    assert outcomes(remote) == outcomes(local)
    assert sum(executions(markers).values()) == 24
    local_boundary = bisect_boundary(lambda e: SailParameters(youngs_modulus=e), 1e8, 1e20,
                                     store_dir=tmp_path / "local", solver="fake", progress=False, workers=2,
                                     case_function=fake_case)
    assert remote_boundary.status == "converged" and remote_boundary.evaluations == local_boundary.evaluations


def fake_threshold(thickness):
    return theory.critical_modulus_max(SailParameters(thickness=thickness))


@pytest.mark.parametrize("lo, hi, points", [(1e8, 1e20, 1), (1e20, 1e21, 1), (1e3, 1e4, 2)])
def test_bisection_brackets_and_converges_to_the_known_threshold(tmp_path, markers, lo, hi, points):
    thicknesses = (1e-7, 1e-6, 1e-5)
    problems = {h: BoundaryProblem(lambda e, h=h: SailParameters(thickness=h, youngs_modulus=e), lo, hi)
                for h in thicknesses}
    options = {"marker_dir": str(markers)}
    found = bisect_boundaries(problems, store_dir=tmp_path, solver="fake", options=options, factor=1.5,
                              workers=2, points_per_round=points, progress=False, case_function=fake_case)
    for h, b in found.items():
        lo_b, hi_b = b.bracket
        assert b.status == "converged" and b.monotone and hi_b / lo_b <= 1.5
        assert b.stable_value == hi_b and b.unstable_value == lo_b           # stiff side stable
        assert lo_b <= fake_threshold(h) <= hi_b
    ran = executions(markers)
    assert set(ran.values()) == {1} and len(ran) == sum(len(b.evaluations) for b in found.values())
    # a rerun (as after a kill) finds every case in the store, takes the same path, computes nothing
    again = bisect_boundaries(problems, store_dir=tmp_path, solver="fake", options=options, factor=1.5,
                              workers=2, points_per_round=points, progress=False, case_function=fake_case)
    assert {h: b.evaluations for h, b in again.items()} == {h: b.evaluations for h, b in found.items()}
    assert executions(markers) == ran


def test_default_stability_verdict():
    assert default_stable({"status": "ok", "failed": False}) is True
    assert default_stable({"status": "ok", "failed": True}) is False
    assert default_stable({"status": "error", "failed": True}) is False    # failed before diverging
    assert default_stable({"status": "error", "failed": False}) is None
    assert default_stable({"status": "error", "failed": None}) is None


def test_bisection_reports_what_it_cannot_decide(tmp_path):
    unbracketed = bisect_boundary(lambda e: SailParameters(youngs_modulus=e), 1e25, 1e26, store_dir=tmp_path,
                                  solver="fake", max_expansions=0, workers=1, progress=False,
                                  case_function=fake_case)
    assert unbracketed.status == "unbracketed" and unbracketed.value is None
    errored = bisect_boundary(lambda e: SailParameters(youngs_modulus=e, mode=2.5), 1e8, 1e20,
                              store_dir=tmp_path, solver="fake", options={"error_modes": [2.5]}, workers=1,
                              progress=False, case_function=fake_case)
    assert errored.status == "error" and "fake divergence" in errored.message
    with pytest.raises(ParameterError, match="bracket"):
        bisect_boundary(lambda e: SailParameters(youngs_modulus=e), 1e9, 1e8, store_dir=tmp_path)
    with pytest.raises(ParameterError, match="workers"):
        run_sweep([], tmp_path, workers=0)


@pytest.mark.parametrize("solver, module", [("reduced", "reduced.solver"), ("exudyn", "exudyn.chain")])
def test_real_solver_sweep_matches_a_direct_solve(tmp_path, solver, module):
    pytest.importorskip(f"lightsail_mbs.solvers.{module}")
    from lightsail_mbs import solve
    cases = [Case(SailParameters(n=8, youngs_modulus=e, t_final=0.02), solver, save_result=True)
             for e in (4.5e9, 4.5e13)]
    records = run_sweep(cases, tmp_path, workers=2, progress=False)
    for case, record in zip(cases, records):
        direct = solve(case.params, solver)
        assert record["status"] == ("error" if direct.error else "ok")
        assert record["failed"] == direct.failed and record["t_end"] == pytest.approx(direct.time[-1])
        assert Result.load(tmp_path / record["result_path"]).amplitude == pytest.approx(direct.amplitude)
