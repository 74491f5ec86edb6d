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


def film_dependent_case(case):
    """Fails at t = 1 + 0.01·film_seed whatever the defect: a stand-in for the spread over films."""
    return {"failed": True, "failure_time": 1.0 + 0.01 * case.params.film_seed, "error": None}


def test_monte_carlo_over_films_varies_the_film_seed_and_keeps_the_defect(tmp_path):
    base = SailParameters(n=12, defect_seed=4, film_rms=1e-9)
    cases = montecarlo.cases(base, "youngs_modulus", [1e10], 5, over="film")
    assert [c.params.film_seed for c in cases] == [0, 1, 2, 3, 4]
    assert {c.params.defect_seed for c in cases} == {4} and {c.params.film_rms for c in cases} == {1e-9}
    rows = montecarlo.run(
        base,
        "youngs_modulus",
        [1e10],
        21,
        tmp_path,
        workers=1,
        progress=False,
        case_function=film_dependent_case,
        over="film",
    )
    times = 1.0 + 0.01 * np.arange(21)
    assert rows[0].failure_time_median == pytest.approx(1.1)
    assert rows[0].failure_time_q05 == pytest.approx(np.percentile(times, 5)) == pytest.approx(1.01)
    assert rows[0].failure_time_q95 == pytest.approx(1.19)
    with pytest.raises(ParameterError, match="film_rms=0.0 is invalid: allowed > 0"):
        montecarlo.cases(SailParameters(), "youngs_modulus", [1e10], 3, over="film")
    with pytest.raises(ParameterError, match="over='roughness' is invalid"):
        montecarlo.cases(base, "youngs_modulus", [1e10], 3, over="roughness")


def test_montecarlo_over_films_from_the_command_line(tmp_path, capsys):
    """A soft sail with a 10 nm film, four films: each finished case is in the store with its film seed, the
    printed distribution is the store's, and the films spread the failure time."""
    import json

    from lightsail_mbs.cli import main
    from lightsail_mbs.studies.store import CaseStore

    store = tmp_path / "store"
    args = ["montecarlo", "--n", "12", "--solver", "reduced", "--seeds", "4", "--modulus", "4.5e8"]
    args += ["--film-rms", "1e-8", "--over", "film", "--store", str(store), "--workers", "1", "--json", "--quiet"]
    assert main(args) == 0
    (row,) = json.loads(capsys.readouterr().out)
    records = CaseStore(store).records()
    seeds = sorted(r["parameters"].get("film_seed", 0) for r in records)  # a record leaves out film_seed = 0
    assert seeds == [0, 1, 2, 3] and all(r["parameters"]["defect_seed"] is None for r in records)
    times = np.array([r["failure_time"] for r in records])
    assert row["value"] == 4.5e8 and row["runs"] == row["failures"] == 4
    assert row["failure_time_median"] == pytest.approx(np.median(times))
    assert (
        row["failure_time_q05"] == pytest.approx(np.percentile(times, 5))
        and row["failure_time_q05"] < row["failure_time_q95"]
    )
    assert main([*args[:-2], "--quiet"]) == 0
    assert "4 films (RMS σ = 1e-08 m" in capsys.readouterr().out
