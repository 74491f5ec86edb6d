"""Plates and membranes from tiles: `python validation/sheet_plates.py`.

1. Statics: square Kirchhoff plate (L = W = 1 m, h = 1 cm, E = 1.2e9 Pa: D = 100 N m) under a uniform
   pressure q = 0.01 Pa (centre deflection ≈ 4e-5 h: the linear range), simply supported and clamped,
   on 9 × 9, 19 × 19 and 39 × 39 tiles (odd: a tile centre on the plate centre); centre deflection of
   both solvers' static solves against Timoshenko & Woinowsky-Krieger (model.plate_theory), with the
   observed order of convergence.
2. Frequencies, from the linearised sheet: simply supported plate (same plate, ρ = 1000 kg/m³) and the
   tensioned membrane (bending off, E_m = 4.5e9 Pa, h = 1 µm, T = 1 N/m, fixed edges), first four modes
   against ω_mn of plate and membrane theory. In-house: eigenvalues of its own linearisation (shift-invert
   Arnoldi); Exudyn: ComputeODE2Eigenvalues for the plate (dense, up to 19 × 19). For the pre-stressed
   membrane Exudyn's eigen-solver is not usable (its symmetric eigenproblem misses the pre-stressed
   connector's non-symmetric tangent), so Exudyn's membrane (and, for comparison, plate) frequencies come
   from the time domain: the 19 × 19 sheet released from rest in a mode shape (no beam), the frequency of
   the tile with the largest initial deflection fitted by least squares (analysis.frequencies) over three
   periods at period/400 steps.
Writes validation/sheet_plates.md.
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
from lightsail_mbs.analysis.frequencies import fit_sinusoid  # noqa: E402
from lightsail_mbs.model import plate_theory  # noqa: E402
from lightsail_mbs.solvers.exudyn import sheet as exudyn_sheet  # noqa: E402
from lightsail_mbs.solvers.reduced import sheet as reduced_sheet  # noqa: E402

solve = functools.partial(solve_with_estimate, uncertainty=False)  # single runs: no error bars in this report

HERE = Path(__file__).resolve().parent
GRIDS = (9, 19, 39)
PLATE = dict(model="sheet", thickness=0.01, youngs_modulus=1.2e9, intensity=0.0, defect_amplitude=0.0)
MEMBRANE = dict(
    model="sheet",
    youngs_modulus=4.5e9,
    bending=False,
    edge_tension=1.0,
    intensity=0.0,
    defect_amplitude=0.0,
    boundary="simply_supported",
)
MODES = plate_theory.lowest_modes(4)


def statics() -> list[str]:
    lines = [
        "## Statics: centre deflection under uniform pressure",
        "",
        "| boundary | grid | theory w D/(q L⁴) | Exudyn | Exudyn − theory | in-house | abs(Exudyn − in-house)/w "
        "| observed order | wall Exudyn / in-house (s) |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for boundary in ("simply_supported", "clamped"):
        errors = []
        for n in GRIDS:
            p = SailParameters(n=n, ny=n, pressure=0.01, boundary=boundary, **PLATE)
            D = plate_theory.bending_rigidity(p)
            exact = plate_theory.centre_deflection(p)
            centre = (n // 2) * n + n // 2
            t0 = time.perf_counter()
            we = exudyn_sheet.static_centres(p)[centre, 2]
            t1 = time.perf_counter()
            wi = reduced_sheet.static_centres(p)[centre, 2]
            t2 = time.perf_counter()
            errors.append(we / exact - 1)
            order = (
                math.log(abs(errors[-2] / errors[-1])) / math.log((n - 1) / (GRIDS[len(errors) - 2] - 1))
                if len(errors) > 1
                else float("nan")
            )
            scale = D / (p.pressure * p.length**4)
            lines.append(
                f"| {boundary} | {n}×{n} | {exact * scale:.7f} | {we * scale:.7f} | {100 * errors[-1]:+.3f} % | "
                f"{wi * scale:.7f} | {abs(we - wi) / exact:.1e} | {order:.2f} | {t1 - t0:.1f} / {t2 - t1:.1f} |"
            )
            print(lines[-1], flush=True)
    return lines


def eigen() -> list[str]:
    lines = [
        "",
        "## Frequencies from the linearised sheet",
        "",
        f"Modes (m, n): {MODES}.",
        "",
        "| case | grid | solver | ω₁ … ω₄ (rad/s) | error vs theory (%) | wall (s) |",
        "|---|---|---|---|---|---|",
    ]
    for kind in ("plate", "membrane"):
        for n in GRIDS:
            if kind == "plate":
                p = SailParameters(n=n, ny=n, boundary="simply_supported", **PLATE)
                exact = np.array([plate_theory.plate_frequency(p, m, k) for m, k in MODES])
            else:
                p = SailParameters(n=n, ny=n, **MEMBRANE)
                exact = np.array([plate_theory.membrane_frequency(p, m, k) for m, k in MODES])
            solvers = [("in-house", reduced_sheet.eigenfrequencies)]
            if kind == "plate" and n <= 19:
                solvers.append(("Exudyn", exudyn_sheet.eigenfrequencies))
            for name, function in solvers:
                t0 = time.perf_counter()
                omega = np.sort(function(p, 6))[:4]
                lines.append(
                    f"| {kind} | {n}×{n} | {name} | {' / '.join(f'{w:.4f}' for w in omega)} | "
                    f"{' / '.join(f'{100 * (w / e - 1):+.3f}' for w, e in zip(omega, exact))} | "
                    f"{time.perf_counter() - t0:.1f} |"
                )
                print(lines[-1], flush=True)
        lines.append(f"| {kind} | theory | | {' / '.join(f'{w:.4f}' for w in exact)} | | |")
    return lines


def time_domain(n: int = 19) -> list[str]:
    lines = [
        "",
        f"## Exudyn in the time domain ({n} × {n})",
        "",
        "Released from rest in the mode shape w = 1 µm sin(mπx/L) sin(nπy/W) (defect_mode = m/2, defect_mode_y = "
        "n/2, no beam); step = period/400; least-squares sinusoid over three periods of the tile with the "
        "largest initial deflection. The in-house column is the eigenvalue of the same grid (above).",
        "",
        "| case | mode | theory ω (rad/s) | Exudyn fitted ω | error vs theory | in-house eigenvalue | "
        "abs(Exudyn − in-house) / ω | wall (s) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for kind in ("membrane", "plate"):
        extra = MEMBRANE if kind == "membrane" else dict(PLATE, boundary="simply_supported")
        linear = SailParameters(n=n, ny=n, **extra)
        eigenvalues = np.sort(reduced_sheet.eigenfrequencies(linear, 10))
        for m, k in ((1, 1), (1, 2), (2, 2)):
            p = SailParameters(
                n=n, ny=n, **{**extra, "defect_amplitude": 1e-6, "defect_mode": m / 2, "defect_mode_y": k / 2}
            )
            omega = (plate_theory.membrane_frequency if kind == "membrane" else plate_theory.plate_frequency)(p, m, k)
            period = 2 * math.pi / omega
            t0 = time.perf_counter()
            r = solve(
                p,
                "exudyn",
                RunSettings(t_final=3 * period, output_interval=period / 200, stop_at_failure=False),
                step_size=period / 400,
            )
            tile = int(np.argmax(np.abs(r.tile_centres[0, :, 2])))
            fitted = 2 * math.pi * fit_sinusoid(r.time, r.tile_centres[:, tile, 2], omega / (2 * math.pi)).frequency
            nearest = eigenvalues[np.argmin(np.abs(eigenvalues - fitted))]
            lines.append(
                f"| {kind} | ({m},{k}) | {omega:.4f} | {fitted:.4f} | {100 * (fitted / omega - 1):+.3f} % | "
                f"{nearest:.4f} | {abs(fitted - nearest) / nearest:.1e} | {time.perf_counter() - t0:.1f} |"
            )
            print(lines[-1], flush=True)
    return lines


def main() -> int:
    lines = [
        "# Plates and membranes from tiles",
        "",
        "Generated by `python validation/sheet_plates.py` (model.sheet: edge springs with D = E h³/12, ν_p = 0; "
        "model.plate_theory: Timoshenko & Woinowsky-Krieger and membrane theory). Wall times on a shared "
        "2-core machine.",
        "",
        *statics(),
        *eigen(),
        *time_domain(),
        "",
    ]
    text = "\n".join(lines)
    (HERE / "sheet_plates.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
