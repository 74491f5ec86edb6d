"""Round sails from tiles: `python validation/circular_plates.py`.

The disc and hexagon planforms (model.sheet_planforms) against circular-plate theory and each other:

1. Statics: the disc of radius R = 0.5 m (h = 1 cm, E = 1.2e9 Pa: D = 100 N m, ν_p = 0) under a uniform
   pressure q = 0.01 Pa, clamped and simply supported, on three polar meshes; the centre tile's deflection
   of both solvers' static solves against Timoshenko & Woinowsky-Krieger (model.plate_theory), with the
   observed order. The same clamped disc on a grid masked to the disc (cells whose centre lies inside: a
   staircase boundary), the alternative to polar tiles, built here with model.sheet_mesh.from_polygons.
   The regular hexagon (no closed form): its centre deflection on three meshes and the observed order.
2. Frequencies of the clamped disc from the linearised sheet (in-house eigenvalues; Exudyn's for the
   meshes it can take densely): the first three distinct λ² = ω R² √(ρh/D) against 10.216, 21.26, 34.88.
3. The tensioned circular membrane (bending off, E_m = 4.5e9 Pa, h = 1 µm, T = 1 N/m, fixed edge): ω₀₁
   against 2.405 √(T/(ρh))/R.
4. The two solvers on round sails under a Gaussian beam (soft sail, E = 4.5e9 Pa, w = 0.6 m, the paper's
   1-D defect): failure times (amplitude doubled).
Writes validation/circular_plates.md.
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
from lightsail_mbs.model import planforms, plate_theory, sheet_mesh  # noqa: E402
from lightsail_mbs.solvers.exudyn import sheet as exudyn_sheet  # noqa: E402
from lightsail_mbs.solvers.reduced import sheet as reduced_sheet  # noqa: E402

solve = functools.partial(solve_with_estimate, uncertainty=False)

HERE = Path(__file__).resolve().parent
DISC_MESHES = ((9, 12), (17, 24), (33, 48))
FINE_DISC = (65, 96)
HEXAGON_MESHES = (8, 16, 32)
PLATE = dict(model="sheet", length=1.0, width=1.0, thickness=0.01, youngs_modulus=1.2e9, intensity=0.0)
PLATE = dict(PLATE, defect_amplitude=0.0)
MEMBRANE = dict(PLATE, thickness=1e-6, youngs_modulus=4.5e9, bending=False, edge_tension=1.0)
MEMBRANE = dict(MEMBRANE, boundary="simply_supported")
CLAMPED_LAMBDA2 = (10.216, 21.26, 34.88)  # λ² of the clamped circular plate's first three distinct frequencies
MEMBRANE_ZERO = 2.405  # j₀,₁, the first zero of J₀
EXUDYN_EIGEN_TILES = 250  # Exudyn's eigenvalues are dense: the meshes up to this many tiles


def masked_grid(n: int, ny: int, length: float, width: float) -> sheet_mesh.Mesh:
    """n × n square cells of the L × L square, those whose centre lies inside the disc of diameter L."""
    step = length / n
    xs = np.arange(n + 1) * step
    vertices = np.array([(x, y) for y in xs for x in xs])
    cells = []
    for j in range(n):
        for i in range(n):
            if math.hypot((i + 0.5) * step - 0.5 * length, (j + 0.5) * step - 0.5 * width) < 0.5 * length:
                v = j * (n + 1) + i
                cells.append([v, v + 1, v + n + 2, v + n + 1])
    return sheet_mesh.from_polygons(vertices, cells, across=(n, n))


def centre_deflection(centres: np.ndarray) -> float:
    return float(centres[np.argmin(np.hypot(centres[:, 0] - 0.5, centres[:, 1] - 0.5)), 2])


def order(errors, sizes) -> str:
    if len(errors) < 2 or errors[-1] == 0:
        return "—"
    return f"{math.log(abs(errors[-2] / errors[-1])) / math.log(sizes[-1] / sizes[-2]):.2f}"


def statics() -> list[str]:
    lines = [
        "## Statics: centre deflection under uniform pressure",
        "",
        "Theory: clamped w₀ = qR⁴/(64D), simply supported w₀ = (5 + ν_p)qR⁴/(64(1 + ν_p)D) with ν_p = 0 "
        "(model.sheet_connectors). 'n × ny': tiles across the diameter × sectors.",
        "",
        "| planform | boundary | mesh | tiles | theory w₀ D/(q R⁴) | Exudyn | Exudyn − theory | in-house | "
        "abs(Exudyn − in-house)/w₀ | observed order | wall Exudyn / in-house (s) |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    q, R = 0.01, 0.5
    for boundary, factor in (("clamped", 1.0), ("simply_supported", 5.0)):
        errors, sizes = [], []
        for n, ny in DISC_MESHES:
            p = SailParameters(n=n, ny=ny, pressure=q, boundary=boundary, planform="disc", **PLATE)
            D = plate_theory.bending_rigidity(p)
            exact = factor * q * R**4 / (64.0 * D)
            t0 = time.perf_counter()
            we = centre_deflection(exudyn_sheet.static_centres(p))
            t1 = time.perf_counter()
            wi = centre_deflection(reduced_sheet.static_centres(p))
            t2 = time.perf_counter()
            errors.append(wi / exact - 1)
            sizes.append(n)
            scale = D / (q * R**4)
            lines.append(
                f"| disc | {boundary} | {n}×{ny} | {planforms.mesh_of(p).count} | {exact * scale:.7f} | "
                f"{we * scale:.7f} | {100 * (we / exact - 1):+.3f} % | {wi * scale:.7f} | {abs(we - wi) / exact:.1e} "
                f"| {order(errors, sizes)} | {t1 - t0:.1f} / {t2 - t1:.1f} |"
            )
            print(lines[-1], flush=True)
    return lines


def staircase() -> list[str]:
    """The clamped disc on a masked grid (the measurement behind the choice of polar tiles)."""
    lines = [
        "",
        "## The alternative: a grid masked to the disc (clamped, in-house statics)",
        "",
        "Square cells of the L × L square whose centre lies inside the disc, clamped along the staircase of "
        "their outer edges (built in this script with model.sheet_mesh.from_polygons; not a planform).",
        "",
        "| cells across | tiles | area / πR² − 1 | w₀ − theory | observed order |",
        "|---|---|---|---|---|",
    ]
    planforms.PLANFORMS["masked-grid"] = planforms.Planform(masked_grid, lambda *a: [], "measurement only")
    try:
        errors, sizes = [], []
        for n in (9, 17, 33, 65):
            p = SailParameters(n=n, ny=n, pressure=0.01, boundary="clamped", planform="masked-grid", **PLATE)
            exact = 0.01 * 0.5**4 / (64.0 * plate_theory.bending_rigidity(p))
            mesh = planforms.mesh_of(p)
            errors.append(centre_deflection(reduced_sheet.static_centres(p)) / exact - 1)
            sizes.append(n)
            lines.append(
                f"| {n} | {mesh.count} | {100 * (mesh.areas.sum() / (math.pi * 0.25) - 1):+.2f} % | "
                f"{100 * errors[-1]:+.3f} % | {order(errors, sizes)} |"
            )
            print(lines[-1], flush=True)
    finally:
        del planforms.PLANFORMS["masked-grid"]
    return lines


def hexagon() -> list[str]:
    lines = [
        "",
        "## The regular hexagon (corner to corner L = 1 m): centre deflection, no closed form",
        "",
        "| boundary | n (triangles 6(n/2)²) | w₀ D/(q L⁴) in-house | Exudyn − in-house | change from the "
        "previous mesh | observed order |",
        "|---|---|---|---|---|---|",
    ]
    for boundary in ("clamped", "simply_supported"):
        values, sizes = [], []
        for n in HEXAGON_MESHES:
            p = SailParameters(n=n, ny=1, pressure=0.01, boundary=boundary, planform="hexagon", **PLATE)
            scale = plate_theory.bending_rigidity(p) / 0.01
            wi = centre_deflection(reduced_sheet.static_centres(p)) * scale
            we = centre_deflection(exudyn_sheet.static_centres(p)) * scale if n <= 16 else float("nan")
            values.append(wi)
            sizes.append(n)
            changes = np.diff(values)
            observed = f"{math.log(abs(changes[-2] / changes[-1])) / math.log(2):.2f}" if len(changes) > 1 else "—"
            change = f"{100 * (values[-1] / values[-2] - 1):+.3f} %" if len(values) > 1 else "—"
            lines.append(f"| {boundary} | {n} | {wi:.7f} | {abs(we - wi) / wi:.1e} | {change} | {observed} |")
            print(lines[-1], flush=True)
    return lines


def frequencies() -> list[str]:
    lines = [
        "",
        "## Frequencies of the clamped disc",
        "",
        "λ² = ω R² √(ρh/D) of the first three distinct frequencies (the second and third are double: the "
        "(1, 1) and (2, 1) modes); in-house: shift-invert Arnoldi on its linearisation; Exudyn: "
        f"ComputeODE2Eigenvalues (dense) up to {EXUDYN_EIGEN_TILES} tiles.",
        "",
        "| mesh | tiles | solver | λ²₁ / λ²₂ / λ²₃ | error vs 10.216 / 21.26 / 34.88 (%) |",
        "|---|---|---|---|---|",
    ]
    R = 0.5
    for n, ny in (*DISC_MESHES, FINE_DISC):
        p = SailParameters(n=n, ny=ny, boundary="clamped", planform="disc", **PLATE)
        scale = math.sqrt(plate_theory.bending_rigidity(p) / (p.density * p.thickness)) / R**2
        count = planforms.mesh_of(p).count
        solvers = [("in-house", reduced_sheet.eigenfrequencies)]
        if count <= EXUDYN_EIGEN_TILES:
            solvers.append(("Exudyn", exudyn_sheet.eigenfrequencies))
        for name, function in solvers:
            omega = np.sort(function(p, 8))
            distinct = [omega[0]]
            for w in omega[1:]:
                if w > distinct[-1] * (1 + 1e-6):
                    distinct.append(w)
            lam = np.array(distinct[:3]) / scale
            lines.append(
                f"| {n}×{ny} | {count} | {name} | {' / '.join(f'{v:.4f}' for v in lam)} | "
                f"{' / '.join(f'{100 * (v / e - 1):+.3f}' for v, e in zip(lam, CLAMPED_LAMBDA2))} |"
            )
            print(lines[-1], flush=True)
    return lines


def membrane() -> list[str]:
    lines = [
        "",
        "## The tensioned circular membrane",
        "",
        "| mesh | tiles | ω₀₁ in-house (rad/s) | theory 2.405 √(T/(ρh))/R | error |",
        "|---|---|---|---|---|",
    ]
    for n, ny in (*DISC_MESHES, FINE_DISC):
        p = SailParameters(n=n, ny=ny, planform="disc", **MEMBRANE)
        exact = MEMBRANE_ZERO * math.sqrt(p.edge_tension / (p.density * p.thickness)) / 0.5
        omega = float(np.min(reduced_sheet.eigenfrequencies(p, 4)))
        lines.append(
            f"| {n}×{ny} | {planforms.mesh_of(p).count} | {omega:.4f} | {exact:.4f} | "
            f"{100 * (omega / exact - 1):+.3f} % |"
        )
        print(lines[-1], flush=True)
    return lines


def crosscheck() -> list[str]:
    lines = [
        "",
        "## The two solvers on round sails under a Gaussian beam",
        "",
        "Soft sail (E = 4.5e9 Pa, L = W = 1 m, the paper's 1-D sine a₀ = 10 µm, ν = 1.5), round Gaussian beam "
        "w = 0.6 m on the centre; output every 20 µs (a Gaussian beam cups a free sail within a millisecond); "
        "default options of both solvers.",
        "",
        "| planform | mesh | tiles | extra | failure time Exudyn (s) | in-house (s) | relative difference |",
        "|---|---|---|---|---|---|---|",
    ]
    settings = RunSettings(t_final=3e-3, output_interval=2e-5)
    base = dict(model="sheet", length=1.0, width=1.0, youngs_modulus=4.5e9, beam_waist=0.6)
    for planform, n, ny, extra in (
        ("disc", 17, 24, {}),
        ("disc", 17, 24, {"edge_tension": 1e-4, "defect_mode_y": 1.0}),
        ("hexagon", 16, 1, {}),
    ):
        p = SailParameters(planform=planform, n=n, ny=ny, **base, **extra)
        te = solve(p, "exudyn", settings).failure_time
        ti = solve(p, "reduced", settings).failure_time
        lines.append(
            f"| {planform} | {n}×{ny} | {planforms.mesh_of(p).count} | {extra or '—'} | {te:.9g} | {ti:.9g} | "
            f"{abs(te - ti) / ti:.1e} |"
        )
        print(lines[-1], flush=True)
    return lines


def main() -> int:
    lines = [
        "# Round sails from tiles: circular plates, membrane, cross-check",
        "",
        "Generated by `python validation/circular_plates.py` (model.sheet_planforms: the disc in polar tiles, "
        "the hexagon in equilateral triangles; edge springs with D = E h³/12, ν_p = 0). Wall times on a shared "
        "2-core machine.",
        "",
        *statics(),
        *staircase(),
        *hexagon(),
        *frequencies(),
        *membrane(),
        *crosscheck(),
        "",
    ]
    text = "\n".join(lines)
    (HERE / "circular_plates.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
