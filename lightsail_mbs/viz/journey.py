"""The journey's figure: speed, temperature and margin along the whole acceleration (studies/journey.py)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightsail_mbs.viz.plots import new_figure, save_figure


def journey_figure(report: dict, path, title: str = "") -> Path:
    """Three panels against lab time: β and the sail-frame acceleration; the maximum and mean temperature with
    the limit temperature; the margin to the paper's criterion (log scale, 1 marked). The verdict as the title."""
    rows = report["snapshots"]
    t = np.array([r["t"] for r in rows])
    fig, axes = new_figure(3, 1, size=(7.0, 7.5))
    ax = axes[0, 0]
    ax.plot(t, [r["beta"] for r in rows], "o-", color="tab:blue", ms=3)
    ax.set_ylabel("β")
    twin = ax.twinx()
    twin.plot(t, [r["acceleration"] for r in rows], "s--", color="tab:orange", ms=3)
    twin.set_ylabel("g₀ (m/s², sail frame)", color="tab:orange")
    ax = axes[1, 0]
    ax.plot(t, [r["temperature_max"] for r in rows], "o-", ms=3, label="T max")
    ax.plot(t, [r["temperature_mean"] for r in rows], "--", label="T mean")
    ax.axhline(report["film"]["limit_temperature"], color="tab:red", lw=1, label="limit")
    ax.set_ylabel("T (K)")
    ax.legend(fontsize=8)
    ax = axes[2, 0]
    margin = np.array([r["margin"] for r in rows])
    shown = np.where(margin > 0, margin, np.nan)
    if np.any(np.isfinite(shown)):
        ax.semilogy(t, shown, "o-", ms=3)
    ax.axhline(1.0, color="tab:red", lw=1)
    ax.set_ylabel("margin (stiffness / critical)")
    ax.set_xlabel("t (s, lab frame)")
    for a in axes[:, 0]:
        a.grid(alpha=0.3)
    fig.suptitle(f"{title}: {report['verdict']['text']}" if title else report["verdict"]["text"], fontsize=10)
    return save_figure(fig, path)
