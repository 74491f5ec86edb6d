"""Stability analysis: the linearised flat sail (both solvers), the finite-amplitude scaling and
critical values, the failure-time law."""
import numpy as np
import pytest

from lightsail_mbs import SailParameters, paper_case
from lightsail_mbs.analysis import linear_stability as st

LINEAR_CASES = {
    "torsion-stable": paper_case("torsion-stable", n=12),
    "torsion-soft": paper_case("torsion-soft", n=12),
    "tnt-inextensible": paper_case("tnt-stable", n=12, axial_springs=False),
    "tnt-extensible": paper_case("tnt-stable", n=8),
    "rigid": paper_case("rigid", n=12),
}


def elastic_shift(lit, dark):
    """Largest |Δω²|/ω² over the modes with ω² > 0 (the rigid-body zeros compared absolutely elsewhere)."""
    w2 = dark.omega_squared
    keep = w2 > 1e-9 * max(w2.max(), 1e-300)
    if not keep.any():
        return 0.0
    return float(np.max(np.abs(lit.omega_squared[keep] - w2[keep]) / w2[keep]))


@pytest.mark.parametrize("name", LINEAR_CASES)
def test_reduced_linear_spectrum_with_load_equals_unloaded(name):
    """The load enters the flat-state Jacobian only through the axial rows: spectrum unchanged,
    to far below the g₀k it would shift it by if it acted transversely at first order."""
    p = LINEAR_CASES[name]
    lit, dark = st.linear_spectrum(p, "reduced"), st.linear_spectrum(st.unlit(p), "reduced")
    assert elastic_shift(lit, dark) < 1e-6
    scale = max(st.load_rate_scale(p), np.abs(dark.omega_squared).max())
    assert np.max(np.abs(lit.omega_squared - dark.omega_squared)) < 1e-9 * scale
    assert lit.max_growth_rate < 1e-6 * np.sqrt(st.load_rate_scale(p))


@pytest.mark.parametrize("name", ["torsion-stable", "torsion-soft", "tnt-inextensible", "rigid"])
def test_exudyn_linear_spectrum_with_load_equals_unloaded_and_reduced(name):
    p = LINEAR_CASES[name]
    lit, dark = st.linear_spectrum(p, "exudyn"), st.linear_spectrum(st.unlit(p), "exudyn")
    assert elastic_shift(lit, dark) < 1e-6
    reduced = st.linear_spectrum(st.unlit(p), "reduced")
    assert elastic_shift(dark, reduced) < 1e-6       # the two solvers' unloaded chains agree


def test_load_acts_along_the_sail_at_first_order():
    """It is there, but axial: ∂ẍ₁/∂θ_k = −g₀/n (the whole chain's x-force −f₀Σθ over its mass),
    while the transverse rows do not see it."""
    p = LINEAR_CASES["torsion-soft"]
    jac, dark = st.reduced_jacobian(p), st.reduced_jacobian(st.unlit(p))
    dof = p.n + 2
    np.testing.assert_allclose(jac[dof, 2:dof], -p.nominal_acceleration / p.n, rtol=1e-6)
    transverse = np.abs(jac[dof + 1:, :dof] - dark[dof + 1:, :dof]).max()
    assert transverse < 1e-9 * p.nominal_acceleration


def test_exudyn_own_forward_difference_jacobian_is_noisy_with_load():
    """Exudyn's forward-difference Jacobian of the lit tree cancels f₀-sized load and frame terms:
    its soft bending frequencies move by ≫ 1e-6 (numerical), the central-difference load stiffness
    does not — why exudyn_linearization adds the load Jacobian itself."""
    p = SailParameters(n=8, youngs_modulus=4.5e11)
    dark = st.linear_spectrum(st.unlit(p), "exudyn")
    noisy = st.spectrum_of_system(*st.exudyn_linearization(p, exudyn_load="solver"))
    assert elastic_shift(noisy, dark) > 1e-4
    assert elastic_shift(st.linear_spectrum(p, "exudyn"), dark) < 1e-6


# ---- finite amplitude: scaling, critical values, failure time ---------------------------------
import json  # noqa: E402

from lightsail_mbs.analysis import finite_amplitude as cr  # noqa: E402
from lightsail_mbs.cli import main as cli_main  # noqa: E402

SMALL_TORSION = SailParameters(model="torsion", n=10, mode=1.5)
SMALL_TNT = SailParameters(model="tnt", n=10, mode=1.5, axial_springs=False, tension=1e-8)


@pytest.mark.parametrize("base", [SMALL_TORSION, SMALL_TNT], ids=["torsion", "tnt"])
def test_failure_time_scales_with_t_c_over_two_decades(base):
    """t_f = F(r) t_c: g₀ over two decades (h) and a₀ over two decades give the same τ_f = t_f/t_c."""
    taus = [cr.failure_tau(cr.with_ratio(base.replace(thickness=h, amplitude=a0), 1.0), 20.0)
            for h, a0 in ((1e-7, 1e-6), (1e-5, 1e-4), (1e-6, 1e-5))]
    assert None not in taus
    assert max(taus) / min(taus) < 1.01


def test_rigid_failure_time_scales_with_t_c():
    p = paper_case("rigid", n=20)
    a = cr.failure_tau(p, 20.0)
    b = cr.failure_tau(p.replace(intensity=1e9, amplitude=1e-4), 20.0)
    assert a is not None and abs(a / b - 1) < 0.01


def test_scaled_failure_time_converged_in_tolerance():
    p = cr.with_ratio(SMALL_TORSION, 1.0)
    assert abs(cr.failure_tau(p, 20.0, rtol=1e-8) / cr.failure_tau(p, 20.0, rtol=1e-10) - 1) < 1e-3


def test_critical_ratio_independent_of_amplitude():
    """E_cr ∝ a₀ (exponent 1): the bisected ratio E/E_cr,max at a₀ = 1 µm and 100 µm brackets overlap."""
    lo, hi = (cr.critical_ratio(SMALL_TORSION.replace(amplitude=a0), 6.0, factor=1.05) for a0 in (1e-6, 1e-4))
    assert lo.failed_ratio <= hi.stable_ratio and hi.failed_ratio <= lo.stable_ratio
    assert 1.0 < lo.value < 30.0       # above the quasi-static E_cr,max, not by orders of magnitude


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


@pytest.mark.parametrize("model, key", [("torsion", "critical_modulus"), ("tnt", "critical_tension")])
def test_stability_command_json(model, key, capsys):
    code = cli_main(["stability", "--model", model, "--n", "10", "--tau-final", "6", "--factor", "1.2",
                     "--linear", "--json"] + (["--tension", "1e-8"] if model == "tnt" else []))
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    lo, hi = out[f"{key}_bracket"]
    assert lo <= out[key] <= hi <= 1.2 * lo * (1 + 1e-12)
    assert out["ratio_to_analytic"] == pytest.approx(out[key] / out["analytic"])
    assert out["linear_relative_shift"] < 1e-9


def test_boundary_for_run_inverts_the_failure_curve():
    ratios, taus = [0.1, 1.0, 4.0, 8.0, 16.0], [1.6, 2.0, 3.5, 50.0, None]
    assert cr.boundary_for_run(ratios, taus, 1.0) is None            # nothing fails within the run
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
    p = SailParameters(model="torsion", mode=1.5, thickness=2e-6, amplitude=3e-5)
    q = cr.with_ratio(p, cr.lowest_mode_buckling_ratio(p))
    euler = q.youngs_modulus * q.thickness ** 3 * cr.FREE_FREE_BETA1_L ** 2 / (12 * q.length ** 2)
    assert euler == pytest.approx(theory.radiation_pressure(q) * q.amplitude, rel=1e-12)


@pytest.mark.slow
def test_stability_scenarios_quick(tmp_path):
    """The three scenario scripts run (quick) and the failure-time fit finds t_f ∝ (g₀ a₀)^(−1/2)."""
    import importlib.util
    from pathlib import Path

    folder = Path(__file__).resolve().parents[1] / "scenarios"
    modules = {}
    for name in ("stability_linear", "stability_critical", "stability_failure_time"):
        spec = importlib.util.spec_from_file_location(name, folder / f"{name}.py")
        modules[name] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(modules[name])
    fits = modules["stability_failure_time"].run(tmp_path, quick=True)["fits"]
    for fit in fits:
        assert fit["g0_exponent"] == pytest.approx(-0.5, abs=0.01)
        assert fit["a0_exponent"] == pytest.approx(-0.5, abs=0.01)
    critical = modules["stability_critical"].run(tmp_path, quick=True)
    assert all(f["a0_exponent"] == pytest.approx(1.0, abs=0.03) for f in critical["fits"])
    rows = modules["stability_linear"].run(tmp_path)["rows"]
    assert max(r["elastic_relative_shift"] for r in rows) < 1e-6
    for png in ("stability_linear.png", "stability_critical.png", "stability_failure_time.png"):
        assert (tmp_path / png).stat().st_size > 10_000
