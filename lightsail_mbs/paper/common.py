"""What the figure pipelines share: the angle-history figures of a stable and a soft case (Figs 6–8,
10–11) and the bisected stability maps (Figs 9, 12), each run through the resumable sweep store.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lightsail_mbs.studies.sweep import run_cases
from lightsail_mbs.studies.tables import print_table, series_csv, write_csv
from lightsail_mbs.viz.plots import MICRO, angle_slices, new_figure, plot_angles, plot_map, save_figure


def store_folder(out, store, name: str) -> Path:
    """The sweep store of the pipeline `name`: STORE/<name>, or OUT/store/<name> without a store."""
    return Path(store or Path(out) / "store") / name


def publish(out, name: str, rows: list[dict], title: str, draw) -> dict:
    """A study's rows as OUT/<name>.csv, printed under `title` and drawn by draw(path, rows) into
    OUT/<name>.png; returns {"rows": rows}, a pipeline's answer."""
    out = Path(out)
    write_csv(out / f"{name}.csv", rows)
    print_table(title, rows)
    draw(out / f"{name}.png", rows)
    return {"rows": rows}


def sweep_options(out, name: str, *, workers=None, scheduler=None, store=None, progress=True) -> dict:
    """The sweep keywords of a pipeline's runs (store_dir, workers, scheduler, progress) from the options
    of its run (paper package docstring)."""
    return dict(store_dir=store_folder(out, store, name), workers=workers, scheduler=scheduler, progress=progress)


# ---- the angle-history figures of a stable and a soft case (Figs 6–8, 10–11) ------------------
def angle_history_figures(
    out,
    name: str,
    cases: dict,
    figures: list[tuple[int, str, float | None]],
    describe,
    *,
    settings,
    columns,
    title: str,
    solver="exudyn",
    workers=None,
    scheduler=None,
    store=None,
    progress=True,
) -> list[dict]:
    """Run the labelled cases ({label: SailParameters}) with the same RunSettings, then per (figure
    number, label, t_max) draw θ_i(t) of a few slices into OUT/fig<number>.png. Writes
    OUT/<name>_summary.csv (failure, frequency of the stable runs by frequencies.angle_frequency) and
    OUT/<name>_angles_<label>.csv; returns the rows, each with the columns(params) of its case (a dict: the
    swept parameter against its critical value), and prints them under `title`.
    describe(params) -> the case's title text (e.g. its E and E_cr,max).
    """
    from lightsail_mbs.analysis.frequencies import angle_frequency

    out = Path(out)
    runs = dict(
        zip(
            cases,
            run_cases(
                list(cases.values()),
                store_folder(out, store, name),
                settings,
                solver=solver,
                workers=workers,
                scheduler=scheduler,
                label=name,
                progress=progress,
            ),
        )
    )
    rows = []
    for label, (record, result) in runs.items():
        stable = result is not None and not record.get("failed") and not record["error"]
        rows.append(
            {
                "case": label,
                "failed": record.get("failed"),
                "failure_time_s": record.get("failure_time"),
                "max_amplitude_ratio": record.get("max_amplitude_ratio"),
                "t_end_s": record.get("t_end"),
                "frequency_Hz": angle_frequency(result) if stable else None,
                "error": record["error"] or "",
            }
        )
        if result is not None:
            series_csv(
                out / f"{name}_angles_{label}.csv",
                result.time,
                {f"theta_slice{i + 1}_rad": result.theta[:, i] for i in angle_slices(result.params.n)},
            )
    write_csv(out / f"{name}_summary.csv", rows)
    for number, label, t_max in figures:
        result = runs[label][1]
        if result is None:
            continue
        fig, ax = new_figure(size=(7, 3.6))
        zoom = f", first {t_max * 1e3:g} ms" if t_max else ""
        plot_angles(ax[0, 0], result, t_max=t_max, title=f"Fig. {number}: {describe(result.params)}{zoom}")
        save_figure(fig, out / f"fig{number}.png")
    for row, p in zip(rows, cases.values()):
        row.update(columns(p))
    print_table(title, rows)
    return rows


# ---- stability maps (Figs 9, 12) -------------------------------------------------------------
def stability_map_figure(
    out,
    name: str,
    number: int,
    base,
    thicknesses,
    modes,
    *,
    settings,
    factor=1.5,
    solver="exudyn",
    workers=None,
    scheduler=None,
    store=None,
    progress=True,
    ratio_limit=10.0,
    recheck_all=False,
    **sweep_options,
) -> list[dict]:
    """Bisect and draw a stability map: OUT/<name>.png, <name>_boundaries.csv, <name>_points.csv.

    Every (thickness, mode) boundary is bisected (studies.maps.boundary_map) at settings.t_final; those
    whose boundary/analytic ratio is outside [1/ratio_limit, ratio_limit] (or not bracketed) — all of
    them if recheck_all — are bisected again at 2 × t_final, to show how the boundary moves with the
    run time. Returns the rows (one per thickness and mode, with boundary_2t and ratio_2t where
    rechecked). sweep_options (options, case_function) go to boundary_map.
    """
    from lightsail_mbs.studies.maps import boundary_map

    out = Path(out)
    store = store_folder(out, store, name)
    pairs = [(float(h), float(nu)) for h in thicknesses for nu in modes]
    kwargs = dict(
        store_dir=store,
        solver=solver,
        factor=factor,
        workers=workers,
        scheduler=scheduler,
        progress=progress,
        **sweep_options,
    )
    found = boundary_map(base, pairs, settings=settings, **kwargs)
    odd = [
        (r.thickness, r.mode)
        for r in found
        if recheck_all or r.ratio is None or not 1.0 / ratio_limit <= r.ratio <= ratio_limit
    ]
    longer = {}
    if odd:
        twice = settings.replace(t_final=2 * settings.t_final)
        longer = {(r.thickness, r.mode): r for r in boundary_map(base, odd, settings=twice, **kwargs)}
    rows = []
    for r in found:
        row = r.as_dict()
        again = longer.get((r.thickness, r.mode))
        row.update(
            boundary_2t=again.boundary if again else None,
            ratio_2t=again.ratio if again else None,
            status_2t=again.status if again else "",
        )
        rows.append(row)
    write_csv(out / f"{name}_boundaries.csv", rows)
    write_csv(
        out / f"{name}_points.csv",
        [
            {"thickness_m": r.thickness, "mode": r.mode, "t_final_s": r.t_final, "value": v, "stable": s}
            for r in [*found, *longer.values()]
            for v, s in r.points
        ],
    )
    _draw_map(out / f"{name}.png", number, base, thicknesses, modes, settings, found, longer)
    return rows


def _draw_map(path, number: int, base, thicknesses, modes, settings, found, longer) -> None:
    """The stability map's figure: each mode's evaluated points, bracket and analytic line, the boundaries
    bisected again at 2 × t_final (`longer`), and a note where a boundary was not bracketed."""
    from lightsail_mbs.studies.maps import SWEPT

    swept, critical = SWEPT[base.model]
    label = {"youngs_modulus": "Young's modulus E (Pa)", "tension": "boundary tension T (N)"}[swept]
    fig, ax = new_figure(size=(9.5, 5))
    h_line = np.logspace(np.log10(min(thicknesses)) - 0.2, np.log10(max(thicknesses)) + 0.2, 50)
    for k, nu in enumerate(modes):
        mine = [r for r in found if r.mode == float(nu)]
        offset = 10 ** (0.04 * (k - (len(modes) - 1) / 2))
        analytic = (h_line, np.array([critical(base.replace(thickness=h, defect_mode=float(nu))) for h in h_line]))
        plot_map(
            ax[0, 0],
            [(r.thickness, v, s) for r in mine for v, s in r.points if s is not None],
            [(r.thickness, *sorted((r.stable_value, r.unstable_value))) for r in mine if r.boundary],
            analytic,
            label,
            label=f"ν = {nu:g}: " if len(modes) > 1 else "",
            color=f"C{k}",
            marker_offset=offset,
        )
        again = [longer[(r.thickness, r.mode)] for r in mine if (r.thickness, r.mode) in longer]
        again = [r for r in again if r.boundary]
        if again:
            ax[0, 0].plot(
                [r.thickness * MICRO * offset for r in again],
                [r.boundary for r in again],
                "s--",
                color=f"C{k}",
                mfc="none",
                lw=0.8,
                ms=6,
                label=f"{f'ν = {nu:g}: ' if len(modes) > 1 else ''}boundary at {2 * settings.t_final:g} s",
            )
    values = [critical(base.replace(thickness=h, defect_mode=float(nu))) for h in thicknesses for nu in modes]
    ax[0, 0].set_ylim(min(values) / 1e3, max(values) * 1e3)
    for r in found:
        if r.boundary is None:
            known = [v for v, s in r.points if s is not None]
            note = (
                (
                    f"{r.status} in {r.t_final:g} s:\n{'stable' if r.points[-1][1] else 'failed'} "
                    f"from {min(known):.2g} to {max(known):.2g}"
                )
                if known
                else f"{r.status}:\nno run finished"
            )
            ax[0, 0].annotate(note, (r.thickness * MICRO, min(values) / 1e2), fontsize=7, ha="center")
    ax[0, 0].set_title(
        f"Fig. {number}: {base.model} stability map, {settings.t_final:g} s runs, n = {base.n}, "
        f"analytic: {'E_cr,max (Eq. 8)' if swept == 'youngs_modulus' else 'T_cr,max (Eq. 10)'}",
        fontsize=9,
    )
    handles, labels = ax[0, 0].get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    ax[0, 0].legend(unique.values(), unique.keys(), fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    save_figure(fig, path)
