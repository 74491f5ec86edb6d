"""Is there a modulus that stabilises the doubly curved sheet for good? The linearised growth rates of the doubly
sinusoidal sheet against E, their symmetry families, and the late failures of the 60 s runs
(validation/sheet_spectrum.md).

The sheet of docs/sheet.md's open question: the paper's soft-sail values, ν_x = ν_y = 1.5, E_m = E, free edges,
in-house solver. Run: ``nice python validation/sheet_spectrum.py [--store DIR]`` (the time-domain runs go through
a store, so a rerun resumes; about an hour on a loaded 2-core machine).

A. Growth rates of the deformation modes (lightsail_mbs.analysis.sheet_spectrum.spectrum: the whole spectrum of
   the solver's ``linearise`` at rest in the initial state, rigid-body motion removed, every mode classified by
   its symmetry family) against E/E_cr,max on GRIDS, beside the late growth rates (1.5 → 2 a₀) of the 60 s runs;
   where the fastest rate, and the defect's own family's (A1), fall below RATE_FLOOR (bisected in log E).
B. How far the linearisation breaks each symmetry (commutator defects) and what that does: the spectrum of each
   family's block of the symmetrised linearisation (family_spectrum) against the whole spectrum.
C. Time domain on each side of the A1 crossing (60 s, both grids), and with a seed that breaks every symmetry
   (the solver's perturbation option) above the A1 crossing and on each side of every family's (the first grid).
D. The 60 s runs of docs/sheet.md (18 × 18 and 24 × 24 tiles, 2–4 E_cr,max): each family's part of the
   deflection (analysis.sheet_spectrum.deflection_families) at the first sample (the seed) and at failure.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from lightsail_mbs import RunSettings, SailParameters  # noqa: E402
from lightsail_mbs.analysis import plane_amplitude  # noqa: E402
from lightsail_mbs.analysis import sheet_spectrum as ss  # noqa: E402
from lightsail_mbs.model import theory  # noqa: E402
from lightsail_mbs.studies.sweep import run_cases  # noqa: E402
from lightsail_mbs.studies.tables import fmt  # noqa: E402

HERE = Path(__file__).resolve().parent
GRIDS = (12, 16)
RATIOS = (0.5, 1.0, 2.0, 3.0, 4.0, 6.0, 10.0)  # E/E_cr,max
RATE_FLOOR = 1e-3  # 1/s: a mode slower than this grows by less than 6 % in 60 s
BRACKET = 1.1  # the crossing is bisected in log E to a bracket this wide
LONG = RunSettings(t_final=60.0, output_interval=0.01)
LONG_RUNS = ((18, 2.0), (18, 3.0), (18, 4.0), (24, 2.0), (24, 3.0), (24, 4.0))  # docs/sheet.md's 60 s runs
SIDES = (1 / 1.5, 1.5)  # the confirming runs: E = E* × these
SEED = 1e-8  # m: RMS of the seeded offsets (the solver's perturbation option) that break every symmetry
BLOCK_GRID, BLOCK_RATIOS = 24, (2.0, 4.0)  # the symmetrised blocks also on a finer grid


def case(grid: int, ratio: float) -> SailParameters:
    p = SailParameters(model="sheet", n=grid, ny=grid, youngs_modulus=4.5e9, defect_mode_y=1.5)
    return p.replace(youngs_modulus=ratio * theory.critical_modulus_max(p))


def spectrum_row(grid: int, ratio: float) -> dict:
    start = time.perf_counter()
    s = ss.spectrum(case(grid, ratio))
    row = {
        "grid": grid,
        "ratio": ratio,
        "rate": s.growth_rate,
        "family": s.family,
        "seconds": time.perf_counter() - start,
    }
    row.update({f"rate_{f}": s.family_rates[f] for f in ss.FAMILIES})
    row.update({f"defect_{g}": s.symmetry_defects[g] for g in ss.GENERATORS})
    print({k: fmt(v) for k, v in row.items()}, flush=True)
    return row


def crossing(grid: int, rows: list[dict], key: str) -> tuple[float, float] | None:
    """The bracket (E/E_cr,max) where rows[key] falls below RATE_FLOOR, bisected in log E to BRACKET."""
    mine = sorted((r for r in rows if r["grid"] == grid), key=lambda r: r["ratio"])
    for a, b in zip(mine, mine[1:]):
        if a[key] > RATE_FLOOR >= b[key]:
            lo, hi = a["ratio"], b["ratio"]
            break
    else:
        return None
    while hi / lo > BRACKET:
        mid = math.sqrt(lo * hi)
        row = spectrum_row(grid, mid)
        rows.append(row)
        lo, hi = (mid, hi) if row[key] > RATE_FLOOR else (lo, mid)
    return lo, hi


def level_time(times: np.ndarray, amplitude: np.ndarray, level: float) -> float | None:
    """The first time the amplitude reaches `level` (linear between samples)."""
    above = np.nonzero(amplitude >= level)[0]
    if not above.size or above[0] == 0:
        return None
    k = above[0]
    return float(
        times[k - 1] + (level - amplitude[k - 1]) / (amplitude[k] - amplitude[k - 1]) * (times[k] - times[k - 1])
    )


def run_row(p: SailParameters, result, label: str) -> dict:
    """Failure time, late growth rate and each family's part of the deflection (in a₀) at the first sample and at
    the end of one run."""
    centres, times = result.tile_centres, result.time
    a0 = plane_amplitude(centres[0])
    amplitude = plane_amplitude(centres) / a0
    parts = ss.deflection_families(p, centres[[1, -1]], a0)
    t15, t2 = level_time(times, amplitude, 1.5), level_time(times, amplitude, 2.0)
    end = {f: parts[f][1] for f in ss.FAMILIES}
    row = {
        "run": label,
        "grid": p.n,
        "ratio": p.youngs_modulus / theory.critical_modulus_max(p),
        "t_2": t2,
        "late_rate": math.log(2 / 1.5) / (t2 - t15) if t15 and t2 else None,
        "max_ratio": float(amplitude.max()),
        "t_end": float(times[-1]),
        "family_end": max(end, key=end.get),
        "error": result.error,
    }
    row.update({f"seed_{f}": parts[f][0] for f in ss.FAMILIES})
    row.update({f"end_{f}": end[f] for f in ss.FAMILIES})
    print({k: fmt(v) for k, v in row.items()}, flush=True)
    return row


def runs(cases: list[tuple[SailParameters, str]], store: Path, options: dict | None = None) -> list[dict]:
    found = run_cases(
        [p for p, _ in cases], store, LONG, solver="reduced", workers=1, label="sheet spectrum", options=options
    )
    return [run_row(p, result, label) for (p, label), (_, result) in zip(cases, found, strict=True)]


def blocks_row(grid: int, ratio: float) -> dict:
    """The fastest rate of each family's block of the symmetrised linearisation (family_spectrum)."""
    modes = ss.family_spectrum(case(grid, ratio))
    row = {"grid": grid, "ratio": ratio}
    row.update({f"block_{f}": modes[f].growth_rate for f in ss.FAMILIES})
    print({k: fmt(v) for k, v in row.items()}, flush=True)
    return row


FAMILY_HEADER = " | ".join(ss.FAMILIES)


def ratio_key(grid: int, ratio: float) -> tuple[int, float]:
    """A run's (grid, E/E_cr,max) as a lookup key: a run's ratio is recomputed from its modulus
    (3 × E_cr,max / E_cr,max = 2.9999999999999996), so it is rounded to 9 digits."""
    return grid, round(ratio, 9)


def table_a(rows: list[dict], long_rows: list[dict]) -> list[str]:
    late = {ratio_key(r["grid"], r["ratio"]): r["late_rate"] for r in long_rows}
    long_ratios = {ratio_key(grid, ratio)[1] for grid, ratio in LONG_RUNS}
    lines = [
        "| E/E_cr,max | grid | fastest rate (1/s) | its family | "
        + FAMILY_HEADER
        + " | late growth 1.5→2 a₀, 60 s runs "
        "(18 × 18 / 24 × 24) |",
        "|---|---|---|---|" + "---|" * len(ss.FAMILIES) + "---|",
    ]
    for r in sorted(rows, key=lambda r: (r["ratio"], r["grid"])):
        runs_ = " / ".join(fmt(late.get(ratio_key(g, r["ratio"])), ".3f") for g in (18, 24))
        lines.append(
            f"| {r['ratio']:.3g} | {r['grid']} | {_rate(r['rate'])} | {r['family']} | "
            + " | ".join(_rate(r[f"rate_{f}"]) for f in ss.FAMILIES)
            + f" | {runs_ if ratio_key(r['grid'], r['ratio'])[1] in long_ratios else ''} |"
        )
    return lines


def _rate(value: float) -> str:
    """A growth rate; at or below RATE_FLOOR: 0 (every mode of the family oscillates or decays)."""
    return "0" if not value > RATE_FLOOR else f"{value:.3f}"


def run_table(rows: list[dict]) -> list[str]:
    lines = [
        "| run | t(2 a₀) (s) | late growth (1/s) | largest a/a₀ | run ends (s) | family at the end | seed (0.01 s): "
        + FAMILY_HEADER
        + " | at the end: "
        + FAMILY_HEADER
        + " |",
        "|---|---|---|---|---|---|" + "---|" * (2 * len(ss.FAMILIES)),
    ]
    for r in rows:
        seeds = " | ".join(f"{r[f'seed_{f}']:.1e}" for f in ss.FAMILIES)
        ends = " | ".join(f"{r[f'end_{f}']:.1e}" for f in ss.FAMILIES)
        lines.append(
            f"| {r['run']} | {fmt(r['t_2'], '.2f')} | {fmt(r['late_rate'], '.3f')} | {r['max_ratio']:.3f} | "
            f"{r['t_end']:.2f}{' (' + r['error'] + ')' if r['error'] else ''} | {r['family_end']} | {seeds} | {ends} |"
        )
    return lines


def crossing_lines(crossings: dict) -> list[str]:
    lines = []
    for (grid, key), bracket in crossings.items():
        which = "the defect's own family A1" if key == "rate_A1" else "every family"
        if bracket is None:
            lines.append(f"* {grid} × {grid}, {which}: no crossing of {RATE_FLOOR:g}/s between the tabulated moduli.")
        else:
            lines.append(
                f"* {grid} × {grid}, {which}: grows at {bracket[0]:.3g} E_cr,max, no rate above {RATE_FLOOR:g}/s at "
                f"{bracket[1]:.3g} E_cr,max (crossing at {math.sqrt(bracket[0] * bracket[1]):.3g} ×÷ "
                f"{math.sqrt(bracket[1] / bracket[0]):.3f})."
            )
    return lines


def block_lines(rows: list[dict], blocks: list[dict]) -> list[str]:
    full = {(r["grid"], r["ratio"]): r for r in rows}
    lines = [
        "| grid | E/E_cr,max | commutator defect M_x / M_y / swap | "
        + " | ".join(f"{f}: whole / symmetrised" for f in ss.FAMILIES)
        + " |",
        "|---|---|---|" + "---|" * len(ss.FAMILIES),
    ]
    for b in blocks:
        r = full.get((b["grid"], b["ratio"]))
        defects = " / ".join(f"{r[f'defect_{g}']:.1e}" for g in ss.GENERATORS) if r else "–"
        cells = [f"{_rate(r[f'rate_{f}']) if r else '–'} / {_rate(b[f'block_{f}'])}" for f in ss.FAMILIES]
        lines.append(f"| {b['grid']} | {b['ratio']:g} | {defects} | " + " | ".join(cells) + " |")
    return lines


def report(rows, crossings, blocks, long_rows, side_rows) -> str:
    return "\n".join(
        [
            "# Growth rates of the doubly sinusoidal sheet against E, by symmetry family",
            "",
            "Generated by `nice python validation/sheet_spectrum.py` (module docstring). The sheet: the paper's",
            "soft-sail values, ν_x = ν_y = 1.5, E_m = E, free edges, in-house solver. Rates are the largest real",
            "parts of the eigenvalues of the deformation modes of the sheet linearised at rest in its initial shape",
            "(lightsail_mbs.analysis.sheet_spectrum), per family; a rate at or below "
            f"{RATE_FLOOR:g}/s is written 0. Families: A1 even in x and y and symmetric under x ↔ y",
            "(the defect's own), A2 even–even antisymmetric, B1 odd–odd symmetric, B2 odd–odd antisymmetric, E odd in",
            "one direction and even in the other.",
            "",
            "## A. The growth rates against E",
            "",
            *table_a(rows, long_rows),
            "",
            "Where the rates fall below the floor (bisected in log E):",
            "",
            *crossing_lines(crossings),
            "",
            "## B. How far the linearisation breaks the symmetries, and what that does",
            "",
            "Commutator defect: ‖G L − L G‖_F / ‖L‖_F of each generator. Rates of the whole linearisation (A) beside",
            "those of each family's block of its symmetrised part (the group average of G L G⁻¹, family_spectrum),",
            "which differ by what the broken symmetry couples across families.",
            "",
            *block_lines(rows, blocks),
            "",
            "## C. Time domain on each side of the crossings (60 s)",
            "",
            "On each side of the A1 crossing from the ideal defect, on both grids; and, seeded (the solver's",
            f"perturbation option: offsets along z of RMS {SEED:g} m, seeded, breaking every symmetry), above the A1",
            "crossing and on each side of every family's.",
            "",
            *run_table(side_rows),
            "",
            "## D. The 60 s runs of docs/sheet.md: which family fails, and its seed",
            "",
            "Each family's part of the deflection (half its peak-to-peak spread, in a₀; A1 without its mean, E",
            "without its rigid tilt) at the first sample after the start and at the end of the run.",
            "",
            *run_table(long_rows),
            "",
        ]
    )


SEEDED = f", seeded {SEED:g} m"


def side_cases(grid: int, bracket, label: str) -> list[tuple[SailParameters, str]]:
    """The cases on each side (SIDES) of a crossing's bracket."""
    if not bracket:
        return []
    middle = math.sqrt(bracket[0] * bracket[1])
    return [(case(grid, middle * s), f"{grid} × {grid}, {middle * s:.3g} E_cr,max{label}") for s in SIDES]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--store", type=Path, default=Path("/tmp/sheet_spectrum_store"), help="the runs' store")
    args = parser.parse_args(argv)
    rows = [spectrum_row(g, r) for g in GRIDS for r in RATIOS]
    crossings = {(g, key): crossing(g, rows, key) for g in GRIDS for key in ("rate_A1", "rate")}
    blocks = [blocks_row(g, r) for g in (*GRIDS, BLOCK_GRID) for r in BLOCK_RATIOS]
    long_rows = runs([(case(g, r), f"{g} × {g}, {r:g} E_cr,max") for g, r in LONG_RUNS], args.store)
    side_rows = runs([c for g in GRIDS for c in side_cases(g, crossings[(g, "rate_A1")], "")], args.store)
    g = GRIDS[0]  # seeded: above the A1 crossing, and on each side of every family's
    seeded = side_cases(g, crossings[(g, "rate_A1")], SEEDED)[1:] + side_cases(g, crossings[(g, "rate")], SEEDED)
    side_rows += runs(seeded, args.store, {"perturbation": SEED})
    text = report(rows, crossings, blocks, long_rows, side_rows)
    (HERE / "sheet_spectrum.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
