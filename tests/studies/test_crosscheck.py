"""Cross-validation of the two solvers (studies.crosscheck): independent formulations agree on short runs."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, paper_case, paper_settings, solve
from lightsail_mbs.studies import crosscheck


@pytest.mark.parametrize("case", ["torsion-stable", "torsion-soft"])
def test_agrees_with_exudyn_on_a_short_torsion_run(case):
    """Independent formulations (Exudyn's KinematicTree + generalized-α or DOPRI5 vs minimal coordinates +
    DOP853) give the same angles to < 1e-8 rad (θ ~ 1e-4 rad) over 0.3 s at Exudyn's rtol 1e-9, and the
    cross-check row passes."""
    pytest.importorskip("exudyn")
    p, settings = paper_case(case, n=10), RunSettings(t_final=0.3)
    row = crosscheck.compare(
        crosscheck.Case(case, p, settings, "short"),
        solve(p, "exudyn", settings, rtol=1e-9, uncertainty=False),
        solve(p, "reduced", settings, uncertainty=False),
    )
    assert row["max_dtheta"] < 1e-8 and row["window_end"] == pytest.approx(0.3)
    assert row["passed"]


def test_thin_sail_agrees_with_reduced_solver():
    """h = 10 nm (g₀ = 6.7e4 m/s²): the load and frame force nearly cancel, so Exudyn's Newton
    tolerance must follow the deforming force f₀·slope, not f₀ (it drifted 1.6e-5 rad in 0.3 s)."""
    pytest.importorskip("exudyn")
    p = paper_case("tnt-stable", defect_mode=1.0, axial_springs=False, thickness=1e-8, tension=1e-4)
    settings = RunSettings(t_final=0.3)
    exudyn, reduced = (
        solve(p, "exudyn", settings, uncertainty=False),
        solve(p, "reduced", settings, rtol=1e-11, uncertainty=False),
    )
    steps = min(len(exudyn.time), len(reduced.time))
    assert np.abs(exudyn.theta[:steps] - reduced.theta[:steps]).max() < 1e-8


def test_cases_run_with_their_own_settings():
    """Every case says how it is run: the paper's runs (10 ms rigid, 6 s otherwise), short free vibrations."""
    assert crosscheck.CASES["rigid-0.5"].settings == paper_settings("rigid")
    assert crosscheck.CASES["torsion-soft"].settings == paper_settings("torsion-soft")
    assert crosscheck.CASES["free-tnt"].settings == RunSettings(t_final=0.02)
    assert [c.name for c in crosscheck.select(["tnt-soft", "rigid-1.5"])] == ["tnt-soft", "rigid-1.5"]
    with pytest.raises(ParameterError, match="nonsense"):
        crosscheck.select(["nonsense"])
