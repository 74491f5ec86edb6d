"""Frames of a sheet riding the beam (viz.ride): the tiles' outlines placed by their centres and rotations, in
the inertial and the rotating frame, and the frames and movie written."""

import numpy as np

from lightsail_mbs.viz.frames import make_movie
from lightsail_mbs.viz.ride import marked_tiles, render_ride_frames, tile_polygons
from lightsail_mbs.viz.spin_frame import in_frame
from tests.helpers import read_image
from tests.viz.test_export import SPIN, spinning_dish


def test_outlines_turn_with_a_rigidly_spinning_dish_and_stand_still_in_its_frame():
    """The dish turns by Ωt about the z axis through the middle: every outline at sample i is the first
    sample's turned by Ωt_i; in the rotating frame every outline stays where it started."""
    run = spinning_dish()
    middle = np.array([0.5, 0.5, 0.0])
    first = tile_polygons(run, 0)
    still = in_frame(run, "rotating")
    for i in (3, len(run.time) - 1):
        a = SPIN * run.time[i]
        turn = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
        for was, now, kept in zip(first, tile_polygons(run, i), tile_polygons(still, i), strict=True):
            np.testing.assert_allclose(now, middle + (was - middle) @ turn.T, atol=1e-12)
            np.testing.assert_allclose(kept, was, atol=1e-9)
    marked = marked_tiles(run)
    assert 0 < marked.sum() < marked.size / 3


def test_frames_and_movie_are_written(tmp_path):
    run = spinning_dish(steps=5)
    paths = render_ride_frames(run, tmp_path, frames=3, size=(500, 250), frame="rotating")
    assert len(paths) == 3 and read_image(paths[0]).shape == (250, 500, 3)
    assert make_movie(paths, tmp_path / "ride.gif", fps=5).stat().st_size > 1000
