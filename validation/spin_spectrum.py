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
C. The spectrum against a time-domain run: the same sail (square, 6 × 6 tiles, lit and unlit) spun at 10 rad/s,
   1 s in the in-house solver; the growth rate of the amplitude's departure from its start
   (a − a(0), least squares of its logarithm over the last half) against the spectrum's fastest Re λ.
D. Where the fast mode of the tiles' tilts comes from: part C's unlit sail with one change at a time (defect,
   film thickness, bending springs and their rest state, the membrane's rest state and modulus, grid, light),
   and the lit 8 × 8 square with its membrane springs at rest flat against the spin rate.
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
from lightsail_mbs.model import failure, sheet_spin, theory  # noqa: E402

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
        p = SailParameters(**SOFT, planform="rectangle", n=6, ny=6, intensity=intensity).replace(spin_rate=10.0)
        s = spin_spectrum.rotating_spectrum(p)
        run = solve(p, "reduced", RunSettings(t_final=1.0, output_interval=0.02), uncertainty=False)
        departure = np.abs(failure.plane_amplitude(run.tile_centres) - failure.plane_amplitude(run.tile_centres[0]))
        late = np.asarray(run.time) >= 0.5
        rate = np.polyfit(np.asarray(run.time)[late], np.log(departure[late]), 1)[0]
        light = "unlit" if intensity == 0 else f"I₀ = {intensity:.2g} W/m²"
        lines.append(f"| {light} | {s.growth_rate:.4g} | {s.tilt_share:.2f} | {rate:.4g} | {run.error or '–'} |")
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
    ("initial_equilibrium", {"initial_equilibrium": True}),
    ("membrane springs at rest flat", {"membrane_reference": "flat"}),
    ("E_m = 4.5e11 Pa", {"membrane_modulus": 4.5e11}),
    ("8 × 8 tiles", {"n": 8, "ny": 8}),
    ("8 × 8 tiles, lit", {"n": 8, "ny": 8, "intensity": 1e8}),
    (
        "8 × 8 tiles, lit, membrane springs at rest flat",
        {"n": 8, "ny": 8, "intensity": 1e8, "membrane_reference": "flat"},
    ),
)
FLAT_MEMBRANE_SPINS = (0.0, 0.1, 0.2, 0.3, 0.5, 1.0)


def diagnosis() -> list[str]:
    lines = [
        "| change (square, 6 × 6 tiles, unlit, Ω = 10 rad/s unless said) | fastest Re λ / Ω | tilt share |",
        "|---|---|---|",
    ]
    base = SailParameters(**SOFT, planform="rectangle", n=6, ny=6, intensity=0.0, spin_rate=10.0)
    for label, changes in DIAGNOSIS:
        s = spin_spectrum.rotating_spectrum(base.replace(**changes))
        lines.append(f"| {label} | {s.growth_rate / base.spin_rate:.3g} | {s.tilt_share:.2f} |")
        print(lines[-1], flush=True)
    lines += [
        "",
        "The lit 8 × 8 square with its membrane springs at rest flat against the spin rate:",
        "",
        "| Ω (rad/s) | fastest Re λ (1/s) | tilt share | fastest shape mode (1/s) |",
        "|---|---|---|---|",
    ]
    lit = base.replace(n=8, ny=8, intensity=1e8, membrane_reference="flat")
    for spin in FLAT_MEMBRANE_SPINS:
        s = spin_spectrum.rotating_spectrum(lit.replace(spin_rate=spin))
        lines.append(f"| {spin:g} | {s.growth_rate:.3g} | {s.tilt_share:.2f} | {s.shape_rate:.3g} |")
        print(lines[-1], flush=True)
    return lines


def report() -> str:
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
        "## C. The spectrum against a time-domain run (square, 6 × 6 tiles, Ω = 10 rad/s, 1 s, in-house solver)",
        "",
        *time_domain(),
        "",
        "## D. Where the tilt mode comes from",
        "",
        *diagnosis(),
        "",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    text = report()
    (HERE / "spin_spectrum.md").write_text(text)
    print(text)
