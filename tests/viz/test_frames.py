"""Headless rendering (viz.frames): frame sampling, size, count, drawn deflection vs amplitude, both renderers,
comparisons, movies.

The runs are synthetic (tests.helpers.growing_sine): slices on w(x, t) = a₀ e^{t/τ} sin(2πνx/L) with exact
chords, so the amplitude ratio at time t is e^{t/τ}; ``run`` is the fixture of tests/conftest.py.
"""

import numpy as np
import pytest

from lightsail_mbs import ParameterError
from lightsail_mbs.viz.frames import frame_indices, make_movie, render_comparison, render_frames
from lightsail_mbs.viz.scene import Layout
from tests.helpers import growing_sine, read_image

RENDERERS = ("matplotlib", "exudyn")
SAIL_STROKE_PX = 4.0  # render_scene: sail strokes are 4·scale pixels wide


def sail_extent(image: np.ndarray) -> int:
    """Vertical extent (pixels) of the dark sail strokes inside the band between text and legend."""
    lay = Layout(image.shape[1], image.shape[0])
    band = image[int(lay.top_band) + 1 : image.shape[0] - int(lay.bottom_band) - 1]
    rows = np.nonzero((band.max(axis=2) < 120).any(axis=1))[0]
    return int(rows.max() - rows.min() + 1)


def test_frame_indices_even_distinct_and_include_failure(run):
    picks = frame_indices(run.time, frames=7, failure_time=run.failure_time)
    assert picks.size == 7 and np.all(np.diff(picks) > 0) and picks[0] == 0 and picks[-1] == run.time.size - 1
    k_fail = np.nonzero(run.time >= run.failure_time)[0][0]  # the first state that shows the failure
    assert k_fail in picks
    every = frame_indices(run.time, every_seconds=0.25)
    np.testing.assert_allclose(run.time[every], [0, 0.25, 0.5, 0.75, 1.0])
    assert frame_indices(run.time, frames=run.time.size).size == run.time.size


def test_a_run_stopped_at_failure_ends_on_a_frame_that_shows_it(tmp_path):
    """Stopped at the first sample past the failure time t_f = ln 2 (0.6931…), which is nearer the sample
    before it (0.69) than that last one (0.70): the last frame is the last state, and it is drawn as failed."""
    run = growing_sine(steps=71, t_final=0.70)
    assert run.time[-2] < run.failure_time < run.time[-1]
    assert run.failure_time - run.time[-2] < run.time[-1] - run.failure_time
    for picks in (
        frame_indices(run.time, frames=5, failure_time=run.failure_time),
        frame_indices(run.time, every_seconds=0.3, failure_time=run.failure_time),
    ):
        assert picks[-1] == run.time.size - 1
    last = read_image(render_frames(run, tmp_path, frames=5, size=(320, 160), renderer="matplotlib")[-1])
    red = (last[..., 0] > 180) & (last[..., 1] < 60) & (last[..., 2] < 60)
    assert red[:3, :].any()  # the failure border


@pytest.mark.parametrize(
    "bad", [dict(frames=0), dict(frames=10_000), dict(every_seconds=0.0), dict(frames=3, every_seconds=0.1)]
)
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


@pytest.mark.parametrize("renderer", RENDERERS)
def test_frames_size_count_differ_and_extent_follows_amplitude(run, tmp_path, renderer):
    size = (400, 200)
    exaggeration = 2000.0
    paths = render_frames(
        run, tmp_path, frames=4, size=size, renderer=renderer, exaggeration=exaggeration, color_by=None, arrows=False
    )
    assert [p.name for p in paths] == [f"frame_{k:04d}.png" for k in range(4)]
    assert sorted(tmp_path.glob("frame_*.png")) == paths
    images = [read_image(p) for p in paths]
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
    last = read_image(paths[-1])
    assert last.shape == (160, 320, 3)
    red = (last[..., 0] > 180) & (last[..., 1] < 60) & (last[..., 2] < 60)
    assert red[:, :3].any() and red[:3, :].any()  # the failure border
    assert not ((read_image(paths[0])[..., 0] > 180) & (read_image(paths[0])[..., 1] < 60))[:3, :].any()


def test_renderers_agree_on_the_drawn_sail(run, tmp_path):
    kwargs = dict(frames=2, size=(400, 200), color_by=None, arrows=False)
    mpl = render_frames(run, tmp_path / "mpl", renderer="matplotlib", **kwargs)
    exu = render_frames(run, tmp_path / "exu", renderer="exudyn", **kwargs)
    for a, b in zip(mpl, exu):
        assert abs(sail_extent(read_image(a)) - sail_extent(read_image(b))) <= 2


def test_comparison_frames_stack_two_runs(run, tmp_path):
    fast = growing_sine(rate=2.0, steps=21)
    paths = render_comparison(
        run,
        fast,
        tmp_path,
        labels=("slow", "fast"),
        frames=3,
        size=(400, 400),
        renderer="matplotlib",
        color_by=None,
        arrows=False,
    )
    assert len(paths) == 3
    im = read_image(paths[-1])
    assert im.shape == (400, 400, 3)
    top, bottom = sail_extent(im[:200]), sail_extent(im[200:])
    assert bottom > top  # same exaggeration: the faster-growing run (e² vs e¹) is drawn taller


def test_movies_are_written_and_readable(run, tmp_path):
    import imageio.v2 as imageio

    paths = render_frames(run, tmp_path, frames=5, size=(322, 161), renderer="matplotlib")
    gif = make_movie(paths, tmp_path / "run.gif", fps=10)
    frames = imageio.mimread(gif)
    assert len(frames) == 5 and frames[0].shape[:2] == (161, 322)
    mp4 = make_movie(paths, tmp_path / "run.mp4", fps=10)
    with imageio.get_reader(mp4, format="FFMPEG") as reader:
        video = [f for f in reader]
    assert len(video) == 5 and video[0].shape[:2] == (162, 322)  # padded to even height for yuv420p
    with pytest.raises(ParameterError, match="path"):
        make_movie(paths, tmp_path / "run.avi")
