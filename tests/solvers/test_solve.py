"""solve(): any case the package accepts runs in both solvers without a crash (property-based)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from lightsail_mbs import Result, solve
from lightsail_mbs.result import ARRAYS
from tests.strategies import EXAMPLES, accepted_cases, check_property, short_run


@pytest.mark.parametrize("examples", EXAMPLES)
@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_any_accepted_case_runs_briefly_to_finite_output_or_a_recorded_error(solver, examples):
    """Property: for any accepted case and a short run (a few samples over a fraction of √(L/g₀)), solve
        returns a Result — never raises — on the sample grid it reports (the requested one, or the finer one that
    located its failure), with finite arrays; a failure of the
        method is a non-empty Result.error, and the samples before it stay finite."""

    @given(st.data())
    def runs(data):
        p = data.draw(accepted_cases(), label="case")
        settings = data.draw(short_run(p), label="settings")
        # the base run: the uncertainty twins are this solver at other settings (tests/solvers/test_uncertainty.py)
        result = solve(p, solver, settings, uncertainty=False)
        assert isinstance(result, Result) and result.settings == settings and result.params == p
        steps = result.time.shape[0]
        assert steps >= 1 and result.time[0] == 0.0
        assert all(getattr(result, name).shape[0] == steps for name in ARRAYS)
        sampling = result.info["sampling"]  # solve() may refine the grid to locate a failure (solvers.events)
        grid = settings.replace(output_interval=sampling["output_interval"], t_final=sampling["t_final"]).sample_times()
        np.testing.assert_allclose(result.time, grid[:steps], rtol=1e-12, atol=1e-12 * settings.t_final)
        for name in ARRAYS:
            assert np.all(np.isfinite(getattr(result, name))), (name, result.error)
        if result.error is None:
            stopped = settings.stop_at_failure and result.failed
            assert stopped or steps == grid.size, "ended early without failure or error"
        else:
            assert isinstance(result.error, str) and result.error.strip()
        summary = result.summary()
        assert summary["error"] == result.error and summary["settings"] == settings.to_dict()

    check_property(runs, examples)
