"""The Doppler shift inside time-domain runs (docs/journey.md): two chains run to failure from a speed β₀ by both
solvers with the Doppler term (model/terms/doppler.py), against the same chain at the constant sail-frame
intensity I₀ D(β₀) of their start.

**The soft torsion sail at a high intensity.** The paper's soft torsion sail (E = 4.5 GPa, a 1 g/m² mirror,
L = 1 m, n = 30) at I₀ = 1e13 W/m² in the lab frame (1e5 × the paper's 1e8 W/m²), from β₀ = 0.1
(D₀ = 0.818): g₀ = 6.7e7 m/s² (at the lab intensity), failure in 7.35 ms, so that g₀ t_f/c = 1.6e-3 and the
sail-frame intensity falls by r t_f = 2 D₀ g₀ t_f/c = 0.27 % over the run. At the paper's intensity the same
sail fails in about 2 s (2.11 s from rest, docs/journey.md) with g₀ t_f/c ≈ 5e-6: too little to see against
the solvers' error. So far above critical (E/E_cr,max = 1e-7) the chain is ill-posed in n (its fastest wave
sits at the grid scale: analysis.resolvedness), so its t_f is the n = 30 chain's, not a converged one: what is
compared is the two solvers on the same chain and the delay the Doppler term causes.

**The heated journey snapshot.** The journey's Starshot-class TnT chain
(:func:`~lightsail_mbs.paper.journey.starshot_case`, n = 10) at its β = 0.15 snapshot under 40 GW with 1 g
carried, pre-tensioned so that heating to the snapshot's steady temperature (1185 K) leaves half the critical
tension: the case with its tension already relieved by the expansion (N₀ − E h W α_T ⟨ΔT⟩,
:mod:`lightsail_mbs.model.expansion`), lit at the lab's peak intensity, from β₀ = 0.15. The temperature, and
so the tension, stay those of the snapshot during the run (the quasi-steady temperature of docs/journey.md:
over the 43 ms run D changes by 4e-5 of itself and T ∝ D^(1/4) by 1e-5; the time-dependent temperature is
not part of a run). The case's craft is the sail alone (the carried 1 g is not on the TnT chain, as in the
journey's shape runs), so its trajectory's rate is the sail's g₀ = 2.7e5 m/s².

**The estimate.** A shape growing as exp(∫σ dτ) at a rate σ ∝ √I' (the soft sail far above critical) slows as
σ₀ √(D(τ)/D₀) ≈ σ₀ (1 − r τ/2), so it reaches the same amplitude later by the fraction r t_f/4.
"""

from __future__ import annotations

import math

from lightsail_mbs import solvers
from lightsail_mbs.base.constants import SPEED_OF_LIGHT
from lightsail_mbs.base.settings import RunSettings
from lightsail_mbs.model import relativity, theory
from lightsail_mbs.model.cases import paper_case
from lightsail_mbs.paper.journey import starshot_case
from lightsail_mbs.studies.journey import Journey, JourneySettings
from lightsail_mbs.studies.tables import markdown_table

SOLVERS = ("reduced", "exudyn")
HOT = 1e5  # the soft sail's intensity over the paper's
SOFT_BETA = 0.1
SNAPSHOT_BETA = 0.15
JOURNEY = JourneySettings(power=4e10, carried_mass=1e-3)


def soft_case() -> tuple:
    """(case, settings): the soft torsion sail at 1e13 W/m² from β₀ = 0.1, run for the paper's 6 s scaled by the
    growth time ∝ 1/√I₀, sampled every 20 µs."""
    p = paper_case("torsion-soft")
    p = p.replace(intensity=p.intensity * HOT, initial_beta=SOFT_BETA)
    return p, RunSettings(t_final=6.0 / math.sqrt(HOT), output_interval=2e-5)


def heated_case() -> tuple:
    """(case, settings): the heated, tension-relieved β = 0.15 snapshot of the Starshot-class TnT chain, at the
    lab's peak intensity from β₀ = 0.15, run for 20 finite-amplitude times at its start."""
    p = starshot_case(10)
    row = Journey(p, JOURNEY).snapshot(SNAPSHOT_BETA)
    p = p.replace(tension=p.tension - row["tension"] + 0.5 * row["critical"])
    journey = Journey(p, JOURNEY)
    row = journey.snapshot(SNAPSHOT_BETA)
    case = p.replace(tension=row["tension"], intensity=journey.peak, initial_beta=SNAPSHOT_BETA)
    start = case.replace(intensity=row["intensity_sail"], initial_beta=0.0)
    return case, RunSettings(t_final=20.0 * theory.time_scale(start))


CASES = {"soft torsion sail, 1e13 W/m², β₀ = 0.1": soft_case, "heated TnT snapshot, β₀ = 0.15": heated_case}


def measure(p, settings, solver: str) -> dict:
    """One solver on the case with the Doppler term and at its constant start: the failure times (s) with their
    numerical ± (twin runs, solvers.uncertainty), the shift (t_D − t_const)/t_const, and the trajectory's numbers
    over the run (g₀ t_f/c, r t_f and the estimate r t_f/4)."""
    doppler = solvers.solve(p, solver, settings)
    still = solvers.solve(theory.at_start(p), solver, settings)  # the constant intensity I₀ D(β₀)
    rate = 2.0 * float(relativity.intensity_factor(p.initial_beta)) * p.nominal_acceleration / SPEED_OF_LIGHT
    t = doppler.failure_time
    return {
        "solver": solver,
        "failure_time": t,
        "uncertainty": doppler.failure_time_uncertainty,
        "constant_failure_time": still.failure_time,
        "constant_uncertainty": still.failure_time_uncertainty,
        "shift": (t - still.failure_time) / still.failure_time,
        "g0_t_over_c": p.nominal_acceleration * t / SPEED_OF_LIGHT,
        "dimming": rate * t,
        "estimate": rate * t / 4.0,
    }


def measure_case(name: str) -> list[dict]:
    """Both solvers on the named case (CASES)."""
    p, settings = CASES[name]()
    return [{"case": name, **measure(p, settings, solver)} for solver in SOLVERS]


def agreement(rows: list[dict]) -> dict:
    """The two solvers' failure times on one case: their difference relative to the first, and their combined ±
    relative to it."""
    a, b = rows
    return {
        "difference": abs(a["failure_time"] - b["failure_time"]) / a["failure_time"],
        "combined": (a["uncertainty"] + b["uncertainty"]) / a["failure_time"],
    }


def report() -> str:
    """The Markdown table of both cases and solvers, and each case's agreement."""
    rows, lines = [], []
    for name in CASES:
        measured = measure_case(name)
        rows += measured
        agree = agreement(measured)
        lines.append(
            f"- {name}: the solvers' failure times differ by {agree['difference']:.2g} of t_f, their combined ± is "
            f"{agree['combined']:.2g}; the Doppler shifts differ by "
            f"{abs(measured[0]['shift'] - measured[1]['shift']) / measured[0]['shift']:.2g} of the shift."
        )
    columns = {"case": "case", "solver": "solver", "failure_time": "t_f, Doppler (s)", "uncertainty": "±"}
    columns.update(constant_failure_time="t_f at I₀D(β₀) (s)", shift="shift", estimate="r t_f/4")
    columns.update(g0_t_over_c="g₀t_f/c")
    table = [
        {
            **r,
            "failure_time": f"{r['failure_time']:.10g}",
            "constant_failure_time": f"{r['constant_failure_time']:.10g}",
        }
        for r in rows
    ]
    return markdown_table(table, columns) + "\n\n" + "\n".join(lines) + "\n"
