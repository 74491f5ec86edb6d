"""Per-frame cost of both renderers: 200 frames at 800×400 of a synthetic growing sine.

Usage: python scenarios/render_benchmark.py [--frames 200] [--size 800x400] [--repeats 3]
Prints the wall time of render_frames (scene building, drawing, PNG writing) per renderer; the
minimum over the repeats is the figure to quote (the machine is shared).
"""

from __future__ import annotations

import argparse
import tempfile
import time

import numpy as np

from lightsail_mbs import Result, RunSettings, SailParameters
from lightsail_mbs.model.shapes import hinge_points
from lightsail_mbs.viz.frames import render_frames


def growing_sine(n: int = 30, steps: int = 1001, rate: float = 1.2, t_final: float = 1.0) -> Result:
    """Slices on w(x, t) = a₀ e^{rate·t} sin(2πνx/L), exact chords (shapes.hinge_points), at rest."""
    p = SailParameters(model="torsion", n=n)
    time_ = np.linspace(0.0, t_final, steps)
    x, y, theta = (np.empty((steps, n)) for _ in range(3))
    for k, t in enumerate(time_):
        amplitude = p.defect_amplitude * np.exp(rate * t)
        pts = hinge_points(p, lambda s, a=amplitude: a * np.sin(2 * np.pi * p.defect_mode * s / p.length))
        d = np.diff(pts, axis=0)
        theta[k] = np.arctan2(d[:, 1], d[:, 0])
        x[k] = pts[:-1, 0] + 0.5 * p.slice_length * np.cos(theta[k])
        y[k] = pts[:-1, 1] + 0.5 * p.slice_length * np.sin(theta[k])
    zero = np.zeros_like(x)
    return Result.from_trajectory(
        p, "synthetic", time_, x, y, theta, zero, zero, zero, settings=RunSettings(t_final=t_final)
    )


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=200)
    ap.add_argument("--size", default="800x400")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    result = growing_sine()
    for renderer in ("matplotlib", "exudyn"):
        walls = []
        for _ in range(args.repeats):
            with tempfile.TemporaryDirectory() as out:
                start = time.perf_counter()
                render_frames(result, out, frames=args.frames, size=args.size, renderer=renderer)
                walls.append(time.perf_counter() - start)
        best = min(walls)
        print(
            f"{renderer:10s} {args.frames} frames at {args.size}: {best:.2f} s "
            f"({1000 * best / args.frames:.1f} ms/frame; all runs {', '.join(f'{w:.2f}' for w in walls)} s)"
        )


if __name__ == "__main__":
    main()
