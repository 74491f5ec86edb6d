"""`lightsail-mbs theory`: the closed forms of Section II (Eqs 4, 7–10) for a case, its stiffness against the
critical values (E/E_cr,max, T/T_cr,max) and what the paper's criteria predict for it."""

from __future__ import annotations

import json

from lightsail_mbs.cli.options import add_case_options, params_from_args


def register(sub) -> None:
    p = sub.add_parser(
        "theory",
        help="the closed-form theory of a case: g0, E_cr,max, T_cr,max (paper Eqs 4, 8, 10), its E/E_cr,max and "
        "T/T_cr,max and what the paper's criteria predict",
    )
    add_case_options(p, run=False)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(func=run)


def run(args) -> int:
    from lightsail_mbs.model import theory

    p = params_from_args(args)
    start = theory.at_start(p)
    numbers = {**theory.summary(start), **criteria(start)}
    if start is not p:  # the sail recedes at β₀: every number is at the Doppler-dimmed intensity of its start
        numbers = {"initial_beta": p.initial_beta, "intensity_at_start": start.intensity, **numbers}
        numbers["paper_prediction"] += (
            "; at the run's start, the beam dimmed by the Doppler factor (1 − β₀)/(1 + β₀) to "
            f"{start.intensity:.6g} W/m² (it dims further during the run)"
        )
    if args.json:
        print(json.dumps(numbers))
    else:
        for key, value in numbers.items():
            text = value if value is None or isinstance(value, str) else f"{value:.6g}"
            print(f"{key:26s} {text}")
    return 0


def criteria(p) -> dict:
    """The case's stiffness ratios E/E_cr,max (bending springs; 0 without) and T/T_cr,max (the TnT chain's
    boundary tension, a sheet's edge tension per metre of edge), and the prediction of the paper's criteria:
    the defect is held where a ratio exceeds 1 (Eqs 8, 10). (The stability command measures the boundary of
    the motion, lightsail_mbs.analysis.finite_amplitude.)"""
    from lightsail_mbs.model import theory

    e_ratio = p.youngs_modulus / theory.critical_modulus_max(p) if p.bending and p.defect_amplitude > 0 else 0.0
    if p.model == "sheet":
        tension = p.edge_tension / (theory.critical_tension_max(p) / p.width) if p.defect_amplitude > 0 else 0.0
    else:
        tension = p.tension / theory.critical_tension_max(p) if p.defect_amplitude > 0 else 0.0
    out = {"e_over_e_cr_max": e_ratio, "t_over_t_cr_max": tension}
    if p.defect_amplitude == 0:
        out["paper_prediction"] = "keeps its shape (a flat sail: no defect for the load to grow)"
        return out
    held = [name for name, ratio in (("E > E_cr,max, Eq. 8", e_ratio), ("T > T_cr,max, Eq. 10", tension)) if ratio > 1]
    if p.model == "rigid":
        out["paper_prediction"] = "fails (the rigid chain has no stiffness to hold its defect, Sec. IV.A)"
    elif held:
        out["paper_prediction"] = f"keeps its shape ({' and '.join(held)})"
    else:
        out["paper_prediction"] = "fails (E ≤ E_cr,max and T ≤ T_cr,max: nothing holds the defect, Eqs 8, 10)"
    if p.model == "sheet":
        out["paper_prediction"] += "; the criteria are the strip's, the doubly curved sheet can fail above them"
    if p.model in ("torsion", "tnt"):
        out["paper_prediction"] += "; lightsail-mbs stability measures where the motion fails"
    return out
