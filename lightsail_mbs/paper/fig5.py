"""Paper Fig. 5: the rigid sail (no bending, no tension) under I₀ = 100 GW/m², n = 40, a₀ = 1 mm,
modes ν = 1/2 … 5, 10 ms. Modes ν ≥ 1 fail (amplitude doubled) at a trough; ν = 1/2 does not.

Writes fig5.png (shapes at failure, amplitude ratio vs time), fig5_failure_times.csv and
fig5_shapes.csv. Run: lightsail-mbs reproduce --figure 5 --out DIR [--quick].
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightsail_mbs import analysis, paper_case, paper_settings
from lightsail_mbs.paper.common import store_folder
from lightsail_mbs.studies.sweep import run_cases
from lightsail_mbs.studies.tables import print_table, write_csv
from lightsail_mbs.viz.plots import new_figure, plot_shape, save_figure

FIGURES = (5,)
MODES = tuple(0.5 * k for k in range(1, 11))  # ν = 1/2, 1, …, 5
QUICK_MODES = (0.5, 1.0, 1.5, 3.0)


def run(out, *, solver="exudyn", workers=None, scheduler=None, quick=False, store=None, progress=True) -> dict:
    out = Path(out)
    modes = QUICK_MODES if quick else MODES
    params = [paper_case("rigid", defect_mode=nu) for nu in modes]
    runs = run_cases(
        params,
        store_folder(out, store, "fig5"),
        paper_settings("rigid"),
        solver=solver,
        workers=workers,
        scheduler=scheduler,
        label="fig 5",
        progress=progress,
    )
    rows, shapes = [], []
    for nu, (record, result) in zip(modes, runs):
        last = -1
        end = analysis.line_offsets(result.x[last], result.y[last]) if result else np.array([np.nan])
        rows.append(
            {
                "mode": nu,
                "failed": record.get("failed"),
                "failure_time_ms": _ms(record.get("failure_time")),
                "at_trough": analysis.fails_at_trough(result.x[last], result.y[last])
                if result and record.get("failed")
                else None,
                "end_trough_mm": -1e3 * end.min(),
                "end_crest_mm": 1e3 * end.max(),
                "max_amplitude_ratio": record.get("max_amplitude_ratio"),
                "t_end_ms": _ms(record.get("t_end")),
                "error": record["error"] or "",
            }
        )
        if result is not None:
            initial = analysis.line_offsets(result.x[0], result.y[0])
            final = analysis.line_offsets(result.x[last], result.y[last])
            shapes += [
                {
                    "mode": nu,
                    "slice": i + 1,
                    "x_m": result.x[last, i],
                    "offset_initial_m": initial[i],
                    "offset_end_m": final[i],
                }
                for i in range(result.params.n)
            ]
    write_csv(out / "fig5_failure_times.csv", rows)
    write_csv(out / "fig5_shapes.csv", shapes)
    _plot(out / "fig5.png", modes, runs)
    print_table("Fig. 5 — rigid sail, I0 = 1e11 W/m², a0 = 1 mm, 10 ms: failure (amplitude ≥ 2 a0)", rows)
    return {"rows": rows}


def _ms(seconds):
    return None if seconds is None else 1e3 * seconds


def _plot(path, modes, runs) -> None:
    fig, ax = new_figure(2, 2, size=(10, 7))
    by_mode = dict(zip(modes, runs))
    for axis, nu in ((ax[0, 0], 1.5), (ax[0, 1], 0.5)):
        result = by_mode.get(nu, (None, None))[1]
        if result is None:
            continue
        plot_shape(axis, result, 0, "t = 0", color="0.5")
        end = f"failure, t = {result.time[-1] * 1e3:.2f} ms" if result.failed else f"t = {result.time[-1] * 1e3:.0f} ms"
        plot_shape(axis, result, -1, end, color="C3" if result.failed else "C0")
        axis.set_title(f"ν = {nu:g}: {'fails at a trough' if result.failed else 'no failure'}", fontsize=9)
        axis.legend(fontsize=7)
    for nu, (_record, result) in zip(modes, runs):
        if result is None:
            continue
        ratio = result.amplitude / result.amplitude[0]
        ax[1, 0].plot(result.time * 1e3, ratio, lw=0.9, label=f"ν = {nu:g}")
        off = analysis.line_offsets(result.x[-1], result.y[-1])
        scale = np.max(np.abs(off))
        ax[1, 1].plot(result.x[-1], off / scale + 2.5 * nu, lw=0.9)
        ax[1, 1].text(result.params.length * 1.01, 2.5 * nu, f"ν = {nu:g}", fontsize=7, va="center")
    ax[1, 0].axhline(2.0, color="k", ls="--", lw=0.8)
    ax[1, 0].set_xlabel("t (ms)")
    ax[1, 0].set_ylabel("amplitude / a(0)")
    ax[1, 0].legend(fontsize=6, ncol=2)
    ax[1, 1].set_xlabel("x (m)")
    ax[1, 1].set_ylabel("shape at the end (normalised, offset by ν)")
    ax[1, 1].set_yticks([])
    fig.suptitle("Fig. 5: rigid sail, I₀ = 100 GW/m², a₀ = 1 mm, n = 40")
    save_figure(fig, path)
