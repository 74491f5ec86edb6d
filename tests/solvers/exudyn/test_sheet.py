"""The Exudyn sheet: the same accelerations as the in-house solver of the same tiles, the same motion on a
small sheet, the chain it reduces to, plates against Kirchhoff theory, and the limits it reports."""

import numpy as np
import pytest

from lightsail_mbs import ParameterError, RunSettings, SailParameters, solve
from lightsail_mbs.model import plate_theory, sheet, terms
from lightsail_mbs.solvers.exudyn import sheet as exudyn_sheet
from lightsail_mbs.solvers.exudyn.console import MAX_COORDINATES, check_size
from lightsail_mbs.solvers.reduced import sheet as reduced_sheet
from tests.helpers import plate
from tests.model.grating_layouts import PIZZA, write

SOFT = dict(model="sheet", youngs_modulus=4.5e9)


def test_initial_accelerations_equal_the_in_house_solvers():
    """A 2-D defect, an off-centre round Gaussian beam, a partial reflector and edge tension: every tile's
    acceleration at t = 0 from Exudyn's assembled system equals the in-house right-hand side."""
    import exudyn as exu

    p = SailParameters(
        n=5,
        ny=4,
        defect_mode_y=1.5,
        beam_waist=1.5,
        beam_centre=0.4,
        beam_centre_y=0.6,
        edge_tension=1e-5,
        reflectivity=0.9,
        absorptivity=0.05,
        **SOFT,
    )
    model = reduced_sheet.SheetModel(p)
    expected = model.rhs(0.0, model.y0()).reshape(-1, reduced_sheet.STATE)[:, 7:10]
    system = exudyn_sheet.SheetSystem(p)
    s = exudyn_sheet.simulation_settings(1e-6, 1e-6, 1e-10, 1e-16, 0.9)
    solver = exu.MainSolverImplicitSecondOrder()
    from lightsail_mbs.solvers.exudyn.console import silenced

    with silenced():
        solver.InitializeSolver(system.mbs, s)  # computes the initial accelerations
    got = np.asarray(system.mbs.systemData.GetODE2Coordinates_tt()).reshape(-1, 6)[:, :3]
    assert np.max(np.abs(got - expected)) < 1e-6 * np.max(np.abs(expected))


def test_exudyn_and_in_house_sheets_move_alike():
    """6 × 5 tiles, doubly sinusoidal defect, 0.5 s: the tile deflections of the two solvers agree within
    1e-3 a₀ (Exudyn at a quarter of its default step, as the cross-check)."""
    p = SailParameters(n=6, ny=5, defect_mode_y=1.0, **SOFT)
    settings = RunSettings(t_final=0.5, output_interval=0.01)
    a = solve(p, "exudyn", settings, step_size=2.5e-4)
    b = solve(p, "reduced", settings)
    assert a.time.shape == b.time.shape
    assert np.max(np.abs(a.deflection() - b.deflection())) < 1e-3 * p.defect_amplitude
    assert abs(a.amplitude[-1] / a.amplitude[0] - 1) > 1e-3  # the sheet did move


def test_sheet_with_one_defect_across_is_the_chain():
    p = SailParameters(n=30, ny=1, **SOFT)
    settings = RunSettings(t_final=3.0)
    strip = solve(sheet.as_strip(p), "reduced", settings)
    tiles = solve(p, "exudyn", settings)
    assert tiles.failure_time == pytest.approx(strip.failure_time, rel=1e-3)
    assert tiles.info["njev"] <= 3  # modified Newton: the load is not in the Jacobian


def test_plate_statics_and_modes_on_a_coarse_grid():
    p = plate("clamped")
    w = exudyn_sheet.static_centres(p)[40, 2]
    assert w == pytest.approx(reduced_sheet.static_centres(p)[40, 2], rel=1e-9)
    assert w == pytest.approx(plate_theory.centre_deflection(p), rel=0.11)  # 9 × 9: +10 % (grid error)
    supported = p.replace(boundary="simply_supported", pressure=0.0)
    np.testing.assert_allclose(
        exudyn_sheet.eigenfrequencies(supported, 4), reduced_sheet.eigenfrequencies(supported, 4), rtol=1e-6
    )


def test_limits_are_reported():
    tensioned = SailParameters(
        n=4,
        ny=4,
        bending=False,
        edge_tension=1.0,
        boundary="simply_supported",
        intensity=0.0,
        defect_amplitude=0.0,
        **SOFT,
    )
    with pytest.raises(ParameterError, match="edge_tension"):
        exudyn_sheet.eigenfrequencies(tensioned)
    stiff = SailParameters(n=30, ny=1, model="sheet", youngs_modulus=4.5e13)
    assert "round-off" in exudyn_sheet.round_off_warning(stiff)
    assert exudyn_sheet.round_off_warning(stiff.replace(membrane_modulus=4.5e9)) is None
    assert exudyn_sheet.default_abs_tol(stiff) >= 2 * exudyn_sheet.round_off_floor(stiff)
    with pytest.raises(ParameterError, match="step_size"):
        solve(stiff, "exudyn", RunSettings(t_final=0.01), step_size=-1.0)
    with pytest.raises(ParameterError, match="rtol"):
        solve(stiff, "exudyn", RunSettings(t_final=0.01), rtol=1e-3)


@pytest.mark.slow
def test_two_sheet_solvers_agree_to_failure_on_a_doubly_sinusoidal_defect():
    """The cross-check's doubly sinusoidal case on 6 × 6 tiles, to failure: failure times within 1 % and
    deflections within 1e-3 a₀ while both amplitudes are below 1.5 a₀ (studies.sheet; 20 × 20 in
    validation/sheet_crosscheck.py)."""
    from lightsail_mbs.studies import sheet as sheet_study

    p = SailParameters(n=6, ny=6, defect_mode_y=1.5, **SOFT)
    settings = RunSettings(t_final=3.0, output_interval=5e-3)
    a = solve(p, "exudyn", settings, step_size=2.5e-4)
    b = solve(p, "reduced", settings)
    assert a.failed and b.failed and a.error is None and b.error is None
    assert a.failure_time == pytest.approx(b.failure_time, rel=sheet_study.FAILURE_TIME_LIMIT)
    difference, _ = sheet_study.compare_deflections(a, b)
    assert difference <= sheet_study.DEFLECTION_LIMIT


def test_initial_equilibrium_is_at_rest_in_exudyn_too():
    """initial_equilibrium (the corrected rest offsets, shared model data): Exudyn's initial transverse
    accelerations of the unlit, tensioned doubly curved sheet are those of a rigid body (the followers' net
    force), 1e-6 of the released sheet's or less, and equal the in-house right-hand side."""
    import exudyn as exu

    from lightsail_mbs.solvers.exudyn.console import silenced

    def accelerations(p):
        system = exudyn_sheet.SheetSystem(p)
        s = exudyn_sheet.simulation_settings(1e-6, 1e-6, 1e-10, 1e-16, 0.9)
        solver = exu.MainSolverImplicitSecondOrder()
        with silenced():
            solver.InitializeSolver(system.mbs, s)
        return np.asarray(system.mbs.systemData.GetODE2Coordinates_tt()).reshape(-1, 6)[:, :3]

    released = SailParameters(n=5, ny=4, defect_mode_y=1.5, edge_tension=3e-5, intensity=0.0, **SOFT)
    held = released.replace(initial_equilibrium=True)
    before, after = accelerations(released), accelerations(held)
    model = reduced_sheet.SheetModel(held)
    expected = model.rhs(0.0, model.y0()).reshape(-1, reduced_sheet.STATE)[:, 7:10]
    scale = np.max(np.abs(before[:, 2]))
    spread = after[:, 2] - after[:, 2].mean()  # the rigid-body remainder is the same on every tile
    assert np.max(np.abs(spread)) < 1e-6 * scale
    assert np.max(np.abs(after[:, 2] - expected[:, 2])) < 1e-6 * scale
    # in-plane: Exudyn's round-off floor k_∥ ε L / m (docs: sheet), the same before and after
    assert np.max(np.abs(after[:, :2] - expected[:, :2])) < 1e-7


def test_samples_lie_on_the_grid_when_the_interval_does_not_divide_the_run():
    """Contract rule 4: an interval that does not divide t_final, and a t_final that no whole number of steps
    reaches, still give samples at exactly settings.sample_times(); the last one, between two steps, is the
    cubic Hermite interpolant, close to the line between the two steps around it."""
    p = SailParameters(model="sheet", n=4, ny=4, youngs_modulus=4.5e9, beam_waist=0.6, intensity=1e9)
    coarse = RunSettings(t_final=1.0005e-3, output_interval=3e-4, stop_at_failure=False)
    result = exudyn_sheet.run(p, coarse, step_size=1e-5)
    np.testing.assert_allclose(result.time, coarse.sample_times(), rtol=0, atol=1e-15)
    fine_settings = RunSettings(t_final=1.01e-3, output_interval=1e-5, stop_at_failure=False)
    fine = exudyn_sheet.run(p, fine_settings, step_size=1e-5)
    before, after = fine.tile_centres[-2], fine.tile_centres[-1]
    line = before + 0.05 * (after - before)  # 1.0005e-3 s is 5 % into the step from 1e-3 s to 1.01e-3 s
    np.testing.assert_allclose(result.tile_centres[-1], line, rtol=0, atol=0.01 * np.max(np.abs(after - before)))
    assert np.max(np.abs(after - before)) > 0


def test_samples_lie_on_the_grid_when_newton_shortens_steps():
    """A stiff clamped strip whose first steps Newton fails: Exudyn shortens them, and its later steps pass
    the output times instead of landing on them; the samples are still at settings.sample_times()."""
    length = 0.10809697574952476
    p = SailParameters(
        model="sheet", n=19, ny=3, length=length, thickness=4.08e-7, density=551.8, youngs_modulus=5.66e12,
        intensity=1e6, defect_amplitude=3.77e-3, defect_mode=0.5, beam_waist=length, reflectivity=0.455,
        boundary="clamped",
    )  # fmt: skip
    settings = RunSettings(t_final=0.01, output_interval=0.0025, stop_at_failure=False)
    result = exudyn_sheet.run(p, settings)
    assert result.info["steps"] > round(settings.t_final / result.info["step_size"])  # steps were shortened
    np.testing.assert_allclose(result.time, settings.sample_times(), rtol=0, atol=1e-15)
    assert np.all(np.isfinite(result.tile_centres))


def test_a_sheet_too_large_for_exudyn_is_one_line_before_any_solving():
    check_size(MAX_COORDINATES, "a sheet", 6)  # the largest that runs (n² just below 2³¹)
    assert MAX_COORDINATES**2 < 2**31 - 1 < (MAX_COORDINATES + 1) ** 2
    p = SailParameters(model="sheet", n=92, ny=84)  # 7728 tiles, 46,368 coordinates: Exudyn 1.13 crashes
    with pytest.raises(ParameterError) as err:
        exudyn_sheet.run(p, RunSettings(t_final=0.002), progress=False)
    message = str(err.value)
    assert len(message.splitlines()) == 1 and "7728 tiles" in message and "--solver reduced" in message, message


BEAM_AND_MOTION = dict(beam_waist=0.6, beam_centre=0.3, edge_tension=1e-4, velocity_terms=True)


@pytest.mark.parametrize("extra", [dict(), BEAM_AND_MOTION, dict(grating=write("pizza", PIZZA), beam_waist=0.6)])
def test_compiled_load_is_the_terms_numpy_sum_at_any_coordinates(extra):
    """The force vector Exudyn's load writes (one compiled pass) at random coordinates and rates: the terms'
    numpy sum on the tiles' centres, normals n = R ẑ of the xyz angles, velocities and angular velocities
    ω(φ, φ̇), to round-off; no torques."""
    p = SailParameters(n=5, ny=4, **SOFT, **extra)
    system = exudyn_sheet.SheetSystem(p)
    rng = np.random.default_rng(3)
    q, q_t = rng.normal(0, 0.05, (2, system.force.size)) * [[1], [20]]
    reads = bool(system.reads_velocities)
    force = system.force_vector(q, q_t if reads else None, 0.25).reshape(-1, 6)
    Q, R = q.reshape(-1, 6), q_t.reshape(-1, 6)
    rates = (R[:, :3], exudyn_sheet.angular_velocity_xyz(Q[:, 3:], R[:, 3:])) if reads else (None, None)
    axes = sheet.rotation_xyz(Q[:, 3:])[..., 0]  # R x̂, read by the grating term
    centres = system.flat + Q[:, :3]
    expected = terms.tile_forces(p, centres, sheet.normal_xyz(Q[:, 3:]), *rates, time=0.25, axes=axes)
    assert reads == bool(extra.get("velocity_terms"))
    np.testing.assert_allclose(force[:, :3], expected, rtol=1e-13, atol=1e-15 * np.abs(expected).max())
    assert not force[:, 3:].any()
