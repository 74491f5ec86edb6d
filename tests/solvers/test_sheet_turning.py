"""The in-house sheet in the frame that turns with its spin (solvers.reduced.sheet_turning): the transformation
is exact, a run in either frame is the same run, and the spun sail rests in the turning frame in long steps."""

import numpy as np
import pytest

from lightsail_mbs import RunSettings, SailParameters, solve
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import materials
from lightsail_mbs.solvers.reduced.sheet import SheetModel

SPIN = 2 * np.pi * 120.0  # FlexSailSim's spin (rad/s)


def film_disc(**changes) -> SailParameters:
    """A 1 m disc of 49 tiles of a 200 nm Si₃N₄ film (materials table), spinning at 120 Hz."""
    fields = dict(model="sheet", planform="disc", n=9, ny=12, length=1.0, width=1.0, material="silicon-nitride")
    fields.update(thickness=2e-7, spin_rate=SPIN, **changes)
    return SailParameters(**materials.fill(fields))


def test_turning_rates_are_the_inertial_rates_seen_from_the_turning_frame():
    """For a perturbed state y_r at time t, d/dt of its inertial image along the turning frame's rates (central
    difference in time) equals the inertial kernel's rates at that image: v̇, ω̇_b and u̇, to 1e-7 of their
    size (the difference quotient's own error is ~δ² ≈ 1e-12 of it)."""
    p = film_disc(beam_waist=0.4, intensity=1e9, initial_tilt=0.01)
    turning, inertial = SheetModel(p, frame="turning"), SheetModel(p)
    rng = np.random.default_rng(1)
    y = turning.y0() + 1e-6 * rng.standard_normal(turning.n)
    t, dt = 3.7e-3, 1e-7
    rates = turning.rhs(t, y)
    ahead = turning.inertial([t + dt], (y + dt * rates)[None])[0]
    behind = turning.inertial([t - dt], (y - dt * rates)[None])[0]
    image = turning.inertial([t], y[None])[0]
    expected = inertial.rhs(t, image).reshape(-1, 13)
    seen = ((ahead - behind) / (2 * dt)).reshape(-1, 13)
    for part in (slice(0, 3), slice(7, 10)):  # u̇ = v and v̇; the body rates below in the body's axes
        scale = np.abs(expected[:, part]).max()
        assert np.abs(seen[:, part] - expected[:, part]).max() < 1e-7 * scale
    omega_b = image.reshape(-1, 13)[:, 10:13]
    rel = ((ahead - behind).reshape(-1, 13)[:, 10:13] / (2 * dt) - expected[:, 10:13]) / np.abs(omega_b).max()
    assert np.abs(rel).max() < 1e-7 * SPIN


def test_both_frames_give_the_same_run_of_a_spinning_disc_in_a_gaussian_beam():
    """The spinning disc of the two-solver test (300 rad/s, Gaussian beam, 2-D defect): inertial and turning
    frame give amplitudes within 1e-6 a₀ at every sample and failure times within 1e-9 (relative)."""
    beam = dict(beam_waist=0.6, edge_tension=1e-4, defect_mode_y=1.0)
    p = SailParameters(model="sheet", planform="disc", n=9, ny=12, length=1.0, width=1.0, youngs_modulus=4.5e9, **beam)
    p = p.replace(spin_rate=300.0)
    settings = RunSettings(t_final=2e-3, output_interval=2e-5)
    runs = [solve(p, "reduced", settings, uncertainty=False, frame=frame) for frame in ("inertial", "turning")]
    assert [r.info["frame"] for r in runs] == ["inertial", "turning"]
    count = min(len(r.time) for r in runs)
    assert np.abs(runs[0].amplitude[:count] - runs[1].amplitude[:count]).max() < 1e-6 * p.defect_amplitude
    assert abs(runs[0].failure_time - runs[1].failure_time) < 1e-9 * runs[0].failure_time


def test_the_spun_film_disc_rests_in_the_turning_frame_in_long_steps():
    """The unlit flat Si₃N₄ disc at 120 Hz over 6 turns: every tile stays within 1e-9 m of its start turned by
    Ωt, the spin rate within 1e-9 Ω, and the turning frame needs at most 40 steps and one Jacobian, where the
    inertial frame takes more steps in a tenth of the time (measured over the 6 turns: 17 steps against 1294,
    and 1267 Jacobians)."""
    p = film_disc(intensity=0.0, defect_amplitude=0.0)
    settings = RunSettings(t_final=0.05, output_interval=5e-3, stop_at_failure=False)
    run = solve(p, "reduced", settings, uncertainty=False)
    assert run.info["frame"] == "turning" and run.error is None and run.info["steps"] <= 40 and run.info["njev"] == 1
    angle = SPIN * np.asarray(run.time)[:, None]
    rel = run.tile_centres - run.tile_centres[0].mean(axis=0)
    x = np.cos(angle) * rel[..., 0] + np.sin(angle) * rel[..., 1]
    y = -np.sin(angle) * rel[..., 0] + np.cos(angle) * rel[..., 1]
    assert np.hypot(x - x[0], y - y[0]).max() < 1e-9
    assert np.abs(np.asarray(run.info["ride"]["spin_rate"]) / SPIN - 1).max() < 1e-9
    short = RunSettings(t_final=5e-3, output_interval=5e-3, stop_at_failure=False)
    assert solve(p, "reduced", short, uncertainty=False, frame="inertial").info["steps"] > run.info["steps"]


def test_an_unknown_frame_is_one_line():
    with pytest.raises(ParameterError, match="frame"):
        solve(film_disc(), "reduced", RunSettings(t_final=1e-3), uncertainty=False, frame="sideways")
