"""Spinning sheets: `python validation/spin.py [--turns N]` (part 3: N turns, default 100, ~40 s of one core
per turn; part 4: eight runs of one turn).

The case field spin_rate (model.sheet_spin) against closed forms:

1. The spun equilibrium's in-plane stress of a free disc (R = 0.5 m, ρ = 1000 kg/m³, Ω = 100 rad/s) on three
   polar meshes: the normal stress across every shared edge (the connector's force over the edge's
   cross-section e h: radial connectors give σ_r, circumferential ones σ_θ) against
   σ_r = 3ρΩ²(R² − r²)/8 and σ_θ = ρΩ²(3R² − r²)/8 (the in-plane springs' ν_p = 0), at the marker's radius;
   the largest error over the edges, as a fraction of the centre's stress 3ρΩ²R²/8, and its observed order.
2. The unlit spinning flat sail at rest in its rotating frame (all three planforms, both solvers, Ω = 20
   rad/s, E_m = 1e8 Pa, 0.1 s): the tiles' largest displacement from their initial positions turned by Ωt
   about the centre of mass, and its largest height. Exudyn at three steps (its generalized-α phase error).
3. A very stiff disc (h = 0.1 m, E = 1e11 Pa: lowest elastic frequency ~1000 Ω, 13 tiles; in-plane springs
   E_m = 1e9 Pa, whose lowest frequency is still ~300 Ω) spun at Ω = 2π rad/s with its angular velocity
   tilted by β = 1 mrad from its normal, over N turns: the centre tile's body rates against the free
   symmetric top (Euler's equations, ω⊥ turning at (I₃ − I₁)ω₃/I₁ in the body axes, I from the tiles as one
   rigid body), Exudyn at h = 2.5e-4 s, ρ∞ = 1, Newton's relative tolerance 1e-12.
4. What moves ω₃ (a free top keeps it): the same disc over one turn with one change at a time (no nutation,
   membrane damping, step, Newton's tolerance, E_m).
Writes validation/spin.md.
"""

import functools
import math
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from lightsail_mbs import RunSettings, SailParameters  # noqa: E402
from lightsail_mbs import solve as solve_with_estimate  # noqa: E402
from lightsail_mbs.model import sheet, sheet_spin  # noqa: E402

solve = functools.partial(solve_with_estimate, uncertainty=False)

HERE = Path(__file__).resolve().parent
DISC_MESHES = ((9, 12), (17, 24), (33, 48))
UNLIT = dict(model="sheet", length=1.0, width=1.0, intensity=0.0, defect_amplitude=0.0)
PLANFORM_MESHES = {"rectangle": (6, 6), "disc": (5, 6), "hexagon": (6, 1)}


def disc_stress_rows():
    """Part 1: (n, ny, edges, σ_r error, σ_θ error) as fractions of the centre's stress."""
    rows = []
    for n, ny in DISC_MESHES:
        p = SailParameters(planform="disc", n=n, ny=ny, spin_rate=100.0, **UNLIT)
        conn = sheet.connectors(p)
        rows.append((n, ny, *sheet_spin.disc_stress_errors(p, conn.offset, conn.stiffness)))
    return rows


def rotating_frame_drift(result, p):
    """(largest displacement from the initial positions turned by Ωt, largest height) of a run (m)."""
    centres = result.tile_centres
    rel = centres - sheet_spin.spin_centre(p, centres[0])
    angle = -p.spin_rate * np.asarray(result.time)[:, None]
    back_x = np.cos(angle) * rel[..., 0] - np.sin(angle) * rel[..., 1]
    back_y = np.sin(angle) * rel[..., 0] + np.cos(angle) * rel[..., 1]
    drift = np.hypot(back_x - back_x[0], back_y - back_y[0])
    return float(drift.max()), float(np.abs(rel[..., 2]).max())


def rest_rows():
    """Part 2: (planform, tiles, solver, step, drift, height, wall time)."""
    rows = []
    settings = RunSettings(t_final=0.1, output_interval=0.01)
    for planform, (n, ny) in PLANFORM_MESHES.items():
        p = SailParameters(planform=planform, n=n, ny=ny, spin_rate=20.0, membrane_modulus=1e8, **UNLIT)
        runs = [("reduced", {}, "adaptive")] + [("exudyn", {"step_size": h}, f"{h:g} s") for h in (1e-2, 1e-3, 1e-4)]
        for solver, options, step in runs:
            start = time.perf_counter()
            result = solve(p, solver, settings, **options)
            drift, height = rotating_frame_drift(result, p)
            rows.append((planform, sheet.tile_count(p), solver, step, drift, height, time.perf_counter() - start))
    return rows


NUTATION_DISC = dict(
    planform="disc", n=5, ny=6, thickness=0.1, youngs_modulus=1e11, spin_rate=2.0 * math.pi, spin_tilt=1e-3, **UNLIT
)
NUTATION_RUN = dict(step_size=2.5e-4, spectral_radius=1.0, newton_rel_tol=1e-12)  # with membrane_modulus 1e9 Pa
# part 4: what moves ω₃ (label, case changes, Exudyn options), each over DRIFT_TURNS turns
DRIFT_TURNS = 1.0
DRIFT_ROWS = (
    ("E_m = E, h = 2.5e-4 s, Newton rel. tol. 1e-8 (the solver's default)", {}, {}),
    ("as above, β = 0 (no nutation)", {"spin_tilt": 0.0}, {}),
    ("as above, membrane damping 1e-3 s (73 × the default)", {"membrane_damping": 1e-3}, {}),
    ("E_m = E, h = 1.25e-4 s", {}, {"step_size": 1.25e-4}),
    ("E_m = E, Newton rel. tol. 1e-12", {}, {"newton_rel_tol": 1e-12}),
    ("E_m = E, Newton rel. tol. 1e-12, h = 1.25e-4 s", {}, {"newton_rel_tol": 1e-12, "step_size": 1.25e-4}),
    ("E_m = 1e9 Pa, Newton rel. tol. 1e-8", {"membrane_modulus": 1e9}, {}),
    ("E_m = 1e9 Pa, Newton rel. tol. 1e-12 (part 3's setting)", {"membrane_modulus": 1e9}, {"newton_rel_tol": 1e-12}),
)


def top_errors(p, turns: float, **options):
    """(result, times, body-rate errors (T, 3) / Ω against the free symmetric top, wall time) of an Exudyn run."""
    omega = p.spin_rate
    start = time.perf_counter()
    settings = RunSettings(t_final=turns * 2.0 * math.pi / omega, output_interval=0.05)
    result = solve(p, "exudyn", settings, **{"step_size": 2.5e-4, "spectral_radius": 1.0, **options})
    wall = time.perf_counter() - start
    centres, quaternions = sheet.initial_quaternions(p)
    inertia = sheet_spin.rigid_inertia(p, centres, quaternions)
    exact = sheet_spin.free_top_rates(
        result.time, omega * math.cos(p.spin_tilt), omega * math.sin(p.spin_tilt), (inertia[0, 0], inertia[2, 2])
    )
    rotations = sheet.rotation_xyz(result.tile_angles[:, 0])
    body = np.einsum("tji,tj->ti", rotations, result.tile_angular_velocities[:, 0])
    return result, np.asarray(result.time), (body - exact) / omega, wall


def nutation(turns: float):
    """Part 3: (p, I₁, I₃, largest |ω_b − closed form| per component / Ω, ω₃'s drift per turn / Ω, wall, error)."""
    p = SailParameters(**NUTATION_DISC).replace(membrane_modulus=1e9)
    result, t, errors, wall = top_errors(p, turns, **NUTATION_RUN)
    centres, quaternions = sheet.initial_quaternions(p)
    inertia = sheet_spin.rigid_inertia(p, centres, quaternions)
    late = t >= 0.5
    drift = np.polyfit(t[late], errors[late, 2], 1)[0] * 2.0 * math.pi / p.spin_rate
    return p, inertia[0, 0], inertia[2, 2], np.max(np.abs(errors), axis=0), drift, wall, result.error


def drift_rows():
    """Part 4: (label, ω₃ error at 0.2 s / Ω, its drift per turn / Ω, largest transverse error / Ω, wall)."""
    rows = []
    for label, changes, options in DRIFT_ROWS:
        p = SailParameters(**NUTATION_DISC).replace(**changes)
        _, t, errors, wall = top_errors(p, DRIFT_TURNS, **options)
        late = t >= 0.5
        drift = np.polyfit(t[late], errors[late, 2], 1)[0] * 2.0 * math.pi / p.spin_rate
        early = errors[np.searchsorted(t, 0.2), 2]
        rows.append((label, early, drift, np.abs(errors[:, :2]).max(), wall))
        print(rows[-1], flush=True)
    return rows


def report(turns: int) -> str:
    command = "python validation/spin.py" + ("" if turns == 100 else f" --turns {turns}")
    lines = [
        "# Spinning sheets",
        "",
        f"Made by `{command}` (model.sheet_spin; the script's docstring says what each part does).",
        "",
        "## 1. In-plane stress of a spinning free disc",
        "",
        "R = 0.5 m, ρ = 1000 kg/m³, Ω = 100 rad/s, ν_p = 0. Largest error over the shared edges as a fraction of",
        "the centre's stress 3ρΩ²R²/8.",
        "",
        "| mesh (n × ny) | edges | σ_r error | σ_θ error |",
        "|---|---|---|---|",
    ]
    rows = disc_stress_rows()
    for n, ny, edges, er, et in rows:
        lines.append(f"| {n} × {ny} | {edges} | {er:.2%} | {et:.2%} |")
    orders = [math.log(rows[k][3] / rows[k + 1][3]) / math.log(rows[k + 1][0] / rows[k][0]) for k in range(2)]
    lines += ["", f"Observed order (σ_r): {orders[0]:.2f}, {orders[1]:.2f}.", ""]
    lines += [
        "## 2. The unlit spinning flat sail rests in its rotating frame",
        "",
        "Ω = 20 rad/s, E_m = 1e8 Pa, 0.1 s; drift: the largest distance of a tile from its initial position",
        "turned by Ωt; height: the largest |z|.",
        "",
        "| planform | tiles | solver | step | drift (m) | height (m) | wall (s) |",
        "|---|---|---|---|---|---|---|",
    ]
    for planform, tiles, solver, step, drift, height, wall in rest_rows():
        lines.append(f"| {planform} | {tiles} | {solver} | {step} | {drift:.2e} | {height:.1e} | {wall:.1f} |")
    p, i1, i3, errors, drift, wall, error = nutation(turns)
    lines += [
        "",
        "## 3. A stiff spinning disc nutates as a free symmetric top",
        "",
        f"Disc of {sheet.tile_count(p)} tiles, h = {p.thickness} m, E = {p.youngs_modulus:g} Pa (bending; lowest "
        f"elastic frequency ~1000 Ω), in-plane springs E_m = {p.membrane_modulus:g} Pa, Ω = 2π rad/s, "
        f"β = {p.spin_tilt} rad, {turns} turns; I₁ = {i1:.6g} kg m², I₃ = {i3:.6g} kg m² "
        f"(λ/ω₃ = {(i3 - i1) / i1:.6f}). Exudyn, h = 2.5e-4 s, ρ∞ = 1, Newton's relative tolerance 1e-12"
        f"{'' if error is None else ', error: ' + error}.",
        "",
        "The in-house solver is not run here: its Radau refreshes its frozen Jacobian as often as the stiff",
        "disc turns noticeably (its bending frequencies ~1000 Ω), too slow for 100 turns.",
        "",
        "| body rate | largest error / Ω | / ω⊥ |",
        "|---|---|---|",
    ]
    transverse = math.sin(p.spin_tilt)
    for name, value in zip(("ω₁", "ω₂", "ω₃"), errors):
        lines.append(f"| {name} | {value:.2e} | {value / transverse:.2e} |")
    lines += [
        "",
        f"ω₃'s drift: {drift:.2e} Ω per turn (least squares over t ≥ 0.5 s). Wall time {wall:.0f} s (loaded machine).",
        "",
        "## 4. What moves ω₃",
        "",
        f"The same disc over {DRIFT_TURNS:g} turn, one change at a time (Exudyn, h = 2.5e-4 s unless said, ρ∞ = 1):",
        "ω₃'s error at 0.2 s (the offset the first steps leave), its drift per turn (least squares over",
        "t ≥ 0.5 s) and the largest error of the transverse rates.",
        "",
        "| run | ω₃ error at 0.2 s / Ω | ω₃ drift per turn / Ω | transverse error / Ω | wall (s) |",
        "|---|---|---|---|---|",
    ]
    for label, early, rate, side, seconds in drift_rows():
        lines.append(f"| {label} | {early:.2e} | {rate:.2e} | {side:.1e} | {seconds:.0f} |")
    lines.append("")
    return "\n".join(lines)


if __name__ == "__main__":
    text = report(int(sys.argv[sys.argv.index("--turns") + 1]) if "--turns" in sys.argv else 100)
    (HERE / "spin.md").write_text(text)
    print(text)
