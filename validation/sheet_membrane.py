"""What the membrane modulus does to a doubly curved sheet, and why it once did far more:
`python validation/sheet_membrane.py [--grid 12]`.

A doubly curved defect cannot be flattened without stretching (Gauss), so unlike the chain's 1-D defect
it couples bending to the in-plane (membrane) springs, and the membrane modulus E_m enters 2-D results.
A first version of the tiles gave a ~6× shorter failure time with E_m = E than with E_m = 4.5e9 Pa. This
script shows where that came from and what is left:

A. Linearised spectrum at the initial state (8 × 8 tiles, ν = 1.5 × 1.5, E = 10.83 E_cr,max, in-house
   Jacobian, dense eigenvalues of the first-order system in the 6N generalised coordinates): the largest
   growth rates with the drilling springs at their former stiffness E_m h e³/(12 s) (the within-tile
   in-plane bending) and at the current D_m e/s, lit and unlit, with the bending springs at rest flat
   (the paper's convention) or in the initial shape (a stress-free defect: unlit, an exact equilibrium,
   which no conservative model can make unstable), and the fastest deformation mode with the rigid-body motion
   removed (analysis.sheet_spectrum). The former drilling springs, through the connector
   law's Tait–Bryan moments A₀Kφ (not the gradient of a potential), coupled in-plane rotation to tilt
   with a circulatory stiffness ~ k_drill θ and made even the unlit, stress-free sheet grow at ~15/s.
B. Time domain (in-house, grid × grid tiles, 6 s): failure time and largest amplitude ratio with the
   current model, for E_m = 4.5e9 Pa, 4.5e11 Pa and E, at E = 10.83 and 13.45 E_cr,max, and with the
   membrane damping β_m × 10 (a numerical regularisation: how much it moves the answer).
Writes validation/sheet_membrane.md.
"""

import argparse
import functools
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from lightsail_mbs import RunSettings, SailParameters  # noqa: E402
from lightsail_mbs import solve as solve_with_estimate  # noqa: E402
from lightsail_mbs.analysis import sheet_spectrum  # noqa: E402
from lightsail_mbs.model import sheet, sheet_connectors, theory  # noqa: E402
from lightsail_mbs.solvers.reduced.sheet import SheetModel  # noqa: E402
from lightsail_mbs.studies.tables import fmt  # noqa: E402

solve = functools.partial(solve_with_estimate, uncertainty=False)  # single runs: no error bars in this report

HERE = Path(__file__).resolve().parent
CURRENT_EDGE_STIFFNESS = sheet_connectors.edge_stiffness


def former_edge_stiffness(p, tiles, edge, span, bending=True):
    """The drilling stiffness of the first version: E_m h e³/(12 s), the within-tile in-plane bending (of one
    edge or of an array of edges, as edge_stiffness)."""
    k = CURRENT_EDGE_STIFFNESS(p, tiles, edge, span, bending)
    k[..., 5] = tiles.membrane_modulus * p.thickness * edge**3 / (12.0 * span)
    return k


def growth_rates(p: SailParameters, count: int = 2) -> np.ndarray:
    model = SheetModel(p)
    y = model.y0()
    J = model.jacobian(0.0, y).toarray()
    X, V = model.position_indices, model.velocity_indices
    K = J[np.ix_(V, X)] @ model.kinematics(y).toarray()
    n = K.shape[0]
    w = np.linalg.eigvals(np.block([[np.zeros((n, n)), np.eye(n)], [K, J[np.ix_(V, V)]]]))
    return w[np.argsort(-w.real)][:count]


def spectra() -> list[str]:
    base = SailParameters(model="sheet", n=8, ny=8, defect_mode_y=1.5, youngs_modulus=4.5e9)
    E = 10.83 * theory.critical_modulus_max(base)
    lines = [
        "## A. Linearised growth rates at the initial state (8 × 8)",
        "",
        f"E = 10.83 E_cr,max = {E:.3g} Pa; growth rate = largest real part of the eigenvalues (1/s). The last",
        "column: the largest over the deformation modes, rigid-body motion removed",
        "(lightsail_mbs.analysis.sheet_spectrum), and the mode's symmetry family; the eigenvalues before it include",
        "the six rigid-body modes, whose zero eigenvalues the non-equilibrium state and the finite differences split.",
        "",
        "| drilling springs | E_m (Pa) | bending at rest | beam | two largest eigenvalues (1/s) | fastest deformation "
        "mode (1/s, family) |",
        "|---|---|---|---|---|---|",
    ]
    for label, stiffness in (("former E_m h e³/(12 s)", former_edge_stiffness), ("current D_m e/s", None)):
        sheet_connectors.edge_stiffness = stiffness or CURRENT_EDGE_STIFFNESS  # what connectors() calls
        try:
            for em in (4.5e9, None):
                for reference in ("flat", "initial"):
                    for lit in (True, False):
                        p = base.replace(
                            youngs_modulus=E,
                            membrane_modulus=em,
                            bending_reference=reference,
                            intensity=1e8 if lit else 0.0,
                        )
                        w = growth_rates(p)
                        s = sheet_spectrum.spectrum(p)
                        lines.append(
                            f"| {label} | {sheet.Tiles.of(p).membrane_modulus:.3g} | {reference} | "
                            f"{'on' if lit else 'off'} | {' , '.join(f'{z.real:.3g}{z.imag:+.2g}j' for z in w)} | "
                            f"{s.growth_rate:.3g} ({s.family}) |"
                        )
                        print(lines[-1], flush=True)
        finally:
            sheet_connectors.edge_stiffness = CURRENT_EDGE_STIFFNESS
    return lines


def time_domain(grid: int) -> list[str]:
    base = SailParameters(model="sheet", n=grid, ny=grid, defect_mode_y=1.5, youngs_modulus=4.5e9)
    e_max = theory.critical_modulus_max(base)
    lines = [
        "",
        f"## B. Time domain, current model (in-house, {grid} × {grid}, 6 s, doubly sinusoidal ν = 1.5 × 1.5)",
        "",
        "| E / E_cr,max | E_m (Pa) | β_m (s) | failure time (s) | max amplitude ratio | steps | wall (s) |",
        "|---|---|---|---|---|---|---|",
    ]
    for ratio in (10.83, 13.45):
        for em, damping in ((4.5e9, None), (4.5e11, None), (None, None), (None, 10.0)):
            p = base.replace(youngs_modulus=ratio * e_max, membrane_modulus=em)
            if damping is not None:
                p = p.replace(membrane_damping=damping * sheet.Tiles.of(p).membrane_damping)
            t0 = time.perf_counter()
            r = solve(p, "reduced", RunSettings(t_final=6.0))
            t = sheet.Tiles.of(p)
            lines.append(
                f"| {ratio:g} | {t.membrane_modulus:.3g} | {t.membrane_damping:.2g}"
                f"{' (×10)' if damping else ''} | {fmt(r.failure_time, '.4f')} | {r.max_amplitude_ratio:.3f} | "
                f"{r.info['steps']} | {time.perf_counter() - t0:.0f} |"
            )
            print(lines[-1], flush=True)
    return lines


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--grid", type=int, default=12)
    args = parser.parse_args(argv)
    lines = [
        "# The membrane modulus and the doubly curved sheet",
        "",
        "Generated by `python validation/sheet_membrane.py`. Wall times on a shared 2-core machine.",
        "",
        *spectra(),
        *time_domain(args.grid),
        "",
    ]
    text = "\n".join(lines)
    (HERE / "sheet_membrane.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
