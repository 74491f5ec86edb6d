"""Lamb & Southwell's spinning-membrane frequencies from Exudyn's runs: `nice python validation/spin_exudyn_modes.py`
(writes validation/spin_exudyn_modes.md from the runs kept in validation/spin_exudyn_modes_rows.json, making the
missing ones; `--only NAME …` makes the named ones again: '9x12', '17x24', '33x48', 'steps 0.0001 1 10' …).

The free disc of validation/spin_spectrum.py part A (R = 0.5 m, h = 1 µm, ρ = 1000 kg/m³, E = 1e9 Pa, ν_p = 0,
Ω = 100 rad/s, unlit), started from its spun equilibrium with the tiles' centres moved along ẑ by seeded random
offsets of RMS 1 µm (the solvers' ``perturbation`` option: every mode is excited, at amplitudes where the
motion is linear), run by Exudyn in the inertial frame for 10 turns (6 on 769 tiles). The tiles' heights
above the centre of mass are the deflections in the turning frame, at each tile's initial polar angle; each
ring's angular harmonic n is a channel, and the matrix pencil of all channels gives the run's frequencies for that n
(analysis.turning_modes). Each (n, s) of the in-house spectrum on the same mesh (analysis.spin_spectrum
.transverse_modes: the in-house solver's linearisation in the turning frame) is paired with the run's pole of
the same n nearest to it.

A. Exudyn against the in-house spectrum on the same mesh, and both against the closed form
   (ω/Ω)² = [3(n + 2s)(n + 2s + 2) − n²]/8 (model.sheet_spin.membrane_disc_frequency), on 49, 193 and 769
   tiles (1729 tiles, where the in-house spectrum meets 1 % for all ten modes, would take Exudyn hours of CPU
   on this machine: its modified Newton renews the Jacobian every few steps as the stiff disc turns); the
   Richardson extrapolation of Exudyn's frequencies from 193 and 769 tiles (second order: the mesh's spacing
   halves, the in-house spectrum's observed order ~1.9); the fit's own spread: the largest change of a paired
   frequency when the pencil's singular-value threshold, 1e-8, is 1e-6, 1e-7 or 1e-9 instead.
B. The step, the numerical damping and the record's length (49 tiles): generalized-α's period error ∝ (ωh)²
   and its damping at ρ∞ < 1, against the same spectrum; the finest mesh's setting (Ωh = 0.02, 6 turns).
C. The membrane limit at this Ω: the in-house spectrum with the bending modulus 100 times smaller (the
   in-plane modulus kept) moves each frequency by less than the tabulated amount.
"""

from __future__ import annotations

import json
import math
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from lightsail_mbs import RunSettings, SailParameters, solve  # noqa: E402
from lightsail_mbs.analysis import spin_spectrum, turning_modes  # noqa: E402
from lightsail_mbs.model import sheet, sheet_spin  # noqa: E402

HERE = Path(__file__).resolve().parent
ROWS = HERE / "spin_exudyn_modes_rows.json"
# (n, ny, Exudyn step h (s), turns): Ωh = 0.01 over 10 turns; 0.02 over 6 on the finest mesh (part B)
MESHES = ((9, 12, 1e-4, 10), (17, 24, 1e-4, 10), (33, 48, 2e-4, 6))
SPIN = 100.0  # rad/s
BELOW = 3.2  # modes below this many Ω
SAMPLE = 4e-4  # s between output samples: Ω Δt = 0.04 (Nyquist at 78 Ω)
SEED = 1e-6  # m, RMS of the tiles' initial offsets along ẑ
RUN = dict(spectral_radius=1.0, newton_rel_tol=1e-12)
STEPS = ((2e-4, 1.0, 10), (1e-4, 1.0, 10), (5e-5, 1.0, 10), (1e-4, 0.9, 10), (1e-4, 0.6, 10), (2e-4, 1.0, 6))
THRESHOLDS = (1e-8, 1e-6, 1e-7, 1e-9)  # the first gives the table; the others the fit's spread
LARGEST_N = 5
DISC = dict(model="sheet", planform="disc", intensity=0.0, defect_amplitude=0.0)


def disc(n: int, ny: int) -> SailParameters:
    return SailParameters(**DISC, n=n, ny=ny).replace(youngs_modulus=1e9, spin_rate=SPIN)


def measure(n: int, ny: int, step: float, turns: int, spectral_radius: float = 1.0) -> dict:
    """One Exudyn run of `turns` turns (module docstring) and its fit: {"modes": [[n, s, ω in-house, ω Exudyn,
    Re λ, weight share, spread]], "steps", "jacobians", "wall"}; spread: the largest change of ω at the other
    THRESHOLDS; each in-house mode (n ≤ LARGEST_N, ω > 0) paired with the run's pole of its n nearest to it."""
    p = disc(n, ny)
    reference = [m for m in spin_spectrum.transverse_modes(p, BELOW * SPIN) if m.frequency > 0]
    settings = RunSettings(
        t_final=SAMPLE * math.ceil(turns * 2 * math.pi / SPIN / SAMPLE), output_interval=SAMPLE, stop_at_failure=False
    )
    start = time.perf_counter()
    options = {**RUN, "step_size": step, "spectral_radius": spectral_radius}
    run = solve(p, "exudyn", settings, uncertainty=False, perturbation=SEED, **options)
    wall = time.perf_counter() - start
    if run.error:
        raise RuntimeError(f"Exudyn run failed: {run.error}")
    fits = [turning_modes.measured_modes(p, run.time, run.tile_centres, LARGEST_N, t) for t in THRESHOLDS]
    modes = []
    for mode in (m for m in reference if m.diameters <= LARGEST_N):
        near = [
            min((m for m in fit if m.diameters == mode.diameters), key=lambda m: abs(m.frequency - mode.frequency))
            for fit in fits
        ]
        spread = max(abs(m.frequency - near[0].frequency) for m in near)
        modes.append([mode.diameters, mode.circles, mode.frequency, near[0].frequency, near[0].growth_rate,
                      near[0].share, spread])  # fmt: skip
    return {"modes": modes, "steps": run.info["steps"], "jacobians": run.info["njev"], "wall": wall}


def summary(record: dict) -> tuple[float, float, float]:
    """(largest |ω_Exudyn/ω_in-house − 1|, largest spread / Ω, largest |Re λ| / Ω) of a measure() record."""
    modes = record["modes"]
    return (
        max(abs(m[3] / m[2] - 1) for m in modes),
        max(m[6] for m in modes) / SPIN,
        max(abs(m[4]) for m in modes) / SPIN,
    )


def part_a(rows: dict) -> list[str]:
    meshes = [(n, ny) for n, ny, _, _ in MESHES]
    head = " | ".join(
        f"{sheet.tile_count(disc(*mesh))} tiles: Exudyn ω/Ω (− in-house; − closed form)" for mesh in meshes
    )
    lines = [f"| n | s | closed form ω/Ω | {head} |", "|---|---|---|" + "---|" * len(meshes)]
    table, notes = {}, []
    for n, ny, step, turns in MESHES:
        record = rows[f"{n}x{ny}"]
        worst, spread, rate = summary(record)
        spread_text = f"≤ {spread:.1e} Ω" if spread else "0 (the four thresholds gave the same poles)"
        notes.append(
            f"{sheet.tile_count(disc(n, ny))} tiles: h = {step:g} s, {turns} turns, {record['steps']} steps, "
            f"{record['jacobians']} Jacobians, {record['wall']:.0f} s wall (loaded machine); largest "
            f"\\|Exudyn − in-house\\| {worst:.1e} relative; fit spread {spread_text}; \\|Re λ\\| ≤ {rate:.1e} Ω"
        )
        for d, c, inhouse, measured, *_ in record["modes"]:
            table.setdefault((d, c), {})[(n, ny)] = (measured, inhouse)
    worst_exact = {}
    for key in sorted(table, key=lambda k: sheet_spin.membrane_disc_frequency(*k)):
        exact = sheet_spin.membrane_disc_frequency(*key)
        cells = []
        for mesh in meshes:
            if mesh not in table[key]:
                cells.append("–")
                continue
            measured, inhouse = table[key][mesh]
            error = measured / SPIN / exact - 1
            worst_exact[mesh] = max(worst_exact.get(mesh, 0.0), abs(error))
            cells.append(f"{measured / SPIN:.5f} ({measured / inhouse - 1:+.1e}; {error:+.2%})")
        lines.append(f"| {key[0]} | {key[1]} | {exact:.5f} | " + " | ".join(cells) + " |")
    largest = " / ".join(f"{worst_exact[mesh]:.2%}" for mesh in meshes)
    tiles = " / ".join(str(sheet.tile_count(disc(*mesh))) for mesh in meshes)
    coarse, fine = meshes[-2:]
    extrapolated = {
        key: (4 * cells[fine][0] - cells[coarse][0]) / 3 / SPIN / sheet_spin.membrane_disc_frequency(*key) - 1
        for key, cells in table.items()
        if coarse in cells and fine in cells
    }
    richardson = ", ".join(f"({n}, {s}) {error:+.2%}" for (n, s), error in extrapolated.items())
    return (
        lines
        + [
            "",
            f"Largest error against the closed form: {largest} on {tiles} tiles. Exudyn's frequencies extrapolated"
            f" (Richardson, second order) from {sheet.tile_count(disc(*coarse))} and {sheet.tile_count(disc(*fine))}"
            f" tiles against the closed form: {richardson}; largest {max(map(abs, extrapolated.values())):.2%}.",
            "",
        ]
        + [f"- {note}" for note in notes]
    )


def part_b(rows: dict) -> list[str]:
    lines = [
        "| h (s) | Ωh | ρ∞ | turns | (1, 0) − Ω (/Ω) | largest \\|Exudyn − in-house\\| (relative) | fit spread / Ω "
        "| largest \\|Re λ\\| / Ω | wall (s) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for h, rho, turns in STEPS:
        record = rows[f"steps {h:g} {rho:g} {turns}"]
        worst, spread, rate = summary(record)
        tilt = next(m[3] for m in record["modes"] if m[:2] == [1, 0]) / SPIN - 1
        lines.append(
            f"| {h:g} | {SPIN * h:g} | {rho:g} | {turns} | {tilt:+.1e} | {worst:.1e} | {spread:.1e} | {rate:.1e} "
            f"| {record['wall']:.0f} |"
        )
    return lines


def part_c() -> list[str]:
    p = disc(*MESHES[0][:2])
    stiff = {(m.diameters, m.circles): m.frequency for m in spin_spectrum.transverse_modes(p, BELOW * SPIN)}
    soft = spin_spectrum.transverse_modes(p.replace(youngs_modulus=1e7, membrane_modulus=1e9), BELOW * SPIN)
    change = max(abs(m.frequency / stiff[(m.diameters, m.circles)] - 1) for m in soft if m.frequency > 0)
    return [
        "49 tiles, E = 1e9 Pa against E = 1e7 Pa for bending (E_m = 1e9 Pa in both): the largest relative change of"
        f" the ten frequencies is {change:.1e}: bending is negligible against the centrifugal tension at"
        f" Ω = {SPIN:g} rad/s."
    ]


def measured_rows(only: list[str]) -> dict:
    """The stored rows (ROWS), with the named ones (all missing ones if none named) measured again."""
    rows = json.loads(ROWS.read_text()) if ROWS.exists() else {}
    jobs = {f"{n}x{ny}": (n, ny, h, turns, 1.0) for n, ny, h, turns in MESHES}
    jobs.update({f"steps {h:g} {rho:g} {turns}": (9, 12, h, turns, rho) for h, rho, turns in STEPS})
    for name, job in jobs.items():
        if name in only or (not only and name not in rows):
            rows[name] = measure(*job)
            print(name, summary(rows[name]), rows[name]["wall"], flush=True)
            stored = json.loads(ROWS.read_text()) if ROWS.exists() else {}  # another process may have added rows
            ROWS.write_text(json.dumps({**stored, name: rows[name]}, indent=1))
    rows = json.loads(ROWS.read_text())
    missing = sorted(set(jobs) - set(rows))
    if missing:
        raise SystemExit(f"rows kept; the report waits for: {', '.join(missing)}")
    return rows


def report(rows: dict) -> str:
    lines = [
        "# Lamb & Southwell's frequencies from Exudyn's runs",
        "",
        "Made by `nice python validation/spin_exudyn_modes.py` (analysis.turning_modes; the script's docstring says"
        " what each part does; its runs are kept in spin_exudyn_modes_rows.json, `--only NAME` measures one again).",
        "",
        f"R = 0.5 m, h = 1 µm, ρ = 1000 kg/m³, E = 1e9 Pa, ν_p = 0, Ω = {SPIN:g} rad/s, unlit; Exudyn (inertial frame),"
        f" ρ∞ = {RUN['spectral_radius']:g}, Newton's relative tolerance {RUN['newton_rel_tol']:g}, sampled every"
        f" {SAMPLE:g} s, started with random tile offsets along ẑ of RMS {SEED:g} m; frequencies in the turning"
        " frame by the matrix pencil of each n's ring harmonics. In each cell: Exudyn's ω/Ω, its relative"
        " difference from the in-house spectrum on the same mesh, and its error against the closed form.",
        "",
        "## A. Exudyn against the in-house spectrum and the closed form",
        "",
        *part_a(rows),
        "",
        "## B. Step, numerical damping and record length (49 tiles)",
        "",
        *part_b(rows),
        "",
        "## C. The membrane limit",
        "",
        *part_c(),
        "",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    names = sys.argv[sys.argv.index("--only") + 1 :] if "--only" in sys.argv else []
    text = report(measured_rows(names))
    (HERE / "spin_exudyn_modes.md").write_text(text)
    print(text)
