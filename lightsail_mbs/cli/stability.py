"""`lightsail-mbs stability`: critical E (torsion) or T (TnT) of a case from short scaled runs; for a sheet,
the stable E or edge tension from full runs.

The finite-amplitude scaling (lightsail_mbs.analysis.finite_amplitude) makes the doubling of the defect depend on
E/E_cr,max (or T/T_cr,max), ν, n and the run length in units of t_c = 1/(k√(g₀a₀)) only; below the
first-passage threshold the amplitude doubles within ≈ 4 t_c. So the boundary is bisected in the
stiffness ratio with runs of --tau-final·t_c (default 8) of the reduced solver instead of 6 s runs
(the TnT chain in its inextensible limit); --run-time gives instead the boundary that a map with runs
of that length finds (below ≈ 1.6 t_c nothing fails: an error says so). Optionally the flat state's
linear spectrum is checked with and without the load (--linear).

A sheet (--model sheet) has no scaled problem yet: its boundary is bisected in E/E_cr,max or
T/T_cr,max (per metre of edge) with full runs of --run-time seconds (default 6) of --solver through a
resumable store (studies.sheet.stability_boundaries).
"""

from __future__ import annotations

import json
import math
import time

from lightsail_mbs.base.validation import check, finite
from lightsail_mbs.cli.options import SOLVER_HELP, add_case_options, params_from_args


def register(sub) -> None:
    p = sub.add_parser(
        "stability",
        help="critical E (torsion) or T (tnt) from short scaled runs; flat-state linear spectrum with/without load",
    )
    add_case_options(p)
    p.add_argument(
        "--tau-final",
        type=float,
        default=8.0,
        help="run length of each bisection run in units of t_c = 1/(k sqrt(g0 a0)) [default: 8]",
    )
    p.add_argument(
        "--run-time",
        type=float,
        default=None,
        help="instead: runs of this many seconds (τ = run-time/t_c), the boundary a stability map "
        "with runs of that length finds (e.g. the paper's 6)",
    )
    p.add_argument(
        "--factor", type=float, default=None, help="bisect until hi/lo ≤ factor [default: 1.05; 1.25 for a sheet]"
    )
    g = p.add_argument_group("sheet (--model sheet): full runs of --run-time (default 6 s) through a store")
    g.add_argument(
        "--quantity",
        choices=("modulus", "edge-tension"),
        default="modulus",
        help="the stiffness bisected: E/E_cr,max or the edge tension T/T_cr,max per metre [default: modulus]",
    )
    g.add_argument(
        "--solver", choices=("reduced", "exudyn"), default="reduced", help=f"{SOLVER_HELP} [default: reduced]"
    )
    g.add_argument("--store", default=None, help="the store of the runs (resumable) [default: a temporary folder]")
    p.add_argument(
        "--linear",
        action="store_true",
        help="also compare the flat state's linear spectra with and without the load (reduced solver)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.analysis import finite_amplitude as critical
    from lightsail_mbs.analysis import linear_stability as stability
    from lightsail_mbs.model import theory

    p = params_from_args(args)
    check(
        "initial_beta",
        p.initial_beta,
        p.initial_beta == 0,
        "0 with stability (its scaled problem is a sail at rest under a constant beam; for a sail receding at "
        f"β₀ give the intensity it meets, --intensity {theory.at_start(p).intensity:.6g} --initial-beta 0)",
    )
    if args.run_time is not None:
        check("run_time", args.run_time, finite("run_time", args.run_time) > 0, "> 0 s")
    if p.model == "sheet":
        return run_sheet(args, p)
    args.factor = 1.05 if args.factor is None else args.factor
    if p.model == "tnt":
        p = p.replace(axial_springs=False)
    start = time.perf_counter()
    tau_final = args.tau_final if args.run_time is None else args.run_time / critical.time_scale(p)
    found = critical.critical_ratio(p, tau_final, factor=args.factor)
    name, analytic = (
        ("critical_modulus", theory.critical_modulus_max(p))
        if p.model == "torsion"
        else ("critical_tension", theory.critical_tension_max(p))
    )
    out = {
        name: found.value * analytic,
        f"{name}_bracket": [found.failed_ratio * analytic, found.stable_ratio * analytic],
        "analytic": analytic,
        "analytic_name": "e_cr_max" if p.model == "torsion" else "t_cr_max",
        "ratio_to_analytic": found.value,
        "time_scale": critical.time_scale(p),
        "tau_final": found.tau_final,
        "run_length": found.tau_final * critical.time_scale(p),
        "runs": found.runs,
        "case_ratio": critical.stiffness_ratio(p),
        "case_fails_within_run": critical.stiffness_ratio(p) < found.value,
        "wall_time": None,
    }
    if p.model == "torsion":
        out["lowest_mode_buckling_modulus"] = critical.lowest_mode_buckling_ratio(p) * analytic
    if args.linear:
        shift = stability.load_shift(p, "reduced")
        out["linear_relative_shift"] = shift["relative_shift"]
        out["linear_growth_rate"] = shift["growth_rate_lit"]
    out["wall_time"] = time.perf_counter() - start
    if args.json:
        print(json.dumps(out))
    else:
        low, high = out[f"{name}_bracket"]
        shown = {
            name: bracketed(out[name], low, high),
            f"{name}_bracket": None,
            "ratio_to_analytic": bracketed(found.value, found.failed_ratio, found.stable_ratio),
        }
        for key, value in out.items():
            text = shown.get(key, value if isinstance(value, (bool, list, str)) or value is None else f"{value:.6g}")
            if text is not None:
                print(f"{key:26s} {text}")
    return 0


def bracketed(value: float, low: float, high: float) -> str:
    """'3.44e+12 (bracket 3.39e+12–3.49e+12)': the value and its bisection bracket, with as many
    significant digits as tell the bracket's ends apart (at least 2); the ends are rounded outwards, so
    the printed bracket contains the bisected one."""
    width = abs(high - low) / abs(value) if value else 0.0
    digits = max(2, math.ceil(-math.log10(width)) + 1) if 0 < width < 1 else 2

    def rounded(x: float, direction) -> float:
        if x == 0 or not math.isfinite(x):
            return x
        unit = 10.0 ** (math.floor(math.log10(abs(x))) - digits + 1)
        return direction(x / unit) * unit

    low, high = rounded(low, math.floor), rounded(high, math.ceil)
    return f"{value:#.{digits}g} (bracket {low:#.{digits}g}–{high:#.{digits}g})"


def run_sheet(args, p) -> int:
    """The sheet: bisect E/E_cr,max or T/T_cr,max with full runs (studies.sheet.stability_boundaries)."""
    import tempfile

    from lightsail_mbs.base.settings import RunSettings
    from lightsail_mbs.cli.options import writable_folder
    from lightsail_mbs.studies import sheet as sheet_study

    quantity = args.quantity.replace("-", "_")
    run_time = 6.0 if args.run_time is None else args.run_time
    factor = 1.25 if args.factor is None else args.factor
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="lightsail-stability-") as scratch:
        store = writable_folder(args.store, "--store") if args.store else scratch
        found = sheet_study.stability_boundaries(
            {"sheet": p},
            quantity,
            store,
            solver=args.solver,
            settings=RunSettings(t_final=run_time),
            factor=factor,
            progress=not args.json,
        )["sheet"]
    name, scale = sheet_study.QUANTITIES[quantity]
    analytic = scale(p)
    out = {
        "quantity": name,
        "status": found.status,
        "message": found.message,
        "ratio_to_analytic": found.value,
        "ratio_bracket": list(found.bracket) if found.bracket else None,
        "value": None if found.value is None else found.value * analytic,
        "analytic": analytic,
        "analytic_name": "e_cr_max" if quantity == "modulus" else "t_cr_max_per_metre",
        "run_length": run_time,
        "runs": len(found.evaluations),
        "solver": args.solver,
        "wall_time": time.perf_counter() - start,
    }
    if args.json:
        print(json.dumps(out))
    else:
        shown = {}
        if found.value is not None and found.bracket:
            low, high = found.bracket
            shown = {
                "ratio_to_analytic": bracketed(found.value, low, high),
                "ratio_bracket": None,
                "value": bracketed(found.value * analytic, low * analytic, high * analytic),
            }
        for key, value in out.items():
            text = shown.get(key, value if not isinstance(value, float) else f"{value:.6g}")
            if text is not None or key not in shown:
                print(f"{key:26s} {text}")
    return 0 if found.status == "converged" else 1
