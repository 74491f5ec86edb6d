"""Sweep engine (studies.sweep): keys, resume after a real kill, failures recorded, Dask = local, real solvers.

The cases run the fake solver of tests/sweep_fake.py (fails iff E < E_cr,max, Eq. 8), so every
expected outcome is known in closed form and the tests take seconds.
"""

import os
import signal
import subprocess
import sys
import time
from collections import Counter

import pytest

from lightsail_mbs import ParameterError, Result, RunSettings, SailParameters, paper_case, paper_settings
from lightsail_mbs.model import theory
from lightsail_mbs.studies.bisection import bisect_boundary
from lightsail_mbs.studies.store import CaseStore
from lightsail_mbs.studies.sweep import Case, run_sweep
from tests import sweep_fake
from tests.sweep_fake import executions, fake_case, small_sweep

OUTCOME = ("key", "status", "failed", "failure_time", "error", "parameters", "options", "solver")


def outcomes(records):
    return [{k: r.get(k) for k in OUTCOME} for r in records]


def test_key_identifies_parameters_solver_and_options():
    p = SailParameters(thickness=1e-6)
    assert Case(p, "fake").key == Case(SailParameters(thickness=1e-6, bending=True), "fake").key
    assert Case(p, "fake").key == Case(p, "fake", save_result=True).key
    assert Case(p, "fake").key == Case(p, "fake", settings=RunSettings()).key
    keys = {
        Case(p, "fake").key,
        Case(p, "reduced").key,
        Case(p, "fake", {"rtol": 1e-8}).key,
        Case(p.replace(thickness=2e-6), "fake").key,
        Case(p, "fake", settings=RunSettings(t_final=1.0)).key,
        Case(p, "fake", settings=RunSettings(failure_ratio=3.0)).key,
    }
    assert len(keys) == 6
    with pytest.raises(ParameterError, match="options"):
        Case(p, "fake", {"bad": object()})


def test_key_follows_the_content_of_an_optical_table_file(tmp_path):
    """A table file rewritten at the same path is a new case: its finished records are not served."""
    from tests.helpers import table_file

    path = table_file(tmp_path / "grating.npz")
    p = SailParameters(optics=str(path))
    first = Case(p, "fake").key
    assert Case(SailParameters(optics=str(path)), "fake").key == first
    table_file(path, scale=1.8)
    assert Case(SailParameters(optics=str(path)), "fake").key != first


def test_keys_of_stores_written_before_run_settings_are_unchanged():
    """The key hashes the case and its run in the key format of before the split (parameters named amplitude,
    mode, defect_modes, with t_final & co. among them): the same case and run have the same key as then."""
    assert Case(SailParameters(thickness=1e-6), "fake").key == "2977fc7a8e2fd190a856"
    assert (
        Case(paper_case("rigid", defect_mode=2.5), "reduced", {"rtol": 1e-8}, settings=paper_settings("rigid")).key
        == "b9e24a0a6b007b0fcf4c"
    )
    assert (
        Case(
            SailParameters(n=8, youngs_modulus=4.5e9, defect_seed=3, defect_mode_count=12),
            "exudyn",
            settings=RunSettings(t_final=0.02),
        ).key
        == "97059f65f8863d97e641"
    )


def test_keys_of_cases_with_a_beam_axis_are_those_of_its_older_name():
    """The store's key names the beam axis beam_center / beam_center_y, as before the field took the spelling
    beam_centre: a sheet under an off-centre Gaussian beam keeps the key it had."""
    p = SailParameters(model="sheet", n=4, ny=3, beam_waist=0.5, beam_centre=0.3, beam_centre_y=0.6)
    case = Case(p, "reduced", settings=RunSettings(t_final=0.01))
    assert {"beam_center", "beam_center_y"} <= set(case.description()["parameters"])
    assert case.key == "600c72b97516e5509d91"


def test_sweep_records_outcomes_and_skips_finished_cases(tmp_path, markers, capsys):
    cases = small_sweep(markers)
    records = run_sweep(cases + cases[:2], tmp_path / "store", workers=2, progress=True, case_function=fake_case)
    assert "12/12" in capsys.readouterr().err  # progress: cases done / total
    assert len(records) == 14 and records[12] == records[0]  # duplicates computed once
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
    cases = [
        Case(SailParameters(defect_mode=m, youngs_modulus=1e12 * (i + 1)), "fake", options) for i, m in enumerate(modes)
    ]
    records = run_sweep(cases, tmp_path / "store", workers=2, progress=False, case_function=fake_case)
    status = {r["parameters"]["defect_mode"]: (r["status"], r["error"]) for r in records}
    assert status[2.0][0] == "error" and "fake solver blew up" in status[2.0][1]
    assert status[2.5] == ("error", "fake divergence")
    assert status[3.0] == ("error", "worker process died running this case")
    assert all(status[m] == ("ok", None) for m in (0.5, 1.0, 1.5))
    assert executions(markers)[cases[4].key] >= 2  # rerun alone before blamed
    # errors are final unless asked: a rerun skips them, retry_errors reruns exactly them
    run_sweep(cases, tmp_path / "store", workers=1, progress=False, case_function=fake_case)
    before = executions(markers)
    run_sweep(cases[:4], tmp_path / "store", workers=1, progress=False, case_function=fake_case, retry_errors=True)
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
    run_sweep(
        [Case(stiff, "fake", options, save_result=True)] + cases[1:],
        tmp_path,
        workers=1,
        progress=False,
        case_function=fake_case,
    )
    assert executions(markers) == Counter({cases[0].key: 2, cases[1].key: 1})


def test_killed_sweep_resumes_without_recomputing(tmp_path, markers):
    script = sweep_fake.__file__
    store = tmp_path / "store"
    args = [sys.executable, str(script), str(store), str(markers), "0.25"]
    proc = subprocess.Popen(args, start_new_session=True, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 30
        while len(list(store.glob("*.json"))) < 4:
            assert proc.poll() is None and time.monotonic() < deadline, "sweep did not get going"
            time.sleep(0.02)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # the script and its pool workers, mid-sweep
        proc.wait()
    finished = set(CaseStore(store).keys())
    assert 4 <= len(finished) < 12
    resumed = run_sweep(small_sweep(markers, 0.25), store, workers=2, progress=False, case_function=fake_case)
    counts = executions(markers)
    assert all(counts[key] == 1 for key in finished)  # nothing finished was recomputed
    assert set(counts) == {r["key"] for r in resumed}
    reference = run_sweep(
        small_sweep(markers, 0.25), tmp_path / "reference", workers=2, progress=False, case_function=fake_case
    )
    assert outcomes(resumed) == outcomes(reference)


def test_dask_cluster_gives_the_local_results(tmp_path, markers):
    distributed = pytest.importorskip("distributed")
    cases = small_sweep(markers)
    local = run_sweep(cases, tmp_path / "local", workers=2, progress=False, case_function=fake_case)
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None, protocol="tcp://", host="127.0.0.1"
    ) as cluster:
        remote = run_sweep(
            cases, tmp_path / "dask", scheduler=cluster.scheduler_address, progress=False, case_function=fake_case
        )
        remote_boundary = bisect_boundary(
            lambda e: SailParameters(youngs_modulus=e),
            1e8,
            1e20,
            store_dir=tmp_path / "dask",
            solver="fake",
            progress=False,
            scheduler=cluster.scheduler_address,
            case_function=fake_case,
        )
    assert outcomes(remote) == outcomes(local)
    assert sum(executions(markers).values()) == 24
    local_boundary = bisect_boundary(
        lambda e: SailParameters(youngs_modulus=e),
        1e8,
        1e20,
        store_dir=tmp_path / "local",
        solver="fake",
        progress=False,
        workers=2,
        case_function=fake_case,
    )
    assert remote_boundary.status == "converged" and remote_boundary.evaluations == local_boundary.evaluations


@pytest.mark.parametrize("solver, module", [("reduced", "reduced.solver"), ("exudyn", "exudyn.chain")])
def test_real_solver_sweep_matches_a_direct_solve(tmp_path, solver, module):
    pytest.importorskip(f"lightsail_mbs.solvers.{module}")
    from lightsail_mbs import solve

    cases = [
        Case(SailParameters(n=8, youngs_modulus=e), solver, save_result=True, settings=RunSettings(t_final=0.02))
        for e in (4.5e9, 4.5e13)
    ]
    records = run_sweep(cases, tmp_path, workers=2, progress=False)
    for case, record in zip(cases, records):
        direct = solve(case.params, solver, case.settings, uncertainty=False)
        assert record["status"] == ("error" if direct.error else "ok")
        assert record["failed"] == direct.failed and record["t_end"] == pytest.approx(direct.time[-1])
        saved = Result.load(tmp_path / record["result_path"])
        assert saved.amplitude == pytest.approx(direct.amplitude) and saved.settings == case.settings
