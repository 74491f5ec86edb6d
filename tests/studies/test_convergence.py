"""Convergence in n (studies.convergence): the three-point power-law fit recovers a known law exactly, refuses
sequences that do not converge, and a study of real runs finds the stiff torsion sail converging in n and the
chain without bending ill-posed."""

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
    assert study.ill_posed and study.fit.order is None and study.fit.verdict.startswith("ill-posed")
    assert all(r.kind == "failure_time" for r in study.rows)
    table = convergence.markdown_table(study)
    assert "ill-posed" in table and table.count("\n| ") == 3 and study.empirical_n_for_one_percent is None
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
