"""Shared pieces of the paper-figure scenarios (scenarios/fig*.py): run cases through the sweep engine,
write CSV, print tables, draw the recurring plots (slice angles, shapes, stability maps).

Plots use matplotlib's object API on an Agg canvas (no display, no pyplot global state).
"""
from __future__ import annotations

import argparse
import csv
import math
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from lightsail_mbs import analysis
from lightsail_mbs.result import Result
from lightsail_mbs.studies.sweep import Case, run_sweep

MICRO = 1e6  # m → µm


# ---- running ---------------------------------------------------------------------------------
def run_cases(params_list, store_dir, settings, *, solver: str = "exudyn", workers=None, scheduler=None,
              label: str = "cases", progress: bool = True) -> list[tuple[dict, Result | None]]:
    """Run (or find in the store) every case with its full Result saved; return (record, Result) pairs
    in order. A case whose solver failed comes back with its record and, if any, its partial Result."""
    cases = [Case(p, solver, save_result=True, settings=settings) for p in params_list]
    records = run_sweep(cases, store_dir, workers=workers, scheduler=scheduler, label=label, progress=progress)
    out = []
    for record in records:
        path = record.get("result_path")
        out.append((record, Result.load(Path(store_dir) / path) if path else None))
    return out


def angle_slices(n: int, count: int = 5) -> list[int]:
    """Indices of `count` slices spread from the first to the last (the paper's 'select elements')."""
    return sorted({int(round(i)) for i in np.linspace(0, n - 1, count)})


def scenario_parser(doc: str, quick_help: str) -> argparse.ArgumentParser:
    """Options shared by the scenario scripts beyond the paper: --out (default scenarios/figures of the
    source checkout), --solver (default reduced), --quick (a smoke test, described by quick_help)."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--out", default=str(Path(__file__).resolve().parents[2] / "scenarios" / "figures"))
    parser.add_argument("--solver", choices=("reduced", "exudyn"), default="reduced")
    parser.add_argument("--quick", action="store_true", help=quick_help)
    return parser


# ---- files and tables -----------------------------------------------------------------------
def write_csv(path, rows: list[dict]) -> Path:
    """Rows of dicts (same keys) to a CSV file; returns its path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]) if rows else [])
        writer.writeheader()
        writer.writerows(rows)
    return path


def series_csv(path, time: np.ndarray, columns: dict) -> Path:
    """A time series CSV: column 'time_s' and one column per entry of `columns` (same length)."""
    rows = [dict(time_s=t, **{k: v[i] for k, v in columns.items()}) for i, t in enumerate(time)]
    return write_csv(path, rows)


def fmt(value) -> str:
    """A table cell: 4 significant digits for numbers, '–' for None/nan."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, (int, np.integer)):
        return str(value)
    if isinstance(value, (float, np.floating)):
        return f"{value:.4g}"
    return str(value)


def print_table(title: str, rows: list[dict]) -> None:
    """A Markdown table of the rows (keys as the header) under a title line."""
    print(f"\n{title}")
    if not rows:
        print("(no rows)")
        return
    keys = list(rows[0])
    print("| " + " | ".join(keys) + " |")
    print("|" + "---|" * len(keys))
    for row in rows:
        print("| " + " | ".join(fmt(row[k]) for k in keys) + " |")


# ---- plots ----------------------------------------------------------------------------------
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


def plot_map(ax, points: list[tuple[float, float, bool]], boundary: list[tuple[float, float, float]],
             analytic: tuple[np.ndarray, np.ndarray], ylabel: str, label: str = "", color: str = "C0",
             marker_offset: float = 1.0) -> None:
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
        ax.errorbar(h * MICRO * marker_offset, mid, yerr=[mid - lo, hi - mid], color=color, lw=1.2,
                    capsize=3, label=f"{label}bisected boundary")
    ax.plot(analytic[0] * MICRO, analytic[1], "k-", lw=1.0, label="analytic")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("thickness h (µm)")
    ax.set_ylabel(ylabel)
    ax.grid(True, which="major", lw=0.3)


# ---- the angle-history figures of a stable and a soft case (Figs 6–8, 10–11) ------------------
def angle_history_figures(out, name: str, cases: dict, figures: list[tuple[int, str, float | None]],
                          describe, *, settings, solver="exudyn", workers=None, scheduler=None, store=None,
                          progress=True) -> list[dict]:
    """Run the labelled cases ({label: SailParameters}) with the same RunSettings, then per (figure number, label, t_max) draw
    θ_i(t) of a few slices into OUT/fig<number>.png. Writes OUT/<name>_summary.csv (failure, frequency
    of the stable runs by spectral.angle_frequency) and OUT/<name>_angles_<label>.csv; returns the rows.
    describe(params) -> the case's title text (e.g. its E and E_cr,max).
    """
    from lightsail_mbs.analysis.spectral import angle_frequency
    out = Path(out)
    runs = dict(zip(cases, run_cases(list(cases.values()), Path(store or out / "store") / name, settings, solver=solver,
                                     workers=workers, scheduler=scheduler, label=name, progress=progress)))
    rows = []
    for label, (record, result) in runs.items():
        stable = result is not None and not record.get("failed") and not record["error"]
        rows.append({"case": label, "failed": record.get("failed"), "failure_time_s": record.get("failure_time"),
                     "max_amplitude_ratio": record.get("max_amplitude_ratio"), "t_end_s": record.get("t_end"),
                     "frequency_Hz": angle_frequency(result) if stable else None, "error": record["error"] or ""})
        if result is not None:
            series_csv(out / f"{name}_angles_{label}.csv", result.time,
                       {f"theta_slice{i + 1}_rad": result.theta[:, i] for i in angle_slices(result.params.n)})
    write_csv(out / f"{name}_summary.csv", rows)
    for number, label, t_max in figures:
        result = runs[label][1]
        if result is None:
            continue
        fig, ax = new_figure(size=(7, 3.6))
        zoom = f", first {t_max * 1e3:g} ms" if t_max else ""
        plot_angles(ax[0, 0], result, t_max=t_max, title=f"Fig. {number}: {describe(result.params)}{zoom}")
        save_figure(fig, out / f"fig{number}.png")
    return rows


# ---- stability maps (Figs 9, 12) -------------------------------------------------------------
def stability_map_figure(out, name: str, number: int, base, thicknesses, modes, *, settings, factor=1.5,
                         solver="exudyn",
                         workers=None, scheduler=None, store=None, progress=True, ratio_limit=10.0,
                         recheck_all=False, **sweep_options) -> list[dict]:
    """Bisect and draw a stability map: OUT/<name>.png, <name>_boundaries.csv, <name>_points.csv.

    Every (thickness, mode) boundary is bisected (studies.maps.boundary_map) at settings.t_final; those
    whose boundary/analytic ratio is outside [1/ratio_limit, ratio_limit] (or not bracketed) — all of
    them if recheck_all — are bisected again at 2 × t_final, to show how the boundary moves with the
    run time. Returns the rows (one per thickness and mode, with boundary_2t and ratio_2t where
    rechecked). sweep_options (options, case_function) go to boundary_map.
    """
    from lightsail_mbs.studies.maps import SWEPT, boundary_map
    out = Path(out)
    store = Path(store or out / "store") / name
    pairs = [(float(h), float(nu)) for h in thicknesses for nu in modes]
    kwargs = dict(store_dir=store, solver=solver, factor=factor, workers=workers, scheduler=scheduler,
                  progress=progress, **sweep_options)
    found = boundary_map(base, pairs, settings=settings, **kwargs)
    odd = [(r.thickness, r.mode) for r in found
           if recheck_all or r.ratio is None or not 1.0 / ratio_limit <= r.ratio <= ratio_limit]
    longer = {}
    if odd:
        twice = settings.replace(t_final=2 * settings.t_final)
        longer = {(r.thickness, r.mode): r for r in boundary_map(base, odd, settings=twice, **kwargs)}
    rows = []
    for r in found:
        row = r.as_dict()
        again = longer.get((r.thickness, r.mode))
        row.update(boundary_2t=again.boundary if again else None, ratio_2t=again.ratio if again else None,
                   status_2t=again.status if again else "")
        rows.append(row)
    write_csv(out / f"{name}_boundaries.csv", rows)
    write_csv(out / f"{name}_points.csv",
              [{"thickness_m": r.thickness, "mode": r.mode, "t_final_s": r.t_final, "value": v, "stable": s}
               for r in [*found, *longer.values()] for v, s in r.points])

    swept, critical = SWEPT[base.model]
    label = {"youngs_modulus": "Young's modulus E (Pa)", "tension": "boundary tension T (N)"}[swept]
    fig, ax = new_figure(size=(9.5, 5))
    h_line = np.logspace(np.log10(min(thicknesses)) - 0.2, np.log10(max(thicknesses)) + 0.2, 50)
    for k, nu in enumerate(modes):
        mine = [r for r in found if r.mode == float(nu)]
        offset = 10 ** (0.04 * (k - (len(modes) - 1) / 2))
        analytic = (h_line, np.array([critical(base.replace(thickness=h, defect_mode=float(nu))) for h in h_line]))
        plot_map(ax[0, 0], [(r.thickness, v, s) for r in mine for v, s in r.points if s is not None],
                 [(r.thickness, *sorted((r.stable_value, r.unstable_value))) for r in mine if r.boundary],
                 analytic, label, label=f"ν = {nu:g}: " if len(modes) > 1 else "", color=f"C{k}",
                 marker_offset=offset)
        again = [longer[(r.thickness, r.mode)] for r in mine if (r.thickness, r.mode) in longer]
        again = [r for r in again if r.boundary]
        if again:
            ax[0, 0].plot([r.thickness * MICRO * offset for r in again], [r.boundary for r in again], "s--",
                          color=f"C{k}", mfc="none", lw=0.8, ms=6,
                          label=f"{f'ν = {nu:g}: ' if len(modes) > 1 else ''}boundary at {2 * settings.t_final:g} s")
    values = [critical(base.replace(thickness=h, defect_mode=float(nu))) for h in thicknesses for nu in modes]
    ax[0, 0].set_ylim(min(values) / 1e3, max(values) * 1e3)
    for r in found:
        if r.boundary is None:
            known = [v for v, s in r.points if s is not None]
            note = (f"{r.status} in {r.t_final:g} s:\n{'stable' if r.points[-1][1] else 'failed'} "
                    f"from {min(known):.2g} to {max(known):.2g}") if known else f"{r.status}:\nno run finished"
            ax[0, 0].annotate(note, (r.thickness * MICRO, min(values) / 1e2), fontsize=7, ha="center")
    ax[0, 0].set_title(f"Fig. {number}: {base.model} stability map, {settings.t_final:g} s runs, n = {base.n}, "
                       f"analytic: {'E_cr,max (Eq. 8)' if swept == 'youngs_modulus' else 'T_cr,max (Eq. 10)'}",
                       fontsize=9)
    handles, labels = ax[0, 0].get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    ax[0, 0].legend(unique.values(), unique.keys(), fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    save_figure(fig, out / f"{name}.png")
    return rows
