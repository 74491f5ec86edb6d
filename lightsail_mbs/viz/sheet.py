"""Headless frames and movies of a sheet run: a coloured deflection map and a 3-D view of the tiles.

A frame of sample i shows, side by side,

* the **deflection map**: each tile's offset from the best-fit plane of the tile centres (the quantity
  the failure rule measures, analysis.plane_offsets), in units of the initial amplitude a(0), on a
  diverging colour scale (blue troughs, red crests; one range for the run, or each frame its own); a
  grid as an image, another planform's tiles as their filled outlines (model.sheet_mesh);
* the **3-D view**: the surface through the tile centres in the best-fit plane's frame (a grid's
  quadrilaterals, another planform's Delaunay triangles of the flat centres), the
  out-of-plane offsets multiplied by an exaggeration factor (automatic: the run's largest offset drawn
  at a tenth of the sail's size; printed on the frame), coloured like the map.

The title gives the time and the amplitude ratio; from the failure time on, the frame carries a red
"FAILED" mark. Drawn by matplotlib's Agg backend (object API, no display); movies through
viz.frames.make_movie.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightsail_mbs import analysis
from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.model import planforms
from lightsail_mbs.result import Result
from lightsail_mbs.viz.frames import _prepare, _write_png, frame_indices, parse_size, write_frames

COLOR_SCALES = ("run", "frame")
VIEW_FRACTION = 0.1  # the automatic exaggeration draws the run's largest offset at this fraction of max(L, W)
CMAP = "RdBu_r"


def require_sheet_result(result: Result) -> None:
    if not result.is_sheet:
        raise ParameterError(f"run of model {result.params.model!r} is invalid here: allowed a sheet run")


def plane_frame(centres: np.ndarray):
    """(centroid, e₁, e₂, n) of the best-fit plane of one state's tile centres (N, 3): n the normal of
    analysis.plane_offsets, e₁ the in-plane direction closest to x̂, e₂ = n × e₁."""
    c = centres.mean(axis=0)
    d = centres - c
    _, axes = np.linalg.eigh(d.T @ d)
    n = axes[:, np.argmax(np.abs(axes[2]))]
    n = n if n[2] >= 0 else -n
    e1 = np.array([1.0, 0.0, 0.0]) - n[0] * n
    e1 /= np.linalg.norm(e1)
    return c, e1, np.cross(n, e1), n


def auto_exaggeration(result: Result) -> float:
    """The factor that draws the run's largest out-of-plane offset at VIEW_FRACTION of the sail's size."""
    peak = float(np.max(np.abs(result.deflection()))) if len(result.time) else 0.0
    size = max(result.params.length, result.params.width)
    return VIEW_FRACTION * size / peak if peak > 0 else 1.0


def draw_frame(result: Result, index: int, size=(1000, 450), exaggeration: float | None = None, vmax=None):
    """The figure of sample `index` (module docstring); vmax: the colour range in units of a(0)
    (None: this frame's largest offset)."""
    require_sheet_result(result)
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.colors import Normalize
    from matplotlib.figure import Figure

    p = result.params
    width, height = parse_size(size)
    dpi = 100
    fig = Figure(figsize=(width / dpi, height / dpi), dpi=dpi)
    FigureCanvasAgg(fig)
    a0 = float(result.amplitude[0]) or max(p.length, p.width) * 1e-6
    offsets = analysis.plane_offsets(result.tile_centres[index])
    scaled = offsets / a0
    vmax = float(np.max(np.abs(scaled))) if vmax is None else float(vmax)
    norm = Normalize(-vmax or -1.0, vmax or 1.0)
    ax = fig.add_axes((0.06, 0.12, 0.36, 0.72))
    mesh = planforms.mesh_of(p)
    if mesh.grid is not None:
        image = ax.imshow(
            scaled.reshape(p.ny, p.n),
            origin="lower",
            extent=(0, p.length, 0, p.width),
            cmap=CMAP,
            norm=norm,
            interpolation="nearest",
            aspect="equal",
        )
    else:  # the tiles' outlines, each filled with its offset
        from matplotlib.collections import PolyCollection

        image = PolyCollection(list(mesh.outlines), array=scaled, cmap=CMAP, norm=norm, edgecolors="face")
        ax.add_collection(image)
        ax.set_xlim(0, p.length)
        ax.set_ylim(0, p.width)
        ax.set_aspect("equal")
    fig.colorbar(image, ax=ax, fraction=0.046, pad=0.03, label="offset from best-fit plane / a(0)")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title("deflection map")
    e = auto_exaggeration(result) if exaggeration is None else float(exaggeration)
    c, e1, e2, n = plane_frame(result.tile_centres[index])
    d = result.tile_centres[index] - c
    shape = (p.ny, p.n) if mesh.grid is not None else (1, mesh.count)
    u = (d @ e1).reshape(shape) + 0.5 * p.length
    v = (d @ e2).reshape(shape) + 0.5 * p.width
    w = e * (d @ n).reshape(shape)
    ax3 = fig.add_axes((0.5, 0.02, 0.48, 0.8), projection="3d")
    from matplotlib import colormaps

    if mesh.grid is None:  # the surface through the tile centres, triangulated in the flat sail's plane
        from matplotlib.tri import Triangulation

        triangles = Triangulation(mesh.centres[:, 0], mesh.centres[:, 1]).triangles
        ax3.plot_trisurf(
            u.ravel(), v.ravel(), w.ravel(), triangles=triangles, cmap=CMAP, norm=norm, linewidth=0.2, shade=False
        ).set_array(scaled[triangles].mean(axis=1))
    elif min(shape) > 1:
        quad = 0.25 * (scaled.reshape(shape)[:-1, :-1] + scaled.reshape(shape)[1:, :-1])
        quad += 0.25 * (scaled.reshape(shape)[:-1, 1:] + scaled.reshape(shape)[1:, 1:])
        ax3.plot_surface(
            u,
            v,
            w,
            facecolors=colormaps[CMAP](norm(quad)),
            shade=False,
            rstride=1,
            cstride=1,
            edgecolor=(0, 0, 0, 0.2),
            linewidth=0.3,
        )
    else:  # one row of tiles: a line
        ax3.plot(u.ravel(), v.ravel(), w.ravel(), color="k")
        ax3.scatter(u.ravel(), v.ravel(), w.ravel(), c=colormaps[CMAP](norm(scaled)), s=12)
    ax3.set_xlim(0, p.length)
    ax3.set_ylim(0, p.width)
    reach = 2.0 * VIEW_FRACTION * max(p.length, p.width)
    ax3.set_zlim(-reach, reach)
    ax3.set_box_aspect((p.length, p.width, 0.6 * max(p.length, p.width)))
    ax3.view_init(elev=25, azim=-60)
    ax3.set_xlabel("x (m)")
    ax3.set_ylabel("y (m)")
    ax3.set_zticks([])
    ax3.text2D(0.5, 0.98, f"3-D view, offsets × {e:.3g}", transform=ax3.transAxes, ha="center", va="top")
    ratio = result.amplitude[index] / result.amplitude[0] if result.amplitude[0] > 0 else float("nan")
    name = "sheet" if mesh.grid is not None else f"{p.planform} sheet"
    fig.suptitle(
        f"{result.solver} {name} {p.n}×{p.ny}: t = {result.time[index]:.6g} s, amplitude {ratio:.3f} × a(0)",
        fontsize=11,
    )
    failed = result.failure_time is not None and result.time[index] >= result.failure_time
    if failed:
        fig.text(0.98, 0.95, "FAILED", color="red", fontsize=14, fontweight="bold", ha="right", va="top")
        fig.patch.set_edgecolor("red")
        fig.patch.set_linewidth(4)
    if result.error and index == result.time.size - 1:
        fig.text(0.98, 0.02, f"solver stopped: {result.error}"[:80], color="red", fontsize=9, ha="right")
    return fig


def frame_image(fig) -> np.ndarray:
    """The RGB pixels of a drawn figure."""
    fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba())[..., :3].copy()


def render_sheet_frames(
    result: Result,
    out_dir,
    frames: int | None = None,
    every_seconds: float | None = None,
    size=(1000, 450),
    exaggeration: float | None = None,
    color_scale: str = "run",
    progress=None,
) -> list[Path]:
    """Write out_dir/frame_0000.png, ... of a sheet run sampled by viz.frames.frame_indices (the failure
    moment included); returns the paths. color_scale: "run" (one range: shows growth) or "frame" (each
    frame its own: shows the pattern); exaggeration: None for automatic (one factor for the run)."""
    require_sheet_result(result)
    if color_scale not in COLOR_SCALES:
        raise ParameterError(f"color_scale={color_scale!r} is invalid: allowed one of {', '.join(COLOR_SCALES)}")
    picks = frame_indices(result.time, frames, every_seconds, result.failure_time)
    vmax = None
    if color_scale == "run":
        vmax = float(np.max(np.abs(result.deflection()[picks]))) / (float(result.amplitude[0]) or 1.0)
    e = auto_exaggeration(result) if exaggeration is None else exaggeration
    out = _prepare(out_dir)
    images = (frame_image(draw_frame(result, int(i), size, e, vmax)) for i in picks)
    return write_frames(out, images, len(picks), progress)


def save_frame(result: Result, index: int, path, size=(1000, 450), exaggeration: float | None = None) -> Path:
    """One frame as a PNG file (a still)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return _write_png(frame_image(draw_frame(result, index, size, exaggeration)), path)
