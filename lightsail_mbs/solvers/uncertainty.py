"""How sure a run is of its answer: an error bar and a conditioning verdict from two twin runs.

The answer q of a run is its failure time t_f when the sail fails within the run, else its largest
amplitude ratio max a(t)/a(0). Two more runs of the same solver say how far q can be trusted:

1. **Tight twin** — the same run with every tolerance divided by a factor F (rtol, and atol or the
   Newton tolerances if given; a fixed step divided by √F, the methods with a fixed step being second
   order). F = TIGHTEN for the adaptive methods; F = STEP_TIGHTEN = 16 (the step quartered) for
   generalized-α, whose error in the peak amplitude ratio of an oscillating survivor is not yet in its h²
   regime at the default step, so that a half-step twin underestimates it; F = WIDE_TIGHTEN = 100 for the
   reduced solver's DOP853, which crosses a whole run in 20–50 steps at its default rtol, where its error
   is not yet proportional to rtol (a seeded case: the failure time moves by 1.0e-4, 3.5e-4 and 2.0e-4 s
   per decade from rtol 1e-8 to 1e-11), so that a one-decade twin underestimates it (measured on seeded
   random cases: validation/accuracy.md). Its runs are cheap, so two decades cost little. With an error
   proportional to the tolerance, the base run's
   integration error is

       E_int = |q_tight − q| / (1 − 1/F).

2. **Probe twin** — the same run started from the shape plus a seeded roughness of PROBE_LEVEL · a₀ at
   every wavelength the chain carries (shapes.roughness_profile with seed shapes.PERTURBATION_SEED, the
   same for every solver): a perturbation at the level of the solvers' own round-off (a few 1e-16 of
   coordinates of order L) and a million times below any real film's roughness. Its effect

       S = |q_probe − q|

   is a property of the question, not of the solver: where the chain's unstable short waves grow
   from perturbations this small, the answer is set by whatever perturbation a run starts from.

The uncertainty of q is U = SAFETY · (E_int + S), and the run is **well-conditioned** when
S ≤ CONDITION_TOL · |q|. When a twin's verdict differs (one fails within the run, the other not), U is
infinite and the run ill-conditioned: the sail is at its stability boundary for that run length.

Measured (validation/accuracy.md, 32 seeded random cases of every model): the two solvers' answers
differ by less than their combined U in 29 of 32 cases (the misses: generalized-α's quarter-step
estimate, too small where its error is not yet in its h² regime), and by ≤ 1e-3 relative on 28 of the 29
well-conditioned ones.

The estimate costs two more runs (the tight one 1.5–3× a base run). It is on for single runs
(``solve(..., uncertainty=True)``, the default, and ``lightsail-mbs simulate``); sweeps run without it
and say so in their outputs.
"""

from __future__ import annotations

import math

from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers.settings import RunSettings

TIGHTEN = 10.0  # the tight twin's tolerances are the base run's / TIGHTEN (adaptive methods)
STEP_TIGHTEN = 16.0  # generalized-α (a fixed step): tolerances / 16, the step / 4
WIDE_TIGHTEN = 100.0  # the reduced solver's DOP853: rtol / 100
PROBE_LEVEL = 1e-12  # the probe twin's roughness amplitude, in units of the defect amplitude a₀
SAFETY = 2.0  # U = SAFETY · (E_int + S)
CONDITION_TOL = 1e-4  # well-conditioned: S ≤ CONDITION_TOL · |q|
RULE = (
    f"U = {SAFETY:g}·(E_int + S); E_int = |q(tolerances/F) − q|/(1 − 1/F), F = {TIGHTEN:g} "
    f"(generalized-α: {STEP_TIGHTEN:g}, the step / {math.sqrt(STEP_TIGHTEN):g}; DOP853: {WIDE_TIGHTEN:g}); "
    f"S = |q(start + seeded roughness {PROBE_LEVEL:g} a₀) − q|; well-conditioned when S ≤ {CONDITION_TOL:g}·|q|"
)


def answer(result) -> tuple[str, bool, float]:
    """(quantity, failed, value) of a run: ("failure_time", True, t_f) or ("max_amplitude_ratio", False, ratio)."""
    if result.failed:
        return "failure_time", True, float(result.failure_time)
    return "max_amplitude_ratio", False, float(result.max_amplitude_ratio)


def tightening(info: dict) -> float:
    """F of the base run (module docstring): STEP_TIGHTEN for generalized-α, WIDE_TIGHTEN for DOP853, else
    TIGHTEN."""
    method = info.get("method")
    return STEP_TIGHTEN if method == "generalized-alpha" else WIDE_TIGHTEN if method == "DOP853" else TIGHTEN


def tightened(options: dict, info: dict) -> dict:
    """The tight twin's options: rtol (the one the base run used, from its info) and atol or the Newton
    tolerances, if given, divided by F = tightening(info); a fixed step divided by √F."""
    factor = tightening(info)
    tight = dict(options)
    if "rtol" in info:
        tight["rtol"] = float(info["rtol"]) / factor
    for name in ("atol", "newton_rel_tol", "newton_abs_tol"):
        if options.get(name) is not None:
            tight[name] = (
                options[name] / factor if not hasattr(options[name], "__len__") else [v / factor for v in options[name]]
            )
    if options.get("step_size") is not None:
        tight["step_size"] = options["step_size"] / math.sqrt(factor)
    return tight


def not_estimated(reason: str) -> dict:
    return {"estimated": False, "well_conditioned": None, "uncertainty": None, "explanation": reason, "rule": RULE}


def assess(module, params: SailParameters, settings: RunSettings, options: dict, result) -> dict:
    """The uncertainty record of `result` (a run of solver module `module` with `options`): runs the two
    twins and returns the dict stored as Result.uncertainty (module docstring)."""
    if result.error is not None:
        return not_estimated(f"not estimated: the run ended with a solver error ({result.error})")
    if params.boundary != "free" or params.tip_load:
        return not_estimated("not estimated: supports and tip loads are validations, not sails")
    if not result.amplitude[0] > 0:
        return not_estimated("not estimated: the sail starts flat (no amplitude ratio to measure)")
    quantity, failed, value = answer(result)
    twins = {}
    tight_options = tightened(options, result.info)
    probe_options = {**options, "perturbation": PROBE_LEVEL * params.displacement_scale}
    for name, twin_options in (("tight", tight_options), ("probe", probe_options)):
        twin = module.run(params, settings, progress=False, **twin_options)
        record = {"options": twin_options, "wall_time": twin.wall_time, "error": twin.error}
        if twin.error is None:
            twin_quantity, twin_failed, twin_value = answer(twin)
            record.update(failed=twin_failed, value=twin_value)
        twins[name] = record
    for name, record in twins.items():
        if record["error"] is not None:
            return {
                **not_estimated(f"not estimated: the {name} twin ended with a solver error ({record['error']})"),
                "quantity": quantity,
                "value": value,
                **twins,
            }
    tight, probe = twins["tight"], twins["probe"]
    factor = tightening(result.info)
    integration = abs(tight["value"] - value) / (1.0 - 1.0 / factor) if tight["failed"] == failed else math.inf
    sensitivity = abs(probe["value"] - value) if probe["failed"] == failed else math.inf
    uncertainty = SAFETY * (integration + sensitivity)
    well = sensitivity <= CONDITION_TOL * abs(value)
    return {
        "estimated": True,
        "quantity": quantity,
        "value": value,
        "uncertainty": uncertainty,
        "integration_error": integration,
        "sensitivity": sensitivity,
        "well_conditioned": bool(well),
        "explanation": explain(params, quantity, value, integration, sensitivity, well, failed, tight, probe),
        "rule": RULE,
        "tight": tight,
        "probe": probe,
    }


def explain(params, quantity, value, integration, sensitivity, well, failed, tight, probe) -> str:
    """One paragraph: how sure the run is and, when it is ill-conditioned, why and what would change it."""
    what = "failure time" if quantity == "failure_time" else "largest amplitude ratio"
    shortest = 2.0 * params.length / params.n
    if well:
        return (
            f"well-conditioned: a roughness of {PROBE_LEVEL:g} a₀ moves the {what} by "
            f"{sensitivity / abs(value):.1g} relative (≤ {CONDITION_TOL:g}); the uncertainty is dominated by "
            f"{'the integration error' if integration >= sensitivity else 'that sensitivity'}"
        )
    remedy = (
        "It is changed by the roughness the sail starts from (set one explicitly: SailParameters.roughness, "
        "--roughness; any real film is rougher than 1e-9 a₀), by the number of slices n (fewer slices carry "
        "fewer unstable short waves) and by bending stiffness or tension; a tighter tolerance does not change it."
    )
    if math.isinf(sensitivity):
        verdict = "fails" if failed else "survives"
        return (
            f"ill-conditioned: the run {verdict}, but started with a roughness of {PROBE_LEVEL:g} a₀ it "
            f"{'survives' if failed else 'fails'} within t_final: the sail is at its stability boundary for this "
            f"run length, and the verdict is set by perturbations far below any real film's roughness. {remedy}"
        )
    return (
        f"ill-conditioned: a seeded roughness of {PROBE_LEVEL:g} a₀ at every wavelength the {params.n}-slice "
        f"chain carries (down to 2L/n = {shortest:.3g} m) moves the {what} by {sensitivity / abs(value):.1g} "
        f"relative (> {CONDITION_TOL:g}): the chain's short waves grow from perturbations at the level of "
        f"round-off, so the answer depends on them, not on the solver. {remedy}"
    )
