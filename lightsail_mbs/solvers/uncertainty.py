"""How sure a run is of its answer: an error bar and a conditioning verdict from twin runs.

The answer q of a run is its failure time t_f when the sail fails within the run, else its largest
amplitude ratio max a(t)/a(0). With the estimate on, a run is a short sequence of runs of the same
solver, and the one reported is the most accurate of them:

1. **A tolerance sequence.** The base run (the solver's default or given tolerances) is repeated with
   every tolerance divided by a factor F (rtol, and atol or the Newton tolerances if given; a fixed
   step divided by √F, the methods with a fixed step being second order):

   - the adaptive methods: one twin, F = TIGHTEN; F = WIDE_TIGHTEN for the reduced solver's DOP853,
     which crosses a whole run in 20–50 steps at its default rtol, where its error is not yet
     proportional to rtol (a seeded case: the failure time moves by 1.0e-4, 3.5e-4 and 2.0e-4 s per
     decade from rtol 1e-8 to 1e-11);
   - generalized-α (a fixed step h): two twins, at h/2 (F = HALF_TIGHTEN) and h/4
     (F = STEP_TIGHTEN). At its default step its error is not in its h² regime: the answers of a
     seeded torsion case at h, h/2, h/4 and h/8 are 1.8158656, 1.8158639, 1.8158687 and 1.8158751 s
     against 1.8158771 s (validation/accuracy.md), not monotone, so no order can be assumed.

   The **reported run is the tightest one** (the last of the sequence), and its integration error is
   bounded by the spread of the sequence, no order of convergence assumed:

       E_int = Σ |q_(k+1) − q_k|   over the sequence base, (h/2,) tight.

   If the error falls by at least half per tightening, the tight run's error is at most the last
   difference, which E_int contains; in the asymptotic regime E_int overstates it by about F.

2. **Probe twin** — the base run started from the shape plus a seeded roughness of PROBE_LEVEL · a₀ at
   every wavelength the chain carries (shapes.roughness_profile with seed shapes.PERTURBATION_SEED, the
   same for every solver): a perturbation at the level of the solvers' own round-off (a few 1e-16 of
   coordinates of order L) and a million times below any real film's roughness. Its effect

       S = |q_probe − q_base|

   is a property of the question, not of the solver: where the chain's unstable short waves grow
   from perturbations this small, the answer is set by whatever perturbation a run starts from.

3. **Sampling** — where the failure falls between the reported run's output samples, E_s = E_loc of
   :mod:`lightsail_mbs.solvers.events` (which has already refined the sampling until E_loc ≤ 1e-6 t_f where
   it could), or for a sail that did not fail, how far its largest amplitude may lie above the largest
   sample (the parabola through the peak sample and its neighbours).

4. **Film twin** — the base run started from the case's shape plus a physical film
   (:mod:`lightsail_mbs.model.film`): the reference film (1 nm RMS, ξ = 0.1 m, H = 0.5) for a case without
   one, or the case's own film at the next seed. It is not part of U: the ideal-defect answer and its U
   stand for a film smoother than any real one, and this twin says whether a real film changes them — the
   run is *defect-dominated* when the film moves q by at most FILM_TOL · |q|, else *roughness-dominated*,
   with the RMS below which the ideal answer would hold estimated as linear in the film's RMS.

The uncertainty of the reported q is U = SAFETY · (E_int + S) + E_s, and the run is **well-conditioned**
when S ≤ CONDITION_TOL · |q|. When a twin's verdict differs (one fails within the run, the other not), U is
infinite and the run ill-conditioned: the sail is at its stability boundary for that run length.

Measured (validation/accuracy.md, 96 seeded random cases of every model; the rule settled on the first
64, the last 32 run once after): the two solvers' answers differ by less than their combined U in all 96
cases, and by ≤ 1e-3 relative (at most 9.6e-5) on all 89 well-conditioned ones. For the tight twin to be
much more accurate than the base run, every error source must shrink: Exudyn's chain tightens its Newton
tolerances as rtol² (its step as √rtol), since on extensible chains the modified Newton's residual, not
the step, can set the error (solvers.exudyn.chain).

The estimate costs the twin runs: 3–4 base runs for the adaptive methods (the tight one 1.5–3× a base
run), 8 for generalized-α (2 + 4 + 1 more). It is on for single runs (``solve(..., uncertainty=True)``,
the default, and ``lightsail-mbs simulate``); sweeps run the base run alone and say so in their outputs.
The reported Result is the tight run's (its trajectories, answer and info), its ``wall_time`` the sum of
every run's, and ``Result.uncertainty`` records each run (options, answer, wall time).
"""

from __future__ import annotations

import math

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model import film
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers import contract, events

TIGHTEN = 10.0  # the tight twin's tolerances are the base run's / TIGHTEN (adaptive methods)
WIDE_TIGHTEN = 100.0  # the reduced solver's DOP853: rtol / 100
HALF_TIGHTEN = 4.0  # generalized-α (a fixed step): the middle twin, tolerances / 4, the step / 2
STEP_TIGHTEN = 16.0  # generalized-α: the tight twin, tolerances / 16, the step / 4
PROBE_LEVEL = 1e-12  # the probe twin's roughness amplitude, in units of the defect amplitude a₀
SAFETY = 2.0  # U = SAFETY · (E_int + S)
CONDITION_TOL = 1e-4  # well-conditioned: S ≤ CONDITION_TOL · |q|
FILM_TOL = 1e-3  # defect-dominated: the film twin moves q by ≤ FILM_TOL · |q|
RULE = (
    f"reported: the run at tolerances/F; U = {SAFETY:g}·(E_int + S) + E_s; E_int = Σ|q_(k+1) − q_k| over the runs at "
    f"tolerances/1, /F: F = {TIGHTEN:g} (DOP853: {WIDE_TIGHTEN:g}; generalized-α: the step /1, /2, /4); "
    f"S = |q(start + seeded roughness {PROBE_LEVEL:g} a₀) − q|; E_s: where q falls between output samples; "
    f"well-conditioned when S ≤ {CONDITION_TOL:g}·|q|"
)


def answer(result) -> tuple[str, bool, float]:
    """(quantity, failed, value) of a run: ("failure_time", True, t_f) or ("max_amplitude_ratio", False, ratio)."""
    if result.failed:
        return "failure_time", True, float(result.failure_time)
    return "max_amplitude_ratio", False, float(result.max_amplitude_ratio)


def is_fixed_step(info: dict) -> bool:
    """Whether the base run is generalized-α at a fixed step (Exudyn's chains and sheets)."""
    return info.get("method") == "generalized-alpha"


def tightening(info: dict) -> float:
    """F of the tight twin (module docstring): STEP_TIGHTEN for generalized-α, WIDE_TIGHTEN for DOP853,
    else TIGHTEN."""
    method = info.get("method")
    return STEP_TIGHTEN if is_fixed_step(info) else WIDE_TIGHTEN if method == "DOP853" else TIGHTEN


def sequence(info: dict) -> list[tuple[str, float]]:
    """The twins of the tolerance sequence after the base run: (name, F), the tightest last."""
    if is_fixed_step(info):
        return [("half", HALF_TIGHTEN), ("tight", STEP_TIGHTEN)]
    return [("tight", tightening(info))]


def tightened(options: dict, info: dict, factor: float | None = None, roles: dict | None = None) -> dict:
    """A twin's options: the relative tolerance (the one the base run used, from its info) and the absolute
    or Newton tolerances, if given, divided by F (default tightening(info)); a fixed step divided by √F —
    the given one, or the base run's (info), with its Newton tolerances / F, when the solver has no rtol to
    derive them from (Exudyn's sheet). `roles`: the solver's option names per role (solvers.contract,
    rule 8; default: every registered solver's). A tolerance never goes below the floor the base run reports
    (info["<name>_floor"]: Exudyn's sheet, the round-off of its stiff connectors, under which Newton
    does not converge and every step is retried at a smaller step; a 12 × 12 sheet at E = E_m = 4.5e9 Pa
    ran 90× slower with its absolute tolerance at a quarter of the base run's)."""
    roles = contract.registered_roles() if roles is None else roles
    factor = tightening(info) if factor is None else factor
    tight = dict(options)
    relative = [name for name in roles["rtol"] if name in info]
    for name in relative:
        tight[name] = float(info[name]) / factor

    def divided(name, value):
        floor = float(info.get(f"{name}_floor") or 0.0)
        return max(value / factor, floor)

    for name in roles["tolerance"]:
        if options.get(name) is not None:
            value = options[name]
            tight[name] = divided(name, value) if not hasattr(value, "__len__") else [divided(name, v) for v in value]
    for name in roles["step"]:
        if options.get(name) is not None:
            tight[name] = options[name] / math.sqrt(factor)
        elif not relative and info.get(name) is not None:
            tight[name] = float(info[name]) / math.sqrt(factor)
            for tolerance in roles["tolerance"]:
                if options.get(tolerance) is None and info.get(tolerance):
                    tight[tolerance] = divided(tolerance, float(info[tolerance]))
    return tight


def held_at_floor(twin_options: dict, info: dict, roles: dict | None = None) -> list[str]:
    """The tolerances of a twin that its floor (info["<name>_floor"]) kept from tightening."""
    roles = contract.registered_roles() if roles is None else roles
    return [
        name
        for name in roles["tolerance"]
        if info.get(f"{name}_floor") and twin_options.get(name) == info[f"{name}_floor"]
    ]


def not_estimated(reason: str) -> dict:
    return {"estimated": False, "well_conditioned": None, "uncertainty": None, "explanation": reason, "rule": RULE}


def record_of(run, options: dict) -> dict:
    """What the uncertainty record keeps of one run: its options, wall time, error and answer."""
    record = {"options": options, "wall_time": run.wall_time, "error": run.error}
    if run.error is None:
        _, failed, value = answer(run)
        record.update(failed=failed, value=value)
    return record


def assess(solver, params: SailParameters, settings: RunSettings, options: dict, result, progress: bool = False):
    """The Result to report for `result` (a run of `solver`, a registered contract.Solver or any object with
    its ``run``, with `options`), with its uncertainty record (Result.uncertainty): runs the twins (module
    docstring; the options they change found by their roles, solvers.contract rule 8) and returns the
    tightest run, or `result` itself when no estimate can be made. `progress`: a bar for every twin too."""
    reason = None
    if result.error is not None:
        reason = f"not estimated: the run ended with a solver error ({result.error})"
    elif params.boundary != "free" or params.tip_load:
        reason = "not estimated: supports and tip loads are validations, not sails"
    elif not result.amplitude[0] > 0:
        reason = "not estimated: the sail starts flat (no amplitude ratio to measure)"
    elif hasattr(solver, "roles") and not solver.roles()["perturbation"]:
        reason = "not estimated: the solver has no perturbation option for the probe twin (contract rule 8)"
    if reason is not None:
        result.uncertainty = not_estimated(reason)
        return result
    quantity, failed, value = answer(result)
    records = {"base": record_of(result, options)}
    runs = {"base": result}
    roles = solver.roles() if hasattr(solver, "roles") else contract.registered_roles()
    twins = [(name, tightened(options, result.info, factor, roles)) for name, factor in sequence(result.info)]
    held = sorted({name for _, twin in twins for name in held_at_floor(twin, result.info, roles)})
    for name in roles["perturbation"][:1]:
        twins.append(("probe", {**options, name: PROBE_LEVEL * params.displacement_scale}))
    for name, twin_options in twins:
        runs[name] = solver.run(params, settings, progress=progress, **twin_options)
        records[name] = record_of(runs[name], twin_options)
    film_case, film_text = film_twin(params)
    if film_case is not None:
        runs["film"] = solver.run(film_case, settings, progress=progress, **options)
        records["film"] = record_of(runs["film"], options)
    total_wall = sum(record["wall_time"] for record in records.values())
    for name, record in records.items():
        if record["error"] is not None and name != "film":  # the film twin's error is its own record's
            result.uncertainty = {
                **not_estimated(f"not estimated: the {name} twin ended with a solver error ({record['error']})"),
                "quantity": quantity,
                "value": value,
                **records,
            }
            return result
    order = ["base", *(name for name, _ in sequence(result.info))]
    reported = runs[order[-1]]
    reported.warnings += [w for w in result.warnings if w not in reported.warnings]  # the sampling's notes too
    quantity, failed, value = answer(reported)
    steps = [records[b]["value"] - records[a]["value"] for a, b in zip(order, order[1:])]
    same_verdict = all(records[name]["failed"] == failed for name in order)
    integration = sum(abs(d) for d in steps) if same_verdict else math.inf
    probe, base = records["probe"], records["base"]
    sensitivity = abs(probe["value"] - base["value"]) if probe["failed"] == base["failed"] else math.inf
    location = sampling_error(reported, settings, failed)
    uncertainty = SAFETY * (integration + sensitivity) + location
    well = sensitivity <= CONDITION_TOL * abs(value)
    if "sampling" in result.info:
        reported.info["sampling"] = {**result.info["sampling"], "location_error": location if failed else None}
    reported.uncertainty = {
        "estimated": True,
        "quantity": quantity,
        "value": value,
        "uncertainty": uncertainty,
        "integration_error": integration,
        "sensitivity": sensitivity,
        "sampling_error": location,
        "well_conditioned": bool(well),
        "explanation": " ".join(
            part
            for part in (
                explain(params, quantity, value, integration, sensitivity, well, failed),
                sampling_note(location, SAFETY * (integration + sensitivity), failed),
                floor_note(held, result.info),
            )
            if part
        ),
        "rule": RULE,
        "film_sensitivity": film_sensitivity(records, film_text, quantity, value),
        "held_at_floor": held,
        "reported": order[-1],
        **records,
    }
    reported.wall_time = total_wall
    return reported


def film_twin(params: SailParameters) -> tuple[SailParameters | None, str]:
    """(the film twin's case, what it is): the case with the reference film (model.film.REFERENCE_FILM) when
    it has none, with its own film at the next seed when it has one (a chain's line scan, a sheet's surface)."""
    if params.film_rms == 0:
        ref = film.REFERENCE_FILM
        twin = params.replace(film_rms=ref.rms, film_correlation_length=ref.correlation_length, film_hurst=ref.hurst)
        return twin, f"the reference film ({ref.describe()})"
    return params.replace(film_seed=params.film_seed + 1), f"the same film at seed {params.film_seed + 1}"


def film_sensitivity(records: dict, text: str, quantity: str, value: float) -> dict:
    """What the film twin says (module docstring, item 4): its answer, the shift from the base run's, and the
    verdict "defect-dominated" (shift ≤ FILM_TOL · |q|) or "roughness-dominated", with, for a case without a
    film, the RMS below which the ideal-defect answer holds, estimated as linear in the film's RMS."""
    if "film" not in records:
        return {"assessed": False, "film": text}
    twin, base = records["film"], records["base"]
    if twin["error"] is not None:
        return {"assessed": False, "film": text, "error": twin["error"]}
    shift = abs(twin["value"] - base["value"]) if twin["failed"] == base["failed"] else math.inf
    relative = shift / abs(value) if value else math.inf
    verdict = "defect-dominated" if relative <= FILM_TOL else "roughness-dominated"
    holds_below = None
    if verdict == "roughness-dominated" and text.startswith("the reference film") and math.isfinite(relative):
        holds_below = film.REFERENCE_FILM.rms * FILM_TOL / relative
    return {
        "assessed": True,
        "film": text,
        "quantity": quantity,
        "value": twin["value"],
        "failed": twin["failed"],
        "shift": shift,
        "relative_shift": relative,
        "verdict": verdict,
        "holds_below": holds_below,
    }


def sampling_error(run, settings: RunSettings, failed: bool) -> float:
    """E_s of the reported run: where its failure falls between output samples (events.location_error), or
    how far its largest amplitude ratio may lie above the largest sample (events.peak_error)."""
    if failed:
        return float(events.location_error(run.time, run.amplitude, settings.failure_ratio) or 0.0)
    return events.peak_error(run.amplitude)


def sampling_note(location: float, numerics: float, failed: bool) -> str:
    """A sentence for the explanation when the sampling error is the larger part of U; empty otherwise."""
    if not location > numerics:
        return ""
    what = "where the failure falls between output samples" if failed else "the peak between output samples"
    return f"Most of the uncertainty is {what} ({location:.2g}); a finer output_interval reduces it."


def floor_note(held: list[str], info: dict) -> str:
    """A sentence for the explanation when a twin's Newton tolerance stayed at its floor; empty otherwise."""
    if not held:
        return ""
    floors = ", ".join(f"{name} {info[name + '_floor']:.2g}" for name in held)
    return (
        f"The twins' Newton tolerances stayed at the connectors' round-off floor ({floors}), so the sequence "
        "refines the step, not the Newton solve; the reduced solver has no such floor."
    )


def explain(params, quantity, value, integration, sensitivity, well, failed) -> str:
    """One paragraph: how sure the run is and, when it is ill-conditioned, why and what would change it."""
    what = "failure time" if quantity == "failure_time" else "largest amplitude ratio"
    shortest = 2.0 * params.length / params.n
    if well:
        return (
            f"well-conditioned: a roughness of {PROBE_LEVEL:g} a₀ moves the {what} by "
            f"{sensitivity / abs(value):.1g} relative (≤ {CONDITION_TOL:g}); the uncertainty is dominated by "
            f"{'the integration error' if integration >= sensitivity else 'that sensitivity'}."
        )
    sheet = params.model == "sheet"
    bodies = "tiles" if sheet else "slices"
    remedy = (
        "It is changed by the roughness the sail starts from (set a film: SailParameters.film_rms, --film-rms; "
        f"any real film is rougher than 1e-9 a₀), by the number of {bodies} (fewer {bodies} carry "
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
        f"ill-conditioned: a seeded roughness of {PROBE_LEVEL:g} a₀ at every wavelength the "
        f"{f'{params.n} × {params.ny}-tile sheet' if sheet else f'{params.n}-slice chain'} carries (down to "
        f"2L/n = {shortest:.3g} m) moves the {what} by {sensitivity / abs(value):.1g} "
        f"relative (> {CONDITION_TOL:g}): the {'sheet' if sheet else 'chain'}'s short waves grow from "
        "perturbations at the level of "
        f"round-off, so the answer depends on them, not on the solver. {remedy}"
    )
