"""Frames and movies of a sheet riding the beam: the craft in 3-D against the beam, and its ride histories.

A frame of sample i shows, side by side,

* the **craft**: every tile's outline placed by its centre and rotation (model.sheet_mesh outlines about
  the flat centres, turned by the tile's rotation: no exaggeration), one sector of tiles in another colour
  so that the spin shows, the stem or tethers to the payload (a dot), the beam's axis and its waist
  (the 1/e² radius) drawn as a circle at the sail's mean height (a cube of a box: z not to scale with x
  and y where the stem is long); in the inertial frame of the run or the
  frame that turns with the sail (viz.spin_frame; the payload turned with it);
* the **histories** up to sample i: the centre of mass's distance from the axis in beam waists and the
  tilt's size (rad), against time, with the verdict (analysis.ride3d.sheet_ride) in the title once it is
  decided.

Drawn by matplotlib's Agg backend (object API, no display); movies through viz.frames.make_movie.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightsail_mbs.analysis.ride3d import sheet_ride
from lightsail_mbs.model import planforms, sheet
from lightsail_mbs.result import Result
from lightsail_mbs.viz.frames import _prepare, frame_indices, parse_size, write_frames
from lightsail_mbs.viz.sheet import frame_image
from lightsail_mbs.viz.spin_frame import frame_rotation, in_frame, require_sheet_run

MARKED, PLAIN = "#d62728", "#9ecae1"  # the marked sector's tiles, the others
SECTOR = np.pi / 3  # the marked sector's opening angle (rad), about the +x axis


def tile_polygons(result: Result, index: int) -> list[np.ndarray]:
    """Each tile's outline (V, 3) at sample `index`: c_k + R_k (o − o_k, 0), o the flat outline and o_k the
    tile's flat centre."""
    mesh = planforms.mesh_of(result.params)
    rotations = sheet.rotation_xyz(result.tile_angles[index])
    polygons = []
    for k, outline in enumerate(mesh.outlines):
        local = np.column_stack([outline - mesh.centres[k], np.zeros(len(outline))])
        polygons.append(result.tile_centres[index, k] + local @ rotations[k].T)
    return polygons


def marked_tiles(result: Result) -> np.ndarray:
    """(N,) True for the tiles whose flat centre lies in the marked sector (polar angle within ±SECTOR/2 of
    the +x axis through the sail's middle; the middle tile is not marked)."""
    p = result.params
    centres = planforms.mesh_of(p).centres
    x, y = centres[:, 0] - 0.5 * p.length, centres[:, 1] - 0.5 * p.width
    return (np.abs(np.arctan2(y, x)) < 0.5 * SECTOR) & (np.hypot(x, y) > 1e-9 * p.length)


def payload_path(result: Result, frame: str) -> np.ndarray | None:
    """(T, 3) the payload's centre in `frame`, or None without a payload."""
    where = result.info.get("payload_centre")
    if where is None:
        return None
    Q, centre = frame_rotation(result, frame)
    return centre + np.einsum("tij,tj->ti", Q, np.asarray(where, float) - centre)


def draw_ride_frame(shown: Result, index: int, ride, payload, size=(900, 420), frame: str = "inertial"):
    """The figure of sample `index` of a run already in its frame (`shown`), its SheetRide and payload path."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    p = shown.params
    width, height = parse_size(size)
    fig = Figure(figsize=(width / 100, height / 100), dpi=100)
    FigureCanvasAgg(fig)
    ax = fig.add_axes((0.0, 0.0, 0.5, 0.92), projection="3d")
    marked = marked_tiles(shown)
    faces = Poly3DCollection(
        tile_polygons(shown, index), facecolors=np.where(marked, MARKED, PLAIN), edgecolors="k", linewidths=0.3
    )
    ax.add_collection3d(faces)
    xc, yc, w = p.beam_centre, p.sheet_beam_centre_y, p.beam_waist
    z_sail = float(shown.tile_centres[index, :, 2].mean())
    points = [shown.tile_centres[index]]
    if payload is not None:
        hub = shown.tile_centres[index].mean(axis=0)
        ax.plot(*np.column_stack([hub, payload[index]]), color="k", lw=1.0)
        ax.scatter(*payload[index], color="k", s=25)
        points.append(payload[index][None])
    circle = np.linspace(0, 2 * np.pi, 73)
    ax.plot(xc + w * np.cos(circle), yc + w * np.sin(circle), np.full(circle.size, z_sail), color="orange", lw=1.0)
    every = np.concatenate(points)
    z_lo, z_hi = min(every[:, 2].min(), z_sail) - 0.1, every[:, 2].max() + 0.1
    ax.plot([xc, xc], [yc, yc], [z_lo, z_hi], color="orange", ls="--", lw=1.0)
    reach = max(1.2 * w, 0.6 * max(p.length, p.width))
    ax.set_xlim(xc - reach, xc + reach)
    ax.set_ylim(yc - reach, yc + reach)
    ax.set_zlim(z_lo, z_hi)
    ax.set_box_aspect((1.0, 1.0, 1.0))  # z drawn shorter than x and y when the stem is long
    ax.view_init(elev=20, azim=-60)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    ax.text2D(0.0, 0.97, f"{frame} frame; beam axis and waist orange", transform=ax.transAxes, fontsize=8)
    h = fig.add_axes((0.6, 0.14, 0.36, 0.68))
    t = ride.time
    h.plot(t[: index + 1], ride.distance[: index + 1] / w, color="C0", label="distance from axis / w")
    h.plot(t[: index + 1], np.hypot(*ride.tilt[: index + 1].T), color="C1", label="tilt (rad)")
    h.set_xlim(t[0], t[-1])
    top = max(1.05, float(ride.distance.max() / w), float(np.hypot(*ride.tilt.T).max()))
    h.set_ylim(0, 1.1 * top)
    h.axhline(1.0, color="0.6", lw=0.8, ls=":")
    h.set_xlabel("t (s)")
    h.legend(loc="upper left", fontsize=8)
    decided = ride.decided_at is not None and t[index] >= ride.decided_at
    verdict = f", {ride.verdict} at {ride.decided_at:.2f} s" if decided else ""
    fig.suptitle(
        f"t = {t[index]:.2f} s, spin {ride.spin_rate[index]:.1f} rad/s, d = {p.payload_stem:.2f} m{verdict}",
        fontsize=11,
    )
    return fig


def render_ride_frames(
    result: Result,
    out_dir,
    frames: int | None = None,
    size=(900, 420),
    frame: str = "inertial",
    crumple: float = 0.05,
    progress=None,
) -> list[Path]:
    """Write out_dir/frame_0000.png, ... of a sheet run (module docstring) at samples picked by
    viz.frames.frame_indices; returns the paths. frame: "inertial" or "rotating"; crumple: the
    verdict's threshold (m)."""
    require_sheet_run(result, "a ride movie")
    ride = sheet_ride(result, crumple=crumple)
    shown = in_frame(result, frame)
    payload = payload_path(result, frame)
    picks = frame_indices(result.time, frames)
    out = _prepare(out_dir)
    images = (frame_image(draw_ride_frame(shown, int(i), ride, payload, size, frame)) for i in picks)
    return write_frames(out, images, len(picks), progress)
