"""Paper Figs 18–23 (Appendix C): trends of the TnT sail (k_T = 0, inextensible slices as in fig10_11.py,
I₀ = 0.1 GW/m², a₀ = 0.01 mm, n = 30, 6 s runs).

Stable regime, T = 3.34e-3 N ≫ T_cr,max = 3.34e-6 N (frequency of θ by spectral.angle_frequency):
  Fig. 18 frequency vs tension (h = 1 µm, ν = 3/2); Fig. 19 frequency vs thickness (ν = 3/2);
  Fig. 20 angle oscillations vs mode (h = 1 µm).

Unstable regime, T ≪ T_cr,max:
  Fig. 21 failure time vs tension (h = 1 µm, ν = 3/2); Fig. 22 vs mode (T = 3.34e-8 N, h = 1 µm);
  Fig. 23 vs thickness (T = 3.34e-8 N, ν = 3/2).

Each figure: left, the time series (θ of one slice, or amplitude / a₀); right, the measured number
against the varied parameter, with its log-log slope. Writes fig18.png … fig23.png,
fig18_23_runs.csv (one row per run and figure), fig18_23_series.csv (the plotted time series) and
fig18_23_trends.csv (the trend numbers). Run: lightsail-mbs reproduce --figure 18 --out DIR [--quick].
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightsail_mbs import RunSettings, paper_case
from lightsail_mbs.analysis.frequencies import angle_frequency
from lightsail_mbs.paper.common import store_folder
from lightsail_mbs.studies.sweep import run_cases
from lightsail_mbs.studies.tables import print_table, write_csv
from lightsail_mbs.viz.plots import new_figure, save_figure

FIGURES = (18, 19, 20, 21, 22, 23)
T_STABLE, T_SOFT = 3.34e-3, 3.34e-8  # N
H, NU = 1e-6, 1.5
# figure -> (varied field, its values, fixed fields, regime)
STUDIES = {
    18: ("tension", [3.34e-5, 3.34e-4, 3.34e-3, 3.34e-2], dict(thickness=H, defect_mode=NU), "stable"),
    19: ("thickness", [1e-8, 1e-7, 1e-6, 1e-5], dict(tension=T_STABLE, defect_mode=NU), "stable"),
    20: ("mode", [1.0, 1.5, 2.0], dict(tension=T_STABLE, thickness=H), "stable"),
    21: ("tension", [3.34e-10, 3.34e-9, 3.34e-8, 3.34e-7], dict(thickness=H, defect_mode=NU), "unstable"),
    22: ("mode", [1.0, 1.5, 2.0], dict(tension=T_SOFT, thickness=H), "unstable"),
    23: ("thickness", [1e-8, 1e-7, 1e-6, 1e-5], dict(tension=T_SOFT, defect_mode=NU), "unstable"),
}
STABLE_WINDOW = 2.0  # s of the stable time series shown (all of it is in the CSV)
UNIT = {"tension": ("T", "N", 1.0), "thickness": ("h", "µm", 1e6), "mode": ("ν", "", 1.0)}
FIELD = {"mode": "defect_mode"}  # varied name (CSV, plots) -> SailParameters field


def run(out, *, solver="exudyn", workers=None, scheduler=None, quick=False, store=None, progress=True) -> dict:
    out = Path(out)
    base = paper_case("tnt-stable", axial_springs=False)
    base = base.replace(n=10) if quick else base
    settings = RunSettings(t_final=3.0 if quick else 6.0)
    params = {
        (fig, v): base.replace(**fixed, **{FIELD.get(field, field): v})
        for fig, (field, values, fixed, _) in STUDIES.items()
        for v in values
    }
    done = dict(
        zip(
            params,
            run_cases(
                list(params.values()),
                store_folder(out, store, "fig18_23"),
                settings,
                solver=solver,
                workers=workers,
                scheduler=scheduler,
                label="figs 18-23",
                progress=progress,
            ),
        )
    )
    rows, series, trends = [], [], []
    for fig, (field, values, _fixed, regime) in STUDIES.items():
        measured = []
        for v in values:
            record, result = done[(fig, v)]
            ok = result is not None and not record["error"]
            freq = angle_frequency(result) if ok and regime == "stable" and not record.get("failed") else None
            measured.append(freq if regime == "stable" else record.get("failure_time"))
            rows.append(
                {
                    "figure": fig,
                    "regime": regime,
                    "tension_N": params[(fig, v)].tension,
                    "thickness_m": params[(fig, v)].thickness,
                    "mode": params[(fig, v)].defect_mode,
                    "failed": record.get("failed"),
                    "failure_time_s": record.get("failure_time"),
                    "frequency_Hz": freq,
                    "max_amplitude_ratio": record.get("max_amplitude_ratio"),
                    "t_end_s": record.get("t_end"),
                    "error": record["error"] or "",
                }
            )
            if result is not None:
                signal = _signal(result, regime)
                series += [
                    {"figure": fig, "varied": field, "value_of_varied": v, "time_s": t, "signal": s}
                    for t, s in zip(result.time, signal)
                ]
        trends.append(_trend(fig, field, values, measured, regime))
        _plot(
            out / f"fig{fig}.png", fig, field, values, [done[(fig, v)][1] for v in values], measured, regime, trends[-1]
        )
    write_csv(out / "fig18_23_runs.csv", rows)
    write_csv(out / "fig18_23_series.csv", series)
    write_csv(out / "fig18_23_trends.csv", trends)
    print_table(
        f"Figs 18–23 — TnT trends ({settings.t_final:g} s runs, n = {base.n})",
        [
            {
                k: r[k]
                for k in (
                    "figure",
                    "regime",
                    "tension_N",
                    "thickness_m",
                    "mode",
                    "failed",
                    "failure_time_s",
                    "frequency_Hz",
                    "error",
                )
            }
            for r in rows
        ],
    )
    print_table("Figs 18–23 — trend numbers (slope: d ln y / d ln x over the finite values)", trends)
    return {"rows": rows, "trends": {t["figure"]: t for t in trends}}


def _signal(result, regime):
    """θ of the slice at a third of the sail (stable) or amplitude / a(0) (unstable)."""
    if regime == "stable":
        return result.theta[:, result.params.n // 3]
    return result.amplitude / result.amplitude[0]


def _trend(fig, field, values, measured, regime) -> dict:
    """The measured number per value, its max/min spread and log-log slope over the finite values."""
    x = np.array(values, float)
    y = np.array([np.nan if m is None else m for m in measured], float)
    finite = np.isfinite(y) & (y > 0)
    slope = float(np.polyfit(np.log(x[finite]), np.log(y[finite]), 1)[0]) if finite.sum() >= 2 else None
    spread = float(y[finite].max() / y[finite].min()) if finite.sum() >= 2 else None
    steps = np.diff(y[finite])
    direction = (
        ("increasing" if np.all(steps > 0) else "decreasing" if np.all(steps < 0) else "mixed")
        if finite.sum() >= 2
        else ""
    )
    return {
        "figure": fig,
        "varied": field,
        "measured": "frequency_Hz" if regime == "stable" else "failure_time_s",
        "values": " ".join(f"{v:.3g}" for v in values),
        "measured_values": " ".join("–" if not np.isfinite(m) else f"{m:.4g}" for m in y),
        "finite": int(finite.sum()),
        "spread_max_over_min": spread,
        "loglog_slope": slope,
        "direction": direction,
    }


def _plot(path, fig_number, field, values, results, measured, regime, trend) -> None:
    name, unit, scale = UNIT[field]
    fig, ax = new_figure(1, 2, size=(10, 3.8))
    for v, result in zip(values, results):
        if result is not None:
            shown = result.time <= (STABLE_WINDOW if regime == "stable" else np.inf)
            ax[0, 0].plot(
                result.time[shown], _signal(result, regime)[shown], lw=0.8, label=f"{name} = {v * scale:.3g} {unit}"
            )
    if regime == "unstable":
        ax[0, 0].axhline(2.0, color="k", ls="--", lw=0.8)
    ax[0, 0].set_xlabel("t (s)")
    ax[0, 0].set_ylabel("θ of slice n/3 (rad)" if regime == "stable" else "amplitude / a(0)")
    ax[0, 0].legend(fontsize=7)
    x = np.array(values, float) * scale
    y = np.array([np.nan if m is None else m for m in measured], float)
    ax[0, 1].plot(x, y, "o-")
    axis_scale = "linear" if field == "mode" or not np.any(np.isfinite(y)) else "log"
    ax[0, 1].set_xscale(axis_scale)
    ax[0, 1].set_yscale(axis_scale)
    ax[0, 1].set_xlabel(f"{name} ({unit})" if unit else name)
    ax[0, 1].set_ylabel("frequency of θ (Hz)" if regime == "stable" else "failure time (s)")
    slope = trend["loglog_slope"]
    ax[0, 1].set_title("" if slope is None else f"log-log slope {slope:.2f}", fontsize=9)
    fig.suptitle(f"Fig. {fig_number}: TnT, {regime} regime, varying {name}")
    save_figure(fig, path)
