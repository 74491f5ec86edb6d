"""Runs of the reduced-Lagrangian solver: sampling and options, failures of the method recorded, energy
conservation, the stop rule, the paper's verdicts."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters, analysis, paper_case, paper_settings, solve
from lightsail_mbs.solvers.reduced import solver as reduced
from lightsail_mbs.solvers.reduced.dynamics import ChainDynamics
from lightsail_mbs.studies import crosscheck
from tests.references import REFERENCES, assert_held


# ---- runs ------------------------------------------------------------------------------------
def test_result_sampling_and_fields():
    p = SailParameters(n=8)
    r = solve(p, "reduced", RunSettings(t_final=0.05, output_interval=0.01), uncertainty=False)
    assert r.solver == "reduced" and r.error is None
    np.testing.assert_allclose(r.time, np.arange(6) * 0.01, atol=1e-15)
    assert r.x.shape == r.omega.shape == (6, 8) and r.z.shape == (6, 0)
    assert r.info["method"] == "DOP853"


def test_options_are_validated():
    p, settings = SailParameters(n=5), RunSettings(t_final=0.01)
    with pytest.raises(ParameterError, match="method"):
        solve(p, "reduced", settings, method="Euler", uncertainty=False)
    with pytest.raises(ParameterError, match="bogus"):
        solve(p, "reduced", settings, bogus=1, uncertainty=False)
    with pytest.raises(ParameterError, match="rtol"):
        solve(p, "reduced", settings, rtol=2.0, uncertainty=False)


@pytest.mark.parametrize("method", ["DOP853", "RK45"])
def test_divergence_is_recorded_not_raised(monkeypatch, method):
    """A non-finite state ends the run with Result.error set and the finite trajectory before it."""
    from lightsail_mbs.solvers.reduced import dop853 as reduced_integrator

    p = SailParameters(n=5)
    original_advance, original_rhs = reduced_integrator.Dop853.advance, ChainDynamics.rhs

    def poisoned_advance(self, samples):
        if self.t > 0.03:
            self.y[:] = np.nan
        return original_advance(self, samples)

    def poisoned_rhs(self, t, y):
        out = original_rhs(self, t, y)
        return out * np.nan if t > 0.03 else out

    monkeypatch.setattr(reduced_integrator.Dop853, "advance", poisoned_advance)
    monkeypatch.setattr(ChainDynamics, "rhs", poisoned_rhs)
    r = solve(p, "reduced", RunSettings(t_final=0.1, output_interval=0.001), method=method, uncertainty=False)
    assert r.error and "failed" in r.error
    # the samples up to the call that met the poisoned state (the integrator's steps run ahead of them)
    assert 0 < r.time[-1] < 0.1 and np.all(np.isfinite(r.theta))


@pytest.mark.parametrize(
    "p, settings",
    [
        (SailParameters(n=12, intensity=0.0, youngs_modulus=4.5e13), RunSettings(t_final=0.5)),
        (crosscheck.free_tnt(), crosscheck.CASES["free-tnt"].settings),
    ],
    ids=["torsion", "tnt-T0"],
)
def test_free_vibration_conserves_energy(p, settings):
    """Zero intensity, no damping: the Lagrangian conserves kinetic + elastic energy (Eqs 23, 29);
    the drift is integration error, below 1e-8 at a tight tolerance and shrinking with it.
    The TnT chain (T = 0, bending on, h = 1 cm so its axial modes stay resolvable) runs explicitly:
    an L-stable implicit method would damp the axial vibration the bending excites."""
    method = "DOP853"
    loose = solve(p, "reduced", settings, rtol=1e-7, method=method, uncertainty=False)
    r = solve(p, "reduced", settings, rtol=1e-9, method=method, uncertainty=False)
    assert r.error is None and r.time[-1] == pytest.approx(settings.t_final)
    energy = analysis.mechanical_energy(r)
    assert energy[0] > 0 and np.ptp(r.theta[:, 0]) > 0.5 * abs(r.theta[0, 0])  # it really vibrates
    drift = np.abs(energy / energy[0] - 1).max()
    assert drift < 1e-8
    assert drift < np.abs(analysis.mechanical_energy(loose) / energy[0] - 1).max()


def test_stop_at_failure_ends_at_the_crossing_sample():
    settings = paper_settings("torsion-soft")
    r = solve(paper_case("torsion-soft"), "reduced", settings, uncertainty=False)
    assert r.amplitude[-1] >= settings.failure_ratio * r.amplitude[0] > r.amplitude[-2]


def test_failure_ratio_of_the_settings_sets_the_stop():
    """failure_ratio = 3 runs on past the doubling and stops at the first sample ≥ 3 a₀."""
    settings = paper_settings("torsion-soft", failure_ratio=3.0)
    r = solve(paper_case("torsion-soft"), "reduced", settings, uncertainty=False)
    assert r.error is None and r.settings.failure_ratio == 3.0
    assert r.amplitude[-1] >= 3.0 * r.amplitude[0] > r.amplitude[-2]
    assert r.failure_time == pytest.approx(r.time[-1], abs=settings.sample_interval)


# ---- the paper's verdicts ----------------------------------------------------------------------
def test_soft_torsion_fails_like_the_paper_and_converges():
    """Fig. 7: E = 4.5e9 Pa fails at ~2 s: at the dated reference, and a 10× tighter tolerance moves the
    failure time by less than the reference's measured uncertainty (tests/references.py)."""
    p, settings = paper_case("torsion-soft"), paper_settings("torsion-soft")
    t1 = solve(p, "reduced", settings, uncertainty=False).failure_time
    t2 = solve(p, "reduced", settings, rtol=reduced.DEFAULT_RTOL["DOP853"] / 10, uncertainty=False).failure_time
    assert_held("soft_torsion_failure_time_reduced", t1)
    assert abs(t2 - t1) <= REFERENCES["soft_torsion_failure_time_reduced"].tolerance


def test_stable_torsion_survives_six_seconds():
    r = solve(paper_case("torsion-stable"), "reduced", paper_settings("torsion-stable"), uncertainty=False)
    assert r.error is None and r.time[-1] == pytest.approx(6.0) and not r.failed


@pytest.mark.parametrize("mode", [1.0, 1.5, 2.0, 3.0, 4.0, 5.0])
def test_rigid_modes_fail_at_a_trough(mode):
    """Fig. 5: every mode ν ≥ 1 of the rigid chain fails within 10 ms, at a trough."""
    r = solve(paper_case("rigid", defect_mode=mode), "reduced", paper_settings("rigid"), uncertainty=False)
    assert r.error is None and r.failed and r.failure_time < 0.01
    assert analysis.fails_at_trough(r.x[-1], r.y[-1])


def test_rigid_half_mode_does_not_fail():
    r = solve(paper_case("rigid", defect_mode=0.5), "reduced", paper_settings("rigid"), uncertainty=False)
    assert r.error is None and not r.failed and r.time[-1] == pytest.approx(0.01)


def test_tnt_stable_survives_six_seconds():
    r = solve(paper_case("tnt-stable"), "reduced", paper_settings("tnt-stable"), uncertainty=False)
    assert r.error is None and r.time[-1] == pytest.approx(6.0) and not r.failed


def test_tnt_soft_fails_like_the_paper_and_converges():
    """Fig. 11 (extensible slices, E = 1e11 Pa): at the dated reference; rtol/10 moves it by less than its
    measured uncertainty."""
    p, settings = paper_case("tnt-soft"), paper_settings("tnt-soft")
    t1 = solve(p, "reduced", settings, uncertainty=False).failure_time
    t2 = solve(p, "reduced", settings, rtol=reduced.DEFAULT_RTOL["Radau"] / 10, uncertainty=False).failure_time
    assert_held("membrane_extensible_soft_failure_time_reduced", t1)
    assert abs(t2 - t1) <= REFERENCES["membrane_extensible_soft_failure_time_reduced"].tolerance


# ---- the method choice -----------------------------------------------------------------------
@pytest.mark.parametrize(
    "case, changes, expected",
    [
        ("torsion-stable", {}, "DOP853"),
        ("torsion-soft", {}, "DOP853"),
        ("torsion-soft", dict(n=1000), "Radau"),
        ("tnt-stable", {}, "Radau"),
        ("tnt-stable", dict(axial_springs=False), "DOP853"),
        ("rigid", {}, "DOP853"),
    ],
)
def test_method_is_chosen_from_the_stiffness(case, changes, expected):
    """Explicit unless the fastest spring mode exceeds the motion the answer needs by the threshold:
    fine torsion chains (top bending mode ∝ n²) and the extensible TnT chain (axial springs) run implicitly."""
    method, figures = reduced.choose_method(paper_case(case, **changes))
    assert method == expected
    ratio = figures["stiffness_ratio"]
    assert (ratio > reduced.STIFFNESS_THRESHOLD) == (expected == "Radau")


def test_torsion_stiffness_ratio_grows_as_n_squared():
    """ω_max = 2√(k_T/J) ∝ n² while ω_slow (failure scale, lowest bending modes) does not depend on n."""
    ratios = [reduced.stiffness(paper_case("torsion-soft", n=n))["stiffness_ratio"] for n in (50, 100, 200)]
    np.testing.assert_allclose(np.diff(np.log(ratios)) / np.log(2), 2.0, rtol=1e-12)


def test_choice_and_its_inputs_are_recorded():
    settings = RunSettings(t_final=0.01)
    auto = solve(paper_case("tnt-soft", n=10), "reduced", settings, uncertainty=False)
    assert auto.info["method"] == "Radau" and auto.info["method_choice"] == "auto"
    assert auto.info["stiffness_ratio"] > auto.info["stiffness_threshold"]
    assert auto.info["omega_axial"] > 0 and auto.info["omega_slow"] > 0 and auto.info["failure_rate"] > 0
    user = solve(paper_case("tnt-soft", n=10), "reduced", settings, method="Radau", uncertainty=False)
    assert user.info["method_choice"] == "user" and user.info["stiffness_ratio"] == auto.info["stiffness_ratio"]
