"""Headless rendering: frame sampling, size, count, drawn deflection vs amplitude, movies, CLI (issue 6).

The runs are synthetic: slices on w(x, t) = a₀ e^{t/τ} sin(2πνx/L) with exact chords, so the
amplitude ratio at time t is e^{t/τ} and the curvature at the hinges is known in closed form.
"""
import math

import numpy as np
import pytest
from PIL import Image

from lightsail_mbs import ParameterError, Result, SailParameters
from lightsail_mbs.cli import main
from lightsail_mbs.viz.frames import frame_indices, make_movie, render_comparison, render_frames
from lightsail_mbs.viz.scene import Layout, auto_exaggeration, frame_exaggeration, hinge_values, make_style
from lightsail_mbs.model.shapes import hinge_points

RENDERERS = ("matplotlib", "exudyn")
SAIL_STROKE_PX = 4.0          # render_scene: sail strokes are 4·scale pixels wide


def growing_sine(model="torsion", n=20, steps=41, rate=1.0, t_final=1.0, **changes) -> Result:
    p = SailParameters(model=model, n=n, t_final=t_final, **changes)
    times = np.linspace(0.0, t_final, steps)
    x, y, theta = (np.empty((steps, n)) for _ in range(3))
    k = 2 * np.pi * p.mode / p.length
    for j, t in enumerate(times):
        pts = hinge_points(p, lambda s, g=math.exp(rate * t): p.amplitude * g * np.sin(k * s))
        d = np.diff(pts, axis=0)
        theta[j] = np.arctan2(d[:, 1], d[:, 0])
        x[j] = pts[:-1, 0] + 0.5 * p.slice_length * np.cos(theta[j])
        y[j] = pts[:-1, 1] + 0.5 * p.slice_length * np.sin(theta[j])
    zero = np.zeros_like(x)
    z = np.zeros((steps, n - 1)) if p.extensible else None
    return Result.from_trajectory(p, "synthetic", times, x, y, theta, zero, zero, zero, z=z, z_rate=z)


def read(path) -> np.ndarray:
    return np.asarray(Image.open(path).convert("RGB"))


def sail_extent(image: np.ndarray) -> int:
    """Vertical extent (pixels) of the dark sail strokes inside the band between text and legend."""
    lay = Layout(image.shape[1], image.shape[0])
    band = image[int(lay.top_band) + 1:image.shape[0] - int(lay.bottom_band) - 1]
    rows = np.nonzero((band.max(axis=2) < 120).any(axis=1))[0]
    return int(rows.max() - rows.min() + 1)


@pytest.fixture(scope="module")
def run():
    return growing_sine()


def test_frame_indices_even_distinct_and_include_failure(run):
    picks = frame_indices(run.time, frames=7, failure_time=run.failure_time)
    assert picks.size == 7 and np.all(np.diff(picks) > 0) and picks[0] == 0 and picks[-1] == run.time.size - 1
    k_fail = np.argmin(np.abs(run.time - run.failure_time))
    assert k_fail in picks
    every = frame_indices(run.time, every_seconds=0.25)
    np.testing.assert_allclose(run.time[every], [0, 0.25, 0.5, 0.75, 1.0])
    assert frame_indices(run.time, frames=run.time.size).size == run.time.size


@pytest.mark.parametrize("bad", [dict(frames=0), dict(frames=10_000), dict(every_seconds=0.0),
                                 dict(frames=3, every_seconds=0.1)])
def test_frame_indices_reject_bad_input(run, bad):
    with pytest.raises(ParameterError):
        frame_indices(run.time, **bad)


def test_bad_options_name_the_parameter(run, tmp_path):
    with pytest.raises(ParameterError, match="color_by='moment'"):
        render_frames(growing_sine(model="rigid"), tmp_path, frames=2, color_by="moment")
    with pytest.raises(ParameterError, match="size"):
        render_frames(run, tmp_path, frames=2, size="10x10")
    with pytest.raises(ParameterError, match="renderer"):
        render_frames(run, tmp_path, frames=2, renderer="povray")
    with pytest.raises(ParameterError, match="exaggeration"):
        render_frames(run, tmp_path, frames=2, exaggeration=-1.0)


def test_hinge_curvature_is_the_sines_second_derivative(run):
    """κ_j = Δθ_j / l ≈ w''(x_j) = −a k² sin(k x_j) at the hinges (small slopes, l ≪ wavelength)."""
    p = run.params
    k = 2 * np.pi * p.mode / p.length
    x_hinge = np.arange(1, p.n) * p.slice_length
    for i in (0, -1):
        expected = -p.amplitude * math.exp(run.time[i]) * k * k * np.sin(k * x_hinge)
        kappa = hinge_values(run, i, "curvature")
        assert np.max(np.abs(kappa - expected)) < 0.03 * np.max(np.abs(expected))
    moment = hinge_values(run, 0, "moment")
    np.testing.assert_allclose(moment, p.torsional_stiffness * p.slice_length * hinge_values(run, 0, "curvature"))


def test_auto_exaggeration_draws_initial_amplitude_at_5_percent_of_length(run):
    lay = Layout(800, 400)
    e = auto_exaggeration([run], [np.arange(run.time.size // 2)], lay)     # grows e^0.5: fits at 5 % of L
    drawn = e * run.amplitude[0] / run.params.length
    assert 0.045 < drawn <= 0.05                  # rounded down to two significant digits
    long_run = growing_sine(rate=4.0)             # grows e^4 ≈ 55×: failure (×2) at t = ln 2 / 4
    every = np.arange(long_run.time.size)
    style = make_style([long_run], [every], lay)
    assert style.exaggeration == e                # up to failure the sail fits at 5 % of L
    peak = np.abs(long_run.y[-1]).max() / long_run.params.length
    e_last = frame_exaggeration(style, [(long_run, every[-1])])
    assert e_last < e and e_last * peak < lay.sail_half_height    # lowered after failure to stay in the band
    assert frame_exaggeration(style, [(long_run, 0)]) == e
    fixed = make_style([long_run], [every], lay, exaggeration=e)
    assert frame_exaggeration(fixed, [(long_run, every[-1])]) == e    # a given factor is never changed


@pytest.mark.parametrize("renderer", RENDERERS)
def test_frames_size_count_differ_and_extent_follows_amplitude(run, tmp_path, renderer):
    size = (400, 200)
    exaggeration = 2000.0
    paths = render_frames(run, tmp_path, frames=4, size=size, renderer=renderer, exaggeration=exaggeration,
                          color_by=None, arrows=False)
    assert [p.name for p in paths] == [f"frame_{k:04d}.png" for k in range(4)]
    assert sorted(tmp_path.glob("frame_*.png")) == paths
    images = [read(p) for p in paths]
    assert all(im.shape == (size[1], size[0], 3) for im in images)
    assert all(np.any(a != b) for a, b in zip(images, images[1:]))
    extents = np.array([sail_extent(im) for im in images])
    assert np.all(np.diff(extents) > 0)
    # peak-to-peak deflection 2·a(t) drawn at E / L · (width / 1.1) pixels per metre, plus the stroke width
    picks = frame_indices(run.time, frames=4, failure_time=run.failure_time)
    expected = 2 * run.amplitude[picks] * exaggeration / run.params.length * size[0] / 1.1
    np.testing.assert_allclose(extents - SAIL_STROKE_PX * Layout(*size).scale, expected, atol=3.0)


@pytest.mark.parametrize("renderer", RENDERERS)
def test_full_frame_with_colours_arrows_tension_and_failure(tmp_path, renderer):
    run = growing_sine(model="tnt", tension=1e-3, rate=2.0)
    paths = render_frames(run, tmp_path, frames=3, size=(320, 160), renderer=renderer, color_by="curvature")
    last = read(paths[-1])
    assert last.shape == (160, 320, 3)
    red = (last[..., 0] > 180) & (last[..., 1] < 60) & (last[..., 2] < 60)
    assert red[:, :3].any() and red[:3, :].any()           # the failure border
    assert not ((read(paths[0])[..., 0] > 180) & (read(paths[0])[..., 1] < 60))[:3, :].any()


def test_renderers_agree_on_the_drawn_sail(run, tmp_path):
    kwargs = dict(frames=2, size=(400, 200), color_by=None, arrows=False)
    mpl = render_frames(run, tmp_path / "mpl", renderer="matplotlib", **kwargs)
    exu = render_frames(run, tmp_path / "exu", renderer="exudyn", **kwargs)
    for a, b in zip(mpl, exu):
        assert abs(sail_extent(read(a)) - sail_extent(read(b))) <= 2


def test_comparison_frames_stack_two_runs(run, tmp_path):
    fast = growing_sine(rate=2.0, steps=21)
    paths = render_comparison(run, fast, tmp_path, labels=("slow", "fast"), frames=3, size=(400, 400),
                              renderer="matplotlib", color_by=None, arrows=False)
    assert len(paths) == 3
    im = read(paths[-1])
    assert im.shape == (400, 400, 3)
    top, bottom = sail_extent(im[:200]), sail_extent(im[200:])
    assert bottom > top        # same exaggeration: the faster-growing run (e² vs e¹) is drawn taller


def test_movies_are_written_and_readable(run, tmp_path):
    import imageio.v2 as imageio
    paths = render_frames(run, tmp_path, frames=5, size=(322, 161), renderer="matplotlib")
    gif = make_movie(paths, tmp_path / "run.gif", fps=10)
    frames = imageio.mimread(gif)
    assert len(frames) == 5 and frames[0].shape[:2] == (161, 322)
    mp4 = make_movie(paths, tmp_path / "run.mp4", fps=10)
    with imageio.get_reader(mp4, format="FFMPEG") as reader:
        video = [f for f in reader]
    assert len(video) == 5 and video[0].shape[:2] == (162, 322)     # padded to even height for yuv420p
    with pytest.raises(ParameterError, match="path"):
        make_movie(paths, tmp_path / "run.avi")


def test_cli_render_writes_frames_and_movie(run, tmp_path, capsys):
    path = run.save(tmp_path / "soft")
    out = tmp_path / "frames"
    code = main(["render", str(path), "--out", str(out), "--frames", "3", "--size", "320x160",
                 "--renderer", "matplotlib", "--movie", "gif"])
    assert code == 0
    assert len(list(out.glob("frame_*.png"))) == 3 and (out / "soft.gif").exists()
    assert read(out / "frame_0002.png").shape == (160, 320, 3)
    assert main(["render", str(path), "--out", str(out), "--frames", "0"]) == 2
    assert "frames=0" in capsys.readouterr().err


def test_animations_script_renders_saved_runs(tmp_path):
    """scenarios/animations.py: reads RUNS/<case>.npz when present, cuts at the amplitude ratio, writes the GIF."""
    import importlib.util
    from pathlib import Path

    script = Path(__file__).resolve().parents[1] / "scenarios" / "animations.py"
    spec = importlib.util.spec_from_file_location("animations", script)
    animations = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(animations)
    growing_sine(rate=3.0).save(tmp_path / "runs" / "soft_torsion.npz")
    animations.main(["--out", str(tmp_path / "docs"), "--runs", str(tmp_path / "runs"), "--cases", "soft_torsion",
                     "--frames", "4", "--size", "300x150", "--until-ratio", "3"])
    import imageio.v2 as imageio
    frames = imageio.mimread(tmp_path / "docs" / "soft_torsion.gif")
    assert len(frames) == 4 and frames[0].shape[:2] == (150, 300)
    cut = animations.until_ratio(growing_sine(rate=3.0), 3.0)
    assert cut.amplitude[-1] >= 3 * cut.amplitude[0] > cut.amplitude[-2]
