"""Frames and movies of a sheet run (viz.sheet): count, size, colours where the sheet is up and down, the
failure mark, and what it refuses."""

import dataclasses

import numpy as np
import pytest

from lightsail_mbs import ParameterError
from lightsail_mbs.viz.frames import make_movie
from lightsail_mbs.viz.sheet import auto_exaggeration, draw_frame, frame_image, render_sheet_frames
from tests.helpers import growing_sine, read_image, synthetic_sheet


def test_frames_count_size_and_failure_mark(tmp_path):
    run = synthetic_sheet(steps=11)  # e^t: fails at ln 2
    paths = render_sheet_frames(run, tmp_path, frames=5, size=(600, 300))
    assert len(paths) == 5
    first, last = read_image(paths[0]), read_image(paths[-1])
    assert first.shape == (300, 600, 3)
    red = np.array([255, 0, 0])
    assert np.abs(last[1, 300].astype(int) - red).sum() < 60  # the failed frame's red border
    assert np.abs(first[1, 300].astype(int) - red).sum() > 200
    movie = make_movie(paths, tmp_path / "sheet.gif", fps=5)
    assert movie.stat().st_size > 1000


def test_a_run_the_solver_stopped_says_so_on_its_last_frame():
    run = dataclasses.replace(synthetic_sheet(), error="step size too small")
    last = draw_frame(run, run.time.size - 1, size=(600, 300))
    assert any("solver stopped: step size too small" in t.get_text() for t in last.texts)
    assert not any("solver stopped" in t.get_text() for t in draw_frame(run, 0, size=(600, 300)).texts)


def test_map_colours_crests_red_and_troughs_blue():
    """w ∝ sin(3πx) sin(πy): the map's pixel over x = 1/6, y = 1/2 (a crest) is red, over x = 1/2 (a trough)
    blue."""
    run = synthetic_sheet()
    image = frame_image(draw_frame(run, 0, size=(1000, 450)))
    # the map's axes span figure x 0.06…0.42 (width) and y 0.12…0.84; equal aspect: find its pixels
    fig = draw_frame(run, 0, size=(1000, 450))
    ax = fig.axes[0]
    fig.canvas.draw()

    def pixel(x, y):
        px, py = ax.transData.transform((x, y))
        return image[int(round(450 - py)), int(round(px))].astype(int)

    crest, trough = pixel(1 / 6, 0.5), pixel(0.5, 0.5)
    assert crest[0] > crest[2] + 60 and trough[2] > trough[0] + 60


def test_exaggeration_and_refusals(tmp_path):
    run = synthetic_sheet()
    e = auto_exaggeration(run)
    assert np.max(np.abs(run.deflection())) * e == pytest.approx(0.1 * max(run.params.length, run.params.width))
    with pytest.raises(ParameterError, match="sheet"):
        render_sheet_frames(growing_sine(), tmp_path)
    with pytest.raises(ParameterError, match="color_scale"):
        render_sheet_frames(run, tmp_path, color_scale="rainbow")


def test_a_disc_is_drawn_as_its_tiles():
    """A disc run (w ∝ x − L/2 on polar tiles): its map is the tiles' outlines, red where x > L/2, blue
    where x < L/2, and the corner of the L × L square outside the disc is left blank."""
    from lightsail_mbs import RunSettings, SailParameters
    from lightsail_mbs.model import sheet
    from lightsail_mbs.result import Result

    p = SailParameters(model="sheet", planform="disc", n=9, ny=12, length=1.0, width=1.0)
    flat = sheet.flat_centres(p)
    times = np.linspace(0, 1, 3)
    w = p.defect_amplitude * (flat[:, 0] - 0.5) ** 3
    centres = np.stack([flat + np.outer([0, 0, 1], np.exp(t) * w).T for t in times])
    zero = np.zeros_like(centres)
    run = Result.from_tiles(p, "synthetic", times, centres, zero, zero, zero, settings=RunSettings(t_final=1.0))
    fig = draw_frame(run, 1, size=(1000, 450))
    image = frame_image(fig)
    ax = fig.axes[0]

    def pixel(x, y):
        px, py = ax.transData.transform((x, y))
        return image[int(round(450 - py)), int(round(px))].astype(int)

    right, left, corner = pixel(0.9, 0.5), pixel(0.1, 0.5), pixel(0.02, 0.02)
    assert right[0] > right[2] + 60 and left[2] > left[0] + 60 and np.all(corner > 240)
