"""The recurring plots, on matplotlib's object API and an Agg canvas (no display, no pyplot state):
slice angles against time, shapes, stability maps, the solver cross-check.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from lightsail_mbs import analysis
from lightsail_mbs.result import Result

MICRO = 1e6  # m → µm


def angle_slices(n: int, count: int = 5) -> list[int]:
    """Indices of `count` slices spread from the first to the last (the paper's 'select elements')."""
    return sorted({int(round(i)) for i in np.linspace(0, n - 1, count)})


def new_figure(rows: int = 1, cols: int = 1, size=(7.0, 4.0)):
    """(figure, axes array) on an Agg canvas."""
    fig = Figure(figsize=size, dpi=110, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(rows, cols, squeeze=False)
    return fig, axes


def save_figure(fig, path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path)
    return path


def plot_angles(ax, result: Result, slices=None, t_max: float | None = None, title: str = "") -> None:
    """θ_i(t) of a few slices (radians) against time, the paper's Figs 6–8, 10–11; failure time marked."""
    slices = angle_slices(result.params.n) if slices is None else slices
    keep = result.time <= (t_max if t_max is not None else np.inf)
    for i in slices:
        ax.plot(result.time[keep], result.theta[keep, i], lw=0.9, label=f"slice {i + 1}")
    ft = result.failure_time
    if ft is not None and (t_max is None or ft <= t_max):
        ax.axvline(ft, color="k", ls="--", lw=0.8, label=f"failure {ft:.3g} s")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("θ (rad)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7, loc="best")


def plot_shape(ax, result: Result, index: int, label: str, **style) -> None:
    """Offsets of the slice centres from their least-squares line (analysis.line_offsets) at one output
    sample, in mm against x."""
    off = analysis.line_offsets(result.x[index], result.y[index])
    ax.plot(result.x[index], off * 1e3, marker=".", ms=3, label=label, **style)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("offset from line (mm)")


def plot_map(
    ax,
    points: list[tuple[float, float, bool]],
    boundary: list[tuple[float, float, float]],
    analytic: tuple[np.ndarray, np.ndarray],
    ylabel: str,
    label: str = "",
    color: str = "C0",
    marker_offset: float = 1.0,
) -> None:
    """A stability map on log-log axes: evaluated (thickness, value, stable) points, the bisected
    boundary (thickness, low, high) as a bracket bar through its geometric mean, the analytic line."""
    for stable in (True, False):
        xs = [h * MICRO * marker_offset for h, v, s in points if s is stable]
        ys = [v for h, v, s in points if s is stable]
        if xs:
            style = dict(marker="o", facecolors="none", edgecolors=color) if stable else dict(marker="x", c=color)
            ax.scatter(xs, ys, s=16, linewidths=1.0, label=f"{label}{'stable' if stable else 'failed'}", **style)
    if boundary:
        h, lo, hi = (np.array(c, float) for c in zip(*boundary))
        mid = np.sqrt(lo * hi)
        ax.errorbar(
            h * MICRO * marker_offset,
            mid,
            yerr=[mid - lo, hi - mid],
            color=color,
            lw=1.2,
            capsize=3,
            label=f"{label}bisected boundary",
        )
    ax.plot(analytic[0] * MICRO, analytic[1], "k-", lw=1.0, label="analytic")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("thickness h (µm)")
    ax.set_ylabel(ylabel)
    ax.grid(True, which="major", lw=0.3)


def crosscheck_figure(exudyn: Result, reduced: Result, ie, ir, title: str, angle_limit: float, path) -> Path:
    """θ of slices 1, n/2, n from both solvers (samples ie of exudyn, ir of reduced, the same times), and
    abs(Δθ) on a log scale with the angle limit, over time."""
    n = reduced.params.n
    t = reduced.time[ir]
    fig, ax = new_figure(2, 1, size=(8, 6))
    top, bottom = ax[0, 0], ax[1, 0]
    bottom.sharex(top)
    for k, colour in zip((0, n // 2, n - 1), ("C0", "C1", "C2")):
        top.plot(t, exudyn.theta[ie, k], color=colour, lw=2.5, alpha=0.45, label=f"θ{k + 1} exudyn")
        top.plot(t, reduced.theta[ir, k], color=colour, lw=1, ls="--", label=f"θ{k + 1} reduced")
        diff = np.abs(exudyn.theta[ie, k] - reduced.theta[ir, k])
        bottom.semilogy(t, np.maximum(diff, 1e-18), color=colour, lw=1, label=f"|Δθ{k + 1}|")
    bottom.axhline(angle_limit, color="k", ls=":", lw=1, label=f"{angle_limit:g} rad")
    top.set_ylabel("θ (rad)")
    top.set_title(title)
    top.legend(fontsize=7, ncol=3)
    bottom.set_ylabel("|θ_exudyn − θ_reduced| (rad)")
    bottom.set_xlabel("t (s)")
    bottom.legend(fontsize=7, ncol=4)
    return save_figure(fig, path)
