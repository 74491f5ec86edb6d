"""The whole acceleration of a chain as one time-domain run: from rest to the target speed (or to failure), with the
sail's world line, the beam's Doppler dimming, the film's temperature and the tension its frame leaves it all
inside the run (docs/journey.md, "The journey in the time domain").

**The run.** The case of :class:`lightsail_mbs.studies.journey.JourneySettings` becomes one run of the chain: lit
at the lab's peak intensity that puts the power P on it (:func:`~lightsail_mbs.studies.journey.lab_peak_intensity`),
its world line in the state (case field ``integrated_trajectory``, model/world_line.py) with the craft's carried
mass slowing it (``carried_mass``), and, for the TnT chain with axial springs, the film heated inside the run
(``heated``, model/heating.py: the quasi-steady temperature at the sail-frame intensity of each moment, the end
tension N(τ) = N₀ − E h W α_T ⟨ΔT(τ)⟩ and the springs' rest lengths following it). The run lasts the proper
time the closed-form trajectory takes to the target speed, τ(β) = K β/(1 − β), K = c/g₀ (model/relativity.py),
and is sampled `samples` times.

**What the rows say.** Each output sample gives a row with the journey's columns (t, tau, beta, distance,
intensity_sail, acceleration, wavelength, temperature_max, temperature_mean, thermal_strain, tension, critical,
margin) read from the run's own record: the world line for t, β and the Doppler factor D, the heating table the
kernels read for the temperatures and the tension at that D, the paper's criterion at I₀ D for the margin, and the
shape's amplitude (``amplitude``, m, and ``amplitude_ratio`` to the start), and the verdict so far
(studies.journey.with_verdict). The verdict is the run's: the limit temperature exceeded at the first sample above
it, a shape failure at the run's failure time (the failure rule of model/failure.py), with its ± by the package's
uncertainty rule on a rerun over [0, WINDOW × t_f] (:func:`failure_uncertainty`), or the target reached intact.

**Not resumable.** Both solvers start a run from the case's initial shape at rest, so the run is not split into
segments (docs/journey.md says why); the snapshot journey resumes (studies/journey_store.py).

**An optical table with a wavelength axis** is read inside the run at the sail-frame wavelength of its state
(model/terms/radiation.py): its force law and c_n(0), which drives the world line; the run lasts the proper time of
the snapshots' quadrature trajectory. The heat reads its absorptance 1 − R − T at λ' too, as the snapshots do
(model/heating.py), unless the settings give one or the table is lossless.

**What it refuses.** The run's heat uses the material's emissivities, deep space around it and 293.15 K as the
tensioning temperature (model/heating.py): settings that change them are refused, as is a film whose
temperature would lag its steady field by more than QUASI_STEADY_LIMIT, a table at one wavelength, and a laser
wavelength other than the table's.
"""

from __future__ import annotations

import math
from dataclasses import asdict

import numpy as np

from lightsail_mbs.base.formatting import with_uncertainty
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.base.validation import ParameterError, check
from lightsail_mbs.model import expansion, heating, relativity, thermal
from lightsail_mbs.model.parameters import SailParameters
from lightsail_mbs.studies.journey import (
    QUASI_STEADY_LIMIT,
    Film,
    Journey,
    JourneySettings,
    craft_mass,
    lab_peak_intensity,
    notes,
    spectrum_of,
    with_verdict,
)

SAMPLES = 500  # output samples over the run
WINDOW = 1.5  # the failure-time estimate reruns the case over [0, WINDOW × t_f]


def run_case(p: SailParameters, s: JourneySettings) -> SailParameters:
    """The case of the time-domain journey: lit at the lab's peak intensity for the power P, the world line in the
    state with the craft's carried mass, and the film heated inside the run (the TnT chain with axial springs)."""
    _check(p, s)
    changes = dict(
        intensity=lab_peak_intensity(p, s.power),
        carried_mass=s.carried_mass,
        integrated_trajectory=True,
    )
    if p.extensible:
        changes.update(heated=True, heat_absorptance=s.absorptance)
    return p.replace(**changes)


def _check(p: SailParameters, s: JourneySettings) -> None:
    """One line for what the run cannot take (module docstring)."""
    check("model", p.model, p.model != "sheet", "a chain model for a time-domain journey (the sheet: snapshots)")
    if p.optics is not None:
        spectrum = spectrum_of(p)
        check(
            "optics",
            p.optics,
            spectrum is not None,
            "R and α, or a table with a wavelength axis, for a time-domain journey (the run reads it at λ')",
        )
        check(
            "wavelength",
            s.wavelength,
            abs(s.wavelength - spectrum.wavelength) <= 1e-12 * spectrum.wavelength,
            f"the optical table's laser wavelength {spectrum.wavelength:.6g} m in a time-domain journey",
        )
    check("initial_beta", p.initial_beta, p.initial_beta == 0, "0 (the journey starts from rest)")
    for name, default in (("emissivity_front", None), ("emissivity_back", None)):
        check(name, getattr(s, name), getattr(s, name) == default, "the material's in a time-domain journey")
    check("environment", s.environment, s.environment == thermal.DEEP_SPACE, f"{thermal.DEEP_SPACE} K (deep space)")
    check(
        "reference_temperature",
        s.reference_temperature,
        s.reference_temperature == heating.REFERENCE_TEMPERATURE,
        f"{heating.REFERENCE_TEMPERATURE} K in a time-domain journey",
    )


def duration(p: SailParameters, s: JourneySettings) -> float:
    """The proper time (s) the craft takes from rest to the target speed: K β/(1 − β), K = c/g₀, or with a table
    that has a wavelength axis its quadrature (the snapshots' trajectory, which checks the table's range)."""
    return float(Journey(p, s).trajectory.proper_time(s.target_speed))


def rows_of(case: SailParameters, run, film: Film, laser: float) -> list[dict]:
    """The journey's rows from the run's record (module docstring); laser: the laser's wavelength (m)."""
    line = run.info["world_line"]
    factor = np.asarray(line["doppler"])
    sail = case.intensity * factor
    if case.heated:
        heat = heating.at(heating.table(case), case.n, factor)
    else:
        nan = np.full(factor.shape, math.nan)
        heat = {"tension": np.full(factor.shape, case.tension), "temperature_mean": nan, "temperature_max": nan}
    rows = []
    for k in range(run.time.size):
        tension = float(heat["tension"][k]) if case.model == "tnt" else None
        limit = expansion.critical(case, float(sail[k]))
        mean = float(heat["temperature_mean"][k])
        rows.append(
            {
                "t": float(line["lab_time"][k]),
                "tau": float(run.time[k]),
                "beta": float(line["beta"][k]),
                "distance": float(line["distance"][k]),
                "intensity_sail": float(sail[k]),
                "acceleration": case.trajectory_acceleration * float(factor[k]),
                "wavelength": laser * float(relativity.wavelength_factor(line["beta"][k])),
                "temperature_max": float(heat["temperature_max"][k]),
                "temperature_mean": mean,
                "thermal_strain": film.expansion * (mean - heating.REFERENCE_TEMPERATURE),
                "tension": math.nan if tension is None else tension,
                "critical": math.nan if limit is None else limit,
                "margin": _number(expansion.margin(case, float(sail[k]), tension)),
                "amplitude": float(run.amplitude[k]),
                "amplitude_ratio": float(run.amplitude[k] / run.amplitude[0]),
            }
        )
    return rows


def verdict(run, rows: list[dict], film: Film, target: float) -> dict:
    """The run's outcome: 'temperature' (the first sample above T_lim), 'shape' (the run failed: at its failure
    time, located between the samples by solvers.events, with t and β interpolated there), 'intact' (the target
    reached), or 'stopped' (the run ended early: its error)."""
    hot = next((r for r in rows if r["temperature_max"] > film.limit_temperature), None)
    if hot is not None:
        what, kind, row = f"exceeds the limit temperature {film.limit_temperature:.4g} K", "temperature", hot
    elif run.failed:
        what, kind = f"fails by shape (amplitude {run.settings.failure_ratio:g} × its start)", "shape"
        tau = [r["tau"] for r in rows]  # the world line between the samples that bracket the failure time
        row = {
            "tau": run.failure_time,
            **{k: float(np.interp(run.failure_time, tau, [r[k] for r in rows])) for k in ("t", "beta")},
        }
    elif run.error:
        return {"verdict": "stopped", "text": f"the run stopped: {run.error}"}
    else:
        return {"verdict": "intact", "text": f"reaches β = {target:g} intact"}
    moment = f"τ = {row['tau']:.4g} s (t = {row['t']:.4g} s, β = {row['beta']:.4g})"
    return {"verdict": kind, "beta": row["beta"], "t": row["t"], "tau": row["tau"], "text": f"{what} at {moment}"}


def run_time_domain(
    p: SailParameters,
    s: JourneySettings,
    solver: str = "reduced",
    samples: int = SAMPLES,
    progress: bool = False,
    uncertainty: bool = True,
    **options,
) -> dict:
    """The time-domain journey's report: the run's case, the settings, the film, the rows, the verdict (with
    uncertainty, a shape failure's time with its ± from :func:`failure_uncertainty`), the run's summary and the
    thermal lag at the start (the hottest moment)."""
    from lightsail_mbs.analysis.runs import solve

    check("samples", samples, isinstance(samples, int) and samples >= 2, "an integer ≥ 2")
    case = run_case(p, s)
    film = Film.of(p, s)
    lag = heating.lag(case, 1.0) if case.heated else 0.0
    if lag > QUASI_STEADY_LIMIT:
        raise ParameterError(
            f"thickness={p.thickness!r} is invalid: allowed a film whose temperature stays within "
            f"{QUASI_STEADY_LIMIT:g} of its steady field (it would lag by {lag:.3g}): the run's heat is quasi-steady"
        )
    tau = duration(p, s)
    settings = RunSettings(t_final=tau, output_interval=tau / samples)
    run = solve(case, solver, settings, uncertainty=False, progress=progress, **options)
    rows = rows_of(case, run, film, s.wavelength)
    outcome = verdict(run, rows, film, s.target_speed)
    if outcome["verdict"] == "shape" and uncertainty:
        outcome.update(failure_uncertainty(case, solver, run.failure_time, tau, samples, options))
        estimate = with_uncertainty(outcome["failure_time"], outcome["failure_time_uncertainty"])
        outcome["text"] += f"; the failure time {estimate} s by the package's uncertainty rule"
    return {
        "case": case.to_dict(),
        "settings": asdict(s),
        "film": asdict(film),
        "solver": solver,
        "mass": craft_mass(p, s.carried_mass),
        "lab_peak_intensity": case.intensity,
        "snapshots": with_verdict(rows, outcome),
        "verdict": outcome,
        "run": {k: v for k, v in run.summary().items() if k not in ("parameters", "provenance", "info")},
        "wall_time": run.wall_time,
        "method": run.info.get("method"),
        "steps": run.info.get("steps"),
        "thermal_lag": lag,
        "notes": notes(p, film),
    }


def failure_uncertainty(case: SailParameters, solver: str, failure: float, tau: float, samples: int, options) -> dict:
    """The failure time's uncertainty by the package's rule (:mod:`lightsail_mbs.solvers.uncertainty`: the base run
    and its loose, probe and film twins, U = SAFETY (E_int + S) + E_s, the n-error of analysis.n_error folded in
    where the case is well posed in n), on the journey's case rerun over the window [0, WINDOW × t_f] (at most the
    journey's τ) with `samples` output samples: the twins need not cross the rest of the journey. A twin that does
    not fail within the window makes U infinite. Returns the window run's failure time, its ±, the window and the
    rule's one-line explanation; the journey's own failure time is the verdict's τ (the two differ by the
    sampling's effect on the step sequence, within U)."""
    from lightsail_mbs.analysis.runs import solve

    window = min(tau, WINDOW * failure)
    run = solve(case, solver, RunSettings(t_final=window, output_interval=window / samples), **options)
    u = run.uncertainty or {}
    return {
        "failure_time": run.failure_time,
        "failure_time_uncertainty": run.failure_time_uncertainty,
        "uncertainty_window": window,
        "uncertainty_text": u.get("explanation", ""),
        "n_error": (u.get("n_error") or {}).get("reason", "folded in") if "n_error" in u else "not estimated",
    }


def _number(value):
    return math.nan if value is None else float(value)
