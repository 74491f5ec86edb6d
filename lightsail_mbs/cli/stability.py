"""`lightsail-mbs stability`: critical E (torsion) or T (TnT) of a case from short scaled runs.

The finite-amplitude scaling (lightsail_mbs.analysis.finite_amplitude) makes the doubling of the defect depend on
E/E_cr,max (or T/T_cr,max), ν, n and the run length in units of t_c = 1/(k√(g₀a₀)) only; below the
first-passage threshold the amplitude doubles within ≈ 4 t_c. So the boundary is bisected in the
stiffness ratio with runs of --tau-final·t_c (default 8) of the reduced solver instead of 6 s runs
(the TnT chain in its inextensible limit); --run-time gives instead the boundary that a map with runs
of that length finds (below ≈ 1.6 t_c nothing fails: an error says so). Optionally the flat state's
linear spectrum is checked with and without the load (--linear).
"""

from __future__ import annotations

import json
import time

from lightsail_mbs.cli.options import add_case_options, params_from_args
from lightsail_mbs.model.parameters import check, finite


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
        help="run length of each bisection run in units of t_c = 1/(k sqrt(g0 a0)) [default 8]",
    )
    p.add_argument(
        "--run-time",
        type=float,
        default=None,
        help="instead: runs of this many seconds (τ = run-time/t_c), the boundary a stability map "
        "with runs of that length finds (e.g. the paper's 6)",
    )
    p.add_argument("--factor", type=float, default=1.05, help="bisect until hi/lo ≤ factor [default 1.05]")
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
    if args.run_time is not None:
        check("run_time", args.run_time, finite("run_time", args.run_time) > 0, "> 0 s")
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
        for key, value in out.items():
            text = value if isinstance(value, (bool, list, str)) or value is None else f"{value:.6g}"
            print(f"{key:26s} {text}")
    return 0
