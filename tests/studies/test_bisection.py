"""Stability bisection (studies.bisection) on the fake solver of tests/sweep_fake.py: brackets the known
threshold, resumes from the store, reports what it cannot decide."""

import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters
from lightsail_mbs.model import theory
from lightsail_mbs.studies.bisection import BoundaryProblem, bisect_boundaries, bisect_boundary, default_stable
from lightsail_mbs.studies.sweep import Case, run_sweep
from tests.sweep_fake import executions, fake_case


def fake_threshold(thickness):
    return theory.critical_modulus_max(SailParameters(thickness=thickness))


@pytest.mark.parametrize("lo, hi, points", [(1e8, 1e20, 1), (1e20, 1e21, 1), (1e3, 1e4, 2)])
def test_bisection_brackets_and_converges_to_the_known_threshold(tmp_path, markers, lo, hi, points):
    thicknesses = (1e-7, 1e-6, 1e-5)
    problems = {
        h: BoundaryProblem(lambda e, h=h: SailParameters(thickness=h, youngs_modulus=e), lo, hi) for h in thicknesses
    }
    options = {"marker_dir": str(markers)}
    found = bisect_boundaries(
        problems,
        store_dir=tmp_path,
        solver="fake",
        options=options,
        factor=1.5,
        workers=2,
        points_per_round=points,
        progress=False,
        case_function=fake_case,
    )
    for h, b in found.items():
        lo_b, hi_b = b.bracket
        assert b.status == "converged" and b.monotone and hi_b / lo_b <= 1.5
        assert b.stable_value == hi_b and b.unstable_value == lo_b  # stiff side stable
        assert lo_b <= fake_threshold(h) <= hi_b
    ran = executions(markers)
    assert set(ran.values()) == {1} and len(ran) == sum(len(b.evaluations) for b in found.values())
    # a rerun (as after a kill) finds every case in the store, takes the same path, computes nothing
    again = bisect_boundaries(
        problems,
        store_dir=tmp_path,
        solver="fake",
        options=options,
        factor=1.5,
        workers=2,
        points_per_round=points,
        progress=False,
        case_function=fake_case,
    )
    assert {h: b.evaluations for h, b in again.items()} == {h: b.evaluations for h, b in found.items()}
    assert executions(markers) == ran


def test_default_stability_verdict():
    assert default_stable({"status": "ok", "failed": False}) is True
    assert default_stable({"status": "ok", "failed": True}) is False
    assert default_stable({"status": "error", "failed": True}) is False  # failed before diverging
    assert default_stable({"status": "error", "failed": False}) is None
    assert default_stable({"status": "error", "failed": None}) is None


def test_bisection_reports_what_it_cannot_decide(tmp_path):
    unbracketed = bisect_boundary(
        lambda e: SailParameters(youngs_modulus=e),
        1e25,
        1e26,
        store_dir=tmp_path,
        solver="fake",
        max_expansions=0,
        workers=1,
        progress=False,
        case_function=fake_case,
    )
    assert unbracketed.status == "unbracketed" and unbracketed.value is None
    errored = bisect_boundary(
        lambda e: SailParameters(youngs_modulus=e, defect_mode=2.5),
        1e8,
        1e20,
        store_dir=tmp_path,
        solver="fake",
        options={"error_modes": [2.5]},
        workers=1,
        progress=False,
        case_function=fake_case,
    )
    assert errored.status == "error" and "fake divergence" in errored.message
    with pytest.raises(ParameterError, match="bracket"):
        bisect_boundary(lambda e: SailParameters(youngs_modulus=e), 1e9, 1e8, store_dir=tmp_path)
    with pytest.raises(ParameterError, match="workers"):
        run_sweep([], tmp_path, workers=0)


def test_bisection_runs_its_cases_with_the_settings(tmp_path, markers):
    """Cases of a bisection carry its RunSettings (part of their keys): other settings, other cases."""
    kwargs = dict(
        store_dir=tmp_path,
        solver="fake",
        options={"marker_dir": str(markers)},
        workers=1,
        progress=False,
        case_function=fake_case,
    )
    short = bisect_boundary(
        lambda e: SailParameters(youngs_modulus=e), 1e8, 1e20, settings=RunSettings(t_final=0.1), **kwargs
    )
    again = bisect_boundary(
        lambda e: SailParameters(youngs_modulus=e), 1e8, 1e20, settings=RunSettings(t_final=0.1), **kwargs
    )
    other = bisect_boundary(lambda e: SailParameters(youngs_modulus=e), 1e8, 1e20, **kwargs)
    assert short.status == other.status == "converged" and short.evaluations == again.evaluations
    keys = {key for _, _, key in short.evaluations}
    assert keys == {
        Case(
            SailParameters(youngs_modulus=v), "fake", {"marker_dir": str(markers)}, settings=RunSettings(t_final=0.1)
        ).key
        for v, _, _ in short.evaluations
    }
    assert not keys & {key for _, _, key in other.evaluations}
    assert sum(executions(markers).values()) == len(short.evaluations) + len(other.evaluations)
