"""The sheet against the strip: what a second dimension does to the paper's answers.

The paper's soft-sail values (h = 1 µm, ρ = 1000 kg/m³, I₀ = 0.1 GW/m², a₀ = 10 µm, L = W = 1 m,
perfect mirror), the sheet's defaults (ν_p = 0, E_m = E, bending springs at rest flat as in the paper,
membrane springs at rest in the defect), in-house solver, 6 s runs unless said otherwise; "strip" is
the same model with one tile across (nx × 1: the paper's chain, model.sheet docstring), so strip and
sheet share the discretisation along x. Each stability number is bisected in log space to a bracket
≤ FACTOR wide, on the grids named below for its grid convergence.

1. Critical modulus: E/E_cr,max (Eq. 8, ν = 1.5) above which the sail survives 6 s, for the strip and the
   sheet with the doubly sinusoidal defect ν_x = ν_y = 1.5 and with half a wave across (ν_y = 0.5), with
   the physical membrane E_m = E and with a soft one (E_m = 4.5e9 Pa), on GRIDS; the doubly sinusoidal
   defect with E_m = E also bisected to a bracket ≤ FINE_FACTOR wide on FINE_GRIDS (its grid convergence).
2. Failure time against E (the doubly sinusoidal defect, E_m = E, HORIZON-long runs, on HORIZON_GRIDS):
   the times at which the amplitude reaches 1.5 and 2 a₀ and the growth rate between them, from which
   the boundary of any run length up to HORIZON can be read; and the same times against the tiles per
   half wavelength, for ν_x = ν_y = 1 and 1.5 at RESOLUTION_RATIO E_cr,max (RESOLUTION).
3. Centred Gaussian beam (waist w = 2, 1, 0.5 m, round on the sheet, a line across the strip), 1-D sine,
   E = 4.5e9 Pa: failure time of sheet and strip (10 µs samples).
4. Edge tension (follower, all four edges, N per metre; soft bending E = 4.5e9 Pa = E_m) above which the
   sail survives 6 s, as T/T_cr,max with T_cr,max = ½(2I₀/c)a₀ (Eq. 10 per metre):
   (a) the paper's rule (amplitude doubled) for the strip and the sheet with the 1-D sine, on GRIDS;
   (b) the unlit-twin rule (studies.sheet.twin_boundary: amplitude twice the largest amplitude the unlit
   twin has had so far) for the strip and the doubly sinusoidal sheet, on TENSION_GRIDS: a doubly
   curved defect is not an equilibrium under tension (the membrane force T∇²w ≠ 0), so the unlit sheet
   oscillates with peaks above a₀;
   (c) unlit runs at UNLIT_TENSION T_cr,max: the defect released under tension, and the same sheet with
   initial_equilibrium (rest offsets that make the defect an equilibrium under tension);
   (d) the doubly sinusoidal sheet above its boundary (SCAN_TENSIONS, TENSION_GRIDS): the peaks of the lit
   run and of its twin, and when the lit run reached 2 a₀ (the paper's rule).

Writes sheet_physics_{modulus,horizon,resolution,gaussian,tension,twin,unlit,scan}.csv (each as soon as its study is
done), their summary sheet_physics.md (brackets as uncertainties, sheet against strip),
sheet_physics.png and sheet_physics_failure.png (the doubly sinusoidal sheet at failure) into OUT; the
runs go to the store OUT/store/sheet_physics, so a rerun resumes from every finished run. Quick (a smoke
test): 6 × 6 grids, 1 s runs, factor 3.
Run: lightsail-mbs reproduce --scenario sheet_physics, or python scenarios/sheet_physics.py.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs.paper.common import store_folder
from lightsail_mbs.paper.sheet_physics_report import plot, summary_markdown
from lightsail_mbs.solvers.contract import lookup
from lightsail_mbs.studies import sheet as sheet_study
from lightsail_mbs.studies.sweep import run_cases
from lightsail_mbs.studies.tables import print_table, write_csv

NAME = "sheet_physics"
DOUBLY = "sheet ν_y = 1.5, E_m = E"
GRIDS = (12, 18)
FINE_GRIDS = (18, 24, 30, 36)  # the doubly sinusoidal defect with E_m = E, bisected to FINE_FACTOR
FINE_BRACKET = (0.2, 0.8)  # its first bracket there, E/E_cr,max
FINE_FACTOR = 1.05
FINE = f"{DOUBLY}, bracket ≤ {FINE_FACTOR}"
HORIZON = RunSettings(t_final=12.0)
HORIZON_GRIDS = (12, 18, 24)
HORIZON_RATIOS = (0.3, 0.5, 1.0, 2.0)  # E/E_cr,max
RESOLUTION = {1.0: (8, 12, 18, 24), 1.5: (12, 18, 24, 30)}  # ν_x = ν_y: grids of the resolution study
RESOLUTION_RATIO = 0.5  # its E/E_cr,max (each defect's own E_cr,max, Eq. 8 with its ν)
TENSION_GRIDS = (12, 18, 24)  # the unlit-twin rule
UNLIT_TENSION = 8.0  # T/T_cr,max of the unlit runs
SCAN_TENSIONS = (4.0, 8.0, 32.0, 128.0)  # T/T_cr,max above the boundary: lit and twin peaks
FACTOR = 1.3
SOFT = 4.5e9  # Pa: the paper's soft sail, and the soft membrane
WAISTS = (2.0, 1.0, 0.5)
RUN = RunSettings(t_final=6.0)
GAUSSIAN = RunSettings(t_final=3e-3, output_interval=1e-5)


def base(grid: int, **changes) -> SailParameters:
    return SailParameters(**{"model": "sheet", "n": grid, "ny": grid, "youngs_modulus": SOFT, **changes})


def in_house(params, store_dir, settings, label: str, *, workers, progress, options=None) -> list:
    """(record, Result) of every case of `params`, run by the in-house solver through the store."""
    return run_cases(
        params, store_dir, settings, solver="reduced", workers=workers, label=label, progress=progress, options=options
    )


def modulus_cases(grids) -> dict:
    """{(label, grid): SailParameters} of the critical-modulus boundaries (E set by the bisection)."""
    cases = {}
    for g in grids:
        cases[("strip", g)] = base(g, ny=1)
        for em_label, em in (("E_m = E", None), ("E_m = 4.5e9 Pa", SOFT)):
            cases[(f"sheet ν_y = 1.5, {em_label}", g)] = base(g, defect_mode_y=1.5, membrane_modulus=em)
            cases[(f"sheet ν_y = 0.5, {em_label}", g)] = base(g, defect_mode_y=0.5, membrane_modulus=em)
    return cases


def tension_cases(grids) -> dict:
    """{(label, grid): SailParameters} of the tension boundaries under the paper's rule."""
    cases = {}
    for g in grids:
        cases[("strip", g)] = base(g, ny=1)
        cases[("sheet, 1-D sine", g)] = base(g)
    return cases


def twin_cases(grids) -> dict:
    """{(label, grid): SailParameters} of the tension boundaries under the unlit-twin rule."""
    cases = {}
    for g in grids:
        cases[("strip", g)] = base(g, ny=1)
        cases[("sheet ν_y = 1.5", g)] = base(g, defect_mode_y=1.5)
    return cases


def boundary_rows(found: dict, quantity: str) -> list[dict]:
    rows = []
    for (label, grid), b in found.items():
        lo, hi = b.bracket if b.bracket else (None, None)
        rows.append(
            dict(
                quantity=quantity,
                case=label,
                grid=f"{grid}×{grid if not label.startswith('strip') else 1}",
                status=b.status,
                ratio_low=lo,
                ratio_high=hi,
                ratio=b.value,
                runs=len(b.evaluations),
                monotone=b.monotone,
            )
        )
    return rows


def horizon_rows(grids, ratios, settings, store_dir, workers, progress, mode=1.5, options=None) -> list[dict]:
    """The doubly sinusoidal sheet ν_x = ν_y = mode (E_m = E) at E = ratio·E_cr,max over `settings.t_final`:
    the first output times with amplitude ≥ 1.5 and 2 a₀ and the mean growth rate ln(2/1.5)/(t₂ − t₁.₅)
    between them; `options`: the in-house solver's (rtol)."""
    cases = [
        (g, k, sheet_study.with_ratio(base(g, defect_mode=mode, defect_mode_y=mode), "modulus", k))
        for g in grids
        for k in ratios
    ]
    done = in_house(
        [c[2] for c in cases], store_dir, settings, "sheet horizon", workers=workers, progress=progress, options=options
    )
    rows = []
    for (g, k, _), (record, result) in zip(cases, done):
        times = {}
        for level in (1.5, 2.0):
            past = np.nonzero(result.amplitude >= level * result.amplitude[0])[0] if result is not None else []
            times[level] = float(result.time[past[0]]) if len(past) else None
        rate = None
        if None not in times.values():
            rate = math.log(2.0 / 1.5) / (times[2.0] - times[1.5])
        rows.append(
            dict(
                mode=mode,
                grid=g,
                tiles_per_half_wave=g / (2.0 * mode),
                ratio=k,
                t_1_5=times[1.5],
                t_2=times[2.0],
                growth_rate=rate,
                max_ratio=None if result is None else float(result.amplitude.max() / result.amplitude[0]),
                t_final=settings.t_final,
                error=record.get("error"),
            )
        )
    return rows


def twin_rows(grids, factor, run, store_dir, progress) -> list[dict]:
    """The tension boundaries of twin_cases under the unlit-twin rule, with the twin's and the lit run's
    peaks (in a₀) at both ends of each bracket."""
    rows = []
    for (label, g), p in twin_cases(grids).items():
        found, verdicts = sheet_study.twin_boundary(
            (label, g),
            p,
            "edge_tension",
            store_dir,
            settings=run,
            lo=0.5,
            hi=8.0,
            factor=factor,
            progress=progress,
        )
        lo, hi = found.bracket if found.bracket else (None, None)
        stable = verdicts.get(found.stable_value)
        unstable = verdicts.get(found.unstable_value)
        rows.append(
            dict(
                quantity="T/T_cr,max (unlit-twin rule)",
                case=label,
                grid=f"{g}×{1 if label == 'strip' else g}",
                status=found.status,
                ratio_low=lo,
                ratio_high=hi,
                ratio=found.value,
                runs=2 * len(found.evaluations),
                unlit_peak_stable=stable and stable.unlit_max_ratio,
                lit_peak_stable=stable and stable.lit_max_ratio,
                departure_stable=stable and stable.max_departure,
                unlit_peak_failed=unstable and unstable.unlit_max_ratio,
                failure_time_failed=unstable and unstable.failure_time,
                message=found.message,
            )
        )
    return rows


def scan_rows(grids, tensions, run, store_dir) -> list[dict]:
    """The doubly sinusoidal sheet at `tensions` T_cr,max with its unlit twin (studies.sheet.twin_runs)."""
    rows = []
    for g in grids:
        for k in tensions:
            p = sheet_study.with_ratio(base(g, defect_mode_y=1.5), "edge_tension", k)
            lit, _, v = sheet_study.twin_runs(p, store_dir, run)
            doubled = np.nonzero(lit.amplitude >= 2.0 * lit.amplitude[0])[0]
            rows.append(
                dict(
                    grid=g,
                    tension_ratio=k,
                    lit_peak=v.lit_max_ratio,
                    twin_peak=v.unlit_max_ratio,
                    peak_ratio=v.lit_max_ratio / v.unlit_max_ratio,
                    twin_rule_failure_time=v.failure_time,
                    papers_rule_failure_time=float(lit.time[doubled[0]]) if doubled.size else None,
                )
            )
    return rows


def unlit_rows(grid, tension, run, store_dir, workers, progress) -> list[dict]:
    """Unlit runs at `tension` T_cr,max: the doubly sinusoidal sheet released under tension and with
    initial_equilibrium, and the strip with initial_equilibrium (amplitude peak and when it reached 2 a₀)."""
    cases = [
        ("sheet ν_y = 1.5, released", base(grid, defect_mode_y=1.5)),
        ("sheet ν_y = 1.5, initial_equilibrium", base(grid, defect_mode_y=1.5, initial_equilibrium=True)),
        ("strip, released", base(grid, ny=1)),
        ("strip, initial_equilibrium", base(grid, ny=1, initial_equilibrium=True)),
    ]
    params = [sheet_study.with_ratio(p, "edge_tension", tension).replace(intensity=0.0) for _, p in cases]
    done = in_house(params, store_dir, run, "sheet unlit", workers=workers, progress=progress)
    rows = []
    for (label, p), (record, result) in zip(cases, done):
        rows.append(
            dict(
                case=label,
                grid=f"{grid}×{p.ny}",
                tension_ratio=tension,
                max_ratio=None if result is None else float(result.amplitude.max() / result.amplitude[0]),
                failure_time=None if result is None else result.failure_time,
                error=record.get("error"),
            )
        )
    return rows


def gaussian_rows(grids, store_dir, workers, progress) -> list[dict]:
    cases = [
        (g, w, label, base(g, beam_waist=w, **({"ny": 1} if label == "strip" else {})))
        for g in grids
        for w in WAISTS
        for label in ("strip", "sheet")
    ]
    done = in_house([c[3] for c in cases], store_dir, GAUSSIAN, "sheet gaussian", workers=workers, progress=progress)
    rows = []
    for (g, w, label, _), (record, _) in zip(cases, done):
        rows.append(
            dict(
                grid=g,
                waist_m=w,
                case=label,
                failure_time_ms=None if record.get("failure_time") is None else 1e3 * record["failure_time"],
                error=record.get("error"),
            )
        )
    return rows


TITLES = {
    "twin": "Stabilising edge tension T/T_cr,max, unlit-twin rule, 6 s runs, E = 4.5e9 Pa",
    "unlit": "Unlit sheets under edge tension, 6 s",
    "scan": "Doubly sinusoidal sheet above its tension boundary: lit and twin peaks, 6 s",
    "modulus": "Critical modulus E/E_cr,max, 6 s runs (sheet vs strip)",
    "horizon": "Doubly sinusoidal sheet, E_m = E: failure time against E",
    "resolution": "Doubly sinusoidal sheets, E_m = E: failure time against the tiles per half wavelength",
    "tension": "Stabilising edge tension T/T_cr,max, paper's rule, 6 s runs, E = 4.5e9 Pa",
    "gaussian": "Centred Gaussian beam, 1-D sine, E = 4.5e9 Pa: failure time (ms)",
}


@dataclass(frozen=True)
class Plan:
    """The grids, bisection factors and run lengths of the studies (module docstring)."""

    grids: tuple = GRIDS
    fine_grids: tuple = FINE_GRIDS
    horizon_grids: tuple = HORIZON_GRIDS
    tension_grids: tuple = TENSION_GRIDS
    factor: float = FACTOR
    fine_factor: float = FINE_FACTOR
    run: RunSettings = RUN
    horizon: RunSettings = HORIZON
    resolution: dict = field(default_factory=lambda: dict(RESOLUTION))
    scan_tensions: tuple = SCAN_TENSIONS


# the smoke test: 6 × 6 grids, 1 s runs, factor 3
QUICK = Plan(
    grids=(6,),
    fine_grids=(8,),
    horizon_grids=(6,),
    tension_grids=(6,),
    factor=3.0,
    fine_factor=3.0,
    run=RunSettings(t_final=1.0),
    horizon=RunSettings(t_final=1.0),
    resolution={1.5: (6,)},
    scan_tensions=(8.0,),
)


def compute(plan: Plan = Plan(), *, store_dir, workers=None, progress=True, out=None) -> dict:
    """Every study of `plan` (module docstring); with `out`, each one's CSV is written as soon as it is done."""
    store_dir = Path(store_dir)
    rows = {}

    def done(kind, data):
        rows[kind] = data
        if out is not None:
            write_csv(Path(out) / f"sheet_physics_{kind}.csv", data)
            print_table(TITLES[kind], data)

    run, horizon, grids, tension_grids = plan.run, plan.horizon, plan.grids, plan.tension_grids
    common = dict(settings=run, factor=plan.factor, workers=workers, progress=progress)
    done("twin", twin_rows(tension_grids, plan.factor, run, store_dir, progress))
    done("unlit", unlit_rows(tension_grids[0], UNLIT_TENSION, run, store_dir, workers, progress))
    done("scan", scan_rows(tension_grids, plan.scan_tensions, run, store_dir))
    modulus = sheet_study.stability_boundaries(modulus_cases(grids), "modulus", store_dir, lo=2.0, hi=16.0, **common)
    fine = {(FINE, g): p for (label, g), p in modulus_cases(plan.fine_grids).items() if label == DOUBLY}
    lo, hi = FINE_BRACKET
    fine_common = {**common, "factor": plan.fine_factor}
    modulus.update(sheet_study.stability_boundaries(fine, "modulus", store_dir, lo=lo, hi=hi, **fine_common))
    done("modulus", boundary_rows(modulus, "E/E_cr,max"))
    done("horizon", horizon_rows(plan.horizon_grids, HORIZON_RATIOS, horizon, store_dir, workers, progress))
    done(
        "resolution",
        [
            row
            for mode, mode_grids in plan.resolution.items()
            for row in horizon_rows(mode_grids, (RESOLUTION_RATIO,), horizon, store_dir, workers, progress, mode)
        ],
    )
    tension = sheet_study.stability_boundaries(
        tension_cases(grids), "edge_tension", store_dir, lo=0.5, hi=8.0, **common
    )
    done("tension", boundary_rows(tension, "T/T_cr,max"))
    done("gaussian", gaussian_rows(grids, store_dir, workers, progress))
    return rows


def run(out, *, solver="reduced", workers=None, scheduler=None, quick=False, store=None, progress=True) -> dict:
    out = Path(out)
    plan = QUICK if quick else Plan()
    rows = compute(plan, store_dir=store_folder(out, store, NAME), workers=workers, progress=progress, out=out)
    (out / "sheet_physics.md").write_text(summary_markdown(rows))
    plot(out / "sheet_physics.png", rows, run_length=RUN.t_final)
    failure_frame(out / "sheet_physics_failure.png", quick)
    return rows


LONG_GRIDS = (18, 24)
LONG_RATIOS = (2.0, 3.0, 4.0)  # E/E_cr,max, above the 12 s horizon study's
LONG = RunSettings(t_final=60.0, output_interval=0.01)


def long_horizon(
    out, *, grids=LONG_GRIDS, ratios=LONG_RATIOS, settings=LONG, store=None, workers=None, progress=True
) -> list[dict]:
    """Does a finite E stabilise the doubly sinusoidal sheet (ν_x = ν_y = 1.5, E_m = E) for good? The
    horizon study (2.) at larger E/E_cr,max and over longer runs: when the amplitude reaches 1.5 and 2 a₀,
    the growth rate between them and the largest amplitude ratio. Writes sheet_long_horizon.csv and
    sheet_long_horizon.md into `out`; the runs go to the store OUT/store/sheet_physics (resumable).

    Each case is run again at a ten times tighter rtol: a late runaway that the solver's own error
    seeds moves with the tolerance (columns t_2_rtol10, max_ratio_rtol10, and error_rtol10 when that run
    ended in a solver error, recorded as a result)."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    store_dir = store_folder(out, store, NAME)
    rows = horizon_rows(grids, ratios, settings, store_dir, workers, progress)
    rtol = lookup("reduced", base(grids[0])).default_options(base(grids[0]), settings)["rtol"]
    tight = horizon_rows(grids, ratios, settings, store_dir, workers, progress, options={"rtol": rtol / 10})
    for row, twin in zip(rows, tight, strict=True):
        row.update(t_2_rtol10=twin["t_2"], max_ratio_rtol10=twin["max_ratio"], error_rtol10=twin["error"])
    write_csv(out / "sheet_long_horizon.csv", rows)
    title = (
        f"Doubly sinusoidal sheet, ν = 1.5 × 1.5, E_m = E, {settings.t_final:g} s runs (in-house solver, samples "
        f"every {settings.sample_interval:g} s): when the amplitude reaches 1.5 and 2 a₀"
    )
    print_table(title, rows)
    columns = {
        "grid": "tiles along L and W",
        "ratio": "E/E_cr,max",
        "t_1_5": "t(1.5 a₀) (s)",
        "t_2": "t(2 a₀) (s)",
        "growth_rate": "growth 1.5→2 a₀ (1/s)",
        "max_ratio": "largest a/a₀",
        "t_2_rtol10": "t(2 a₀) at rtol/10 (s)",
        "max_ratio_rtol10": "largest a/a₀ at rtol/10",
        "error_rtol10": "solver error at rtol/10",
    }
    from lightsail_mbs.studies.tables import markdown_table

    (out / "sheet_long_horizon.md").write_text(f"{title}.\n\n{markdown_table(rows, columns)}\n")
    return rows


def failure_frame(path, quick: bool = False) -> Path:
    """The doubly sinusoidal sheet (E = 10 E_cr,max, E_m = 4.5e9 Pa) at failure: map and 3-D view."""
    from lightsail_mbs.model import theory
    from lightsail_mbs.solvers import solve
    from lightsail_mbs.viz.sheet import save_frame

    grid = 6 if quick else GRIDS[0]
    p = base(grid, defect_mode_y=1.5, membrane_modulus=SOFT)
    p = p.replace(youngs_modulus=10.0 * theory.critical_modulus_max(p))
    r = solve(p, "reduced", RunSettings(t_final=1.0 if quick else 6.0), uncertainty=False)
    return save_frame(r, len(r.time) - 1, path)
