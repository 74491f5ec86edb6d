"""How sure a run is of its answer: an error bar and a conditioning verdict from twin runs.

The answer q of a run is its failure time t_f when the sail fails within the run, else its largest
amplitude ratio max a(t)/a(0). With the estimate on, the **reported run is the base run itself** (the
solver's default or given tolerances: the answer a sweep, which runs the base run alone, gets too) unless
the base run is found inaccurate (item 1), and its error bar comes from twins that cost less than it:

1. **A loose twin.** The base run repeated with every tolerance multiplied by a factor F (rtol, and atol or
   the Newton tolerances if given; a fixed step multiplied by √F, the methods with a fixed step being second
   order): F = LOOSEN for the adaptive methods (about 0.5–0.7 of a base run's steps), F = DOP853_LOOSEN for
   the reduced solver's DOP853, which crosses a run in 20–50 steps at its default rtol where its error is
   not proportional to rtol (against rtol 1e-11, the change at rtol × 10 was 3.4–6.5× the base run's error
   on the paper's soft, stable and rigid sails and a Doppler-shifted soft sail, at rtol × 2 0.6–0.8×, too
   little to bound it, and at rtol × 3 1.1–1.7× on the soft, rigid and Doppler-shifted ones), F =
   STEP_LOOSEN for generalized-α (the step × 2: half the steps; Exudyn's chain loosens its Newton tolerances
   as rtol², by 16, so that the modified Newton's error, which can set an extensible chain's, is loosened
   too). Its integration error bound is the change between the two, no order assumed:

       E_int = |q_base − q_loose|.

   If the error grows at least as fast as linearly with the tolerances, |q_base − q_loose| ≥ (F − 1) ·
   |q_base − q_∞| ≥ the base run's error; generalized-α at its default step is not in its h² regime (a
   seeded torsion case at h, h/2, h/4, h/8: 1.8158656, 1.8158639, 1.8158687, 1.8158751 s against 1.8158771 s),
   which U's SAFETY and the measured coverage (validation/accuracy.md) answer for.

   **Tightened where the base run is not accurate.** When the loose twin's answer is more than ACCURACY · |q|
   from the base run's (or of the other verdict), the base run may be further off than the two solvers are
   held to agree (validation/accuracy.md: a seeded rigid chain of 77 slices, ill-posed in n, whose reduced
   DOP853 base run lies 2.5e-3 from its tightened answer): the first twin of the tightened sequence runs too
   (tolerances / TIGHTEN, DOP853 / WIDE_TIGHTEN, generalized-α the step / 2) and is the run reported, with
   E_int = |q_base − q_loose| + |q_tight − q_base|. The probe, film and n-twins stay at the loose options.

2. **Probe twin** — the base run started from the shape plus a seeded roughness of PROBE_LEVEL · a₀ at
   every wavelength the chain carries (shapes.roughness_profile with seed shapes.PERTURBATION_SEED, the
   same for every solver): a perturbation at the level of the solvers' own round-off (a few 1e-16 of
   coordinates of order L) and a million times below any real film's roughness. Its effect

       S = |q_probe − q_base|

   is a property of the question, not of the solver: where the chain's unstable short waves grow
   from perturbations this small, the answer is set by whatever perturbation a run starts from. It runs
   at the base run's options, not the loose twin's: how fast the grid-scale waves grow depends on the
   step that resolves them (the paper's soft extensible TnT sail, ill-posed in n, on Exudyn's
   generalized-α: S = 1.7e-4 s at the step h, 1.2e-2 s at 2h, whatever the Newton tolerances). **It runs only
   where the film twin (item 4) does not stand for it**: where the film moves q by at most FILM_TOL · |q| (its waves
   stayed small, their effect linear in their amplitudes), S is estimated as c times the film's change, c the
   largest ratio of the probe's amplitude to the film's over the chain's modes (c ≤ 3e-5 on every chain of
   validation/accuracy.md), and the probe is not run (:mod:`~lightsail_mbs.solvers.film_twin`; sheets always run
   it). It saves a base run on the sails whose answers a real film does not move (the paper's stable ones).

3. **Sampling** — where the failure falls between the base run's output samples, E_s = E_loc of
   :mod:`lightsail_mbs.solvers.events` (which has already refined the sampling until E_loc ≤ 1e-6 t_f where
   it could), or for a sail that did not fail, how far its largest amplitude may lie above the largest
   sample (the parabola through the peak sample and its neighbours).

4. **Film twin** — run before the probe (item 2), which waits for its verdict: the loose twin started from the
   case's shape plus a physical film
   (:mod:`lightsail_mbs.model.film`): the reference film (1 nm RMS, ξ = 0.1 m, H = 0.5) for a case without
   one, or the case's own film at the next seed. It is not part of U: the ideal-defect answer and its U
   stand for a film smoother than any real one, and this twin says whether a real film changes them — the
   run is *defect-dominated* when the film moves q (against the loose twin) by at most FILM_TOL · |q|, else
   *roughness-dominated*, with the RMS below which the ideal answer would hold estimated as linear in the
   film's RMS.

The uncertainty of the reported q is U = SAFETY · (E_int + S) + E_s, and the run is **well-conditioned**
when S ≤ CONDITION_TOL · |q|. When a twin's verdict differs (one fails within the run, the other not), U is
infinite and the run ill-conditioned: the sail is at its stability boundary for that run length. The
n-error of :mod:`lightsail_mbs.analysis.n_error` runs its twins at the loose twin's options too
(``Result.uncertainty["reference"]`` names the run they are compared with).

**Fallback: the tolerance sequence.** When the loose twin ends with a solver error (a step too large for
Newton) or could not run looser (Exudyn's sheet caps its step at the output interval), the estimate is the
tighter sequence instead: twins at the tolerances / F (F = TIGHTEN; WIDE_TIGHTEN for the reduced solver's
DOP853; generalized-α: two, the step / 2 and / 4 with tolerances / HALF_TIGHTEN and / STEP_TIGHTEN), the
probe and film twins at the base run's options, E_int = Σ |q_(k+1) − q_k| over the sequence base, (h/2,)
tight, and the tightest run reported.

Cost (validation/uncertainty_cost.md, CPU time): the loose and film twins 0.4–0.8 of a base run each (0.7–1.3 for
the reduced solver's runs of milliseconds), the probe one where it runs, the n-twins 0.1–0.7: 2.2–3.8 base runs
with Exudyn, 2.7–3.6 with the reduced solver, on the paper's benchmark rows. On two cores or more they run in
worker processes, started while the base run runs (`speculation`, :mod:`~lightsail_mbs.solvers.twin_workers`; a
run under its CONCURRENT_AFTER keeps them in process). Coverage: validation/accuracy.md. On for single runs
(``solve``, ``lightsail-mbs simulate``); sweeps run the base run alone. ``Result.uncertainty`` records each run
(options, answer, wall and CPU time: a worker's its own) and ``elapsed``, the default run's wall time (s);
``Result.wall_time`` sums every run's.
"""

from __future__ import annotations

import math

from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.solvers import contract, events, twin_options, twin_workers
from lightsail_mbs.solvers.film_twin import FILM_TOL, film_sensitivity, film_twin, probe_estimate  # noqa: F401 - FILM_TOL
from lightsail_mbs.solvers.twin_options import DOP853_LOOSEN, LOOSEN, TIGHTEN, WIDE_TIGHTEN

PROBE_LEVEL = 1e-12  # the probe twin's roughness amplitude, in units of the defect amplitude a₀
SAFETY = 2.0  # U = SAFETY · (E_int + S)
CONDITION_TOL = 1e-4  # well-conditioned: S ≤ CONDITION_TOL · |q|
PROBE_NICENESS = 19  # a probe worker's priority below this process's where the film twin may stand for it
ACCURACY = 1e-3  # the base run is reported when the loose twin's answer is within ACCURACY · |q| of it
RULE = (
    f"reported: the base run (the run at tolerances/F, F = {TIGHTEN:g}, DOP853 {WIDE_TIGHTEN:g}, generalized-α the "
    f"step / 2, when |q − q_loose| > {ACCURACY:g}·|q|); U = {SAFETY:g}·(E_int + S) + E_s; E_int = Σ|q_(k+1) − q_k| "
    f"over the runs from q_loose, at tolerances × {LOOSEN:g} (DOP853: × {DOP853_LOOSEN:g}; generalized-α: the "
    f"step × 2); "
    f"S = |q(start + seeded roughness {PROBE_LEVEL:g} a₀) − q_base|, or c·|q_film − q_loose| where the film twin "
    f"moves q by ≤ {FILM_TOL:g}·|q| (c: the probe's largest amplitude over the film's, mode by mode); "
    f"E_s: where q falls between output samples; well-conditioned when S ≤ {CONDITION_TOL:g}·|q|"
)
FALLBACK_RULE = (
    f"reported: the run at tolerances/F (the loose twin failed); U = {SAFETY:g}·(E_int + S) + E_s; E_int = "
    f"Σ|q_(k+1) − q_k| over the runs at tolerances/1, /F: F = {TIGHTEN:g} (DOP853: {WIDE_TIGHTEN:g}; generalized-α: "
    f"the step /1, /2, /4); S = |q(start + seeded roughness {PROBE_LEVEL:g} a₀) − q| (or the film twin's "
    f"c·|q_film − q| where it moves q by ≤ {FILM_TOL:g}·|q|); E_s: where q falls between output samples; "
    f"well-conditioned when S ≤ {CONDITION_TOL:g}·|q|"
)


def answer(result) -> tuple[str, bool, float]:
    """(quantity, failed, value) of a run: ("failure_time", True, t_f) or ("max_amplitude_ratio", False, ratio)."""
    if result.failed:
        return "failure_time", True, float(result.failure_time)
    return "max_amplitude_ratio", False, float(result.max_amplitude_ratio)


def accurate(loose: dict, base: dict) -> bool:
    """Whether the loose twin's answer lies within ACCURACY · |q| of the base run's (same verdict): the base run is
    then reported; otherwise the first twin of the tightened sequence is run and reported (module docstring)."""
    return loose["failed"] == base["failed"] and abs(loose["value"] - base["value"]) <= ACCURACY * abs(base["value"])


def not_estimated(reason: str) -> dict:
    return {"estimated": False, "well_conditioned": None, "uncertainty": None, "explanation": reason, "rule": RULE}


def record_of(run, options: dict, cpu_time: float | None = None) -> dict:
    """What the uncertainty record keeps of one run: its options, wall and CPU time, error and answer."""
    record = {"options": options, "wall_time": run.wall_time, "cpu_time": cpu_time, "error": run.error}
    if run.error is None:
        _, failed, value = answer(run)
        record.update(failed=failed, value=value)
    return record


def why_not(solver, params: SailParameters, result) -> str | None:
    """Why no estimate can be made for `result`, or None."""
    if result.error is not None:
        return f"not estimated: the run ended with a solver error ({result.error})"
    if params.boundary == "free" and not params.tip_load and not result.amplitude[0] > 0:
        return "not estimated: the sail starts flat (no amplitude ratio to measure)"
    return why_not_case(solver, params)


def why_not_case(solver, params: SailParameters) -> str | None:
    """Why no estimate can be made for any run of `params` by `solver`, or None."""
    if params.boundary != "free" or params.tip_load:
        return "not estimated: supports and tip loads are validations, not sails"
    if hasattr(solver, "roles") and not solver.roles()["perturbation"]:
        return "not estimated: the solver has no perturbation option for the probe twin (contract rule 8)"
    return None


def probe_level(params: SailParameters) -> float:
    """The probe twin's roughness amplitude (m): PROBE_LEVEL · a₀."""
    return PROBE_LEVEL * params.displacement_scale


def planned(solver, params, settings, options: dict, info: dict, roles: dict, progress: bool) -> tuple[dict, dict]:
    """(twins, loose options): the twins every estimate starts with, by name, as (case, options, Job): the loose
    twin, the probe at the base run's options (its worker at a lower priority where the film twin may stand for
    it) and the film twin at the loose twin's; `info`: the base run's, or
    the options the solver declares it will use (contract rule 10) when the twins start before it ends."""
    loose = twin_options.loosened(options, info, roles)
    twins = {"loose": (params, loose)}
    for name in roles["perturbation"][:1]:
        twins["probe"] = (params, {**options, name: probe_level(params)})
    film_case, _ = film_twin(params)
    if film_case is not None:
        twins["film"] = (film_case, loose)
    jobs = {name: (*twin, twin_job(solver, *twin, settings, progress)) for name, twin in twins.items()}
    for _, _, work in jobs.values():
        work.answer_only = True  # never the run reported: its record and answer are all the estimate reads
    if "probe" in jobs and "film" in jobs and params.model != "sheet":  # the film twin may stand for it
        jobs["probe"][2].niceness = PROBE_NICENESS
    return jobs, loose


def twin_job(solver, case, options: dict, settings, progress: bool) -> twin_workers.Job:
    """The Job of one twin: `solver`'s run of `case` with `options`, keyed by all it depends on."""
    identity = ("twin", getattr(solver, "label", id(solver)), case, settings, progress, options)
    return twin_workers.job(identity, solver.run, case, settings, progress=progress, **options)


def speculation(solver, params, options: dict, progress: bool):
    """For twin_workers.Session.speculation: the settings of a base pass -> (the Jobs of `planned` with the options
    the solver declares it will use standing for its info, the loose options); None when no estimate is made."""
    if why_not_case(solver, params) is not None or not hasattr(solver, "default_options"):
        return None

    def speculate(settings):
        declared = solver.default_options(params, settings, **options)
        info = {name: value for name, value in declared.items() if value is not None}
        twins, loose = planned(solver, params, settings, options, info, solver.roles(), progress)
        return [twin[2] for twin in twins.values()], loose

    return speculate


def twin_runs(solver, params, settings, options, result, roles, progress, base_cpu) -> tuple:
    """(runs, records, order, estimate): the base run's twins (module docstring) by name, and the runs of the
    integration sequence from the loosest to the reported one — ["loose", "base"], or the fallback's ["base",
    (half,) tight] when the loose twin ends with a solver error or did not run looser (twin_options.looser). The
    film twin runs at the options of order[0], then the probe twin at the base run's where the film twin does not
    stand for it (the estimate, or None: film_twin.probe_estimate, the last of the four returned). The twins run
    where twin_workers's open session puts them (worker processes, started before the base run ended where their
    inputs were known; else here)."""
    runs, records = {"base": result}, {"base": record_of(result, options, base_cpu)}
    workers = twin_workers.current()
    twins, loose = planned(solver, params, settings, options, result.info, roles, progress)
    for _, _, work in twins.values():
        workers.submit(work)

    def run(name, case, run_options, work=None):
        runs[name], cpu = workers.take(work or twin_job(solver, case, run_options, settings, progress))
        records[name] = record_of(runs[name], run_options, cpu)

    run("loose", *twins["loose"])
    order, reference = ["loose", "base"], loose
    if runs["loose"].error is not None or not twin_options.looser(runs["loose"].info, result.info):
        order, reference = ["base"], options
        tighter = [
            (name, twin_options.tightened(options, result.info, factor, roles))
            for name, factor in twin_options.sequence(result.info)
        ]
        for _, tight_options in tighter:
            workers.submit(twin_job(solver, params, tight_options, settings, progress))
        for name, tight_options in tighter:
            run(name, params, tight_options)
            order.append(name)
    elif not accurate(records["loose"], records["base"]):
        name, factor = twin_options.sequence(result.info)[0]
        run(name, params, twin_options.tightened(options, result.info, factor, roles))
        order.append(name)
    if "film" in twins:
        if reference is not loose:
            workers.discard(twins["film"][2])
        run("film", twins["film"][0], reference)
    estimate = None
    if "probe" in twins:
        limit = CONDITION_TOL * abs(records["base"]["value"])
        estimate = probe_estimate(params, records, order[0], probe_level(params), limit)
        if estimate is None:
            run("probe", *twins["probe"])
        else:
            workers.discard(twins["probe"][2])
    return runs, records, order, estimate


def assess(
    solver,
    params: SailParameters,
    settings: RunSettings,
    options: dict,
    result,
    progress: bool = False,
    base_cpu: float | None = None,
):
    """The Result to report for `result` (a run of `solver`, a registered contract.Solver or any object with
    its ``run``, with `options`), with its uncertainty record (Result.uncertainty): runs the twins (module
    docstring; the options they change found by their roles, solvers.contract rule 8) and returns the
    reported run (the base run, or the fallback's tightest), or `result` itself when no estimate can be made.
    `progress`: a bar for every twin too; `base_cpu`: the base run's CPU time (s), for the record."""
    reason = why_not(solver, params, result)
    if reason is not None:
        result.uncertainty = not_estimated(reason)
        return result
    quantity, failed, value = answer(result)
    roles = solver.roles() if hasattr(solver, "roles") else contract.registered_roles()
    runs, records, order, estimate = twin_runs(solver, params, settings, options, result, roles, progress, base_cpu)
    total_wall = sum(record["wall_time"] for record in records.values())
    for name, record in records.items():
        if record["error"] is not None and name not in ("film", "loose"):  # the film twin's error is its own record's
            result.uncertainty = {
                **not_estimated(f"not estimated: the {name} twin ended with a solver error ({record['error']})"),
                "quantity": quantity,
                "value": value,
                **records,
            }
            return result
    reported = runs[order[-1]]
    reported.warnings += [w for w in result.warnings if w not in reported.warnings]  # the sampling's notes too
    quantity, failed, value = answer(reported)
    steps = [records[b]["value"] - records[a]["value"] for a, b in zip(order, order[1:])]
    same_verdict = all(records[name]["failed"] == failed for name in order)
    integration = sum(abs(d) for d in steps) if same_verdict else math.inf
    probe, base = records.get("probe"), records["base"]
    if probe is None:
        sensitivity = estimate
    else:
        sensitivity = abs(probe["value"] - base["value"]) if probe["failed"] == base["failed"] else math.inf
    location = sampling_error(reported, settings, failed)
    uncertainty = SAFETY * (integration + sensitivity) + location
    well = sensitivity <= CONDITION_TOL * abs(value)
    if "sampling" in result.info:
        reported.info["sampling"] = {**result.info["sampling"], "location_error": location if failed else None}
    floored = twin_options.held_at_floor
    held = sorted({name for name in order[1:] for name in floored(records[name]["options"], result.info, roles)})
    reported.uncertainty = {
        "estimated": True,
        "quantity": quantity,
        "value": value,
        "uncertainty": uncertainty,
        "integration_error": integration,
        "sensitivity": sensitivity,
        "sensitivity_from": "film" if probe is None else "probe",
        "sampling_error": location,
        "well_conditioned": bool(well),
        "explanation": " ".join(
            part
            for part in (
                explain(params, quantity, value, integration, sensitivity, well, failed, probe is None),
                sampling_note(location, SAFETY * (integration + sensitivity), failed),
                floor_note(held, result.info) if order[0] == "base" else "",
            )
            if part
        ),
        "rule": RULE if order[0] == "loose" else FALLBACK_RULE,
        "film_sensitivity": film_sensitivity(records, film_twin(params)[1], quantity, order[0]),
        "held_at_floor": held if order[0] == "base" else [],
        "reported": order[-1],
        "reference": order[0],
        "cpu_time": sum(record["cpu_time"] or 0.0 for record in records.values()),
        **records,
    }
    reported.wall_time = total_wall
    return reported


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


def explain(params, quantity, value, integration, sensitivity, well, failed, from_film=False) -> str:
    """One paragraph: how sure the run is and, when it is ill-conditioned, why and what would change it; `from_film`:
    the sensitivity is the film twin's estimate (film_twin.probe_estimate), the probe twin not run."""
    what = "failure time" if quantity == "failure_time" else "largest amplitude ratio"
    shortest = 2.0 * params.length / params.n
    if well:
        how = "by about" if from_film else "by"
        why = " (from the film twin's change, its perturbation far larger at every wave)" if from_film else ""
        return (
            f"well-conditioned: a roughness of {PROBE_LEVEL:g} a₀ moves the {what} {how} "
            f"{sensitivity / abs(value):.1g} relative (≤ {CONDITION_TOL:g}){why}; the uncertainty is dominated by "
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
