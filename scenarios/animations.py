"""README animations (issue 6 item 4): the soft torsion sail (paper Fig. 7) and the rigid ν = 3/2 sail
failing at its trough (paper Fig. 5), as GIFs.

Usage: python scenarios/animations.py [--out scenarios/figures] [--runs results/animations] [--solver exudyn]
                                      [--frames 60] [--size 600x300] [--fps 12] [--until-ratio 3]

Each case is simulated past failure (or read back from RUNS/<name>.npz if that file exists), cut
where the amplitude first reaches --until-ratio × its initial value, and rendered by
lightsail_mbs.render into OUT/<name>.gif (frames in RUNS/<name>_frames/).
"""
from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

import numpy as np

from lightsail_mbs import Result, paper_case, solve
from lightsail_mbs.viz.frames import make_movie, render_frames
from lightsail_mbs.result import ARRAYS

# past failure (soft torsion fails at ~2.1 s, the rigid sail at ~6.8 ms), then cut at --until-ratio
CASES = {
    "soft_torsion": lambda: paper_case("torsion-soft", stop_at_failure=False, t_final=3.0),
    "rigid_trough": lambda: paper_case("rigid", stop_at_failure=False),
}


def until_ratio(result: Result, ratio: float) -> Result:
    """The run up to (and including) the first state whose amplitude reaches ratio × the initial one."""
    above = np.nonzero(result.amplitude >= ratio * result.amplitude[0])[0]
    if above.size == 0:
        return result
    end = int(above[0]) + 1
    return dataclasses.replace(result, **{k: getattr(result, k)[:end] for k in ARRAYS})


def simulated(name: str, runs: Path, solver: str) -> Result:
    path = runs / f"{name}.npz"
    if path.exists():
        return Result.load(path)
    result = solve(CASES[name](), solver, progress=True)
    result.save(path)
    return result


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="scenarios/figures", help="folder of the GIFs [default scenarios/figures]")
    ap.add_argument("--runs", default="results/animations",
                    help="folder of the runs and frames [default results/animations]")
    ap.add_argument("--solver", default="exudyn", choices=("exudyn", "reduced"))
    ap.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--size", default="600x300")
    ap.add_argument("--fps", type=float, default=12.0)
    ap.add_argument("--until-ratio", type=float, default=3.0, help="cut each run at this amplitude ratio [default 3]")
    args = ap.parse_args(argv)
    runs, out = Path(args.runs), Path(args.out)
    runs.mkdir(parents=True, exist_ok=True)
    for name in args.cases:
        result = until_ratio(simulated(name, runs, args.solver), args.until_ratio)
        frames = render_frames(result, runs / f"{name}_frames", frames=min(args.frames, result.time.size),
                               size=args.size, progress=True)
        gif = make_movie(frames, out / f"{name}.gif", fps=args.fps)
        summary = result.summary()
        print(f"{name}: {summary['model']}, failure at t = {summary['failure_time']} s; "
              f"{len(frames)} frames -> {gif} ({gif.stat().st_size / 1e3:.0f} kB)")


if __name__ == "__main__":
    main()
