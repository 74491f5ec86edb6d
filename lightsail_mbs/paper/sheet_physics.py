"""The sheet against the strip: what a second dimension does to the paper's answers.

The paper's soft-sail values (h = 1 µm, ρ = 1000 kg/m³, I₀ = 0.1 GW/m², a₀ = 10 µm, L = W = 1 m,
perfect mirror), the sheet's defaults (ν_p = 0, E_m = E, bending springs at rest flat as in the paper,
membrane springs at rest in the defect), in-house solver, 6 s runs unless said otherwise; "strip" is
the same model with one tile across (nx × 1: the paper's chain, model.sheet docstring), so strip and
sheet share the discretisation along x. Each stability number is bisected in log space
(studies.sheet.stability_boundaries) to a bracket ≤ FACTOR wide, on two grids (GRIDS) for its grid
convergence.

1. Critical modulus: E/E_cr,max (Eq. 8, ν = 1.5) above which the sail survives 6 s, for the strip and the
   sheet with the doubly sinusoidal defect ν_x = ν_y = 1.5 and with half a wave across (ν_y = 0.5), with
   the physical membrane E_m = E and with a soft one (E_m = 4.5e9 Pa): a doubly curved defect couples
   bending to stretching, so E_m enters (validation/sheet_membrane.md).
2. Centred Gaussian beam (waist w = 2, 1, 0.5 m, round on the sheet, a line across the strip), 1-D sine,
   E = 4.5e9 Pa: failure time of sheet and strip (10 µs samples).
3. Edge tension (follower, all four edges, N per metre; soft bending E = 4.5e9 Pa = E_m) above which the
   sail survives 6 s, as T/T_cr,max with T_cr,max = ½(2I₀/c)a₀ (Eq. 10 per metre), for the strip, the sheet
   with the 1-D sine and the sheet with the doubly sinusoidal defect.

Writes sheet_physics_modulus.csv, sheet_physics_gaussian.csv, sheet_physics_tension.csv, their summary
sheet_physics.md (brackets as uncertainties, sheet against strip), sheet_physics.png and
sheet_physics_failure.png (the doubly sinusoidal sheet at failure) into OUT; the runs go to the store
OUT/store/sheet_physics. Quick (a smoke test): one 6 × 6 grid, 1 s runs, factor 3.
Run: lightsail-mbs reproduce --scenario sheet_physics, or python scenarios/sheet_physics.py.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from lightsail_mbs import RunSettings, SailParameters
from lightsail_mbs.studies import sheet as sheet_study
from lightsail_mbs.studies.sweep import run_cases
from lightsail_mbs.studies.tables import print_table, write_csv
from lightsail_mbs.viz.plots import new_figure, save_figure

NAME = "sheet_physics"
GRIDS = (12, 18)
FACTOR = 1.3
SOFT = 4.5e9  # Pa: the paper's soft sail, and the soft membrane
WAISTS = (2.0, 1.0, 0.5)
RUN = RunSettings(t_final=6.0)
GAUSSIAN = RunSettings(t_final=3e-3, output_interval=1e-5)


def base(grid: int, **changes) -> SailParameters:
    return SailParameters(**{"model": "sheet", "n": grid, "ny": grid, "youngs_modulus": SOFT, **changes})


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
    cases = {}
    for g in grids:
        cases[("strip", g)] = base(g, ny=1)
        cases[("sheet, 1-D sine", g)] = base(g)
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


def gaussian_rows(grids, store_dir, workers, progress) -> list[dict]:
    cases = [
        (g, w, label, base(g, beam_waist=w, **({"ny": 1} if label == "strip" else {})))
        for g in grids
        for w in WAISTS
        for label in ("strip", "sheet")
    ]
    done = run_cases(
        [c[3] for c in cases],
        store_dir,
        GAUSSIAN,
        solver="reduced",
        workers=workers,
        label="sheet gaussian",
        progress=progress,
    )
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


def compute(*, grids=GRIDS, factor=FACTOR, run=RUN, store_dir, workers=None, progress=True) -> dict:
    store_dir = Path(store_dir)
    modulus = sheet_study.stability_boundaries(
        modulus_cases(grids),
        "modulus",
        store_dir,
        settings=run,
        lo=2.0,
        hi=16.0,
        factor=factor,
        workers=workers,
        progress=progress,
    )
    tension = sheet_study.stability_boundaries(
        tension_cases(grids),
        "edge_tension",
        store_dir,
        settings=run,
        lo=0.5,
        hi=8.0,
        factor=factor,
        workers=workers,
        progress=progress,
    )
    return dict(
        modulus=boundary_rows(modulus, "E/E_cr,max"),
        tension=boundary_rows(tension, "T/T_cr,max"),
        gaussian=gaussian_rows(grids, store_dir, workers, progress),
    )


def run(out, *, solver="reduced", workers=None, scheduler=None, quick=False, store=None, progress=True) -> dict:
    out = Path(out)
    options = dict(grids=(6,), factor=3.0, run=RunSettings(t_final=1.0)) if quick else {}
    rows = compute(store_dir=Path(store or out / "store") / NAME, workers=workers, progress=progress, **options)
    for kind, title in (
        ("modulus", "Critical modulus E/E_cr,max, 6 s runs (sheet vs strip)"),
        ("tension", "Stabilising edge tension T/T_cr,max, 6 s runs, E = 4.5e9 Pa"),
        ("gaussian", "Centred Gaussian beam, 1-D sine, E = 4.5e9 Pa: failure time (ms)"),
    ):
        write_csv(out / f"sheet_physics_{kind}.csv", rows[kind])
        print_table(title, rows[kind])
    (out / "sheet_physics.md").write_text(summary_markdown(rows))
    plot(out / "sheet_physics.png", rows)
    failure_frame(out / "sheet_physics_failure.png", quick)
    return rows


def read_rows(out) -> dict:
    """The rows of a finished run back from its CSV files in `out` (numbers as floats, empty as None)."""
    import csv

    def number(text):
        return None if text in ("", None) else float(text)

    rows = {}
    for kind in ("modulus", "tension", "gaussian"):
        with open(Path(out) / f"sheet_physics_{kind}.csv", newline="") as handle:
            rows[kind] = list(csv.DictReader(handle))
    for r in rows["modulus"] + rows["tension"]:
        r.update({k: number(r[k]) for k in ("ratio", "ratio_low", "ratio_high")})
        r["runs"] = int(r["runs"])
    for r in rows["gaussian"]:
        r.update(grid=int(r["grid"]), waist_m=float(r["waist_m"]), failure_time_ms=number(r["failure_time_ms"]))
    return rows


def _bracket(lo, hi) -> str:
    """A bisected boundary as its geometric middle × or ÷ its half-width factor, and the bracket."""
    if lo is None or hi is None:
        return "not bracketed"
    mid, half = math.sqrt(lo * hi), math.sqrt(hi / lo)
    return f"{mid:.3g} (×÷{half:.3f}; {lo:.3g} – {hi:.3g})"


def summary_markdown(rows) -> str:
    """The three studies as Markdown tables: each boundary with its bisection bracket, each sheet's boundary
    against the strip's of the same grid (ratio range from the two brackets), and the Gaussian failure
    times of sheet and strip with their ratio, on every grid."""
    lines = ["# The sheet against the strip", ""]
    for kind, quantity in (("modulus", "E_stable / E_cr,max"), ("tension", "T_stable / T_cr,max")):
        data = rows[kind]
        lines += [
            f"## {'Critical modulus' if kind == 'modulus' else 'Stabilising edge tension'}: {quantity}",
            "",
            f"| case | grid | {quantity}: middle (×÷ half-width; bracket) | sheet / strip (range) | runs |",
            "|---|---|---|---|---|",
        ]
        for r in data:
            grid = r["grid"].split("×")[0]
            strip = next((q for q in data if q["case"] == "strip" and q["grid"].split("×")[0] == grid), None)
            versus = "–"
            if r["case"] != "strip" and strip and None not in (r["ratio_low"], r["ratio_high"], strip["ratio_low"]):
                lo, hi = r["ratio_low"] / strip["ratio_high"], r["ratio_high"] / strip["ratio_low"]
                versus = f"{math.sqrt(lo * hi):.3g} ({lo:.3g} – {hi:.3g})"
            lines.append(
                f"| {r['case']} | {r['grid']} | {_bracket(r['ratio_low'], r['ratio_high'])} | {versus} | {r['runs']} |"
            )
        lines.append("")
    lines += [
        "## Centred Gaussian beam, 1-D sine, E = 4.5e9 Pa: failure time",
        "",
        "| grid | waist w (m) | strip (ms) | sheet (ms) | sheet / strip |",
        "|---|---|---|---|---|",
    ]
    g = rows["gaussian"]
    for grid in sorted({r["grid"] for r in g}):
        for w in sorted({r["waist_m"] for r in g}, reverse=True):
            pick = {r["case"]: r["failure_time_ms"] for r in g if r["grid"] == grid and r["waist_m"] == w}
            strip, sheet = pick.get("strip"), pick.get("sheet")
            ratio = f"{sheet / strip:.3f}" if strip and sheet else "–"
            lines.append(
                f"| {grid}×{grid} | {w:g} | {'–' if strip is None else f'{strip:.4f}'} | "
                f"{'–' if sheet is None else f'{sheet:.4f}'} | {ratio} |"
            )
    lines.append("")
    return "\n".join(lines)


def plot(path, rows) -> Path:
    """Left: stability ratios with their brackets per case and grid; right: Gaussian failure times."""
    fig, ax = new_figure(1, 3, size=(14.0, 4.2))
    for k, kind in enumerate(("modulus", "tension")):
        data = rows[kind]
        labels = list(dict.fromkeys(r["case"] for r in data))
        grids = list(dict.fromkeys(r["grid"].split("×")[0] for r in data))
        for j, g in enumerate(grids):
            mine = [next(r for r in data if r["case"] == c and r["grid"].split("×")[0] == g) for c in labels]
            y = np.arange(len(labels)) + 0.2 * (j - 0.5)
            mid = np.array([r["ratio"] or np.nan for r in mine])
            lo = np.array([r["ratio_low"] or np.nan for r in mine])
            hi = np.array([r["ratio_high"] or np.nan for r in mine])
            ax[0, k].errorbar(mid, y, xerr=[mid - lo, hi - mid], fmt="o", capsize=3, label=f"{g} tiles along L")
        ax[0, k].set_yticks(np.arange(len(labels)), labels, fontsize=7)
        if any(r["ratio"] for r in data):  # a log axis needs a bracketed boundary
            ax[0, k].set_xscale("log")
        ax[0, k].set_xlabel("E_stable / E_cr,max" if kind == "modulus" else "T_stable / T_cr,max")
        ax[0, k].legend(fontsize=7)
    g = [r for r in rows["gaussian"]]
    for grid in sorted({r["grid"] for r in g}):
        for label, style in (("strip", "s--"), ("sheet", "o-")):
            mine = [r for r in g if r["grid"] == grid and r["case"] == label]
            ax[0, 2].plot(
                [r["waist_m"] for r in mine],
                [r["failure_time_ms"] or np.nan for r in mine],
                style,
                label=f"{label}, {grid} tiles along L",
            )
    ax[0, 2].set_xlabel("beam waist w (m)")
    ax[0, 2].set_ylabel("failure time (ms)")
    ax[0, 2].legend(fontsize=7)
    fig.suptitle("The sheet against the strip (in-house solver, 6 s runs; brackets: bisection)", fontsize=10)
    return save_figure(fig, path)


def failure_frame(path, quick: bool = False) -> Path:
    """The doubly sinusoidal sheet (E = 10 E_cr,max, E_m = 4.5e9 Pa) at failure: map and 3-D view."""
    from lightsail_mbs.model import theory
    from lightsail_mbs.solvers import solve
    from lightsail_mbs.viz.sheet import save_frame

    grid = 6 if quick else GRIDS[0]
    p = base(grid, defect_mode_y=1.5, membrane_modulus=SOFT)
    p = p.replace(youngs_modulus=10.0 * theory.critical_modulus_max(p))
    r = solve(p, "reduced", RunSettings(t_final=1.0 if quick else 6.0))
    return save_frame(r, len(r.time) - 1, path)
