"""The spin map's cap from the spun equilibrium: its spectrum in the turning frame, and the map's spinning cells.

A. **Spectrum** (analysis.spin_spectrum). The map's case (paper.spinning_maps: the 25-tile disc of the stiff film
   on a cap of R_c = 1 m, a stem payload of the sail's mass at 1.15 d*) spinning at 40, 80 and 120 rad/s in its
   beam centred on the spin axis, linearised in its turning frame about its lit spun equilibrium
   (spin_spectrum.lit_state: the relaxation of solvers.reduced.sheet_relax with the light on): the fastest
   eigenvalue of the whole linearisation L, of L on the craft's six rigid motions (spin_spectrum.rigid_modes:
   the shape held) and of the deformations (rotating_spectrum), beside the rigid criterion's fastest root
   (analysis.ride3d_criterion, undamped, on the sphere R_c). The relaxed cap's sag and the radius of the sphere
   through its apex and rim, R_fit = (r² + s²)/(2s), and the criterion's d* on that sphere, tell how far spin
   has flattened it.
B. **Cells**. The spin map's spinning cells (Ω = 40–160 rad/s, d/d* = 0.7–1.3) from the spun equilibrium (the
   map's start, spin_equilibrium), with the map's settings, options and verdict rule (studies.ride_maps), read
   from the map's store where they are finished (run otherwise, unless --stored-only), beside the map's table as
   committed (MAP_TABLE), made from the spun state that held the cap's exact shape (initial_equilibrium).

Run from the repository root:
``nice -n 10 python validation/spin_equilibrium_cells.py [--out validation/spin_equilibrium_cells.md]
[--store scenarios/figures/store/spinning_maps] [--stored-only] [--spins 40 ...] [--cells-only] [--workers 2]``
(--cells-only: part B alone, printed, or written as a report of the cells to --out where that is given; with
--store and without --out it fills the store with the chosen cells).
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from lightsail_mbs.analysis import spin_spectrum
from lightsail_mbs.analysis.ride3d_criterion import cap_criterion
from lightsail_mbs.paper import spinning_maps as maps
from lightsail_mbs.studies.ride_maps import ride_map
from lightsail_mbs.studies.store import CaseStore
from lightsail_mbs.studies.sweep import Case
from lightsail_mbs.studies.tables import markdown_table

SPECTRUM_SPINS, SPECTRUM_RATIO = (40.0, 80.0, 120.0), 1.15
MAP_TABLE = "scenarios/figures/spinning_maps.md"  # the map's table as committed
REPORT = Path("validation/spin_equilibrium_cells.md")


def fastest(values) -> str:
    v = np.asarray(values)[np.argmax(np.real(values))]
    return f"{v.real:+.3f} ± {abs(v.imag):.2f}i"


def spectrum_rows() -> list[dict]:
    rows = []
    for spin in SPECTRUM_SPINS:
        p = maps.BASE.replace(billow_radius=1.0, spin_rate=spin)
        d = SPECTRUM_RATIO * maps.d_star(p)
        p = p.replace(payload_stem=d)
        state = spin_spectrum.lit_state(p)
        L = spin_spectrum.rotating_linearisation(p, state).toarray()
        whole = np.linalg.eigvals(L)
        whole = whole[np.abs(whole) > 1e-6]  # the rigid motions' zero eigenvalues (axial, spin)
        rigid = spin_spectrum.rigid_modes(p, state=state)
        shape = spin_spectrum.rotating_spectrum(p, state=state)
        tiles = spin_spectrum._start(p)[0][:-1] + state.reshape(-1, 13)[:-1, 0:3]
        radius = np.hypot(*(tiles[:, :2] - tiles[:, :2].mean(axis=0)).T)
        sag = float(tiles[np.argmax(radius), 2] - tiles[np.argmin(radius), 2])
        fit = (radius.max() ** 2 + sag**2) / (2 * abs(sag))
        rows.append(
            {
                "Ω (rad/s)": f"{spin:g}",
                "whole L: fastest λ (1/s)": fastest(whole),
                "rigid motions: fastest λ": fastest(rigid),
                "deformations: fastest λ": fastest(shape.eigenvalues),
                "criterion on R_c = 1 m: fastest s": fastest(cap_criterion(p, maps.SAIL_MASS, d).roots),
                "sag (mm), start → spun": f"{spin_sag(p):.1f} → {abs(sag) * 1e3:.1f}",
                "R_fit (m)": f"{fit:.2f}",
                "d/d* on R_fit": f"{d / maps.d_star(p.replace(billow_radius=fit)):.2f}",
            }
        )
        print(rows[-1], flush=True)
    return rows


def spin_sag(p) -> float:
    """The start's sag (mm) of the case's tiles: the rim tile's height above the middle tile's."""
    tiles = spin_spectrum._start(p.replace(spin_rate=0.0))[1][:-1]
    radius = np.hypot(*(tiles[:, :2] - tiles[:, :2].mean(axis=0)).T)
    return abs(float(tiles[np.argmax(radius), 2] - tiles[np.argmin(radius), 2])) * 1e3


def map_cells(path: Path) -> dict:
    """{(Ω, d/d*): the cell's text} of the spin map's table in the map's report."""
    lines = path.read_text().split("## d/d* against spin rate")[1].splitlines()
    rows = [[c.strip() for c in line.strip("|").split("|")] for line in lines if line.startswith("|")]
    spins = [float(v) for v in rows[0][1:]]
    return {(w, float(r[0])): text for r in rows[2:] for w, text in zip(spins, r[1:])}


def cell_rows(store: Path | None, stored_only: bool, workers: int, spins=None) -> list[dict]:
    make = maps.make("spin_rate")
    spins = [w for w in maps.MAPS["spin"][2] if w and (spins is None or w in spins)]
    cases = {(w, r): make(maps.BASE, w, r) for r in maps.SPIN_RATIOS for w in spins}
    if stored_only:  # the cells whose ride_map key is in the store
        found, settings = CaseStore(store), maps.SETTINGS
        cases = {c: p for c, p in cases.items() if found.has(Case(p, "reduced", maps.OPTIONS, settings=settings).key)}
    with tempfile.TemporaryDirectory() as scratch:
        settings, options = maps.SETTINGS, maps.OPTIONS
        cells = ride_map(cases, store_dir=store or scratch, settings=settings, options=options, workers=workers)
    old = map_cells(Path(MAP_TABLE))
    rows = []
    for (w, r), c in sorted(cells.items()):
        when = "" if c.decided_at is None else f" {c.decided_at:.2f} s"
        verdict = c.error if c.verdict is None else f"{maps.SHORT[c.verdict]}{when} ({c.growth:.1f}/s)"
        rows.append(
            {
                "Ω (rad/s)": f"{w:g}",
                "d/d*": f"{r:g}",
                "from the spun equilibrium": verdict,
                "largest distance (m)": f"{c.max_distance:.3f}",
                "largest deformation (m)": f"{c.max_deformation:.4f}",
                "the map (shape held)": old.get((w, r), "-"),
            }
        )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, help=f"the report [default: {REPORT}; none with --cells-only]")
    parser.add_argument("--store", type=Path, help="the map's store (default: a scratch store, every cell run)")
    parser.add_argument("--stored-only", action="store_true", help="only the cells finished in --store")
    parser.add_argument("--spins", type=float, nargs="+", help="only these spin rates' cells (rad/s)")
    parser.add_argument("--cells-only", action="store_true", help="part B only (no report written)")
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    if args.stored_only and args.store is None:
        parser.error("--stored-only needs --store")
    cells = cell_rows(args.store, args.stored_only, args.workers, args.spins)
    if args.cells_only and args.out is None:
        print(markdown_table(cells))
        return
    text = [
        "# The spin map's cap from the spun equilibrium" + (": its spinning cells" if args.cells_only else ""),
        "",
        f"Made by `nice -n 10 python {command(args)}` (its docstring says what it runs).",
    ]
    if not args.cells_only:
        text += spectrum_section(spectrum_rows())
    text += cells_section(cells)
    (args.out or REPORT).write_text("\n".join(text) + "\n")
    print("\n".join(text))


def command(args) -> str:
    """The report's command line: the script and the options that chose its content."""
    parts = ["validation/spin_equilibrium_cells.py"]
    if args.store is not None:
        parts += ["--store", str(args.store)] + (["--stored-only"] if args.stored_only else [])
    if args.spins:
        parts += ["--spins"] + [f"{w:g}" for w in args.spins]
    parts += ["--cells-only"] if args.cells_only else []
    return " ".join(parts + (["--out", str(args.out)] if args.out is not None else []))


def spectrum_section(spectrum: list[dict]) -> list[str]:
    return [
        "",
        f"## A. Spectrum in the turning frame (d = {SPECTRUM_RATIO:g} d*, beam centred, lit spun equilibrium)",
        "",
        "λ = Re λ ± |Im λ| i (1/s); the rigid criterion's s is in the inertial frame (its Re the same).",
        "",
        markdown_table(spectrum),
    ]


def cells_section(cells: list[dict]) -> list[str]:
    total = len(maps.SPIN_RATIOS) * (len(maps.MAPS["spin"][2]) - 1)
    return [
        "",
        f"## B. The spin map's spinning cells ({len(cells)} of {total})",
        "",
        "Verdicts as in the map: R rides, D drifts out, T tips over, C crumples, with the decision time and the",
        "growth rate of the distance from the beam's axis.",
        "",
        markdown_table(cells) if cells else "(none finished)",
    ]


if __name__ == "__main__":
    main()
