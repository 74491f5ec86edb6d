"""Monte Carlo over seeded multi-mode defects (studies.montecarlo): counting, intervals, resuming."""

import numpy as np
import pytest
from scipy import stats

from lightsail_mbs import ParameterError, RunSettings, SailParameters
from lightsail_mbs.studies import montecarlo


def seed_dependent_case(case):
    """Fails for seeds below 10·log10(1e12 / E), at t = 0.1·(1 + seed); deterministic."""
    p = case.params
    failed = p.defect_seed < 10 * np.log10(1e12 / p.youngs_modulus)
    return {"failed": bool(failed), "failure_time": 0.1 * (1 + p.defect_seed) if failed else None, "error": None}


def test_wilson_interval_matches_formula_limits():
    low, high = montecarlo.wilson_interval(0, 50)
    assert low == 0.0 and 0.05 < high < 0.1  # rule of three-ish: ~0.071
    low, high = montecarlo.wilson_interval(25, 50)
    assert low == pytest.approx(1 - high) and low < 0.5 < high
    # large n: Wilson → Wald
    low, high = montecarlo.wilson_interval(5000, 10000)
    assert high - low == pytest.approx(2 * stats.norm.ppf(0.975) * 0.5 / 100, rel=1e-3)


def test_monte_carlo_counts_and_resumes(tmp_path):
    base = SailParameters(n=12, defect_seed=0)
    values = [1e12, 1e11, 1e10]
    rows = montecarlo.run(
        base, "youngs_modulus", values, 20, tmp_path, workers=1, progress=False, case_function=seed_dependent_case
    )
    assert [r.failures for r in rows] == [0, 10, 20]
    assert rows[1].probability == 0.5 and rows[1].failure_time_median == pytest.approx(0.55)
    assert rows[2].failure_time_mean == pytest.approx(np.mean(0.1 * np.arange(1, 21)))
    again = montecarlo.run(
        base, "youngs_modulus", values, 20, tmp_path, workers=1, progress=False, case_function=seed_dependent_case
    )
    assert again == rows


def test_bad_monte_carlo_input():
    with pytest.raises(ParameterError, match="parameter"):
        montecarlo.cases(SailParameters(), "colour", [1.0], 3)
    with pytest.raises(ParameterError, match="seeds"):
        montecarlo.cases(SailParameters(), "youngs_modulus", [1.0], 0)


def test_cases_carry_the_settings_and_vary_the_defect():
    settings = RunSettings(t_final=0.5)
    cases = montecarlo.cases(
        SailParameters(n=12), "defect_amplitude", [1e-6, 1e-5], 3, solver="reduced", settings=settings
    )
    assert len(cases) == 6 and all(c.settings == settings and c.solver == "reduced" for c in cases)
    assert sorted({c.params.defect_amplitude for c in cases}) == [1e-6, 1e-5]
    assert sorted(c.params.defect_seed for c in cases) == [0, 0, 1, 1, 2, 2]
    assert montecarlo.cases(SailParameters(n=12), "defect_amplitude", [1e-6], 1)[0].settings == RunSettings()
