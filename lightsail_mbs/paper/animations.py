"""Animations for the documentation: the soft torsion sail (paper Fig. 7) and the rigid ν = 3/2 sail failing at
its trough (paper Fig. 5), as GIF movies.

Each case is simulated past failure (soft torsion, 3 s: it fails at ≈ 2.1 s; rigid, 10 ms: ≈ 6.8 ms) or
read back from STORE/<case>.npz if that file exists (whatever solver made it), cut where the amplitude
first reaches until_ratio × its initial value, and rendered (viz.frames) into OUT/<case>.gif; the
frames go to STORE/<case>_frames/. STORE defaults to OUT/store/animations.
Quick: n = 10, 12 frames at 300×150 (STORE/<case>_quick.npz and _quick_frames/).
Run: lightsail-mbs reproduce --scenario animations, or python scenarios/animations.py [--cases …]
[--frames N] [--size WxH] [--fps F] [--until-ratio R].
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from lightsail_mbs import Result, paper_case, paper_settings, solve
from lightsail_mbs.paper.common import store_folder
from lightsail_mbs.result import ARRAYS

NAME = "animations"
# movie -> (paper case, changes of its run settings): past failure, then cut at until_ratio
CASES = {
    "soft_torsion": ("torsion-soft", dict(stop_at_failure=False, t_final=3.0)),
    "rigid_trough": ("rigid", dict(stop_at_failure=False)),
}
FRAMES, SIZE, FPS, UNTIL_RATIO = 60, "600x300", 12.0, 3.0
QUICK_FRAMES, QUICK_SIZE = 12, "300x150"


def cut_at_ratio(result: Result, ratio: float) -> Result:
    """The run up to (and including) the first state whose amplitude reaches ratio × the initial one."""
    above = np.nonzero(result.amplitude >= ratio * result.amplitude[0])[0]
    if above.size == 0:
        return result
    end = int(above[0]) + 1
    return dataclasses.replace(result, **{k: getattr(result, k)[:end] for k in ARRAYS})


def simulated(name: str, runs: Path, solver: str, progress: bool = True, quick: bool = False) -> Result:
    """The run of movie `name`: RUNS/<name>.npz (quick: n = 10, <name>_quick.npz) if it exists, else
    solved and saved there."""
    path = Path(runs) / f"{name}_quick.npz" if quick else Path(runs) / f"{name}.npz"
    if path.exists():
        return Result.load(path)
    case, changes = CASES[name]
    params = paper_case(case, **(dict(n=10) if quick else {}))
    result = solve(params, solver, paper_settings(case, **changes), progress=progress, uncertainty=False)
    result.save(path)
    return result


def run(
    out,
    *,
    solver="exudyn",
    workers=None,
    scheduler=None,
    quick=False,
    store=None,
    progress=True,
    cases=None,
    frames: int | None = None,
    size: str | None = None,
    fps: float = FPS,
    until_ratio: float = UNTIL_RATIO,
) -> dict:
    """cases: movie names (default all of CASES); frames, size: default 60 at 600x300 (quick: 12 at
    300x150, n = 10); until_ratio: cut each run at this amplitude ratio. workers and scheduler are not used."""
    from lightsail_mbs.viz.frames import make_movie, render_frames

    out = Path(out)
    runs = store_folder(out, store, NAME)
    runs.mkdir(parents=True, exist_ok=True)
    frames = frames or (QUICK_FRAMES if quick else FRAMES)
    size = size or (QUICK_SIZE if quick else SIZE)
    movies = []
    for name in cases or CASES:
        result = cut_at_ratio(simulated(name, runs, solver, progress, quick), until_ratio)
        stem = f"{name}_quick" if quick else name
        images = render_frames(
            result, runs / f"{stem}_frames", frames=min(frames, result.time.size), size=size, progress=progress
        )
        gif = make_movie(images, out / f"{name}.gif", fps=fps)
        summary = result.summary()
        movies.append(
            dict(
                case=name,
                model=summary["model"],
                failure_time_s=summary["failure_time"],
                frames=len(images),
                gif=str(gif),
                size_kB=gif.stat().st_size / 1e3,
            )
        )
        print(
            f"{name}: {summary['model']}, failure at t = {summary['failure_time']} s; "
            f"{len(images)} frames -> {gif} ({gif.stat().st_size / 1e3:.0f} kB)"
        )
    return {"movies": movies}
