"""Convergence in n (studies.convergence): the three-point power-law fit recovers a known law exactly, refuses
sequences that do not converge (not monotone, unphysical, absurd order), and studies of real runs find the stiff
and the soft torsion sails converging in n and the chain without bending and the Starshot-like uniform-beam sail
ill-posed."""

import math

import numpy as np
import pytest

from lightsail_mbs import ParameterError, paper_case, paper_settings
from lightsail_mbs.studies import convergence


@pytest.mark.parametrize("sizes", [(100, 200, 400), (960, 1920, 3000), (15, 40, 90)])
@pytest.mark.parametrize("limit, c, p", [(2.2, 3.0, 2.0), (1.35, -0.4, 0.9), (7e-3, 2e-2, 1.3)])
def test_power_law_fit_recovers_the_law(sizes, limit, c, p):
    values = [limit + c * n**-p for n in sizes]
    fit = convergence.power_law_fit(list(sizes), values)
    assert fit.verdict == "power law"
    assert fit.order == pytest.approx(p, rel=1e-9)
    assert fit.limit == pytest.approx(limit, rel=1e-9)
    assert fit.n_for_one_percent == pytest.approx((abs(c) / (0.01 * abs(limit))) ** (1 / p), rel=1e-8)


def test_power_law_fit_refuses_what_does_not_converge():
    assert convergence.power_law_fit([10, 20, 40], [1.0, 1.1, 1.05]).verdict.startswith("not converging")
    assert convergence.power_law_fit([10, 20, 40], [1.0, 1.1, 1.3]).verdict.startswith("not converging")
    assert convergence.power_law_fit([10, 20], [1.0, 1.1]).verdict == "fewer than three sizes"
    noisy = convergence.power_law_fit([10, 20, 40], [1.0, 1.1, 1.1 + 1e-7], noise=1e-6)
    assert noisy.verdict == "converged to the tolerance noise" and noisy.limit == pytest.approx(1.1 + 1e-7)


STARSHOT_SIZES = [15, 30, 60, 120, 240]


@pytest.mark.parametrize(
    "values, reason",
    [
        ([0.961, 0.997, 1.015, 0.557, 0.285], "not monotone"),  # the uniform-beam Starshot-like sail's answers
        ([1.015, 0.557, 0.285], "failure time of"),  # its last three alone: a power law to a negative time
        ([2.0, 1.0, 0.4], "failure time of"),
        ([2.0, 1.99, 1.9824], "lies further"),  # changes shrink by 2^0.4 per doubling: p = 0.4 < 1/2
    ],
)
def test_power_law_fit_refuses_unphysical_or_non_monotone_sequences(values, reason):
    sizes = STARSHOT_SIZES[-len(values) :]
    fit = convergence.power_law_fit(sizes, values)
    assert fit.verdict.startswith("not converging") and reason in fit.verdict
    assert fit.limit is None and fit.order is None and fit.n_for_one_percent is None


def test_power_law_fit_refuses_an_absurd_order():
    values = [1.0 + 2.0**-k for k in (0, 10, 20)]  # changes shrinking 1024-fold per doubling: p = 10
    fit = convergence.power_law_fit([10, 20, 40], values)
    assert fit.verdict.startswith("not converging") and "order" in fit.verdict and fit.limit is None
    ratio = convergence.power_law_fit([10, 20, 40], [0.7, 0.8, 0.85], kind="max_amplitude_ratio")
    assert "below 1" in ratio.verdict


def test_starshot_uniform_beam_does_not_converge():
    """The Starshot-like uniform-beam sail (E/E_cr,max ≈ 1.5e-6): its failure time first rises then falls with
    n, as the grid-scale waves' growth rate doubles with n; the study says not converging, ill-posed in n, and
    gives no limit and no n for 1 %."""
    from lightsail_mbs import RunSettings, SailParameters

    p = SailParameters(
        model="torsion", length=3.2, width=3.2, thickness=100e-9, density=2200.0, youngs_modulus=70e9,
        intensity=1e10, defect_amplitude=1e-6,
    )  # fmt: skip
    study = convergence.converge(p, RunSettings(), STARSHOT_SIZES, noise=False)
    values = [r.value for r in study.rows]
    assert values[1] > values[0] and values[-1] < 0.5 * values[-3]  # not monotone, and falling ∝ 1/σ ∝ 1/n
    assert study.ill_posed and study.fit.verdict.startswith("not converging: ill-posed in n")
    assert study.fit.limit is None and study.empirical_n_for_one_percent is None
    rates = [r.resolvedness["growth_rate"] for r in study.rows]
    assert all(b / a == pytest.approx(2.0, rel=0.1) for a, b in zip(rates, rates[1:]))
    # the finest failures are the round-off seed of the grid-scale wave growing at σ: t_f ≈ ln(1/ε)/σ
    assert values[-1] * rates[-1] == pytest.approx(values[-2] * rates[-2], rel=0.1)
    assert "no limit and no n for 1 %" in convergence.markdown_table(study)


def test_soft_torsion_sail_converges_to_its_limit():
    """The paper's soft torsion sail (E = 0.01 E_cr,max), refined where its fastest-growing wave is resolved
    (n = 120–480): well posed, a power law of order ≈ 2, and a limit within 1e-3 s of a run at n = 1920."""
    from lightsail_mbs import solve

    settings = paper_settings("torsion-soft", t_final=3.0)
    study = convergence.converge(paper_case("torsion-soft"), settings, [120, 240, 480], noise=False)
    assert not study.ill_posed and study.fit.verdict == "power law" and 1.5 < study.fit.order < 3
    assert study.rows[1].resolvedness["well_posed"] and not study.rows[2].resolvedness["assessed"]
    finest = solve(paper_case("torsion-soft", n=1920), "reduced", settings, uncertainty=False)
    assert study.fit.limit == pytest.approx(finest.failure_time, abs=1e-3)
    assert abs(study.fit.limit - finest.failure_time) < abs(study.rows[-1].value - finest.failure_time)


def test_geometric_sizes_and_their_checks():
    assert convergence.geometric_sizes(15, 240) == [15, 30, 60, 120, 240]
    assert convergence.geometric_sizes(15, 3000) == [15, 30, 60, 120, 240, 480, 960, 1920, 3000]
    with pytest.raises(ParameterError, match="factor"):
        convergence.geometric_sizes(10, 100, 1.0)
    with pytest.raises(ParameterError, match="n_max"):
        convergence.geometric_sizes(10, 5)


def test_empirical_n_for_one_percent():
    assert convergence.empirical_n_for_one_percent([10, 20, 40, 80], [1.0, 1.5, 1.995, 2.0]) == 40
    assert convergence.empirical_n_for_one_percent([10, 20], [1.0, None]) is None


def test_stiff_torsion_sail_converges_in_n():
    """The stable torsion sail (E = 4.5e13 Pa, 1 s): its largest amplitude ratio changes less with every
    doubling of n, by more than the tolerance noise, and the fit is a power law."""
    study = convergence.converge(
        paper_case("torsion-stable"), paper_settings("torsion-stable", t_final=1.0), [15, 30, 60]
    )
    assert [r.kind for r in study.rows] == ["max_amplitude_ratio"] * 3
    changes = [abs(r.change) for r in study.rows[1:]]
    assert changes[1] < changes[0]
    assert all(r.tolerance_noise < 0.01 * c for r, c in zip(study.rows[1:], changes))
    assert study.fit.verdict == "power law" and 0.3 < study.fit.order < 4
    assert not study.ill_posed and math.isfinite(study.fit.n_for_one_percent)


def test_chain_without_bending_is_ill_posed():
    """The rigid chain (ν = 3/2, the paper's Fig. 5 case): flagged, no fit offered, whatever the numbers."""
    study = convergence.converge(paper_case("rigid"), paper_settings("rigid"), [10, 20, 40], noise=False)
    assert study.ill_posed and study.fit.order is None
    assert study.fit.verdict.startswith("not converging: ill-posed in n") and "grid scale" in study.fit.verdict
    assert all(r.kind == "failure_time" for r in study.rows)
    table = convergence.markdown_table(study)
    assert "ill-posed" in table and table.count("\n| ") == 3 and study.empirical_n_for_one_percent is None
    assert "no limit and no n for 1 %" in table and "limit —" not in table
    assert np.isfinite(study.to_dict()["rows"][0]["value"])


def test_bad_sizes_raise_before_running():
    with pytest.raises(ParameterError, match="sizes"):
        convergence.converge(paper_case("rigid"), paper_settings("rigid"), [20, 10])


def test_a_sheet_is_refined_in_both_directions():
    """A sheet of W = L/2: n tiles along L and n/2 across at each size; its single method repeated at
    rtol/10 for the tolerance noise; a row of tiles (ny = 1) stays one row; a chain method is refused."""
    from lightsail_mbs import RunSettings, SailParameters

    p = SailParameters(model="sheet", n=4, ny=2, width=0.5, youngs_modulus=4.5e9, defect_mode_y=0.5)
    study = convergence.converge(p, RunSettings(t_final=0.3), [4, 8])
    assert [(r.n, r.ny) for r in study.rows] == [(4, 2), (8, 4)]
    assert all(r.method == "Radau" and r.tolerance_noise is not None for r in study.rows)
    assert "| 8×4 |" in convergence.markdown_table(study) and not study.ill_posed
    strip = convergence.converge(p.replace(ny=1, defect_mode_y=None), RunSettings(t_final=0.1), [4, 6], noise=False)
    assert [r.ny for r in strip.rows] == [1, 1]
    with pytest.raises(ParameterError, match="method"):
        convergence.converge(p, RunSettings(t_final=0.1), [4], method="DOP853")


def test_ill_posed_verdict_says_which_way_the_failure_time_moved():
    """A torsion sail at E_cr,max/1000 is ill-posed in n (its fastest wave at the grid scale, its rate doubling
    with n) while its failure time, set by the seeded ν = 3/2 defect, still rises over n = 15, 30, 60: the
    verdict must say it rises, not that it keeps falling."""
    from lightsail_mbs import RunSettings, SailParameters

    p = SailParameters(model="torsion", youngs_modulus=450628119.28)
    study = convergence.converge(p, RunSettings(t_final=3.0), [15, 30, 60], noise=False)
    changes = [r.change for r in study.rows[1:]]
    assert study.ill_posed and all(r.kind == "failure_time" for r in study.rows)
    assert all(c > 0 for c in changes)
    assert "keeps falling" not in study.fit.verdict and "still rising" in study.fit.verdict


def test_a_row_not_yet_resolved_in_n_says_so_as_the_runs_warning_does():
    """At n = 120 the sail at E_cr,max/1000 is well posed but its fastest rate still moves by 38 % to 2n: the run
    warns "not resolved in n", and the study's row must say the same, not just "well posed"."""
    from lightsail_mbs import RunSettings, SailParameters

    p = SailParameters(model="torsion", youngs_modulus=450628119.28)
    study = convergence.converge(p, RunSettings(t_final=0.05), [120], noise=False)
    verdict = study.rows[0].resolvedness
    assert verdict["well_posed"] and verdict["resolved"] is False
    assert "(well posed, not resolved)" in convergence.markdown_table(study)
