"""Headless frames and movies of a saved Result.

render_frames(result, out_dir, ...) writes out_dir/frame_0000.png, ... of states sampled evenly
(by count or simulated time); render_comparison does the same for two runs, one panel above the
other with one exaggeration and colour scale; make_movie turns frames into an MP4 (imageio-ffmpeg,
no system ffmpeg) or a GIF (Pillow). What a frame shows is render_scene's job; drawing it is the job
of a renderer: "matplotlib" (Agg) or "exudyn" (Exudyn's software raytracer, no display).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from PIL import Image

from lightsail_mbs.base.validation import ParameterError
from lightsail_mbs.result import Result
from lightsail_mbs.viz.scene import Layout, build_scene, frame_exaggeration, make_style

RENDERERS = ("auto", "matplotlib", "exudyn")
# "auto": the faster of the two for 200 frames at 800×400 (scenarios/render_benchmark.py), then the other
AUTO_ORDER = ("exudyn", "matplotlib")
DEFAULT_FRAMES = 100


def frame_indices(
    time: np.ndarray, frames: int | None = None, every_seconds: float | None = None, failure_time: float | None = None
) -> np.ndarray:
    """Indices of the stored states to draw, increasing and distinct.

    frames=N: the states nearest to N evenly spaced times from the first to the last stored time;
    every_seconds=Δt: nearest to t₀, t₀ + Δt, ...; neither: DEFAULT_FRAMES (or every state if fewer).
    With a failure time, the first state at or after it (the first that shows the failure) replaces its nearest
    pick: the failure moment has a frame, and a run that stopped at failure ends on a frame that shows it.
    """
    time = np.asarray(time, float)
    count = time.size
    if frames is not None and every_seconds is not None:
        raise ParameterError("frames and every_seconds are invalid together: allowed one of them")
    if every_seconds is not None:
        dt = float(every_seconds)
        span = time[-1] - time[0]
        if not (math.isfinite(dt) and dt > 0):
            raise ParameterError(f"every_seconds={every_seconds!r} is invalid: allowed a finite number > 0")
        targets = time[0] + dt * np.arange(int(math.floor(span / dt + 1e-9)) + 1)
    else:
        n = min(DEFAULT_FRAMES, count) if frames is None else frames
        if not (isinstance(n, (int, np.integer)) and 1 <= n <= count):
            raise ParameterError(
                f"frames={frames!r} is invalid: allowed an integer 1 ≤ frames ≤ {count} (the number of stored states)"
            )
        targets = np.linspace(time[0], time[-1], int(n))
    picks = _nearest(time, targets)
    if failure_time is not None:
        after = np.nonzero(time >= failure_time)[0]
        k = int(after[0]) if after.size else count - 1
        if k not in picks:
            picks[np.argmin(np.abs(time[picks] - time[k]))] = k
    picks = np.unique(picks)
    if every_seconds is None and picks.size < targets.size:
        # several targets fell on one state (uneven output): fill up with the unused states nearest the gaps
        spare = np.setdiff1d(np.arange(count), picks)
        extra = spare[np.argsort(np.abs(time[spare][:, None] - targets[None, :]).min(axis=1), kind="stable")]
        picks = np.sort(np.concatenate([picks, extra[: targets.size - picks.size]]))
    return picks


def _nearest(time: np.ndarray, targets: np.ndarray) -> np.ndarray:
    right = np.clip(np.searchsorted(time, targets), 1, time.size - 1) if time.size > 1 else np.zeros(targets.size, int)
    if time.size == 1:
        return right
    left = right - 1
    return np.where(np.abs(time[left] - targets) <= np.abs(time[right] - targets), left, right)


MIN_WIDTH, MIN_HEIGHT, MAX_SIDE = 200, 120, 8192


def parse_size(size) -> tuple[int, int]:
    """(width, height) from a pair or 'WxH': width 200 … 8192, height 120 … 8192 pixels."""
    given = size
    if isinstance(size, str):
        try:
            size = tuple(int(v) for v in size.lower().split("x"))
        except ValueError:
            size = ()
    ok = (
        len(size) == 2
        and all(isinstance(v, (int, np.integer)) for v in size)
        and MIN_WIDTH <= size[0] <= MAX_SIDE
        and MIN_HEIGHT <= size[1] <= MAX_SIDE
    )
    if not ok:
        raise ParameterError(
            f"size={given!r} is invalid: allowed WIDTHxHEIGHT with integers "
            f"{MIN_WIDTH} ≤ WIDTH ≤ {MAX_SIDE} and {MIN_HEIGHT} ≤ HEIGHT ≤ {MAX_SIDE} pixels"
        )
    return int(size[0]), int(size[1])


def open_canvas(renderer: str, width: int, height: int):
    """A canvas with draw(scene) -> RGB array; 'auto' takes the first of AUTO_ORDER that works."""
    if renderer not in RENDERERS:
        raise ParameterError(f"renderer={renderer!r} is invalid: allowed one of {', '.join(RENDERERS)}")
    names = AUTO_ORDER if renderer == "auto" else (renderer,)
    for name in names:
        try:
            if name == "exudyn":
                from lightsail_mbs.viz.raytrace import ExudynCanvas

                return ExudynCanvas(width, height)
            from lightsail_mbs.viz.matplotlib_canvas import MatplotlibCanvas

            return MatplotlibCanvas(width, height)
        except ImportError as exc:
            if renderer != "auto":
                raise
            warnings.warn(f"renderer {name} unavailable ({exc}); trying the next", stacklevel=2)
    raise RuntimeError("no renderer available")


def _write_png(image: np.ndarray, path: Path) -> Path:
    Image.fromarray(image).save(path, compress_level=1)
    return path


@dataclass(frozen=True)
class FrameOptions:
    """How the frames of a chain run are picked and drawn (the keywords of render_frames and
    render_comparison).

    frames, every_seconds: how many frames, or one every Δt of simulated time (frame_indices);
    exaggeration: the factor E on the deflection (None: automatic, render_scene.auto_exaggeration, lowered
    frame by frame after failure where the sail would leave its band: frame_exaggeration);
    renderer: one of RENDERERS; color_by: 'curvature' (Δθ/l), 'moment' (k_T Δθ) or None; color_scale:
    'frame' (each frame its own range, shows where it concentrates) or 'run' (one range, shows growth);
    arrows: radiation load and boundary tension; progress: True for a bar on stderr, or a callable called
    with the number of frames written so far.
    """

    frames: int | None = None
    every_seconds: float | None = None
    exaggeration: float | None = None
    renderer: str = "auto"
    color_by: str | None = "curvature"
    color_scale: str = "frame"
    arrows: bool = True
    progress: object = None


def render_frames(result: Result, out_dir, size=(800, 400), label: str | None = None, **options) -> list[Path]:
    """Write out_dir/frame_0000.png, ... of `result` sampled by frame_indices; returns the paths.
    options: those of FrameOptions."""
    o = FrameOptions(**options)
    width, height = parse_size(size)
    picks = frame_indices(result.time, o.frames, o.every_seconds, result.failure_time)
    layout = Layout(width, height)
    style = make_style([result], [picks], layout, o.exaggeration, o.color_by, o.arrows, o.color_scale)
    out = _prepare(out_dir)
    canvas = open_canvas(o.renderer, width, height)
    images = (canvas.draw(build_scene(result, int(i), style, label)) for i in picks)
    return write_frames(out, images, len(picks), o.progress, canvas.close)


def render_comparison(
    first: Result, second: Result, out_dir, labels=("run 1", "run 2"), size=(800, 800), **options
) -> list[Path]:
    """Frames of two runs at the same simulated times, `first` above `second` (each half the height),
    with one exaggeration per frame for both and one colour scale. A run that ended earlier (e.g. stopped at failure)
    keeps showing its last state. options: those of FrameOptions."""
    o = FrameOptions(**options)
    width, height = parse_size(size)
    panel = Layout(width, height // 2)
    if panel.height < MIN_HEIGHT:
        raise ParameterError(f"size={size!r} is invalid: allowed a height ≥ {2 * MIN_HEIGHT} pixels for two panels")
    longer = first if first.time[-1] >= second.time[-1] else second
    picks = frame_indices(longer.time, o.frames, o.every_seconds)
    times = longer.time[picks]
    runs = (first, second)
    per_run = [np.unique(_nearest(r.time, np.minimum(times, r.time[-1]))) for r in runs]
    style = make_style(runs, per_run, panel, o.exaggeration, o.color_by, o.arrows, o.color_scale)
    out = _prepare(out_dir)
    canvas = open_canvas(o.renderer, width, panel.height)

    def stacked():
        for t in times:
            states = [(r, int(_nearest(r.time, np.array([min(t, r.time[-1])]))[0])) for r in runs]
            e = frame_exaggeration(style, states)  # one factor for both panels
            images = [
                canvas.draw(build_scene(r, i, style, name, exaggeration=e)) for (r, i), name in zip(states, labels)
            ]
            image = np.concatenate(
                [images[0], np.full((height - 2 * panel.height, width, 3), 255, np.uint8), images[1]]
            )
            image[panel.height - 1 : panel.height + 1] = 120  # a grey rule between the panels
            yield image

    return write_frames(out, stacked(), len(times), o.progress, canvas.close)


def write_frames(out: Path, images, count: int, progress, close=None) -> list[Path]:
    """Write the `count` RGB arrays of the iterable `images` as out/frame_0000.png, ... as they come,
    reporting progress (_progress); close(), if given, at the end, also after an error. Returns the paths."""
    report, done = _progress(progress, count)
    paths = []
    try:
        for k, image in enumerate(images):
            paths.append(_write_png(image, out / f"frame_{k:04d}.png"))
            report(k + 1)
    finally:
        if close is not None:
            close()
        done()
    return paths


def _progress(progress, total: int):
    """(report(count), done()) for progress=True (a tqdm bar on stderr), a callable, or None/False."""
    if progress is True:
        import sys

        from tqdm import tqdm

        bar = tqdm(total=total, desc="rendering", unit="frame", file=sys.stderr, mininterval=0.5)
        return (lambda k: bar.update(k - bar.n)), bar.close
    if callable(progress):
        return progress, lambda: None
    return (lambda k: None), (lambda: None)


def _prepare(out_dir) -> Path:
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("frame_[0-9][0-9][0-9][0-9].png"):
        old.unlink()
    return out


def check_fps(fps) -> None:
    """ParameterError unless 0 < fps ≤ 120 (a movie's frame rate)."""
    if not (isinstance(fps, (int, float)) and math.isfinite(fps) and 0 < fps <= 120):
        raise ParameterError(f"fps={fps!r} is invalid: allowed a number 0 < fps ≤ 120")


def make_movie(frames, path, fps: float = 20.0) -> Path:
    """Encode frame images (paths or RGB arrays) into path: .mp4 (H.264 via imageio-ffmpeg) or .gif (Pillow)."""
    path = Path(path)
    check_fps(fps)
    suffix = path.suffix.lower()
    if suffix not in (".mp4", ".gif"):
        raise ParameterError(f"path={str(path)!r} is invalid: allowed a .mp4 or .gif file name")
    frames = list(frames)
    if not frames:
        raise ParameterError("frames=[] is invalid: allowed one or more frames")
    images = (np.asarray(Image.open(f).convert("RGB")) if not isinstance(f, np.ndarray) else f for f in frames)
    path.parent.mkdir(parents=True, exist_ok=True)
    if suffix == ".gif":
        pictures = [Image.fromarray(im) for im in images]
        pictures[0].save(
            path, save_all=True, append_images=pictures[1:], duration=round(1000.0 / fps), loop=0, optimize=False
        )
        return path
    import imageio.v2 as imageio

    with imageio.get_writer(
        path, format="FFMPEG", fps=fps, codec="libx264", quality=7, macro_block_size=1, pixelformat="yuv420p"
    ) as writer:
        for im in images:
            writer.append_data(_even(im))
    return path


def _even(image: np.ndarray) -> np.ndarray:
    """Pad to even width and height (yuv420p) by repeating the last row/column."""
    h, w = image.shape[:2]
    return np.pad(image, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge")
