"""The body-force term (model/terms/body_force.py) in both solvers of both families: on a free sail in a
uniform beam a uniform in-plane body force per unit mass b only translates the sail, every body by
b t²/2 along x, and leaves its shape, its angles and its velocities across the beam as they are."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters, paper_case, solve

B = 0.3  # N/kg


def translated(p, solver, settings):
    """(the run without the body force, the run with it) of case p, on the samples both have."""
    still = solve(p, solver, settings, uncertainty=False)
    pushed = solve(p.replace(body_force=B), solver, settings, uncertainty=False)
    assert still.error is None and pushed.error is None
    assert abs(still.time.size - pushed.time.size) <= 1  # both stop at the first sample past failure
    count = min(still.time.size, pushed.time.size)
    assert np.array_equal(still.time[:count], pushed.time[:count])
    return still, pushed, count


# the paper's soft torsion sail in a beam 25 times brighter: it fails at 0.38 s
CHAIN = paper_case("torsion-soft", n=12).replace(intensity=2.5e9)
CHAIN_RUN = RunSettings(t_final=0.6, output_interval=0.01)


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_body_force_translates_the_chain(solver):
    still, pushed, k = translated(CHAIN, solver, CHAIN_RUN)
    t = pushed.time[:k, None]
    a0 = CHAIN.defect_amplitude
    assert still.failure_time is not None and pushed.amplitude[k - 1] > 1.9 * pushed.amplitude[0]
    assert pushed.failure_time == pytest.approx(still.failure_time, rel=1e-6)
    drift = 0.5 * B * t[-1, 0] ** 2  # 2 cm, 2000 a₀
    np.testing.assert_allclose(pushed.x[:k] - still.x[:k] - 0.5 * B * t**2, 0.0, rtol=0, atol=1e-7 * drift)
    # generalized-α's first step misses b in ẋ by 8 % (its start transient, damped within steps)
    np.testing.assert_allclose(pushed.vx[:k] - still.vx[:k] - B * t, 0.0, rtol=0, atol=1e-4 * B * t[-1, 0])
    np.testing.assert_allclose(pushed.y[:k], still.y[:k], rtol=0, atol=1e-6 * a0)
    turn = np.abs(still.theta[:k]).max()  # the instability amplifies round-off: θ to 1e-5 of its largest value
    np.testing.assert_allclose(pushed.theta[:k], still.theta[:k], rtol=0, atol=1e-5 * turn)


def agreeing(p, settings):
    """The pushed case p by both solvers, on the samples both have."""
    reduced = solve(p.replace(body_force=B), "reduced", settings, uncertainty=False)
    exudyn = solve(p.replace(body_force=B), "exudyn", settings, uncertainty=False)
    assert reduced.failure_time is not None
    assert exudyn.failure_time == pytest.approx(reduced.failure_time, rel=1e-3)
    count = min(reduced.time.size, exudyn.time.size)
    return reduced, exudyn, count


def test_both_chain_solvers_agree_on_the_pushed_sail():
    reduced, exudyn, k = agreeing(CHAIN, CHAIN_RUN)
    a0 = CHAIN.defect_amplitude
    np.testing.assert_allclose(exudyn.x[:k].mean(axis=1), reduced.x[:k].mean(axis=1), rtol=0, atol=1e-3 * a0)
    np.testing.assert_allclose(exudyn.theta[:k], reduced.theta[:k], rtol=0, atol=1e-2 * np.abs(reduced.theta).max())


# the 6 × 6 sheet in the same bright beam: its chain limit fails near 0.38 s
SHEET = SailParameters(model="sheet", n=6, ny=6, youngs_modulus=4.5e9, intensity=2.5e9)
SHEET_RUN = RunSettings(t_final=0.6, output_interval=0.01)


@pytest.mark.parametrize("solver", ["reduced", "exudyn"])
def test_body_force_translates_the_sheet(solver):
    still, pushed, k = translated(SHEET, solver, SHEET_RUN)
    t = pushed.time[:k, None]
    a0 = SHEET.defect_amplitude
    assert still.failure_time is not None
    assert pushed.failure_time == pytest.approx(still.failure_time, rel=1e-6)
    shift = pushed.tile_centres[:k] - still.tile_centres[:k]
    drift = 0.5 * B * t[-1, 0] ** 2
    np.testing.assert_allclose(shift[..., 0] - 0.5 * B * t**2, 0.0, rtol=0, atol=1e-7 * drift)
    np.testing.assert_allclose(shift[..., 1:], 0.0, rtol=0, atol=1e-6 * a0)
    np.testing.assert_allclose(pushed.tile_angles[:k], still.tile_angles[:k], rtol=0, atol=1e-6 * a0 / SHEET.length)


def test_both_sheet_solvers_agree_on_the_pushed_sail():
    reduced, exudyn, k = agreeing(SHEET, SHEET_RUN)
    mean_x = [r.tile_centres[:k, :, 0].mean(axis=1) for r in (reduced, exudyn)]
    np.testing.assert_allclose(mean_x[1], mean_x[0], rtol=0, atol=1e-3 * SHEET.defect_amplitude)


def test_body_force_is_checked():
    with pytest.raises(ParameterError, match="body_force"):
        SailParameters(body_force=float("nan"))
    with pytest.raises(ParameterError, match="body_force"):
        SailParameters(n=12, payload_mass=1e-4, payload_stem=0.2, body_force=1.0)
