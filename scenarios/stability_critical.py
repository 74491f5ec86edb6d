"""Critical E (torsion) and T (TnT) from short scaled runs, against a₀, the analytic Eqs 8/10 and the
bisected 6 s map boundary; run-length dependence and divergence of neighbouring runs (issue 8, part 2).

* critical_modulus / critical_tension (lightsail_mbs.critical.critical_ratio, runs of 8 t_c) for
  a₀ = 1–100 µm (h = 1 µm, I₀ = 0.1 GW/m², ν = 3/2, n = 30), fitted exponent in a₀ next to the analytic 1;
* the same boundary bisected with 6 s runs of the reduced solver (lightsail_mbs.bisection, factor 1.1)
  at a₀ = 1, 10, 100 µm: 6 s is 1.5, 4.6 and 15 t_c there;
* the ratio against ν, with the lowest free–free bending mode's buckling estimate critical.lowest_mode_buckling_ratio;
* the failure curves τ_f(r) = t_f/t_c up to runs of 120 t_c (late failures above the first-passage
  boundary), and from them the boundary a map with runs of t_final finds, r*(t_final/t_c), at the
  thicknesses of Figs 9 and 12 for 6 s and 12 s (next to their boundaries CSVs if --fig9/--fig12 are given);
* paired runs: growth of a 1e-9 angle perturbation at r = 2, 10, 30.
Writes stability_critical.png and stability_critical_*.csv. Usage: python scenarios/stability_critical.py
[--out DIR] [--quick] [--store DIR] [--fig9 fig9_boundaries.csv] [--fig12 fig12_boundaries.csv].
"""
from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path

import numpy as np

from lightsail_mbs import SailParameters
from lightsail_mbs.model import theory
from lightsail_mbs.analysis import finite_amplitude as cr
from lightsail_mbs.studies.bisection import BoundaryProblem, bisect_boundaries
from lightsail_mbs.paper.common import new_figure, print_table, save_figure, write_csv

BASES = {"torsion": SailParameters(model="torsion", n=30, mode=1.5, t_final=6.0),
         "tnt": SailParameters(model="tnt", n=30, mode=1.5, axial_springs=False, tension=1e-8, t_final=6.0)}
ANALYTIC = {"torsion": theory.critical_modulus_max, "tnt": theory.critical_tension_max}
NAME = {"torsion": "critical_modulus", "tnt": "critical_tension"}
AMPLITUDES = (1e-6, 3e-6, 1e-5, 3e-5, 1e-4)
MAP_AMPLITUDES = (1e-6, 1e-5, 1e-4)
MODES = (1.0, 1.5, 2.0, 3.0)
CURVE_RATIOS = {"torsion": (0.1, 0.3, 0.5, 1, 1.5, 2, 3, 4, 5, 6, 7, 7.5, 8, 9, 10, 12, 15, 20),
                "tnt": (0.1, 0.5, 1, 2, 3, 4, 4.5, 5, 6, 8, 10, 15)}
QUICK_CURVE_RATIOS = (0.1, 1, 4, 7)
MAP_THICKNESSES = np.logspace(-8, -5, 7)      # Figs 9 and 12
DIVERGENCE_RATIOS = (2, 10, 30)


def critical_rows(model, amplitudes) -> list[dict]:
    rows = []
    for a0 in amplitudes:
        p = BASES[model].replace(amplitude=a0)
        found = cr.critical_ratio(p, 8.0, factor=1.05)
        analytic = ANALYTIC[model](p)
        rows.append(dict(model=model, amplitude_m=a0, analytic=analytic, critical=found.value * analytic,
                         ratio=found.value, t_c=cr.time_scale(p), runs=found.runs))
    return rows


def exponent(rows, key="critical") -> float:
    return float(np.polyfit(np.log([r["amplitude_m"] for r in rows]), np.log([r[key] for r in rows]), 1)[0])


def map_rows(model, amplitudes, store) -> list[dict]:
    """The 6 s boundary bisected with the sweep engine (reduced solver), one boundary per a₀."""
    base = BASES[model]
    name = "youngs_modulus" if model == "torsion" else "tension"
    problems = {}
    for a0 in amplitudes:
        p = base.replace(amplitude=a0)
        a = ANALYTIC[model](p)
        problems[a0] = BoundaryProblem(lambda v, p=p: p.replace(**{name: float(v)}), a, 30 * a)
    found = bisect_boundaries(problems, store_dir=store / model, solver="reduced", factor=1.1, workers=1,
                              progress=False, max_expansions=3)
    rows = []
    for a0, b in found.items():
        p = base.replace(amplitude=a0)
        rows.append(dict(model=model, amplitude_m=a0, map_boundary=b.value, map_status=b.status,
                         map_ratio=None if b.value is None else b.value / ANALYTIC[model](p),
                         run_in_t_c=base.t_final / cr.time_scale(p)))
    return rows


def map_prediction(model, curve, map_csv=None) -> list[dict]:
    """r*(t_final/t_c) at the thicknesses of Figs 9/12 (ν = 3/2, a₀ = 10 µm, I₀ = 0.1 GW/m²) for 6 s and 12 s
    runs; with a map's bisected ratios (columns ratio, ratio_2t of fig9/fig12_boundaries.csv, ν = 3/2 rows)."""
    ratios, taus = [c["ratio"] for c in curve], [c["tau_f"] for c in curve]
    mapped = {}
    if map_csv:
        with open(map_csv) as handle:
            for row in csv.DictReader(handle):
                if float(row["mode"]) == 1.5:
                    mapped[round(float(row["thickness_m"]), 12)] = (row["ratio"], row["ratio_2t"])
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


def run(out, quick=False, store=None, map_csvs=None) -> dict:
    out = Path(out)
    store = Path(store or Path(__file__).resolve().parents[1] / "results" / "stability_critical")
    amps = AMPLITUDES[::2] if quick else AMPLITUDES
    table, fits, maps = [], [], []
    for model in BASES:
        rows = critical_rows(model, amps)
        table += rows
        fits.append(dict(model=model, name=NAME[model], a0_exponent=exponent(rows), analytic_exponent=1.0,
                         ratio_mean=np.mean([r["ratio"] for r in rows]),
                         ratio_spread=np.ptp([r["ratio"] for r in rows]) / np.mean([r["ratio"] for r in rows])))
        if not quick:
            maps += map_rows(model, MAP_AMPLITUDES, store)
    for m in maps:
        match = [r for r in table if r["model"] == m["model"] and np.isclose(r["amplitude_m"], m["amplitude_m"])]
        m["critical"] = match[0]["critical"] if match else None
        m["critical_over_map"] = (m["critical"] / m["map_boundary"]) if match and m["map_boundary"] else None
    modes = []
    for nu in (MODES[:2] if quick else MODES):
        p = BASES["torsion"].replace(mode=nu)
        found = cr.critical_ratio(p, 8.0, factor=1.05)
        modes.append(dict(mode=nu, ratio=found.value, buckling_estimate=cr.lowest_mode_buckling_ratio(p),
                          tnt_ratio=cr.critical_ratio(BASES["tnt"].replace(mode=nu), 8.0, factor=1.05).value))
    one_mode = cr.one_mode_model(BASES["torsion"]).critical_ratio()
    curves, predicted = {}, []
    for model in BASES:
        curves[model] = [dict(model=model, ratio=r,
                              tau_f=cr.failure_tau(cr.with_ratio(BASES[model], r), 8.0 if quick else 120.0))
                         for r in (QUICK_CURVE_RATIOS if quick else CURVE_RATIOS[model])]
        predicted += map_prediction(model, curves[model], (map_csvs or {}).get(model))
    curve = curves["torsion"] + curves["tnt"]
    divergence = {r: cr.divergence(cr.with_ratio(BASES["torsion"], r), 8.0 if quick else 60.0, samples_per_tau=5)
                  for r in (DIVERGENCE_RATIOS[:1] if quick else DIVERGENCE_RATIOS)}
    rates = [dict(ratio=r, tau_end=float(t[-1]), growth=float(s[-1]),
                  rate_per_t_c=float(np.polyfit(t[t > 1], np.log(s[t > 1]), 1)[0]) if (t > 1).sum() > 2 else None)
             for r, (t, s) in divergence.items()]
    write_csv(out / "stability_critical_amplitude.csv", table)
    write_csv(out / "stability_critical_fits.csv", fits)
    if maps:
        write_csv(out / "stability_critical_map.csv", maps)
    write_csv(out / "stability_critical_modes.csv", modes)
    write_csv(out / "stability_critical_curve.csv", curve)
    write_csv(out / "stability_critical_maps_predicted.csv", predicted)
    write_csv(out / "stability_critical_divergence.csv", rates)
    print_table("Critical value from 8 t_c runs against a0 (h = 1 um, I0 = 0.1 GW/m2, nu = 3/2, n = 30)", table)
    print_table("Fitted exponent in a0 (analytic 1) and ratio to E_cr,max / T_cr,max", fits)
    if maps:
        print_table("Against the bisected 6 s boundary (reduced solver, factor 1.1)", maps)
    print_table(f"Ratio against the mode (one-mode Galerkin model of the sine: {one_mode:.3g})", modes)
    print_table("Failure curves tau_f(r) = t_f/t_c (runs up to 120 t_c)", curve)
    print_table("Fig. 9 (E/E_cr,max) and Fig. 12 (T/T_cr,max, nu = 3/2) boundaries predicted from tau_f(r), "
                "runs of 6 s and 12 s", predicted)
    print_table("Paired runs: growth of a 1e-9 angle perturbation", rates)
    figure(out, table, maps, curve, divergence)
    return {"table": table, "fits": fits, "maps": maps, "modes": modes, "curve": curve, "predicted_maps": predicted, "rates": rates,
            "one_mode_ratio": one_mode}


def figure(out, table, maps, curve, divergence) -> Path:
    fig, axes = new_figure(2, 2, size=(10.0, 7.5))
    for ax, model, unit in ((axes[0, 0], "torsion", "E (Pa)"), (axes[0, 1], "tnt", "T (N)")):
        rows = [r for r in table if r["model"] == model]
        a = np.array([r["amplitude_m"] for r in rows])
        ax.loglog(a, [r["critical"] for r in rows], "o-", label=f"{NAME[model]} (8 t_c runs)")
        ax.loglog(a, [r["analytic"] for r in rows], "k--", label="Eq. 8" if model == "torsion" else "Eq. 10")
        m = [r for r in maps if r["model"] == model and r["map_boundary"]]
        if m:
            ax.loglog([r["amplitude_m"] for r in m], [r["map_boundary"] for r in m], "s", mfc="none", ms=9,
                      label="bisected 6 s boundary")
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
    return save_figure(fig, out / "stability_critical.png")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(Path(__file__).parent / "figures"))
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--store", default=None, help="sweep store of the bisections [default results/stability_critical]")
    ap.add_argument("--fig9", default=None, help="fig9_boundaries.csv of scenarios/fig9.py to compare with")
    ap.add_argument("--fig12", default=None, help="fig12_boundaries.csv of scenarios/fig12.py to compare with")
    args = ap.parse_args(argv)
    run(args.out, quick=args.quick, store=args.store, map_csvs={"torsion": args.fig9, "tnt": args.fig12})
    return 0


if __name__ == "__main__":
    sys.exit(main())
