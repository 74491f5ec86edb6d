"""The spinning sheet's spectrum in its turning frame: `nice python validation/spin_spectrum.py` (writes
validation/spin_spectrum.md; ~25 min of one core).

A. Lamb & Southwell (1921): the transverse frequencies of a free membrane disc spinning at Ω (R = 0.5 m,
   h = 1 µm, E = 1e9 Pa: bending ~1e-8 of the centrifugal stiffness) in its turning frame, from the transverse
   block of the in-house solver's ``linearise_rotating`` (analysis.spin_spectrum.transverse_modes), against
   (ω/Ω)² = [3(n + 2s)(n + 2s + 2) − n²]/8 (model.sheet_spin.membrane_disc_frequency) on four polar meshes.
B. Spin against tension: the paper's soft sail (h = 1 µm, ρ = 1000 kg/m³, a₀ = 10 µm, ν_x = ν_y = 1.5, square
   and disc, 8 × 8 and 9 × 12 tiles) at E and I₀ of a small grid: T_cr,max per metre of edge (Eq. 10), the spin rate
   Ω_T whose centrifugal membrane force at the centre, 3ρhΩ²R²/8, equals it, the sheet's measured critical
   edge tension (scenarios/figures/sheet_physics.md, unlit-twin rule) and the fastest growth rate of the
   deformation spectrum in the turning frame at Ω = 0, Ω_T and 10 Ω_T with its mode's share of kinetic energy
   in the tiles' tilts.
C. The spectrum against a time-domain run: the same sail (square, 6 × 6 tiles, lit and unlit) spun at 10 rad/s
   in the exact spun equilibrium of its curved shape (initial_equilibrium, which has the tile-tilt mode of
   part D), 1 s in the in-house solver; the growth rate of the amplitude's departure from its start
   (a − a(0), least squares of its logarithm over the last half) against the spectrum's fastest Re λ.
D. Where the fast mode of the tiles' tilts came from: part C's unlit sail with one change at a time (defect,
   film thickness, bending springs and their rest state, the membrane's rest state and modulus, grid, light),
   in the flat sheet's centrifugal stress (the model's spun state) and in the exact spun equilibrium of the
   curved shape, with the most compressed tile's principal membrane force (model.sheet_spin.
   tile_membrane_forces); the same against the grid, with the rate of a uniformly compressed zig-zag of
   tiles, √(12P/(ρh a²)); and the unlit tensioned sheet (8 T_cr,max) with and without initial_equilibrium.
E. The critical spin rate for shape stability (analysis.spin_spectrum.critical_spin: the smallest spin from
   which the fastest deformation grows slower than ln 2/(6 s) at every scanned faster spin up to 32 Ω_T) of
   the paper's soft sail (square and disc, two grids, E and I₀ of part B), the membrane force it implies
   (at the centre, 3ρhΩ²R²/8, and the area mean of the flat sheet's isotropic force (N₁ + N₂)/2) against
   T_cr,max and the measured critical edge tension; and 6 s runs with their unlit twins (the unlit-twin rule)
   at half and twice the bracket.
"""

from __future__ import annotations

import math
import os
import re
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from lightsail_mbs import RunSettings, SailParameters, solve  # noqa: E402
from lightsail_mbs.analysis import spin_spectrum  # noqa: E402
from lightsail_mbs.model import failure, sheet, sheet_spin, theory  # noqa: E402
from lightsail_mbs.studies.sheet import TWIN_STOP_RATIO  # noqa: E402

HERE = Path(__file__).resolve().parent
DISC_MESHES = ((9, 12), (17, 24), (33, 48), (49, 72))
SPIN = 100.0  # rad/s, part A
BELOW = 3.2  # part A: modes below this many Ω
SOFT = dict(model="sheet", youngs_modulus=4.5e9, defect_mode_y=1.5)
GRID = 8
MODULI = (4.5e9, 4.5e10)
INTENSITIES = (1e8, 1e9)


def lamb_southwell() -> list[str]:
    found = {}
    for n, ny in DISC_MESHES:
        p = SailParameters(model="sheet", planform="disc", n=n, ny=ny, intensity=0.0, defect_amplitude=0.0)
        p = p.replace(youngs_modulus=1e9, spin_rate=SPIN)
        start = time.perf_counter()
        modes = spin_spectrum.transverse_modes(p, BELOW * SPIN)
        found[(n, ny)] = ({(m.diameters, m.circles): m for m in modes}, time.perf_counter() - start)
        print(n, ny, [(m.diameters, m.circles, round(m.frequency / SPIN, 4)) for m in modes], flush=True)
    keys = sorted(
        {k for table, _ in found.values() for k in table if sheet_spin.membrane_disc_frequency(*k) < BELOW},
        key=lambda k: sheet_spin.membrane_disc_frequency(*k),
    )
    head = " | ".join(f"{n} × {ny}: ω/Ω (error)" for n, ny in DISC_MESHES)
    lines = [f"| n | s | closed form ω/Ω | {head} |", "|---|---|---|" + "---|" * len(DISC_MESHES)]
    for key in keys:
        exact = sheet_spin.membrane_disc_frequency(*key)
        cells = []
        for mesh in DISC_MESHES:
            mode = found[mesh][0].get(key)
            if mode is None:
                cells.append("–")
            else:
                ratio = mode.frequency / SPIN
                cells.append(f"{ratio:.4f} ({ratio / exact - 1:+.2%})" if exact else f"{ratio:.1e}")
        lines.append(f"| {key[0]} | {key[1]} | {exact:.4f} | " + " | ".join(cells) + " |")
    rates = " · ".join(
        f"{n} × {ny}: {max(abs(m.growth_rate) for m in found[(n, ny)][0].values()) / SPIN:.1e} Ω "
        f"({found[(n, ny)][1]:.0f} s)"
        for n, ny in DISC_MESHES
    )
    return lines + ["", f"Largest |Re λ| of these modes (and the time to compute each mesh): {rates}."]


def measured_tension() -> str:
    """The sheet's critical edge tension rows (unlit-twin rule) of the committed sheet_physics report."""
    text = (HERE.parent / "scenarios" / "figures" / "sheet_physics.md").read_text()
    rows = re.findall(r"^\| sheet ν_y = 1\.5 \| (\d+×\d+) \| ([\d.]+) \(", text, flags=re.M)
    return ", ".join(f"{value} on {grid}" for grid, value in rows)


def spin_against_tension() -> list[str]:
    lines = [
        "| planform | E (Pa) | I₀ (W/m²) | T_cr,max (N/m) | Ω_T (rad/s) | fastest Re λ at Ω = 0, Ω_T, 10 Ω_T (1/s) |"
        " its tilt share | fastest shape mode (tilt share < ½) at Ω = 0, Ω_T, 10 Ω_T (1/s) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for planform, mesh in (("rectangle", dict(n=GRID, ny=GRID)), ("disc", dict(n=9, ny=12))):
        for modulus in MODULI:
            for intensity in INTENSITIES:
                p = SailParameters(**SOFT, planform=planform, **mesh).replace(
                    youngs_modulus=modulus, intensity=intensity
                )
                tension = theory.critical_tension_max(p) / p.width
                radius = 0.5 * p.length
                omega_t = math.sqrt(8.0 * tension / (3.0 * p.density * p.thickness * radius**2))
                spectra = [
                    spin_spectrum.rotating_spectrum(p.replace(spin_rate=w)) for w in (0.0, omega_t, 10 * omega_t)
                ]
                lines.append(
                    f"| {planform} | {modulus:.2g} | {intensity:.2g} | {tension:.3g} | {omega_t:.3g} | "
                    + ", ".join(f"{s.growth_rate:.3g}" for s in spectra)
                    + " | "
                    + ", ".join(f"{s.tilt_share:.2f}" for s in spectra)
                    + " | "
                    + ", ".join(f"{s.shape_rate:.3g}" for s in spectra)
                    + " |"
                )
                print(lines[-1], flush=True)
    return lines


def time_domain() -> list[str]:
    lines = [
        "| light | spectrum's fastest Re λ (1/s) | tilt share | run's growth rate (1/s) | run's error |",
        "|---|---|---|---|---|",
    ]
    for intensity in (0.0, 1e8):
        p = SailParameters(**SOFT, planform="rectangle", n=6, ny=6, intensity=intensity, initial_equilibrium=True)
        p = p.replace(spin_rate=10.0)
        s = spin_spectrum.rotating_spectrum(p)
        run = solve(p, "reduced", RunSettings(t_final=1.0, output_interval=0.02), uncertainty=False)
        departure = np.abs(failure.plane_amplitude(run.tile_centres) - failure.plane_amplitude(run.tile_centres[0]))
        late = np.asarray(run.time) >= 0.5
        rate = np.polyfit(np.asarray(run.time)[late], np.log(departure[late]), 1)[0]
        light = "unlit" if intensity == 0 else f"I₀ = {intensity:.2g} W/m²"
        lines.append(f"| {light} | {s.growth_rate:.4g} | {s.tilt_share:.2f} | {rate:.4g} | {run.error or '–'} |")
        print(lines[-1], flush=True)
    return lines + ["", *released()]


def released() -> list[str]:
    """The same unlit sail in the model's spun state (the flat sheet's stress), 1 s in both solvers."""
    lines = [
        "The same unlit sail in the model's spun state (the flat sheet's centrifugal stress, the defect released):",
        "",
        "| solver | spectrum's fastest Re λ (1/s) | run's amplitude / a₀: least, largest, at 1 s | run's error |",
        "|---|---|---|---|",
    ]
    p = SailParameters(**SOFT, planform="rectangle", n=6, ny=6, intensity=0.0).replace(spin_rate=10.0)
    rate = spin_spectrum.rotating_spectrum(p).growth_rate
    for solver, options in (("reduced", {}), ("exudyn", {"step_size": 1e-3})):
        run = solve(p, solver, RunSettings(t_final=1.0, output_interval=0.02), uncertainty=False, **options)
        a = np.asarray(run.amplitude) / run.amplitude[0]
        lines.append(f"| {solver} | {rate:.3g} | {a.min():.3g}, {a.max():.3g}, {a[-1]:.3g} | {run.error or '–'} |")
        print(lines[-1], flush=True)
    return lines


DIAGNOSIS = (
    ("as part C (a₀ = 10 µm, doubly sinusoidal)", {}),
    ("flat sail (a₀ = 0)", {"defect_amplitude": 0.0}),
    ("a₀ = 3 µm", {"defect_amplitude": 3e-6}),
    ("1-D sine (ν_y: none)", {"defect_mode_y": None}),
    ("film 10 µm thick", {"thickness": 1e-5}),
    ("bending springs off", {"bending": False}),
    ("bending springs at rest in the initial shape", {"bending_reference": "initial"}),
    ("membrane springs at rest flat", {"membrane_reference": "flat"}),
    ("E_m = 4.5e11 Pa", {"membrane_modulus": 4.5e11}),
    ("8 × 8 tiles", {"n": 8, "ny": 8}),
    ("8 × 8 tiles, lit", {"n": 8, "ny": 8, "intensity": 1e8}),
    (
        "8 × 8 tiles, lit, membrane springs at rest flat",
        {"n": 8, "ny": 8, "intensity": 1e8, "membrane_reference": "flat"},
    ),
)
DIAGNOSIS_GRIDS = (4, 5, 6, 8, 10, 12, 16)
TENSION = 8.0  # T_cr,max: the unlit tensioned sheet of docs/sheet.md's unlit-twin rule


def _least_force(p: SailParameters) -> float:
    """The most compressed tile's smaller principal membrane force (N/m) of p in its initial shape."""
    centres, quaternions = sheet.initial_quaternions(p)
    return float(sheet_spin.tile_membrane_forces(p, sheet.connectors(p), centres, quaternions)[:, 0].min())


def _centre_force(p: SailParameters) -> float:
    """3ρhΩ²R²/8 (N/m): the centrifugal membrane force at the centre of a free disc of radius L/2."""
    return 3.0 / 8.0 * p.density * p.thickness * p.spin_rate**2 * (0.5 * p.length) ** 2


def _both_states(p: SailParameters) -> str:
    """Cells: growth rate / Ω, tilt share and least principal force / centre force in the flat sheet's stress
    and in the exact spun equilibrium."""
    cells = []
    for exact in (False, True):
        q = p.replace(initial_equilibrium=exact)
        s = spin_spectrum.rotating_spectrum(q)
        cells.append(
            f"{s.growth_rate / p.spin_rate:.3g} | {s.tilt_share:.2f} | {_least_force(q) / _centre_force(q):.3g}"
        )
    return " | ".join(cells)


def diagnosis() -> list[str]:
    head = "fastest Re λ / Ω | tilt share | least N / N_c"
    lines = [
        "N: the principal membrane forces of a tile (virial of its springs' forces), N_c = 3ρhΩ²R²/8 the",
        "centrifugal force at a disc's centre. Flat stress: the model's spun state; exact: initial_equilibrium.",
        "",
        f"| change (square, 6 × 6 tiles, unlit, Ω = 10 rad/s unless said) | flat stress: {head} | exact: {head} |",
        "|---|---|---|---|---|---|---|",
    ]
    base = SailParameters(**SOFT, planform="rectangle", n=6, ny=6, intensity=0.0, spin_rate=10.0)
    for label, changes in DIAGNOSIS:
        lines.append(f"| {label} | {_both_states(base.replace(**changes))} |")
        print(lines[-1], flush=True)
    lines += [
        "",
        "Against the grid (part C's unlit sail, n × n tiles); P = −least N of the exact state, a = L/n:",
        "",
        f"| n | flat stress: {head} | exact: {head} | √(12P/(ρh a²)) / Ω |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for n in DIAGNOSIS_GRIDS:
        p = base.replace(n=n, ny=n)
        compression = max(-_least_force(p.replace(initial_equilibrium=True)), 0.0)
        zigzag = math.sqrt(12.0 * compression / (p.density * p.thickness * (p.length / n) ** 2)) / p.spin_rate
        lines.append(f"| {n} | {_both_states(p)} | {zigzag:.3g} |")
        print(lines[-1], flush=True)
    return lines + ["", *tensioned()]


def tensioned() -> list[str]:
    lines = [
        f"The unlit sheet under the edge tension {TENSION:g} T_cr,max (no spin; I₀ = 1e8 W/m² sets T_cr,max):",
        "",
        "| n × n | initial_equilibrium | fastest Re λ (1/s) | tilt share | least N / T |",
        "|---|---|---|---|---|",
    ]
    for n in (8, 12):
        p = SailParameters(**SOFT, planform="rectangle", n=n, ny=n, intensity=1e8)
        p = p.replace(intensity=0.0, edge_tension=TENSION * theory.critical_tension_max(p) / p.width)
        for exact in (False, True):
            q = p.replace(initial_equilibrium=exact)
            s = spin_spectrum.rotating_spectrum(q)
            least = _least_force(q) / q.edge_tension
            lines.append(f"| {n} × {n} | {exact} | {s.growth_rate:.3g} | {s.tilt_share:.2f} | {least:.3g} |")
            print(lines[-1], flush=True)
    return lines


CRITICAL_MESHES = {"rectangle": ((8, 8), (12, 12)), "disc": ((9, 12), (13, 18))}
SCAN = (0.25, 32.0)  # the spins scanned, × Ω_T
TWIN_SPINS = (0.5, 2.0)  # × the critical bracket's middle: the 6 s runs with their unlit twins


def _mean_force(p: SailParameters) -> float:
    """The area mean of (N₁ + N₂)/2 (N/m) of the flat sheet of p (its centrifugal stress)."""
    flat = p.replace(defect_amplitude=0.0)
    centres, quaternions = sheet.initial_quaternions(flat)
    forces = sheet_spin.tile_membrane_forces(flat, sheet.connectors(flat), centres, quaternions)
    areas = sheet.Tiles.of(flat).masses
    return float(areas @ forces.mean(axis=1) / areas.sum())


def critical_spins() -> tuple[list[str], SailParameters]:
    lines = [
        "| planform | tiles | E (Pa) | I₀ (W/m²) | Ω_T (rad/s) | Ω_cr (rad/s) | Ω_cr / Ω_T | N_c(Ω_cr) / T_cr,max |"
        " mean (N₁ + N₂)/2 at Ω_cr / T_cr,max | Λ(Ω_cr) | fastest Re λ at Ω = 0 (1/s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    first = None
    for planform, meshes in CRITICAL_MESHES.items():
        for n, ny in meshes:
            for modulus in MODULI:
                for intensity in INTENSITIES:
                    if (n, ny) != meshes[0] and modulus != MODULI[0]:
                        continue  # the finer mesh at the paper's soft modulus only
                    p = SailParameters(**SOFT, planform=planform, n=n, ny=ny).replace(
                        youngs_modulus=modulus, intensity=intensity
                    )
                    tension = theory.critical_tension_max(p) / p.width
                    omega_t = math.sqrt(8.0 * tension / (3.0 * p.density * p.thickness * (0.5 * p.length) ** 2))
                    low, high = spin_spectrum.critical_spin(p, (SCAN[0] * omega_t, SCAN[1] * omega_t))
                    middle = math.sqrt(low * high)
                    spun = p.replace(spin_rate=middle)
                    slope = p.defect_amplitude * 2.0 * math.pi * p.defect_mode / p.length
                    shell = (
                        p.density * middle**2 * (0.5 * p.length) ** 2 / (sheet.Tiles.of(p).membrane_modulus * slope**2)
                    )
                    rest = spin_spectrum.rotating_spectrum(p).growth_rate
                    lines.append(
                        f"| {planform} | {n} × {ny} | {modulus:.2g} | {intensity:.2g} | {omega_t:.3g} | "
                        f"{low:.3g}–{high:.3g} | {middle / omega_t:.3g} | {_centre_force(spun) / tension:.3g} | "
                        f"{_mean_force(spun) / tension:.3g} | {shell:.2g} | {rest:.3g} |"
                    )
                    print(lines[-1], flush=True)
                    first = spun if first is None else first
    return lines, first


def twin_checks(p: SailParameters) -> list[str]:
    lines = [
        "6 s runs of the first row's sail (in-house solver) with their unlit twins: the lit sail fails where",
        "a(t) ≥ 2 max_{s ≤ t} a_twin(s) (docs: sheet, the unlit-twin rule; the twin's envelope at the lit samples):",
        "",
        "| Ω (rad/s) | spectrum's fastest Re λ (1/s) | lit peak / a₀ | twin's peak / a₀ | fails at (s) |",
        "|---|---|---|---|---|",
    ]
    settings = RunSettings(t_final=6.0, output_interval=0.02, failure_ratio=TWIN_STOP_RATIO)
    for factor in TWIN_SPINS:
        q = p.replace(spin_rate=factor * p.spin_rate)
        lit, twin = (solve(c, "reduced", settings, uncertainty=False) for c in (q, q.replace(intensity=0.0)))
        a0 = lit.amplitude[0]
        envelope = np.interp(lit.time, twin.time, np.maximum.accumulate(twin.amplitude))
        past = np.nonzero(np.asarray(lit.amplitude) >= 2.0 * envelope)[0]
        when = f"{lit.time[past[0]]:.2f}" if past.size else "–"
        rate = spin_spectrum.rotating_spectrum(q).growth_rate
        lines.append(
            f"| {q.spin_rate:.3g} | {rate:.3g} | {max(lit.amplitude) / a0:.3g} | {max(twin.amplitude) / a0:.3g} "
            f"| {when} |"
        )
        print(lines[-1], flush=True)
    return lines


def report() -> str:
    critical_table, first = critical_spins()
    lines = [
        "# The spinning sheet's spectrum in its turning frame",
        "",
        "Made by `nice python validation/spin_spectrum.py` (analysis.spin_spectrum, the in-house solver's",
        "``linearise_rotating``; the script's docstring says what each part does).",
        "",
        "## A. Transverse frequencies of a spinning free membrane disc (Lamb & Southwell 1921)",
        "",
        f"R = 0.5 m, h = 1 µm, ρ = 1000 kg/m³, E = 1e9 Pa, Ω = {SPIN:g} rad/s, in the turning frame.",
        "",
        *lamb_southwell(),
        "",
        "## B. Spin against edge tension (the paper's soft sail, ν_x = ν_y = 1.5)",
        "",
        "Ω_T: the spin whose centrifugal membrane force at the centre, 3ρhΩ²R²/8, equals T_cr,max (Eq. 10, per",
        "metre of edge). The sheet's measured critical edge tension (scenarios/figures/sheet_physics.md,",
        f"unlit-twin rule, 1 m square, E = 4.5e9 Pa, I₀ = 1e8 W/m²): {measured_tension()} T_cr,max.",
        f"Square {GRID} × {GRID} tiles, disc 9 × 12.",
        "",
        *spin_against_tension(),
        "",
        "## C. The spectrum against a time-domain run (square, 6 × 6 tiles, Ω = 10 rad/s, exact spun equilibrium,",
        "1 s, in-house solver)",
        "",
        *time_domain(),
        "",
        "## D. Where the tilt mode came from",
        "",
        *diagnosis(),
        "",
        "## E. The critical spin rate for shape stability against edge tension",
        "",
        "Ω_cr: the bracket of the smallest spin from which the fastest deformation grows slower than ln 2/(6 s)",
        "(it does not double in the paper's 6 s run) at every scanned faster spin up to 32 Ω_T (Ω_T, T_cr,max:",
        "part B). N_c = 3ρhΩ²R²/8: the centrifugal membrane force at a disc's centre; the mean of (N₁ + N₂)/2:",
        "the flat sheet's isotropic membrane force averaged over its area (an edge tension T gives T everywhere).",
        f"The measured critical edge tension: {measured_tension()} T_cr,max (part B). Λ = ρΩ²R²/(E (2πν a₀/L)²):",
        "the spin's membrane strain over the defect's squared slope (Λ ≫ 1: the spin pulls the defect flat).",
        "",
        *critical_table,
        "",
        *twin_checks(first),
        "",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    text = report()
    (HERE / "spin_spectrum.md").write_text(text)
    print(text)
