"""Finite-amplitude stability (analysis.finite_amplitude): the failure time scales with t_c, the critical
stiffness ratio, divergence, the one-mode model, the boundary a map of finite runs finds."""

import numpy as np
import pytest

from lightsail_mbs import SailParameters, paper_case
from lightsail_mbs.analysis import finite_amplitude as cr
from tests.references import REFERENCES

SMALL_TORSION = SailParameters(model="torsion", n=10, defect_mode=1.5)
SMALL_TNT = SailParameters(model="tnt", n=10, defect_mode=1.5, axial_springs=False, tension=1e-8)


@pytest.mark.parametrize("base", [SMALL_TORSION, SMALL_TNT], ids=["torsion", "tnt"])
def test_failure_time_scales_with_t_c_over_two_decades(base):
    """t_f = F(r) t_c: g₀ over two decades (h) and a₀ over two decades give the same τ_f = t_f/t_c."""
    taus = [
        cr.failure_tau(cr.with_ratio(base.replace(thickness=h, defect_amplitude=a0), 1.0), 20.0)
        for h, a0 in ((1e-7, 1e-6), (1e-5, 1e-4), (1e-6, 1e-5))
    ]
    assert None not in taus
    assert max(taus) / min(taus) < 1.01


def test_rigid_failure_time_scales_with_t_c():
    p = paper_case("rigid", n=20)
    a = cr.failure_tau(p, 20.0)
    b = cr.failure_tau(p.replace(intensity=1e9, defect_amplitude=1e-4), 20.0)
    assert a is not None and abs(a / b - 1) < 0.01


def test_scaled_failure_time_converged_in_tolerance():
    p = cr.with_ratio(SMALL_TORSION, 1.0)
    assert abs(cr.failure_tau(p, 20.0, rtol=1e-8) / cr.failure_tau(p, 20.0, rtol=1e-10) - 1) < 1e-3


def test_critical_ratio_independent_of_amplitude():
    """E_cr ∝ a₀ (exponent 1): the bisected ratio E/E_cr,max at a₀ = 1 µm and 100 µm brackets overlap."""
    lo, hi = (cr.critical_ratio(SMALL_TORSION.replace(defect_amplitude=a0), 6.0, factor=1.05) for a0 in (1e-6, 1e-4))
    assert lo.failed_ratio <= hi.stable_ratio and hi.failed_ratio <= lo.stable_ratio


def test_critical_ratio_brackets_the_dated_reference():
    """The bisection of `lightsail-mbs stability` (paper case, runs of 8 t_c, ×1.05) ends in a bracket at most
    1.05 wide that contains the reference boundary [7.584, 7.598] E_cr,max (tests/references.py)."""
    found = cr.critical_ratio(paper_case("torsion-stable"), 8.0, factor=1.05)
    ref = REFERENCES["torsion_critical_ratio"]
    assert found.stable_ratio / found.failed_ratio <= 1.05
    assert found.failed_ratio <= ref.failed and ref.stable <= found.stable_ratio, (found, ref)


def test_divergence_grows_in_the_unstable_regime():
    tau, sep = cr.divergence(cr.with_ratio(SMALL_TORSION, 0.5), 10.0)
    assert sep[-1] > 100.0


def test_one_mode_potentials_are_cubic_load_and_quadratic_stiffness():
    """The sine family's load potential is odd and cubic in a (second-order load), the bending one
    even and quadratic — the one-mode model's content."""
    m = cr.one_mode_model(SMALL_TORSION, span=2.0, points=81)
    v0 = lambda x: np.interp(x, m.a_over_a0, m.load_potential)  # noqa: E731
    v1 = lambda x: np.interp(x, m.a_over_a0, m.unit_stiffness_potential)  # noqa: E731
    np.testing.assert_allclose([v0(-1.0), v0(2.0)], [-v0(1.0), 8 * v0(1.0)], rtol=0.03)
    np.testing.assert_allclose([v1(-1.0), v1(2.0)], [v1(1.0), 4 * v1(1.0)], rtol=0.03)


def test_boundary_for_run_inverts_the_failure_curve():
    ratios, taus = [0.1, 1.0, 4.0, 8.0, 16.0], [1.6, 2.0, 3.5, 50.0, None]
    assert cr.boundary_for_run(ratios, taus, 1.0) is None  # nothing fails within the run
    assert cr.boundary_for_run(ratios, taus, 2.0) == pytest.approx(1.0)
    assert 1.0 < cr.boundary_for_run(ratios, taus, 3.0) < 4.0
    assert cr.boundary_for_run(ratios, taus, 10.0) == pytest.approx(4.0 * 2.0 ** ((10 - 3.5) / 46.5))
    assert cr.boundary_for_run(ratios, taus, 60.0) == pytest.approx(np.sqrt(8.0 * 16.0))


def test_boundary_for_run_takes_the_last_crossing_of_a_non_monotone_curve():
    ratios, taus = [1.0, 1.5, 2.0, 3.0], [2.0, 3.0, 2.5, 4.0]
    assert cr.boundary_for_run(ratios, taus, 2.75) == pytest.approx(2.0 * 1.5 ** (1 / 6))
    assert cr.boundary_for_run(ratios, taus, 5.0) == float("inf")


def test_lowest_mode_buckling_ratio_balances_euler_load_and_defect_compression():
    from lightsail_mbs.model import theory

    p = SailParameters(model="torsion", defect_mode=1.5, thickness=2e-6, defect_amplitude=3e-5)
    q = cr.with_ratio(p, cr.lowest_mode_buckling_ratio(p))
    euler = q.youngs_modulus * q.thickness**3 * cr.FREE_FREE_BETA1_L**2 / (12 * q.length**2)
    assert euler == pytest.approx(theory.radiation_pressure(q) * q.defect_amplitude, rel=1e-12)


def test_failure_ratio_of_a_scaled_run():
    """The stop rule's ratio: tripling takes longer than doubling, and no stop runs on past it."""
    p = cr.with_ratio(SMALL_TORSION, 1.0)
    double, triple = cr.failure_tau(p, 20.0), cr.failure_tau(p, 20.0, failure_ratio=3.0)
    assert double is not None and triple is not None and triple > double
    run = cr.scaled_run(p, 1.5 * triple, stop_at_failure=False)
    assert run.failure_tau == pytest.approx(double, rel=1e-3) and run.tau[-1] > triple
