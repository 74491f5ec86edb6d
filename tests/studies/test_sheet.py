"""Sweeps, the store and the stability bisection take sheets like chains: a small sheet through the store,
its boundary in the strip's units, and the solvers' comparison."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters, solve
from lightsail_mbs.model import plate_theory
from lightsail_mbs.studies import sheet as sheet_study
from lightsail_mbs.studies.store import CaseStore
from lightsail_mbs.studies.sweep import Case, run_sweep
from tests.helpers import synthetic_sheet

SMALL = SailParameters(model="sheet", n=8, ny=3, youngs_modulus=4.5e9)


def test_sheet_cases_sweep_through_the_store(tmp_path):
    cases = [
        Case(SMALL, "reduced", settings=RunSettings(t_final=0.2)),
        Case(SMALL.replace(defect_mode_y=1.0), "reduced", save_result=True, settings=RunSettings(t_final=0.2)),
    ]
    records = run_sweep(cases, tmp_path, workers=1, progress=False)
    assert [r["status"] for r in records] == ["ok", "ok"]
    assert records[0]["ny"] == 3 and records[0]["parameters"]["model"] == "sheet"
    assert len({c.key for c in cases}) == 2
    again = run_sweep(cases, tmp_path, workers=1, progress=False)  # found, not rerun
    assert [r["case_wall_time"] for r in again] == [r["case_wall_time"] for r in records]
    assert len(CaseStore(tmp_path).records()) == 2


def test_stability_bisection_of_a_small_sheet(tmp_path):
    """The edge tension that keeps a 8 × 3 soft sheet from failing within 3 s is bracketed, and the
    bracket's ends are a failed and a surviving run in the store."""
    found = sheet_study.stability_boundaries(
        {"sheet": SMALL},
        "edge_tension",
        tmp_path,
        settings=RunSettings(t_final=3.0),
        lo=0.25,
        hi=8.0,
        factor=2.0,
        workers=1,
        progress=False,
    )["sheet"]
    assert found.status == "converged" and found.monotone
    lo, hi = found.bracket
    assert hi / lo <= 2.0 and found.unstable_value == lo
    records = {r["key"]: r for r in CaseStore(tmp_path).records()}
    verdicts = {v: records[k]["failed"] for v, s, k in found.evaluations}
    assert verdicts[lo] is True and verdicts[hi] is False
    t = records[[k for v, s, k in found.evaluations if v == hi][0]]["parameters"]["edge_tension"]
    assert t == pytest.approx(hi * plate_theory.critical_tension_per_width(SMALL))


def test_with_ratio_and_its_errors():
    p = sheet_study.with_ratio(SMALL, "modulus", 2.0)
    assert p.youngs_modulus == pytest.approx(2 * 4.506e11, rel=1e-3)
    with pytest.raises(ParameterError, match="quantity"):
        sheet_study.with_ratio(SMALL, "density", 2.0)


def test_compare_deflections_of_identical_and_shifted_runs():
    a = synthetic_sheet(steps=9)
    assert sheet_study.compare_deflections(a, a) == (0.0, pytest.approx(0.375))  # e^t < 1.5 up to 0.375 s
    b = synthetic_sheet(steps=9)
    b.tile_centres = b.tile_centres.copy()
    b.tile_centres[:, 0, 2] += 1e-3 * a.amplitude[0]
    d, _ = sheet_study.compare_deflections(a, b)
    assert 5e-4 < d < 2e-3
    with pytest.raises(ParameterError):
        from tests.helpers import growing_sine

        sheet_study.compare_deflections(a, growing_sine())
    assert np.isfinite(d)


def test_twin_rule_is_the_papers_rule_without_tension(tmp_path):
    """Without tension the unlit soft strip holds its shape over 3 s (its bending period is ~2 min), so the
    twin rule fails the lit strip at the paper's failure time, sample for sample; the departure from the
    twin reaches a(0) earlier (the defect changes shape as it grows), which is why it is not the rule."""
    p = SailParameters(model="sheet", n=12, ny=1, youngs_modulus=4.5e9)
    lit, unlit, v = sheet_study.twin_runs(p, tmp_path, RunSettings(t_final=3.0))
    assert v.unlit_max_ratio == pytest.approx(1.0, abs=1e-6)
    doubled = lit.time[np.nonzero(lit.amplitude >= 2.0 * lit.amplitude[0])[0][0]]
    assert v.failed and v.failure_time == doubled
    papers = solve(p, "reduced", RunSettings(t_final=3.0))  # the paper's rule: stops at 2 a(0)
    assert v.failure_time == pytest.approx(papers.failure_time, abs=1.5e-3)
    departure = sheet_study.twin_departure(lit, unlit) / lit.amplitude[0]
    early = lit.time[np.nonzero(departure >= 1.0)[0][0]]
    assert 0.9 * doubled < early < 0.99 * doubled
    assert np.all(sheet_study.twin_departure(unlit, unlit) == 0.0)


def test_twin_boundary_brackets_the_tension_of_a_strip(tmp_path):
    p = SailParameters(model="sheet", n=8, ny=1, youngs_modulus=4.5e9)

    def boundary():
        return sheet_study.twin_boundary(
            "strip",
            p,
            "edge_tension",
            tmp_path,
            settings=RunSettings(t_final=3.0),
            lo=0.25,
            hi=8.0,
            factor=2.0,
            progress=False,
        )

    found, verdicts = boundary()
    assert found.status == "converged"
    lo, hi = found.bracket
    assert hi / lo <= 2.0
    assert verdicts[found.unstable_value].failed and not verdicts[found.stable_value].failed
    again, _ = boundary()  # from the store
    assert again.bracket == found.bracket
