"""Four cells of the spin map (paper.spinning_maps: the 25-tile billowed disc, R_c = 1 m, a stem payload of the
sail's mass, the beam's axis 0.2 w off the middle) run from the spun equilibrium (spin_equilibrium: the unlit
shape at rest in the turning frame, solvers.reduced.sheet_relax) for the map's 1.2 s, with the map's settings,
solver options and verdict rule (studies.ride_maps.cell_of), beside the map's own cells, which started
from the spun state that held the cap's shape.

Run from the repository root:
``python validation/spin_equilibrium_cells.py [--out validation/spin_equilibrium_cells.md] [--workers 2]``.
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from lightsail_mbs.paper import spinning_maps as maps
from lightsail_mbs.studies.ride_maps import ride_map
from lightsail_mbs.studies.tables import markdown_table

CELLS = [(80.0, 1.0), (80.0, 1.3), (120.0, 1.0), (120.0, 1.3)]  # (Ω (rad/s), d/d*)
MAP_TABLE = "scenarios/figures/spinning_maps.md"  # the map's table, made from the held cap's spun state


def map_cells(path: Path) -> dict:
    """{(Ω, d/d*): the cell's text} of the spin map's table in the map's report."""
    lines = path.read_text().split("## d/d* against spin rate")[1].splitlines()
    rows = [[c.strip() for c in line.strip("|").split("|")] for line in lines if line.startswith("|")]
    spins = [float(v) for v in rows[0][1:]]
    return {(w, float(r[0])): text for r in rows[2:] for w, text in zip(spins, r[1:])}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", type=Path, default=Path("validation/spin_equilibrium_cells.md"))
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    make = maps.make("spin_rate")
    cases = {(w, r): make(maps.BASE, w, r).replace(spin_equilibrium=True) for w, r in CELLS}
    with tempfile.TemporaryDirectory() as store:
        cells = ride_map(
            cases, store_dir=store, settings=maps.SETTINGS, options=maps.OPTIONS, workers=args.workers, label="cells"
        )
    old = map_cells(Path(MAP_TABLE))
    rows = []
    for (w, r), c in cells.items():
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
    text = [
        "# Spin map cells from the spun equilibrium",
        "",
        "Made by `python validation/spin_equilibrium_cells.py` (its docstring says what it runs).",
        "Verdicts as in the map: R rides, D drifts out, T tips over, C crumples, with the decision time and the",
        "growth rate of the distance from the beam's axis.",
        "",
        markdown_table(rows),
    ]
    args.out.write_text("\n".join(text) + "\n")
    print("\n".join(text))


if __name__ == "__main__":
    main()
