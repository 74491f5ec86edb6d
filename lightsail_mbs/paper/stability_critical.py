"""Critical E (torsion) and T (TnT) from short scaled runs, against a₀, the analytic Eqs 8/10 and the
bisected 6 s map boundary; run-length dependence and divergence of neighbouring runs.

* critical_modulus / critical_tension (analysis.finite_amplitude.critical_ratio, runs of 8 t_c) for
  a₀ = 1–100 µm (h = 1 µm, I₀ = 0.1 GW/m², ν = 3/2, n = 30), fitted exponent in a₀ next to the analytic 1;
* the same boundary bisected with 6 s runs of the solver (reduced by default; studies.bisection,
  factor 1.1) at a₀ = 1, 10, 100 µm: 6 s is 1.5, 4.6 and 15 t_c there;
* the ratio against ν, with the lowest free–free bending mode's buckling estimate
  (finite_amplitude.lowest_mode_buckling_ratio) and the one-mode Galerkin model's critical ratio;
* the failure curves τ_f(r) = t_f/t_c up to runs of 120 t_c (late failures above the first-passage
  boundary), and from them the boundary a map with runs of t_final finds, r*(t_final/t_c), at the
  thicknesses of Figs 9 and 12 for 6 s and 12 s (next to the maps' own boundaries when their
  fig9_boundaries.csv / fig12_boundaries.csv are given);
* paired runs: growth of a 1e-9 angle perturbation at r = 2, 10, 30.

The scaled runs integrate the reduced equations (scipy's DOP853) in this process; only the map
bisection goes through the solver and the sweep store (OUT/store/stability_critical/<model>).

Writes stability_critical.png and stability_critical_{amplitude,fits,map,modes,curve,maps_predicted,
divergence}.csv. Quick: a₀ = 1, 10, 100 µm, ν = 1 and 3/2, no map bisection, short failure curves
(8 t_c) and one paired run. Run: lightsail-mbs reproduce --scenario stability_critical, or
python scenarios/stability_critical.py [--fig9 CSV] [--fig12 CSV].
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs.analysis import finite_amplitude as cr
from lightsail_mbs.model import theory
from lightsail_mbs.paper.common import sweep_options
from lightsail_mbs.studies.bisection import BoundaryProblem, bisect_boundaries
from lightsail_mbs.studies.tables import print_table, write_csv
from lightsail_mbs.viz.plots import new_figure, save_figure

NAME = "stability_critical"
BASES = {
    "torsion": SailParameters(model="torsion", n=30, defect_mode=1.5),
    "tnt": SailParameters(model="tnt", n=30, defect_mode=1.5, axial_springs=False, tension=1e-8),
}
MAP_SETTINGS = RunSettings(t_final=6.0)
ANALYTIC = {"torsion": theory.critical_modulus_max, "tnt": theory.critical_tension_max}
SWEPT = {"torsion": "youngs_modulus", "tnt": "tension"}
LABEL = {"torsion": "critical_modulus", "tnt": "critical_tension"}
AMPLITUDES = (1e-6, 3e-6, 1e-5, 3e-5, 1e-4)
MAP_AMPLITUDES = (1e-6, 1e-5, 1e-4)
MODES = (1.0, 1.5, 2.0, 3.0)
CURVE_RATIOS = {
    "torsion": (0.1, 0.3, 0.5, 1, 1.5, 2, 3, 4, 5, 6, 7, 7.5, 8, 9, 10, 12, 15, 20),
    "tnt": (0.1, 0.5, 1, 2, 3, 4, 4.5, 5, 6, 8, 10, 15),
}
QUICK_CURVE_RATIOS = (0.1, 1, 4, 7)
MAP_THICKNESSES = np.logspace(-8, -5, 7)  # Figs 9 and 12
DIVERGENCE_RATIOS = (2, 10, 30)
RUN_TAU = 8.0  # critical ratios: runs of 8 t_c
CURVE_TAU = 120.0  # failure curves: runs of up to 120 t_c
DIVERGENCE_TAU = 60.0


# ---- computation -----------------------------------------------------------------------------
def critical_rows(model: str, amplitudes) -> list[dict]:
    """The critical value from runs of 8 t_c per a₀, with the analytic one and t_c."""
    rows = []
    for a0 in amplitudes:
        p = BASES[model].replace(defect_amplitude=a0)
        found = cr.critical_ratio(p, RUN_TAU, factor=1.05)
        analytic = ANALYTIC[model](p)
        rows.append(
            dict(
                model=model,
                amplitude_m=a0,
                analytic=analytic,
                critical=found.value * analytic,
                ratio=found.value,
                t_c=cr.time_scale(p),
                runs=found.runs,
            )
        )
    return rows


def exponent(rows, key: str = "critical") -> float:
    """The fitted exponent of rows[key] in a₀ (log-log least squares)."""
    return float(np.polyfit(np.log([r["amplitude_m"] for r in rows]), np.log([r[key] for r in rows]), 1)[0])


def fit_row(model: str, rows: list[dict]) -> dict:
    ratios = [r["ratio"] for r in rows]
    return dict(
        model=model,
        name=LABEL[model],
        a0_exponent=exponent(rows),
        analytic_exponent=1.0,
        ratio_mean=np.mean(ratios),
        ratio_spread=np.ptp(ratios) / np.mean(ratios),
    )


def map_rows(
    model: str, amplitudes, store_dir, *, solver="reduced", workers=None, scheduler=None, progress=False
) -> list[dict]:
    """The 6 s boundary (MAP_SETTINGS) bisected with the sweep engine, one boundary per a₀."""
    base = BASES[model]
    name = SWEPT[model]
    problems = {}
    for a0 in amplitudes:
        p = base.replace(defect_amplitude=a0)
        a = ANALYTIC[model](p)
        problems[a0] = BoundaryProblem(lambda v, p=p: p.replace(**{name: float(v)}), a, 30 * a)
    found = bisect_boundaries(
        problems,
        store_dir=store_dir,
        solver=solver,
        settings=MAP_SETTINGS,
        factor=1.1,
        workers=workers,
        scheduler=scheduler,
        progress=progress,
        max_expansions=3,
    )
    rows = []
    for a0, b in found.items():
        p = base.replace(defect_amplitude=a0)
        rows.append(
            dict(
                model=model,
                amplitude_m=a0,
                map_boundary=b.value,
                map_status=b.status,
                map_ratio=None if b.value is None else b.value / ANALYTIC[model](p),
                run_in_t_c=MAP_SETTINGS.t_final / cr.time_scale(p),
            )
        )
    return rows


def attach_critical(maps: list[dict], table: list[dict]) -> None:
    """Add to each map row the critical value of the same model and a₀ and its ratio to the boundary."""
    for m in maps:
        match = [r for r in table if r["model"] == m["model"] and np.isclose(r["amplitude_m"], m["amplitude_m"])]
        m["critical"] = match[0]["critical"] if match else None
        m["critical_over_map"] = (m["critical"] / m["map_boundary"]) if match and m["map_boundary"] else None


def mode_rows(modes) -> list[dict]:
    """The critical ratio (8 t_c runs) against ν, torsion and TnT, with the buckling estimate."""
    rows = []
    for nu in modes:
        p = BASES["torsion"].replace(defect_mode=nu)
        found = cr.critical_ratio(p, RUN_TAU, factor=1.05)
        rows.append(
            dict(
                mode=nu,
                ratio=found.value,
                buckling_estimate=cr.lowest_mode_buckling_ratio(p),
                tnt_ratio=cr.critical_ratio(BASES["tnt"].replace(defect_mode=nu), RUN_TAU, factor=1.05).value,
            )
        )
    return rows


def curve_rows(model: str, ratios, tau_final: float) -> list[dict]:
    """The failure curve τ_f(r) (None: no failure within tau_final)."""
    return [dict(model=model, ratio=r, tau_f=cr.failure_tau(cr.with_ratio(BASES[model], r), tau_final)) for r in ratios]


def read_map(path) -> dict:
    """{thickness (m, rounded): (ratio, ratio_2t)} of the ν = 3/2 rows of a fig9/fig12_boundaries.csv."""
    mapped = {}
    with open(path) as handle:
        for row in csv.DictReader(handle):
            if float(row["mode"]) == 1.5:
                mapped[round(float(row["thickness_m"]), 12)] = (row["ratio"], row["ratio_2t"])
    return mapped


def map_prediction(model: str, curve: list[dict], map_csv=None) -> list[dict]:
    """r*(t_final/t_c) at the thicknesses of Figs 9/12 (ν = 3/2, a₀ = 10 µm, I₀ = 0.1 GW/m²) for 6 s and 12 s
    runs; with a map's bisected ratios (columns ratio, ratio_2t of fig9/fig12_boundaries.csv, ν = 3/2 rows)."""
    ratios, taus = [c["ratio"] for c in curve], [c["tau_f"] for c in curve]
    mapped = read_map(map_csv) if map_csv else {}
    rows = []
    for h in MAP_THICKNESSES:
        tc = cr.time_scale(BASES[model].replace(thickness=float(h)))
        row = dict(model=model, thickness_um=h * 1e6, t_c=tc)
        for label, t in (("6s", 6.0), ("12s", 12.0)):
            row[f"tau_run_{label}"] = t / tc
            row[f"predicted_{label}"] = cr.boundary_for_run(ratios, taus, t / tc)
        if mapped:
            got = mapped.get(round(float(h), 12), ("", ""))
            row["map_6s"], row["map_12s"] = (float(v) if v else None for v in got)
        rows.append(row)
    return rows


def divergence_rows(ratios, tau_final: float) -> tuple[dict, list[dict]]:
    """Paired runs per ratio: ({ratio: (τ, growth)}, rows of the end τ, end growth and fitted rate per t_c
    over τ > 1)."""
    divergence = {r: cr.divergence(cr.with_ratio(BASES["torsion"], r), tau_final, samples_per_tau=5) for r in ratios}
    rates = [
        dict(
            ratio=r,
            tau_end=float(t[-1]),
            growth=float(s[-1]),
            rate_per_t_c=float(np.polyfit(t[t > 1], np.log(s[t > 1]), 1)[0]) if (t > 1).sum() > 2 else None,
        )
        for r, (t, s) in divergence.items()
    ]
    return divergence, rates


def compute(
    *,
    quick=False,
    solver="reduced",
    store_dir,
    workers=None,
    scheduler=None,
    progress=False,
    map_csvs: dict | None = None,
) -> dict:
    """Every table of the study (and the divergence curves for the figure)."""
    amps = AMPLITUDES[::2] if quick else AMPLITUDES
    table, fits, maps = [], [], []
    for model in BASES:
        rows = critical_rows(model, amps)
        table += rows
        fits.append(fit_row(model, rows))
        if not quick:
            maps += map_rows(
                model,
                MAP_AMPLITUDES,
                Path(store_dir) / model,
                solver=solver,
                workers=workers,
                scheduler=scheduler,
                progress=progress,
            )
    attach_critical(maps, table)
    modes = mode_rows(MODES[:2] if quick else MODES)
    one_mode = cr.one_mode_model(BASES["torsion"]).critical_ratio()
    curves, predicted = {}, []
    for model in BASES:
        curves[model] = curve_rows(
            model, QUICK_CURVE_RATIOS if quick else CURVE_RATIOS[model], RUN_TAU if quick else CURVE_TAU
        )
        predicted += map_prediction(model, curves[model], (map_csvs or {}).get(model))
    divergence, rates = divergence_rows(
        DIVERGENCE_RATIOS[:1] if quick else DIVERGENCE_RATIOS, RUN_TAU if quick else DIVERGENCE_TAU
    )
    return {
        "table": table,
        "fits": fits,
        "maps": maps,
        "modes": modes,
        "curve": curves["torsion"] + curves["tnt"],
        "predicted_maps": predicted,
        "rates": rates,
        "one_mode_ratio": one_mode,
        "divergence": divergence,
    }


# ---- pipeline --------------------------------------------------------------------------------
def run(out, *, solver="reduced", quick=False, fig9=None, fig12=None, **options) -> dict:
    """fig9, fig12: fig9_boundaries.csv / fig12_boundaries.csv of `lightsail-mbs reproduce --figure 9/12`,
    whose boundaries are set next to the predicted ones (columns map_6s, map_12s); options: workers,
    scheduler, store, progress (paper package docstring)."""
    out = Path(out)
    map_csvs = {"torsion": fig9, "tnt": fig12}
    found = compute(quick=quick, solver=solver, map_csvs=map_csvs, **sweep_options(out, NAME, **options))
    write_csv(out / "stability_critical_amplitude.csv", found["table"])
    write_csv(out / "stability_critical_fits.csv", found["fits"])
    if found["maps"]:
        write_csv(out / "stability_critical_map.csv", found["maps"])
    write_csv(out / "stability_critical_modes.csv", found["modes"])
    write_csv(out / "stability_critical_curve.csv", found["curve"])
    write_csv(out / "stability_critical_maps_predicted.csv", found["predicted_maps"])
    write_csv(out / "stability_critical_divergence.csv", found["rates"])
    print_table(
        "Critical value from 8 t_c runs against a0 (h = 1 um, I0 = 0.1 GW/m2, nu = 3/2, n = 30)", found["table"]
    )
    print_table("Fitted exponent in a0 (analytic 1) and ratio to E_cr,max / T_cr,max", found["fits"])
    if found["maps"]:
        print_table(f"Against the bisected 6 s boundary ({solver} solver, factor 1.1)", found["maps"])
    print_table(
        f"Ratio against the mode (one-mode Galerkin model of the sine: {found['one_mode_ratio']:.3g})", found["modes"]
    )
    print_table("Failure curves tau_f(r) = t_f/t_c (runs up to 120 t_c)", found["curve"])
    print_table(
        "Fig. 9 (E/E_cr,max) and Fig. 12 (T/T_cr,max, nu = 3/2) boundaries predicted from tau_f(r), "
        "runs of 6 s and 12 s",
        found["predicted_maps"],
    )
    print_table("Paired runs: growth of a 1e-9 angle perturbation", found["rates"])
    plot(out / "stability_critical.png", found["table"], found["maps"], found["curve"], found["divergence"])
    return found


def plot(path, table, maps, curve, divergence) -> Path:
    """Top: critical E and T against a₀ (runs, analytic, bisected boundary); bottom left: the failure
    curves; bottom right: the paired runs' separation."""
    fig, axes = new_figure(2, 2, size=(10.0, 7.5))
    for ax, model, unit in ((axes[0, 0], "torsion", "E (Pa)"), (axes[0, 1], "tnt", "T (N)")):
        rows = [r for r in table if r["model"] == model]
        a = np.array([r["amplitude_m"] for r in rows])
        ax.loglog(a, [r["critical"] for r in rows], "o-", label=f"{LABEL[model]} (8 t_c runs)")
        ax.loglog(a, [r["analytic"] for r in rows], "k--", label="Eq. 8" if model == "torsion" else "Eq. 10")
        m = [r for r in maps if r["model"] == model and r["map_boundary"]]
        if m:
            ax.loglog(
                [r["amplitude_m"] for r in m],
                [r["map_boundary"] for r in m],
                "s",
                mfc="none",
                ms=9,
                label="bisected 6 s boundary",
            )
        ax.set_xlabel("defect amplitude a₀ (m)")
        ax.set_ylabel(unit)
        ax.set_title(f"{model}: h = 1 µm, I₀ = 0.1 GW/m², ν = 3/2", fontsize=9)
        ax.legend(fontsize=8)
    ax = axes[1, 0]
    if curve:
        for model, marker in (("torsion", "o-"), ("tnt", "s-")):
            pts = [(r["ratio"], r["tau_f"]) for r in curve if r["model"] == model and r["tau_f"] is not None]
            ax.loglog(*zip(*pts), marker, label=f"{model}: τ_f (runs up to 120 t_c)")
        for h, ls in ((1e-8, ":"), (1e-6, "--"), (1e-5, "-.")):
            tau = 6.0 / cr.time_scale(BASES["torsion"].replace(thickness=h))
            ax.axhline(tau, color="grey", ls=ls, lw=0.8, label=f"6 s at h = {h * 1e6:g} µm")
        ax.set_xlabel("r = E / E_cr,max  or  T / T_cr,max")
        ax.set_ylabel("failure time τ_f = t_f / t_c")
        ax.set_title("a map with runs of t_final finds r* where τ_f(r*) = t_final/t_c", fontsize=9)
        ax.legend(fontsize=7)
    ax = axes[1, 1]
    for r, (t, s) in divergence.items():
        ax.semilogy(t, s, label=f"E/E_cr,max = {r}")
    ax.set_xlabel("τ = t / t_c")
    ax.set_ylabel("‖Δθ(τ)‖ / ‖Δθ(0)‖")
    ax.set_title("paired runs (perturbation 1e-9 of the defect slope)", fontsize=9)
    ax.legend(fontsize=8)
    return save_figure(fig, path)
